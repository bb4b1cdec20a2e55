//! S007: modal groups used before the program sets them.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::{block_g_codes, block_has_axis};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks that an RS274/NGC program sets the modes it relies on before using them:
    /// the plane (`G17`/`G18`/`G19`) before the first arc, canned cycle or cutter
    /// compensation; the distance mode (`G90`/`G91`) before the first axis word; the feed
    /// mode (`G93`/`G94`/`G95`) before the first feed move; and the canned-cycle return
    /// level (`G98`/`G99`) before the first cycle.
    ///
    /// ## Why is this bad?
    /// Modes carry over from the previous program and from MDI, so a program that does
    /// not set them behaves differently depending on what ran before. A preamble line
    /// such as `G17 G21 G40 G49 G54 G80 G90 G94` makes it self-contained.
    ///
    /// ## Example
    /// ```ngc
    /// G21
    /// G0 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G17 G21 G90 G94
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, warning (info for the return level), off by default. The file is read
    /// top to bottom; each group is reported once.
    ///
    /// Implements: NGC320, NGC703
    pub static PREAMBLE = {
        code: "S007",
        name: "mode-not-set",
        summary: "Modal group used before the program sets it",
        implements: &["NGC320", "NGC703"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct Preamble;

impl Rule for Preamble {
    fn meta(&self) -> &'static RuleMeta {
        &PREAMBLE
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        // (set, reported) per group: plane, distance, feed mode, return level.
        let mut state = [(false, false); 4];
        let sets: [&[u32]; 4] = [
            &[170, 180, 190, 171, 181, 191],
            &[900, 910],
            &[930, 940, 950],
            &[980, 990],
        ];
        let cycles: &[u32] = &[730, 740, 760, 810, 820, 830, 840, 850, 860, 870, 880, 890];
        for b in &p.blocks {
            let g = block_g_codes(p, b);
            for (i, s) in sets.iter().enumerate() {
                if g.iter().any(|c| s.contains(c)) {
                    state[i].0 = true;
                }
            }
            let span = p.items_of(b).first().map(|i| i.span).unwrap_or(b.span);
            let arc = g.contains(&20) || g.contains(&30);
            let cycle = g.iter().any(|c| cycles.contains(c));
            let comp = g.iter().any(|c| [410, 420, 411, 421].contains(c));
            let feed = arc || g.contains(&10) || cycle;
            let uses = [
                (
                    arc || cycle || comp,
                    "the plane (G17/G18/G19)",
                    "an arc, canned cycle or cutter compensation",
                ),
                (
                    block_has_axis(p, b, cx.settings),
                    "the distance mode (G90/G91)",
                    "axis words",
                ),
                (feed, "the feed mode (G94/G93/G95)", "a feed move"),
                (
                    cycle,
                    "the canned-cycle return level (G98/G99)",
                    "a canned cycle",
                ),
            ];
            for (i, (used, what, by)) in uses.into_iter().enumerate() {
                if used && !state[i].0 && !state[i].1 {
                    state[i].1 = true;
                    let sev = if i == 3 {
                        Severity::Info
                    } else {
                        Severity::Warning
                    };
                    out.push(PREAMBLE.diagnostic(
                        sev,
                        span,
                        format!("This line uses {by}, but the program has not set {what}; it inherits whatever was active before. Set it in a preamble at the top."),
                    ));
                }
            }
        }
    }
}
