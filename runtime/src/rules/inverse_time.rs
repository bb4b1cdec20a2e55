//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Severity};

use super::check::{is_feed_motion, Cx};
use crate::interp::is_cycle;

declare_rule! {
    /// ## What it does
    /// Flags, in inverse-time mode (G93), a G1/G2/G3 move without its own F word (error), an F word on a line without a feed move (ignored, info), and a canned cycle (error).
    ///
    /// ## Why is this bad?
    /// Under G93 the F word is the reciprocal of the move's time and applies to that move only; LinuxCNC refuses a feed move without F and refuses canned cycles in G93.
    ///
    /// ## Example
    /// ```gcode
    /// G93
    /// G1 X1 F10
    /// G1 X2
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G93
    /// G1 X1 F10
    /// G1 X2 F10
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error (info for an ignored F).
    ///
    /// Implements: NGC201, NGC202, NGC310
    pub static INVERSE_TIME = {
        code: "F009",
        name: "inverse-time-feed",
        summary: "Inverse-time feed (G93) misuse",
        implements: &["NGC201", "NGC202", "NGC310"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// G93: every feed move needs its own F; F alone does nothing; no cycles.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    if !cx.ngc() {
        return Ok(());
    }
    let g93 = w.has_g(930) || (st.modal.feed_mode == 930 && !w.has_g(940) && !w.has_g(950));
    if !g93 {
        return Ok(());
    }
    let motion = cx.motion;
    match motion {
        Some((g, s)) if is_cycle(g) => Err(cx.out.err(
            &INVERSE_TIME,
            s,
            "canned cycles cannot be used in inverse-time feed mode (G93): switch to G94 first",
        )),
        Some((g, s)) if is_feed_motion(g) && !w.has(b'F') => Err(cx.out.err(
            &INVERSE_TIME,
            s,
            // LinuxCNC's own words: each move in G93 carries its own F.
            if g == 10 {
                "F word missing with inverse time g1 move"
            } else {
                "F word missing with inverse time arc move"
            },
        )),
        Some((g, _)) if is_feed_motion(g) => Ok(()),
        _ => {
            if w.has(b'F') {
                cx.out.diag(
                    &INVERSE_TIME,
                    Severity::Info,
                    w.sp(b'F'),
                    "F on a line without a feed move is ignored in inverse-time mode (G93): each move carries its own F",
                );
            }
            Ok(())
        }
    }
}
