//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a canned cycle with cutter compensation on, L0 repeats, or R below Z.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses each case.
    ///
    /// ## Example
    /// ```gcode
    /// G0 Z5
    /// G81 X1 Z2 R1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 Z5
    /// G81 X1 Z-2 R1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error.
    ///
    /// Implements: NGC303, NGC304, NGC311, NGC313, NGC315, FAN024
    pub static CYCLE_STATE = {
        code: "C003",
        name: "cycle-state",
        summary: "Canned cycle in an impossible state",
        implements: &["NGC303", "NGC304", "NGC311", "NGC313", "NGC315", "FAN024"],
        origin: Runtime,
        default_enabled: true,
    }
}
