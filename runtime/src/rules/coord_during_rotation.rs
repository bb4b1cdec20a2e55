//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/decode.rs`, `interp/exec/offsets.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags reference returns, coordinate-system changes and plane changes while coordinate rotation (G68) is active.
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
    /// Implements: SW070, SW071, SW108, FAN154
    pub static COORD_DURING_ROTATION = {
        code: "K001",
        name: "coordinate-change-during-rotation",
        summary: "G28/G30/G52–G59 or a plane change while G68 rotation is on",
        implements: &["SW070", "SW071", "SW108", "FAN154"],
        origin: Runtime,
        default_enabled: true,
    }
}
