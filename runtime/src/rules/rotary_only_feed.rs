//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a feed move under G311 (feed excludes rotary axes) that moves only rotary axes.
    ///
    /// ## Why is this bad?
    /// The feed is computed from the linear axes alone, which do not move: the feed has no basis and the speed is undefined.
    ///
    /// ## Example
    /// ```gcode
    /// G311
    /// G01 A90. F100.
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G310
    /// G01 A90. F100.
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Warning.
    ///
    /// Implements: SW050
    pub static ROTARY_ONLY_FEED = {
        code: "F016",
        name: "rotary-only-feed",
        summary: "G311 block moving only rotary axes",
        implements: &["SW050"],
        origin: Runtime,
        default_enabled: true,
    }
}
