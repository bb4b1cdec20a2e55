//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Checks the LinuxCNC tool table the run reads: a line without T or P, or with a value that is not a number, is an error; a pocket used twice is a warning (the last line wins). The example program runs with a table holding `T1 P1` and `T2 P1`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC cannot load a malformed line, and a duplicated pocket silently hides a tool.
    ///
    /// ## Example
    /// ```gcode
    /// T1 M6
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// T1 M6
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC (the table the host reads). Error; warning for duplicate pockets.
    ///
    /// Implements: NGC430, NGC432
    pub static TOOL_TABLE = {
        code: "T008",
        name: "tool-table",
        summary: "Malformed tool table line or duplicate pocket",
        implements: &["NGC430", "NGC432"],
        origin: Runtime,
        default_enabled: true,
    }
}
