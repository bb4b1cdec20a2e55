//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags an R-format arc whose sweep is between 165° and 195° (and in RS274/NGC 345° or more).
    ///
    /// ## Why is this bad?
    /// Near a half or full circle the centre moves a long way for a tiny change of the end point, so rounding puts the arc somewhere unexpected; the manuals advise I/J/K there.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G2 X1.99 Y0 R1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G2 X1 Y-1 R1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, FANUC. Warning.
    ///
    /// Implements: NGC213, FAN034
    pub static ARC_ILL_CONDITIONED = {
        code: "A009",
        name: "arc-ill-conditioned",
        summary: "Radius-format arc sweeping nearly 180° or 360°",
        implements: &["NGC213", "FAN034"],
        origin: Runtime,
        default_enabled: true,
    }
}
