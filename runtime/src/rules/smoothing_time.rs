//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

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
