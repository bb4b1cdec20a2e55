//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Reports `#3000 = n` (FANUC macro alarm) and `(abort, …)` (LinuxCNC).
    ///
    /// ## Why is this bad?
    /// The program stops here on the machine.
    ///
    /// ## Example
    /// ```gcode
    /// #3000 = 1
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC, RS274/NGC. Error.
    ///
    /// The control stops at the alarm: so does the dry run, and the run's figures are partial.
    ///
    /// Implements: — (no catalogue id)
    pub static MACRO_ALARM = {
        code: "X004",
        name: "macro-alarm",
        summary: "Program raises an alarm or aborts",
        implements: &[],
        origin: Runtime,
        default_enabled: true,
    }
}
