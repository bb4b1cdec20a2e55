//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a main program that reaches the end of the file without M2/M30.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops with `File ended with no percent sign or program end`; the other controls skip the end-of-program resets.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC error, others warning.
    ///
    /// Reported by P005, not this rule, when both see a program without an end on the same text (one diagnostic per fault).
    ///
    /// Implements: SW019, NGC024, FAN012
    pub static MISSING_END = {
        code: "F006",
        name: "missing-program-end",
        summary: "Program without M2/M30 (or closing %)",
        implements: &["SW019", "NGC024", "FAN012"],
        origin: Runtime,
        default_enabled: true,
    }
}
