//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Severity;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags a G10 L108 smoothing time outside 0–5000 ms (servo rate ≤ 1 kHz), 0–2500 ms (2 kHz) or 0–1250 ms (4 kHz); the rate is `machine.servo_rate_khz` (default 1).
    ///
    /// ## Why is this bad?
    /// ServoWorks refuses the value.
    ///
    /// ## Example
    /// ```gcode
    /// G04
    /// G10 L108 P1 R6000
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G04
    /// G10 L108 P1 R1000
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Error.
    ///
    /// Implements: SW064
    pub static SMOOTHING_TIME = {
        code: "D003",
        name: "smoothing-time",
        summary: "G10 L108 smoothing time out of range for the servo rate",
        implements: &["SW064"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// ServoWorks: G10 L108 smoothing times against the servo rate.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) {
    let w = cx.w;
    // Smoothing time by servo rate (G10 L108).
    if w.has_g(100) && w.get(b'L').map(|l| l.round() as i64) == Some(108) {
        let khz = cx.input.machine.servo_rate_khz.unwrap_or(1.0);
        let max = if khz <= 1.0 {
            5000.0
        } else if khz <= 2.0 {
            2500.0
        } else {
            1250.0
        };
        for c in [b'R', b'X', b'Y', b'Z', b'A', b'B', b'C'] {
            if let Some(v) = w.get(c).filter(|v| *v < 0.0 || *v > max) {
                cx.out.diag(&SMOOTHING_TIME, Severity::Error, w.sp(c), format!("smoothing time {v} ms is out of range: at a {khz} kHz servo rate G10 L108 accepts 0 to {max} ms"));
            }
        }
    }
}
