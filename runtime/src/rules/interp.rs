//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec.rs` and most of `interp/exec/`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags run-time conditions not covered by a more specific rule: dwell without time, M98 with motion in the block, M99 in a main program.
    ///
    /// ## Why is this bad?
    /// The control alarms or does something the programmer did not intend.
    ///
    /// ## Example
    /// ```gcode
    /// G4
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G4 P1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All.
    ///
    /// After this error the dry run stops (the message says so) and the run's figures are partial, except where the message says the dry run goes on.
    ///
    /// Reported by W003, not this rule, when both see a code without a word it needs (G4 without P, …) on the same text (one diagnostic per fault).
    ///
    /// Reported by L011, not this rule, when both see a `%` that is not a program end on the same text (one diagnostic per fault).
    ///
    /// Reported by W005, not this rule, when both see a word letter the machine or profile does not have on the same text (one diagnostic per fault).
    ///
    /// Reported by W020, not this rule, when both see M98 in a block with a canned cycle's axis words on the same text (one diagnostic per fault).
    ///
    /// Implements: SW024, SW026, NGC223, NGC231, NGC416, NGC417, NGC418
    pub static INTERP = {
        code: "X003",
        name: "interpreter-error",
        summary: "Other run-time condition the control rejects or handles surprisingly",
        implements: &["SW024", "SW026", "NGC223", "NGC231", "NGC416", "NGC417", "NGC418"],
        origin: Runtime,
        default_enabled: true,
    }
}
