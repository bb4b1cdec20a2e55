//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/cycles.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G73/G83 without Q or with Q ≤ 0.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops (`Negative or zero Q value used`); FANUC ignores a negative sign.
    ///
    /// ## Example
    /// ```gcode
    /// G0 Z5
    /// G83 X1 Z-5 R1 Q0 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 Z5
    /// G83 X1 Z-5 R1 Q1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All.
    ///
    /// After this error the dry run continues as if the cycle block had been skipped with the tool over its hole (X/Y of the block) at the height it had.
    ///
    /// Reported by W003, not this rule, when both see a peck cycle without Q on the same text (one diagnostic per fault).
    ///
    /// Reported by W007, not this rule, when both see a negative peck depth Q on the same text (one diagnostic per fault).
    ///
    /// Implements: SW121, NGC307, NGC308, FAN072
    pub static CYCLE_Q = {
        code: "C002",
        name: "cycle-peck-q",
        summary: "Peck cycle without a positive Q",
        implements: &["SW121", "NGC307", "NGC308", "FAN072"],
        origin: Runtime,
        default_enabled: true,
    }
}
