//! Rename of local named parameters `#<name>` and RS274/NGC o-word labels, in
//! byte offsets over in-memory programs: what the name under the cursor
//! becomes in this program ([`rename`]) and in any other one
//! ([`Rename::edits_in`]), and, for a named subroutine, the file names that
//! go with it. Which files to look in, and reading them, is the host's.

use analyzer::names::{self, Sym};
use analyzer::syntax::Program;
use analyzer::{Span, TextEdit};

/// The name under `offset` that a rename would change, or why it cannot be
/// renamed; `None` when there is no name there.
pub fn prepare(program: &Program, offset: u32) -> Option<Result<Span, String>> {
    let occ = names::occurrence_at(program, offset)?;
    if let Some(why) = names::rename_refusal(&occ) {
        return Some(Err(why.to_string()));
    }
    Some(Ok(occ.span))
}

/// A decided rename: the symbol, the new name as typed, and this program's
/// edits.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rename {
    pub sym: Sym,
    pub new_name: String,
    /// The edits of the program the rename was asked in.
    pub edits: Vec<TextEdit>,
    /// A named subroutine, which other files call by its file name.
    pub subroutine: Option<SubroutineFile>,
}

/// A named subroutine's file name (`name.ngc`), before and after.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SubroutineFile {
    pub old: String,
    /// `None` when the new symbol names no file (a numbered label).
    pub new: Option<String>,
}

/// Renames the name under `offset` of `program` to `new_name`. `Ok(None)`:
/// no name there; `Err`: the message shown to the user (a name that cannot
/// be renamed, an invalid or clashing new name).
pub fn rename(program: &Program, offset: u32, new_name: &str) -> Result<Option<Rename>, String> {
    let Some(occ) = names::occurrence_at(program, offset) else {
        return Ok(None);
    };
    if let Some(why) = names::rename_refusal(&occ) {
        return Err(why.to_string());
    }
    let edits = names::rename_edits(program, &occ.sym, new_name)?;
    let subroutine = match names::subroutine_file_name(&occ.sym) {
        Some(old) => {
            let new_sym = names::new_symbol(&occ.sym, new_name)?;
            Some(SubroutineFile {
                old,
                new: names::subroutine_file_name(&new_sym),
            })
        }
        None => None,
    };
    Ok(Some(Rename {
        sym: occ.sym,
        new_name: new_name.to_string(),
        edits,
        subroutine,
    }))
}

impl Rename {
    /// The edits of another program (an open document, a library file):
    /// `None` when the symbol does not occur in it.
    pub fn edits_in(&self, other: &Program) -> Result<Option<Vec<TextEdit>>, String> {
        if !names::occurrences(other).iter().any(|o| o.sym == self.sym) {
            return Ok(None);
        }
        names::rename_edits(other, &self.sym, &self.new_name).map(Some)
    }
}
