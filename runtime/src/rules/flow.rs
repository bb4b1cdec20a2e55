//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/decode.rs`, `interp/exec/context.rs`, `interp/exec/flow.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags GOTO to a missing sequence number, WHILE without END, O-word structures without their end, `return`/`break` outside their construct.
    ///
    /// ## Why is this bad?
    /// The control alarms when it reaches the statement.
    ///
    /// ## Example
    /// ```gcode
    /// GOTO 99
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// GOTO 10
    /// N10 M30
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// The state after this error is undefined (where the control would go is unknown): the dry run stops here and says so in the message; the run's figures are partial.
    ///
    /// Reported by P001, not this rule, when both see an O-word statement closing or returning from the wrong block on the same text (one diagnostic per fault).
    ///
    /// Reported by P002, not this rule, when both see an END without its DO on the same text (one diagnostic per fault).
    ///
    /// Reported by P003, not this rule, when both see a GOTO to a sequence number that does not exist on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN121, FAN122, FAN124, NGC601, NGC603, NGC605
    pub static FLOW = {
        code: "F007",
        name: "flow-control-error",
        summary: "Broken loop, branch or jump target",
        implements: &["FAN121", "FAN122", "FAN124", "NGC601", "NGC603", "NGC605"],
        origin: Runtime,
        default_enabled: true,
    }
}
