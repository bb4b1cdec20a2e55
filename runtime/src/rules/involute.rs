//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Checks FANUC involute interpolation: start or end point inside the base circle, more than 100 turns from the involute's start, end point off the involute through the start by more than parameter 5610 (`machine.involute_tolerance`, default 0.01 mm), G40/G41/G42 or another G code than G04, G10, G17–G19, G65–G67, G90, G91 in involute mode, involute in cylindrical interpolation (G07.1), optional chamfer/corner R in involute mode, a cutter-compensated path that enters the base circle, and more than four additional helical axes.
    ///
    /// ## Why is this bad?
    /// The control alarms (PS0242/PS0243) or refuses the block.
    ///
    /// ## Example
    /// ```gcode
    /// G00 X-1. Y0
    /// G02.2 X1. Y10. I1. J0 R1. F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G00 X-1. Y0
    /// G02.2 X1. Y9.425 I1. J0 R1. F100
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error (cutter-compensated path into the base circle: warning).
    ///
    /// Implements: FAN043, FAN044, FAN045, FAN046, FAN047, FAN048, FAN049, FAN050, FAN051
    pub static INVOLUTE = {
        code: "A012",
        name: "involute",
        summary: "Invalid involute interpolation (G02.2/G03.2)",
        implements: &["FAN043", "FAN044", "FAN045", "FAN046", "FAN047", "FAN048", "FAN049", "FAN050", "FAN051"],
        origin: Runtime,
        default_enabled: true,
    }
}
