//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/decode.rs`, `interp/exec/flow.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags an `M98 P…`, `G65 P…` or `o<name> call` whose target is neither in the file nor found by the host (`O<name>.dat`, `O1234`, `<name>.ngc`).
    ///
    /// ## Why is this bad?
    /// The control alarms at the call (FANUC PS0076).
    ///
    /// ## Example
    /// ```gcode
    /// o<missing> call
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// o<here> sub
    /// G0 X1
    /// o<here> endsub
    /// o<here> call
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error the dry run continues as if the call were not there: the block's remaining words are skipped and the run goes on with the next block.
    ///
    /// Reported by W003, not this rule, when both see M98 or G65 without P on the same text (one diagnostic per fault).
    ///
    /// Implements: SW021, NGC609, FAN140
    pub static SUB_NOT_FOUND = {
        code: "F002",
        name: "subprogram-not-found",
        summary: "Called subprogram or macro not found",
        implements: &["SW021", "NGC609", "FAN140"],
        origin: Runtime,
        default_enabled: true,
    }
}
