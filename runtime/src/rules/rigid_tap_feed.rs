//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::Cx;
use crate::interp::is_cycle;

declare_rule! {
    /// ## What it does
    /// Flags rigid tapping (M29 with G84/G74) with F0, and with a feed above `machine.max_cutting_feed` (mm/min) when it is set.
    ///
    /// ## Why is this bad?
    /// F0 gives a zero lead (PS0201); a feed above the upper limit alarms.
    ///
    /// ## Example
    /// ```gcode
    /// S500 M29
    /// G84 X0 Y0 Z-10. R2. F0
    /// G80
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S500 M29
    /// G84 X0 Y0 Z-10. R2. F500
    /// G80
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Reported by this rule, not F001, when both see rigid tapping with F0 on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN105, FAN106
    pub static RIGID_TAP_FEED = {
        code: "C009",
        name: "rigid-tap-feed",
        summary: "Rigid-tap feed zero or above the cutting-feed limit",
        implements: &["FAN105", "FAN106"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// FANUC: the feed of a rigid tapping cycle (`motion` as `involute::check` answers it).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, motion: Option<(u32, Span)>) {
    let (w, st) = (cx.w, cx.st);
    let Some((m, _)) = motion else {
        return;
    };
    if is_cycle(m) && matches!(m, 840 | 740) && st.modal.rigid_tap {
        if let Some(f) = w.get(b'F') {
            if f == 0.0 {
                cx.out.diag(&RIGID_TAP_FEED, Severity::Error, w.sp(b'F'), "rigid tapping with F0: the lead is zero, so the tap cannot advance (PS0201); give F = lead × S");
            } else if let Some(max) = cx.input.machine.max_cutting_feed {
                let f_mm = if st.modal.feed_mode == 950 {
                    f * st.spindle
                } else {
                    f
                } * if st.modal.inch { 25.4 } else { 1.0 };
                if f_mm > max {
                    cx.out.diag(&RIGID_TAP_FEED, Severity::Error, w.sp(b'F'), format!("rigid tapping feed {f_mm} mm/min is above the cutting-feed upper limit {max} mm/min: the control alarms; lower S or the lead"));
                }
            }
        }
    }
}
