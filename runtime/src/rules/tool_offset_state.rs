//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags M6 with no T since the start, a T replaced before any M6 used it, G43 with a negative H or an H other than the tool in the spindle, LinuxCNC's G43 without H before any tool change (it applies the tool in the spindle: tool 0, offset zero, when none is loaded), an M6 under G43 followed by Z motion without a new G43, and (ServoWorks) G43/G44 while TCP is on or a T change while length compensation is on without H.
    ///
    /// ## Why is this bad?
    /// The machine cuts with a length offset that belongs to another tool, or the control refuses the block.
    ///
    /// ## Example
    /// ```gcode
    /// G43 H-1
    /// G0 Z1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// T1 M6
    /// G43 H1
    /// G0 Z1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error for G43 H-1 and G43/G44 under TCP; warning for M6 with no tool (LinuxCNC 2.9 runs it); info for the hints.
    ///
    /// Implements: NGC414, NGC415, NGC504, NGC505, NGC510, SW096, SW146
    pub static TOOL_OFFSET_STATE = {
        code: "T003",
        name: "tool-offset-state",
        summary: "Tool selection or length offset in an inconsistent state",
        implements: &["NGC414", "NGC415", "NGC504", "NGC505", "NGC510", "SW096", "SW146"],
        origin: Runtime,
        default_enabled: true,
    }
}
