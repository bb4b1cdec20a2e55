//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Checks G43/G44/G49 and G37 against the machine's Tool Length Compensation Type (`machine.tlc_type`, default 0): type 0 (A) compensates and calibrates only Z, type 1 (B) only the axis perpendicular to the plane (G17 Z, G18 Y, G19 X), type 2 (C) any axis but needs G49 and H0 together to cancel and has no G37; G37 needs a preceding G43/G44 with a non-zero H; and a G37 whose measurement (`machine.g37_measured`, the dry run's stand-in for the sensor) falls outside the G37 Limit (`machine.g37_limit`).
    ///
    /// ## Why is this bad?
    /// ServoWorks raises an alarm or error for each of these.
    ///
    /// ## Example
    /// ```gcode
    /// G37 Z20.
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G43 H1
    /// G37 Z20.
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Error.
    ///
    /// Implements: SW077, SW078, SW079, SW092, SW093, SW094
    pub static TLC_TYPE = {
        code: "T005",
        name: "tlc-type",
        summary: "Length compensation or G37 not allowed for the TLC type",
        implements: &["SW077", "SW078", "SW079", "SW092", "SW093", "SW094"],
        origin: Runtime,
        default_enabled: true,
    }
}
