//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags the 101st consecutive block without motion while tool radius compensation is on.
    ///
    /// ## Why is this bad?
    /// ServoWorks' compensation looks ahead 100 blocks; beyond them it cannot see the next move and the corner is offset wrongly.
    ///
    /// ## Example
    /// ```gcode
    /// G41 D1 G01 X10. F100.
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G04
    /// G01 X20.
    /// G40 G01 X30.
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G41 D1 G01 X10. F100.
    /// G04
    /// G01 X20.
    /// G40 G01 X30.
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Info.
    ///
    /// Implements: SW085
    pub static TRC_LOOKAHEAD = {
        code: "T006",
        name: "trc-lookahead",
        summary: "More than 100 blocks without motion in TRC mode",
        implements: &["SW085"],
        origin: Runtime,
        default_enabled: true,
    }
}
