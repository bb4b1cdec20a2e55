//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/decode.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G/M words with a computed value that is not a valid code number.
    ///
    /// ## Why is this bad?
    /// The control stops.
    ///
    /// ## Example
    /// ```gcode
    /// #1=1.55
    /// G#1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G1 X1 F10
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error the dry run continues as if the block were not there (the rest of the block is skipped).
    ///
    /// Reported by W007, not this rule, when both see a minus sign on an M or G code on the same text (one diagnostic per fault).
    ///
    /// Reported by G004, not this rule, when both see a G code that does not exist on the same text (one diagnostic per fault).
    ///
    /// Implements: — (no catalogue id)
    pub static UNKNOWN_CODE = {
        code: "X002",
        name: "invalid-code-value",
        summary: "G or M word whose value is not a code",
        implements: &[],
        origin: Runtime,
        default_enabled: true,
    }
}
