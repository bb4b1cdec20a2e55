//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags rigid tapping (M29 with G84/G74) without an S value.
    ///
    /// ## Why is this bad?
    /// FANUC alarms PS0203/PS0204.
    ///
    /// ## Example
    /// ```gcode
    /// M29
    /// G84 X0 Y0 Z-10 R2 F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S500 M29
    /// G84 X0 Y0 Z-10 R2 F500
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Implements: FAN203, FAN204
    pub static RIGID_TAP = {
        code: "C004",
        name: "rigid-tap-state",
        summary: "Rigid tapping without spindle speed",
        implements: &["FAN203", "FAN204"],
        origin: Runtime,
        default_enabled: true,
    }
}
