//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Severity;

use super::check::Cx;
use crate::interp::{is_cycle, Words};

declare_rule! {
    /// ## What it does
    /// Flags a line that moves only the drilling axis (Z in G17) without a motion code while a canned cycle is modal.
    ///
    /// ## Why is this bad?
    /// The line does not move the tool: it drills the hole again at the same position. The intent was usually to leave the cycle.
    ///
    /// ## Example
    /// ```gcode
    /// G81 X1 Y1 Z-1 R1 F100
    /// Z5
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G81 X1 Y1 Z-1 R1 F100
    /// G80
    /// G0 Z5
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Info.
    ///
    /// Implements: NGC318
    pub static CYCLE_STILL_ACTIVE = {
        code: "C008",
        name: "cycle-still-active",
        summary: "Canned cycle still active on a drilling-axis move",
        implements: &["NGC318"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// RS274/NGC: a cycle repeated by a line that moves only the drilling axis.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) {
    let (w, st) = (cx.w, cx.st);
    let Some((m, s)) = cx.motion else {
        return;
    };
    // A cycle repeated by a line that moves only the drilling axis.
    if motion_is_modal(w, m) && is_cycle(m) {
        let n = b"ZYX"[match st.modal.plane {
            180 => 1,
            190 => 2,
            _ => 0,
        }];
        let plane_word = b"XYZ".iter().any(|c| *c != n && w.has(*c));
        if w.has(n) && !plane_word {
            cx.out.diag(&CYCLE_STILL_ACTIVE, Severity::Info, s, format!("the canned cycle G{} is still active: this {} move drills again at the same hole instead of moving; give G80 before leaving the holes", m / 10, n as char));
        }
    }
}

/// Whether the motion of the block comes from the modal state (no group-01 code written).
fn motion_is_modal(w: &Words, m: u32) -> bool {
    !w.has_g(m)
}
