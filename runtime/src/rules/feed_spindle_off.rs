//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Severity;

use super::check::Cx;
use crate::interp::is_cycle;

declare_rule! {
    /// ## What it does
    /// Flags G1/G2/G3 and canned cycles while the spindle is stopped (no M3/M4 in force). Off by default: plotters, lasers and dry runs feed without a spindle.
    ///
    /// ## Why is this bad?
    /// A cutting move with the spindle off rubs or breaks the tool.
    ///
    /// ## Example
    /// ```gcode
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S1000 M3
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Warning; enable it with `select`.
    ///
    /// Implements: NGC232
    pub static FEED_SPINDLE_OFF = {
        code: "F015",
        name: "feed-spindle-off",
        summary: "Feed move with the spindle stopped",
        implements: &["NGC232"],
        origin: Runtime,
        default_enabled: false,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// Whether the rule is selected, looked up once: the registry search costs
    /// more than the rest of a motion block's checks.
    pub(crate) wanted: Option<bool>,
}

/// RS274/NGC: feed moves with the spindle stopped (off by default, so computed
/// only when selected).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) {
    let st = cx.st;
    let Some((m, s)) = cx.motion else {
        return;
    };
    // Feed moves with the spindle off (optional rule).
    // Off by default, so it is computed only when selected.
    let wanted = wanted(cx, mem);
    if wanted && (matches!(m, 10 | 20 | 30) || is_cycle(m)) && st.spindle_dir == 0 {
        cx.out.diag(&FEED_SPINDLE_OFF, Severity::Warning, s, "feed move with the spindle stopped: the tool would rub or break; start the spindle (M3/M4) first");
    }
}

/// Whether the rule is selected (looked up once).
fn wanted(cx: &Cx<'_, '_>, mem: &mut Mem) -> bool {
    match mem.wanted {
        Some(w) => w,
        None => {
            let w = cx.input.settings.rule_enabled(&FEED_SPINDLE_OFF);
            mem.wanted = Some(w);
            w
        }
    }
}
