//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Severity;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags G51 with a magnification P of 0 or of 10 and more (P10000 and above in 0.001 units).
    ///
    /// ## Why is this bad?
    /// The control alarms (PS0142).
    ///
    /// ## Example
    /// ```gcode
    /// G51 X0 Y0 P0
    /// G50
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G51 X0 Y0 P2000
    /// G50
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Implements: FAN157
    pub static SCALING_MAGNIFICATION = {
        code: "K005",
        name: "scaling-magnification",
        summary: "Scaling magnification 0 or 10 and above",
        implements: &["FAN157"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// FANUC: the G51 scaling magnification.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) {
    let w = cx.w;
    // Scaling magnification.
    if w.has_g(510) {
        if let Some(p) = w.get(b'P') {
            let m = if w.point[(b'P' - b'A') as usize] {
                p
            } else {
                p * 0.001
            };
            if m <= 0.0 || m >= 10.0 {
                cx.out.diag(&SCALING_MAGNIFICATION, Severity::Error, w.sp(b'P'), format!("scaling magnification {m} is out of range (PS0142): it must be above 0 and below 10 (P1 to P9999)"));
            }
        }
    }
}
