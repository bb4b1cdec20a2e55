//! S011: cutter compensation without a G40 at the start.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::block_g_codes;
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Warns when an RS274/NGC program turns cutter compensation on (`G41`/`G42`) without
    /// a `G40` earlier in the file.
    ///
    /// ## Why is this bad?
    /// If the previous program was aborted with compensation on, the interpreter may still
    /// be in compensation mode and refuse the new `G41`/`G42`. Starting with `G40` is the
    /// seed's advice.
    ///
    /// ## Example
    /// ```ngc
    /// G17 G21
    /// G41 D1 G1 X10 F100
    /// G40 G1 X20
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G17 G21 G40
    /// G41 D1 G1 X10 F100
    /// G40 G1 X20
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, warning, off by default.
    ///
    /// Implements: NGC712
    pub static START_WITH_G40 = {
        code: "S011",
        name: "start-with-g40",
        summary: "Cutter compensation used without an initial G40",
        implements: &["NGC712"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct StartWithG40;

impl Rule for StartWithG40 {
    fn meta(&self) -> &'static RuleMeta {
        &START_WITH_G40
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        for b in &p.blocks {
            let g = block_g_codes(p, b);
            if g.contains(&400) {
                return;
            }
            if g.iter().any(|c| [410, 420, 411, 421].contains(c)) {
                let span = p.items_of(b).first().map(|i| i.span).unwrap_or(b.span);
                out.push(START_WITH_G40.diagnostic(
                    Severity::Warning,
                    span,
                    "Cutter compensation is turned on, but the program does not start with G40; after an aborted run the interpreter may still be compensating. Put G40 in the preamble.",
                ));
                return;
            }
        }
    }
}
