//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/cycles.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a canned cycle started without its R plane, its depth Z, or (G82/G86/G88/G89 in RS274/NGC) its dwell P.
    ///
    /// ## Why is this bad?
    /// The control alarms (`R clearance plane unspecified in cycle`).
    ///
    /// ## Example
    /// ```gcode
    /// G0 Z5
    /// G81 X1 Y1 Z-2 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 Z5
    /// G81 X1 Y1 Z-2 R1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC and ServoWorks: error. FANUC: a missing R is a
    /// warning (FAN090); after it the dry run continues as if R were the initial level,
    /// where the cycle then starts its feed. A missing Z is an error everywhere.
    ///
    /// After this error the dry run continues as if the cycle block had been skipped with the tool over its hole (X/Y of the block) at the height it had; the later blocks of the cycle mode run with the data they give.
    ///
    /// Implements: SW126, NGC301, NGC302, NGC306, FAN090
    pub static CYCLE_MISSING = {
        code: "C001",
        name: "cycle-missing-data",
        summary: "Canned cycle without R, Z or dwell P",
        implements: &["SW126", "NGC301", "NGC302", "NGC306", "FAN090"],
        origin: Runtime,
        default_enabled: true,
    }
}
