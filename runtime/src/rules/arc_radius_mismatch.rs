//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a centre-format arc (I/J/K) whose end point lies farther from the centre than the start point by more than the control tolerates.
    ///
    /// ## Why is this bad?
    /// The control stops with an alarm: LinuxCNC 2.9 refuses when the radii differ by more than 0.0283 mm (0.00283 in) and 0.1 %, or by more than 2.83 mm (the emc2 profile: 0.002 mm / 0.0002 in); FANUC raises PS0020 when the difference exceeds parameter 3410 (`arc_radius_tolerance`, default 0.02 mm); ServoWorks reports "Invalid center point for circular interpolation" when |r1 - r2| exceeds the circle error allowance (`circle_error_allowance`, default 0) or the machine-unit bound sqrt(m1² + m2²).
    ///
    /// ## Example
    /// ```gcode
    /// G17 G90 G0 X0 Y0
    /// G2 X100 Y0 I49 J0 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G17 G90 G0 X0 Y0
    /// G2 X100 Y0 I50 J0 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error. Reads `arc_radius_tolerance` (FANUC), `circle_error_allowance` and `machine_unit` (ServoWorks).
    ///
    /// After this error the dry run continues as if the block were a straight feed move to the programmed end point (the tool ends where the program says; with no feed rate the position is set there without a move).
    ///
    /// Reported by A007, not this rule, when both see I/J/K in polar coordinate mode (the radius check then fails too) on the same text (one diagnostic per fault).
    ///
    /// Implements: SW038, NGC211, NGC212, FAN031
    pub static ARC_RADIUS_MISMATCH = {
        code: "A001",
        name: "arc-radius-mismatch",
        summary: "Arc end point is not on the circle given by the centre",
        implements: &["SW038", "NGC211", "NGC212", "FAN031"],
        origin: Runtime,
        default_enabled: true,
    }
}
