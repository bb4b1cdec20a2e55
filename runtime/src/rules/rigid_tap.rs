//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/cycles.rs`, `interp/exec/modal.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags rigid tapping (M29 with G84/G74) without an S value.
    ///
    /// ## Why is this bad?
    /// FANUC alarms PS0203/PS0204.
    ///
    /// ## Example
    /// ```gcode
    /// M29
    /// G84 X0 Y0 Z-10 R2 F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S500 M29
    /// G84 X0 Y0 Z-10 R2 F500
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Implements: FAN100, FAN101, FAN103
    pub static RIGID_TAP = {
        code: "C004",
        name: "rigid-tap-state",
        summary: "Rigid tapping without spindle speed",
        implements: &["FAN100", "FAN101", "FAN103"],
        origin: Runtime,
        default_enabled: true,
    }
}
