//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags M72 (restore modal state) when no M70 or M73 saved one at the same call level.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops: there is nothing to restore ("missing M70/M73?").
    ///
    /// ## Example
    /// ```gcode
    /// M72
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M70
    /// G91
    /// M72
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC813
    pub static CONTEXT_RESTORE = {
        code: "F013",
        name: "context-restore",
        summary: "M72 without a saved modal state",
        implements: &["NGC813"],
        origin: Runtime,
        default_enabled: true,
    }
}
