//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags an R-format arc whose |R| is smaller than half the distance from the start to the end point.
    ///
    /// ## Why is this bad?
    /// No circle of that radius passes through both points. LinuxCNC stops (`Arc radius too small to reach end point`, tolerance 0.00005 in); FANUC alarms PS0020 beyond parameter 3410; ServoWorks reports "Invalid center point" when half chord − |R| exceeds the circle error allowance.
    ///
    /// ## Example
    /// ```gcode
    /// G90 G0 X0 Y0
    /// G2 X100 Y0 R40 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G90 G0 X0 Y0
    /// G2 X100 Y0 R50 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error the dry run continues as if the arc had been skipped with the tool at its programmed end point (no motion, no time).
    ///
    /// Implements: SW036, NGC207, FAN035
    pub static ARC_RADIUS_TOO_SMALL = {
        code: "A002",
        name: "arc-radius-too-small",
        summary: "R-format arc radius shorter than half the chord",
        implements: &["SW036", "NGC207", "FAN035"],
        origin: Runtime,
        default_enabled: true,
    }
}
