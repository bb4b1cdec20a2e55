//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a centre offset along the axis normal to the plane (K under G17), a radius-format arc with no in-plane end point (RS274/NGC; `emc2` also centre format), G90.1 absolute centres with one offset missing, and in ServoWorks an arc whose axis words do not match the plane or that moves more than two helical axes.
    ///
    /// ## Why is this bad?
    /// The control cannot build the arc the words describe: LinuxCNC stops, ServoWorks alarms.
    ///
    /// ## Example
    /// ```gcode
    /// G17 G0 X0 Y0
    /// G2 X1 Y1 K1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G17 G0 X0 Y0
    /// G2 X1 Y1 J1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error.
    ///
    /// After this error the dry run continues as if the arc had been skipped with the tool at its programmed end point (no motion, no time).
    ///
    /// Implements: NGC205, NGC208, NGC210, NGC216, SW033, SW034, SW042
    pub static ARC_WORDS = {
        code: "A008",
        name: "arc-words",
        summary: "Arc words that do not fit the active plane",
        implements: &["NGC205", "NGC208", "NGC210", "NGC216", "SW033", "SW034", "SW042"],
        origin: Runtime,
        default_enabled: true,
    }
}
