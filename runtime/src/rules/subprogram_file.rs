//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags (in the called file) a ServoWorks subprogram that does not end with M99 (warning) and one whose first line is not `O<name>` with the name it was called by (info).
    ///
    /// ## Why is this bad?
    /// A subprogram returns only at M99; without it execution runs off the end of the file. The O line names the program; a different name is confusing.
    ///
    /// ## Example
    /// ```gcode
    /// M98 PNoReturn
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M98 PMoveXY
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Warning (no M99), info (O line).
    ///
    /// Implements: SW025, SW027
    pub static SUBPROGRAM_FILE = {
        code: "F017",
        name: "subprogram-file",
        summary: "Subprogram without M99 or without its O line",
        implements: &["SW025", "SW027"],
        origin: Runtime,
        default_enabled: true,
    }
}
