//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Severity;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags a feed move under G311 (feed excludes rotary axes) that moves only rotary axes.
    ///
    /// ## Why is this bad?
    /// The feed is computed from the linear axes alone, which do not move: the feed has no basis and the speed is undefined.
    ///
    /// ## Example
    /// ```gcode
    /// G311
    /// G01 A90. F100.
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G310
    /// G01 A90. F100.
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Warning.
    ///
    /// Implements: SW050
    pub static ROTARY_ONLY_FEED = {
        code: "F016",
        name: "rotary-only-feed",
        summary: "G311 block moving only rotary axes",
        implements: &["SW050"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// G311 (feed excludes rotary axes) is in force.
    pub(crate) g311: bool,
}

/// ServoWorks: under G311 a feed block moving only rotary axes has no feed basis.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) {
    let w = cx.w;
    // G311: rotary axes are not part of the feed; a block moving only rotary axes has none.
    if w.has_g(3110) {
        mem.g311 = true;
    } else if w.has_g(3100) {
        mem.g311 = false;
    }
    if let Some((m, s)) = cx.motion {
        let rotary = b"ABC".iter().any(|c| w.has(*c));
        let linear = b"XYZ".iter().any(|c| w.has(*c));
        if mem.g311 && matches!(m, 10 | 20 | 30) && rotary && !linear {
            cx.out.diag(&ROTARY_ONLY_FEED, Severity::Warning, s, "G311 leaves rotary axes out of the feed, and this block moves only rotary axes: the feed has no basis; use G310 for this block");
        }
    }
}
