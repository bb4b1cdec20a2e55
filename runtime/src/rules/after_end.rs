//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/decode.rs`, `interp/exec/flow.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags blocks after the program end that are never executed.
    ///
    /// ## Why is this bad?
    /// They look like part of the program but the control never reads them.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1
    /// M30
    /// G0 X2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1
    /// G0 X2
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC and ServoWorks (files may hold subprograms after M30, which start with O and are not flagged). Warning.
    ///
    /// Reported by P006, not this rule, when both see code after M2/M30 on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC026, FAN013
    pub static AFTER_END = {
        code: "F005",
        name: "code-after-program-end",
        summary: "Code after M2/M30 that never runs",
        implements: &["NGC026", "FAN013"],
        origin: Runtime,
        default_enabled: true,
    }
}
