//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/flow.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a call that nests deeper than the control's limit (ServoWorks 8, FANUC `max_call_depth` default 15) — usually unbounded recursion.
    ///
    /// ## Why is this bad?
    /// The control alarms (FANUC PS0077).
    ///
    /// ## Example
    /// ```gcode
    /// o<r> sub
    /// o<r> call
    /// o<r> endsub
    /// o<r> call
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// o<r> sub
    /// G0 X1
    /// o<r> endsub
    /// o<r> call
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// The dry run stops here (the message says so); the run's figures are partial.
    ///
    /// Implements: SW023, NGC607, FAN139, FAN138
    pub static CALL_DEPTH = {
        code: "F003",
        name: "call-depth-exceeded",
        summary: "Subprogram nesting deeper than the control allows",
        implements: &["SW023", "NGC607", "FAN139", "FAN138"],
        origin: Runtime,
        default_enabled: true,
    }
}
