//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a read of a vacant variable in an assignment or a word value: FANUC local variables #1–#33 of the current level (warning), and ServoWorks variables (info). Comparisons with EQ/NE are exempt, as that is how a macro tests whether an argument was given.
    ///
    /// ## Why is this bad?
    /// A vacant value reads as 0 in arithmetic (and drops the word it is in), so the program computes with a value nobody set.
    ///
    /// ## Example
    /// ```gcode
    /// #101 = #1 + 1
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// #1 = 2
    /// #101 = #1 + 1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC (warning, locals; information inside a G65/G66 macro, where a local is an
    /// argument the caller may leave out and reads as 0 in arithmetic; nothing for a
    /// local set from a machine value the dry run does not know, `#24 = #516`),
    /// ServoWorks (info).
    ///
    /// Implements: SW017, FAN144
    pub static VACANT_READ = {
        code: "X010",
        name: "vacant-read",
        summary: "Variable read before it is assigned",
        implements: &["SW017", "FAN144"],
        origin: Runtime,
        default_enabled: true,
    }
}
