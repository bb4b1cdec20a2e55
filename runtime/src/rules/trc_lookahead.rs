//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Dialect, Severity};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags the 101st consecutive block without motion while tool radius compensation is on.
    ///
    /// ## Why is this bad?
    /// ServoWorks' compensation looks ahead 100 blocks; beyond them it cannot see the next move and the corner is offset wrongly.
    ///
    /// ## Example
    /// ```gcode
    /// G41 D1 G01 X10. F100.
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G01 X20.
    /// G40 G01 X30.
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G41 D1 G01 X10. F100.
    /// G04
    /// G01 X20.
    /// G40 G01 X30.
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Info.
    ///
    /// Implements: SW085
    pub static TRC_LOOKAHEAD = {
        code: "T006",
        name: "trc-lookahead",
        summary: "More than 100 blocks without motion in TRC mode",
        implements: &["SW085"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// Blocks since the last motion while radius compensation is on.
    pub(crate) blocks_without_motion: u32,
    pub(crate) motions_seen: usize,
}

/// The look-ahead of ServoWorks radius compensation counts blocks between motions
/// (every dialect keeps the count).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) {
    let st = cx.st;
    // The look-ahead of ServoWorks radius compensation counts blocks between motions.
    let n = cx.motions_buffered;
    if n > mem.motions_seen || st.modal.comp == 400 {
        mem.blocks_without_motion = 0;
    } else {
        mem.blocks_without_motion += 1;
        if cx.dialect == Dialect::Servoworks && mem.blocks_without_motion == 101 {
            cx.out.diag(&TRC_LOOKAHEAD, Severity::Info, cx.bspan, "more than 100 blocks without motion in tool radius compensation: the look-ahead buffer holds 100 blocks, so the offset at the next corner cannot see the next move; keep blocks without motion few");
        }
    }
    mem.motions_seen = n;
}
