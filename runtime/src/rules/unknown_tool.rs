//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/offsets.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags T and H numbers that the tool table (given with `--tool-table` or `[machine] tools`) does not contain.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses unknown tools at M6; other controls use a zero offset, silently.
    ///
    /// ## Example
    /// ```gcode
    /// T99 M6
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
    /// All, only when a tool table is given. RS274/NGC: error, the run stops there (rs274: "Requested tool N not found in the tool table"); ServoWorks and FANUC: warning.
    ///
    /// Implements: NGC413, NGC503
    pub static UNKNOWN_TOOL = {
        code: "T001",
        name: "unknown-tool",
        summary: "Tool number not in the tool table",
        implements: &["NGC413", "NGC503"],
        origin: Runtime,
        default_enabled: true,
    }
}
