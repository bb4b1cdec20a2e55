//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags H (with G43/G44/G49) or D (with G41/G42) beyond the available offsets (`machine.offset_count`, default 400), and G10 with a missing or unknown L, tool-offset data without P, or G10 L2 with P outside 0–6.
    ///
    /// ## Why is this bad?
    /// The control alarms (PS0030, PS0031).
    ///
    /// ## Example
    /// ```gcode
    /// G43 H500 Z10.
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G43 H5 Z10.
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Reported by W007, not this rule, when both see a negative offset number on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN156, FAN161
    pub static OFFSET_NUMBER = {
        code: "T007",
        name: "offset-number",
        summary: "Offset number beyond the offsets, or illegal G10 data kind",
        implements: &["FAN156", "FAN161"],
        origin: Runtime,
        default_enabled: true,
    }
}
