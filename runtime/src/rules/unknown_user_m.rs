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
    /// RS274/NGC. Error; interpretation stops.
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
