//! Go-to-definition and references: subprograms (`o<name> call` → `o<name>
//! sub`, `M98 P1234`/`G65 P9100` → `O1234`, ServoWorks `M98 PMoveXY` →
//! `OMoveXY.dat`), O-word labels, `GOTO n` → `N n`, and variables, in one
//! program. A symbol the document calls but does not define is the host's to
//! find in another file ([`Definition::Elsewhere`]); the host then asks
//! [`definition_in`] and [`references_in`] of that file's program.

use analyzer::names::{self as nav, Sym};
use analyzer::syntax::Program;
use analyzer::Span;

use super::Analysis;

/// Where the symbol under the cursor is defined.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Definition {
    /// In this document.
    Here(Span),
    /// Not in this document: a program or subprogram of another file.
    Elsewhere(Sym),
}

pub fn definition(a: &Analysis<'_>, offset: u32) -> Option<Definition> {
    let occ = nav::occurrence_at(a.program, offset)?;
    Some(match nav::definition(a.program, &occ.sym) {
        Some(span) => Definition::Here(span),
        None => Definition::Elsewhere(occ.sym),
    })
}

/// Where another file's program defines `sym`.
pub fn definition_in(program: &Program, sym: &Sym) -> Option<Span> {
    nav::definition(program, sym)
}

/// The occurrences of the symbol under the cursor in this document.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct References {
    pub sym: Sym,
    pub spans: Vec<Span>,
}

impl References {
    /// Programs and subprograms are shared with other files, which the host
    /// searches too; labels, sequence numbers and variables are not.
    pub fn crosses_files(&self) -> bool {
        matches!(self.sym, Sym::OLabel(_) | Sym::Program(_))
    }
}

pub fn references(a: &Analysis<'_>, offset: u32, include_declaration: bool) -> Option<References> {
    let occ = nav::occurrence_at(a.program, offset)?;
    let spans = references_in(a.program, &occ.sym, include_declaration);
    Some(References {
        sym: occ.sym,
        spans,
    })
}

/// The occurrences of `sym` in a program (its definitions only when asked).
pub fn references_in(program: &Program, sym: &Sym, include_declaration: bool) -> Vec<Span> {
    nav::references(program, sym)
        .iter()
        .filter(|o| include_declaration || !o.def)
        .map(|o| o.span)
        .collect()
}
