//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags reference returns and coordinate-system changes while coordinate rotation (G68) is active.
    ///
    /// ## Why is this bad?
    /// The controls forbid them until G69 cancels the rotation.
    ///
    /// ## Example
    /// ```gcode
    /// G68 X0 Y0 R30
    /// G28 X0
    /// G69
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G68 X0 Y0 R30
    /// G69
    /// G28 X0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC and ServoWorks. Error.
    ///
    /// Implements: SW090, FAN060
    pub static COORD_DURING_ROTATION = {
        code: "K001",
        name: "coordinate-change-during-rotation",
        summary: "G28/G30/G52–G59 while G68 rotation is on",
        implements: &["SW090", "FAN060"],
        origin: Runtime,
        default_enabled: true,
    }
}
