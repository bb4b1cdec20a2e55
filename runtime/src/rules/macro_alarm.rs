//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/messages.rs`, `interp/exec/params.rs`.

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
