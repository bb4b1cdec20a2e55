//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G5.3 without an open G5.2 block, a control-point weight P ≤ 0, and a control point without both X and Y.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses these NURBS blocks and stops.
    ///
    /// ## Example
    /// ```gcode
    /// G5.3
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G1 X0 Y0 F100
    /// G5.2 X1 Y0 P1 L3
    /// X2 Y1 P1
    /// X3 Y0 P1
    /// G5.3
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC802
    pub static NURBS_BLOCK = {
        code: "A010",
        name: "nurbs-block",
        summary: "Malformed G5.2/G5.3 NURBS block",
        implements: &["NGC802"],
        origin: Runtime,
        default_enabled: true,
    }
}
