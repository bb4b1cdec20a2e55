//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags an R-format arc with the end point equal to the start point.
    ///
    /// ## Why is this bad?
    /// A full circle cannot be given with R: infinitely many circles pass through one point. The control alarms.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G2 X0 Y0 R10 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G2 X0 Y0 I10 J0 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error the dry run continues as if the arc had been skipped (the tool stays where it is, which is the programmed end).
    ///
    /// Implements: SW035, NGC206, FAN033
    pub static ARC_SAME_END_R = {
        code: "A006",
        name: "arc-full-circle-with-r",
        summary: "R-format arc whose end point equals its start point",
        implements: &["SW035", "NGC206", "FAN033"],
        origin: Runtime,
        default_enabled: true,
    }
}
