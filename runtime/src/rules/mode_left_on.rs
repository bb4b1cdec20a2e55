//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags M2/M30 reached with a mode still on that the program should cancel: cutter compensation, a G92/G52 offset, 3D-DLACC, a canned cycle, polar coordinates, G66, rotation or scaling (which ones depends on the dialect).
    ///
    /// ## Why is this bad?
    /// The end code does not reset these modes on every control (LinuxCNC keeps G92, ServoWorks keeps G52 and DLACC, FANUC keeps G16/G66/G68/G51 unless reset is configured), so the next program or MDI command starts in an unexpected mode.
    ///
    /// ## Example
    /// ```gcode
    /// G41.1 D0.2
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G41.1 D0.2
    /// G1 X1 F100
    /// G40 G1 X2
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Warning. RS274/NGC: cutter comp, G92/G52. ServoWorks: cutter comp, DLACC, G52, canned cycle. FANUC: G16, G66, G68, G51.
    ///
    /// Implements: SW058, SW086, SW111, SW135, NGC422, NGC428, FAN063
    pub static MODE_LEFT_ON = {
        code: "F008",
        name: "mode-left-on-at-end",
        summary: "A mode still active at program end",
        implements: &["SW058", "SW086", "SW111", "SW135", "NGC422", "NGC428", "FAN063"],
        origin: Runtime,
        default_enabled: true,
    }
}
