//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/decode.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a FANUC/ServoWorks address word whose value is a vacant (never assigned) macro variable, for example `X#24` in a macro called without X.
    ///
    /// ## Why is this bad?
    /// Custom Macro B drops a word whose value is vacant, so the block runs without it: an axis does not move, or a code is not given, without any alarm.
    ///
    /// ## Example
    /// ```gcode
    /// #1 = 5
    /// G01 X#1 Y#2 F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// #1 = 5
    /// #2 = 0
    /// G01 X#1 Y#2 F100
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC, ServoWorks. Warning.
    ///
    /// Implements: FAN141
    pub static VACANT_WORD = {
        code: "X005",
        name: "vacant-word",
        summary: "Address word whose value is a vacant variable",
        implements: &["FAN141"],
        origin: Runtime,
        default_enabled: true,
    }
}
