//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags M100–M199 unless the number is listed in `machine.user_m_codes`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC runs a user M code from a program file of that name; without it the interpreter stops with "Unknown m code used".
    ///
    /// ## Example
    /// ```gcode
    /// M101
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error, and interpretation stops, when `machine.user_m_codes` is
    /// configured or the machine's search path is (`machine.subroutine_path`).
    /// Without either the program file may well exist on the machine: information,
    /// once per code, and the dry run continues as if the code did nothing.
    ///
    /// Implements: NGC507
    pub static UNKNOWN_USER_M = {
        code: "X009",
        name: "unknown-user-m",
        summary: "User M code M100–M199 that is not configured",
        implements: &["NGC507"],
        origin: Runtime,
        default_enabled: true,
    }
}
