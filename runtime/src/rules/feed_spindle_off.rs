//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G1/G2/G3 and canned cycles while the spindle is stopped (no M3/M4 in force). Off by default: plotters, lasers and dry runs feed without a spindle.
    ///
    /// ## Why is this bad?
    /// A cutting move with the spindle off rubs or breaks the tool.
    ///
    /// ## Example
    /// ```gcode
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S1000 M3
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Warning; enable it with `select`.
    ///
    /// Implements: NGC232
    pub static FEED_SPINDLE_OFF = {
        code: "F015",
        name: "feed-spindle-off",
        summary: "Feed move with the spindle stopped",
        implements: &["NGC232"],
        origin: Runtime,
        default_enabled: false,
    }
}
