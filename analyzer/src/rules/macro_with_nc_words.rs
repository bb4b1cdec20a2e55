//! P004: a FANUC macro statement sharing a block with NC words.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{ItemKind, MacroStmt};

use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags a FANUC block that holds both a macro statement (an assignment `#i = …`,
    /// `GOTO`, `IF`, `WHILE`, `END`) and NC words such as `G01 X10.`. A sequence number
    /// `N` in front of the statement is allowed.
    ///
    /// ## Why is this bad?
    /// Macro statements and NC statements are executed by different parts of the control
    /// and cannot share a block: alarm PS0127 (duplicate NC, macro statement).
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = 10. G01 X#1 F100.;
    /// M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = 10.;
    /// G01 X#1 F100.;
    /// M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// FANUC, error.
    ///
    /// Implements: FAN133
    pub static MACRO_WITH_NC_WORDS = {
        code: "P004",
        name: "macro-with-nc-words",
        summary: "Macro statement and NC words in one block",
        implements: &["FAN133"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct MacroWithNcWords;

impl Rule for MacroWithNcWords {
    fn meta(&self) -> &'static RuleMeta {
        &MACRO_WITH_NC_WORDS
    }

    /// A report needs a macro statement or an assignment.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Fanuc {
            return;
        }
        let items = cx.items();
        let is_stmt = |k: &ItemKind| match k {
            ItemKind::Assign { .. } => true,
            ItemKind::Macro(m) => !matches!(m, MacroStmt::Output),
            _ => false,
        };
        let Some(stmt) = items.iter().find(|i| is_stmt(&i.kind)) else {
            return;
        };
        let Some(nc) = items
            .iter()
            .find(|i| matches!(i.kind, ItemKind::Word(w) if w.letter != b'N'))
        else {
            return;
        };
        out.push(
            MACRO_WITH_NC_WORDS.error(
                nc.span,
                "NC words in the same block as a macro statement: the control raises alarm PS0127. Put the macro statement and the NC words in separate blocks.",
            )
            .with_related(stmt.span, "macro statement"),
        );
    }
}
