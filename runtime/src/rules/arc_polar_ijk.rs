//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags I/J/K centre words on an arc while polar coordinate command (G16) is active.
    ///
    /// ## Why is this bad?
    /// In polar mode the centre must be given with R; I/J/K are not converted and the control alarms.
    ///
    /// ## Example
    /// ```gcode
    /// G17 G16
    /// G2 X50 Y90 I-50 F100
    /// G15
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G17 G16
    /// G2 X50 Y90 R50 F100
    /// G15
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Reported by this rule, not A001, when both see I/J/K in polar coordinate mode (the radius check then fails too) on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN038
    pub static ARC_POLAR_IJK = {
        code: "A007",
        name: "arc-ijk-in-polar-mode",
        summary: "I/J/K arc while polar coordinates (G16) are on",
        implements: &["FAN038"],
        origin: Runtime,
        default_enabled: true,
    }
}
