//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a G1/G2/G3 (or canned-cycle) move while the feed rate is zero.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops (`Cannot do g1 with zero feed rate`); FANUC and ServoWorks alarm or do not move.
    ///
    /// ## Example
    /// ```gcode
    /// G1 X10
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G1 X10 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error (RS274/NGC, where it is an error) the dry run continues as if the move had been skipped with the tool at its programmed end point (no motion, no time).
    ///
    /// Reported by C009, not this rule, when both see rigid tapping with F0 on the same text (one diagnostic per fault).
    ///
    /// Implements: SW047, NGC200, NGC228, NGC312, FAN039, FAN091, FAN037
    pub static ZERO_FEED = {
        code: "F001",
        name: "zero-feed",
        summary: "Feed move with no feed rate",
        implements: &["SW047", "NGC200", "NGC228", "NGC312", "FAN039", "FAN091", "FAN037"],
        origin: Runtime,
        default_enabled: true,
    }
}
