//! Flow-sensitive rule metadata; the check runs in the interpreter.

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
    /// Implements: FAN124, FAN126, FAN128, NGC121
    pub static FLOW = {
        code: "F007",
        name: "flow-control-error",
        summary: "Broken loop, branch or jump target",
        implements: &["FAN124", "FAN126", "FAN128", "NGC121"],
        origin: Runtime,
        default_enabled: true,
    }
}
