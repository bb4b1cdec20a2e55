//! Flow-sensitive rule metadata; the check runs in the interpreter.

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
    /// Implements: NGC030, FAN112, FAN115, FAN116, FAN119
    pub static EXPRESSION = {
        code: "X001",
        name: "expression-error",
        summary: "Expression or parameter error at run time",
        implements: &["NGC030", "FAN112", "FAN115", "FAN116", "FAN119"],
        origin: Runtime,
        default_enabled: true,
    }
}
