//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G53 with a motion other than G0/G1 or in G91 (RS274/NGC), and in ServoWorks G29 with no earlier G28/G30, G20/G21 after motion, G52 in G91, cutter compensation with scaling or mirror, scaling and mirror together, and the order G51 → G68 → G41 / G69 before G50. Also G10 without a valid L (LinuxCNC 2.9: L0, L1, L2, L10, L11, L20; `emc2`: L2) and G10 L0 while a tool is loaded. Warns at a ServoWorks G68 centre word on the axis normal to the plane.
    ///
    /// ## Why is this bad?
    /// The control refuses the block, ignores it, or transforms the path in an order the manual does not support.
    ///
    /// ## Example
    /// ```gcode
    /// G91
    /// G53 G0 X0
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G90
    /// G53 G0 X0
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error (ServoWorks G29, G52 and ordering: warning; units after motion: info).
    ///
    /// Implements: NGC404, NGC406, SW072, SW074, SW081, SW103, SW107, SW113, NGC400, NGC821, SW112
    pub static COORDINATE_MODE = {
        code: "K003",
        name: "coordinate-mode",
        summary: "Coordinate, unit or transformation command in a refused or ignored state",
        implements: &["NGC404", "NGC406", "SW072", "SW074", "SW081", "SW103", "SW107", "SW113", "NGC400", "NGC821", "SW112"],
        origin: Runtime,
        default_enabled: true,
    }
}
