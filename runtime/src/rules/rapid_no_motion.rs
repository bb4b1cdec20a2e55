//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::Cx;
use crate::interp::dist;

declare_rule! {
    /// ## What it does
    /// Flags a G0 with axis words whose target is where the tool already is (after the first motion).
    /// A block that runs more than once (in a subprogram or a loop) is flagged only if it never
    /// moves the tool on any pass. A subprogram's first motion is never flagged: it positions the
    /// tool for each call, wherever one caller already stands.
    ///
    /// ## Why is this bad?
    /// The block does nothing but costs a block; it often hides a wrong coordinate.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1 Y1
    /// G0 X1 Y1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1 Y1
    /// G0 X2 Y1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Info.
    ///
    /// Implements: NGC230
    pub static RAPID_NO_MOTION = {
        code: "F014",
        name: "rapid-no-motion",
        summary: "Rapid to the current position",
        implements: &["NGC230"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// Rapid blocks (file, block) that have moved the tool at least once, and
    /// those that carry a note: a rapid in a subprogram or loop is a no-op on
    /// some passes only, and the note is for rapids that never move.
    pub(crate) moved: std::collections::HashSet<(usize, u32)>,
    pub(crate) noted: std::collections::HashSet<(usize, u32)>,
    /// Every block runs at most once (a program without calls, loops or jumps):
    /// the per-block bookkeeping above is not needed.
    pub(crate) single_pass: bool,
}

/// RS274/NGC: a G0 to where the tool already is.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) {
    let (w, st) = (cx.w, cx.st);
    let Some((m, s)) = cx.motion else {
        return;
    };
    // A rapid to where the tool already is.
    if m == 0 && w.has_g(0) && w.any_axis() && cx.any_motion() {
        let t = cx.target();
        let here = cx.cur;
        // A subprogram's first motion positions the tool for each call: that
        // a caller is already there does not make it useless.
        let made = cx.motions_made;
        let positions_call = cx.motions_at_call == Some(made);
        if positions_call {
            if mem.moved.insert(here) {
                withdraw(cx, mem, here, s);
            }
        } else if dist(&t, &st.pos) < 1e-9 {
            if mem.single_pass {
                cx.out.diag(&RAPID_NO_MOTION, Severity::Info, s, "this rapid goes to where the tool already is: it does nothing but costs a block; remove it or check the coordinates");
            } else if !mem.moved.contains(&here) && !mem.noted.contains(&here) {
                mem.noted.insert(here);
                cx.out.diag(&RAPID_NO_MOTION, Severity::Info, s, "this rapid goes to where the tool already is: it does nothing but costs a block; remove it or check the coordinates");
            }
        } else if !mem.single_pass && mem.moved.insert(here) {
            withdraw(cx, mem, here, s);
        }
    }
}

/// Removes the note of a rapid block that has now moved the tool.
fn withdraw(cx: &mut Cx<'_, '_>, mem: &mut Mem, here: (usize, u32), span: Span) {
    if mem.noted.remove(&here) {
        cx.out.withdraw(&RAPID_NO_MOTION, span);
    }
}
