//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a line that moves only the drilling axis (Z in G17) without a motion code while a canned cycle is modal.
    ///
    /// ## Why is this bad?
    /// The line does not move the tool: it drills the hole again at the same position. The intent was usually to leave the cycle.
    ///
    /// ## Example
    /// ```gcode
    /// G81 X1 Y1 Z-1 R1 F100
    /// Z5
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G81 X1 Y1 Z-1 R1 F100
    /// G80
    /// G0 Z5
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Info.
    ///
    /// Implements: NGC318
    pub static CYCLE_STILL_ACTIVE = {
        code: "C008",
        name: "cycle-still-active",
        summary: "Canned cycle still active on a drilling-axis move",
        implements: &["NGC318"],
        origin: Runtime,
        default_enabled: true,
    }
}
