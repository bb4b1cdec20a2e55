//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/params.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags run-time expression errors: division by zero, domain errors of functions, undefined named parameters, parameter numbers out of range, writes to #0.
    ///
    /// ## Why is this bad?
    /// The control stops with an alarm (FANUC PS0112/PS0115/PS0116/PS0119).
    ///
    /// ## Example
    /// ```gcode
    /// #1 = [1/0]
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// #1 = [1/2]
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error the dry run continues as if the expression had an unknown value, read as 0: the block runs with it and its other diagnostics are not reported (they would follow from the unknown value), a parameter assigned from it is unknown too (reads of it report nothing more), and where an unknown value decides a branch (IF, WHILE, o-word if/while/repeat) an Info note says the branch taken may not be the control's.
    ///
    /// Reported by W015, not this rule, when both see a constant expression that cannot be evaluated on the same text (one diagnostic per fault).
    ///
    /// Reported by W016, not this rule, when both see a write to a read-only parameter on the same text (one diagnostic per fault).
    ///
    /// Reported by W017, not this rule, when both see EXISTS without a parameter on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC014, NGC018, NGC019, NGC028, FAN127, FAN128, FAN129
    pub static EXPRESSION = {
        code: "X001",
        name: "expression-error",
        summary: "Expression or parameter error at run time",
        implements: &["NGC014", "NGC018", "NGC019", "NGC028", "FAN127", "FAN128", "FAN129"],
        origin: Runtime,
        default_enabled: true,
    }
}
