//! S006: RS274/NGC units set late, or more than once.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::{block_g_codes, block_has_axis};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks that an RS274/NGC program sets its units (`G20` inch or `G21` mm) once, near
    /// the start and before the first axis word; it warns when there is no units code
    /// before the first motion, and when units are set again later or after motion.
    ///
    /// ## Why is this bad?
    /// The start-up units come from the machine configuration and from whatever ran
    /// before, so a program that does not set them can run ten times too large or small.
    /// Changing units in the middle makes every later number mean something else.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G21
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, warning, off by default. The file is read top to bottom; calls and
    /// loops are not followed.
    ///
    /// Implements: NGC241, NGC704
    pub static UNITS_SETTING = {
        code: "S006",
        name: "units-setting",
        summary: "Units not set before motion, or set again",
        implements: &["NGC241", "NGC704"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct UnitsSetting;

impl Rule for UnitsSetting {
    fn meta(&self) -> &'static RuleMeta {
        &UNITS_SETTING
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let mut units_set: Option<crate::span::Span> = None;
        let mut moved = false;
        for b in &p.blocks {
            let g = block_g_codes(p, b);
            let units_word = p.words(b).find(|(_, w)| {
                w.letter == b'G' && w.num().is_some_and(|n| n.value == 20.0 || n.value == 21.0)
            });
            if let Some((item, _)) = units_word {
                if let Some(first) = units_set {
                    out.push(
                        UNITS_SETTING.diagnostic(Severity::Warning, item.span, "Units are set a second time: set G20 or G21 once, at the start of the program.")
                            .with_related(first, "units first set here"),
                    );
                } else if moved {
                    out.push(UNITS_SETTING.diagnostic(
                        Severity::Warning,
                        item.span,
                        "Units are set after motion: the moves above ran in whatever units were active. Set G20 or G21 at the start of the program.",
                    ));
                }
                units_set.get_or_insert(item.span);
            }
            if !moved && block_has_axis(p, b, cx.settings) {
                moved = true;
                if units_set.is_none() && !(g.contains(&200) || g.contains(&210)) {
                    let span = p
                        .words(b)
                        .find(|(_, w)| super::util::is_machine_axis(cx.settings, w.letter))
                        .map(|(i, _)| i.span)
                        .unwrap_or(b.span);
                    out.push(UNITS_SETTING.diagnostic(
                        Severity::Warning,
                        span,
                        "First motion before any G20/G21: the units come from the machine's start-up state. Put G21 (mm) or G20 (inch) at the top of the program.",
                    ));
                }
            }
        }
    }
}
