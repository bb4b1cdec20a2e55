//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Checks the LinuxCNC parameter (`.var`) file the run reads: every line must be `number value`, with increasing numbers. The example program runs with a file holding `5221 1.0` then `5220 1.0`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses a parameter file that is out of order or cannot be read.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC (the file the host reads). Error.
    ///
    /// Implements: NGC429
    pub static VAR_FILE = {
        code: "X011",
        name: "var-file",
        summary: "Malformed or out-of-order parameter file",
        implements: &["NGC429"],
        origin: Runtime,
        default_enabled: true,
    }
}
