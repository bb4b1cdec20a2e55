//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G2/G3 while a UVW plane (G17.1, G18.1, G19.1) is selected.
    ///
    /// ## Why is this bad?
    /// LinuxCNC makes arcs only in the XYZ planes and stops.
    ///
    /// ## Example
    /// ```gcode
    /// G17.1
    /// G2 X1 Y1 I1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G17
    /// G2 X1 Y1 I1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC214
    pub static ARC_UVW_PLANE = {
        code: "A011",
        name: "arc-uvw-plane",
        summary: "Arc in a UVW plane",
        implements: &["NGC214"],
        origin: Runtime,
        default_enabled: true,
    }
}
