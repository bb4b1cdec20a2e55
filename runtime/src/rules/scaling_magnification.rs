//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

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
