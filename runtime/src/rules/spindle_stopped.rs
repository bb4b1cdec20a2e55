//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G33/G76 with the spindle not turning, a feed-per-revolution (G95) move with spindle speed 0, and (RS274/NGC) M3/M4 with S0.
    ///
    /// ## Why is this bad?
    /// Motion synchronised to the spindle cannot proceed with the spindle stopped: LinuxCNC stops on G33/G76 and a G95 move at S0 never finishes; ServoWorks computes a zero feed.
    ///
    /// ## Example
    /// ```gcode
    /// G95 F0.1
    /// G1 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S1000 M3
    /// G95 F0.1
    /// G1 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error in RS274/NGC (warning for M3/M4 with S0); warning in ServoWorks.
    ///
    /// Implements: NGC220, NGC338, NGC506, NGC808, SW049
    pub static SPINDLE_STOPPED = {
        code: "F010",
        name: "spindle-stopped",
        summary: "Spindle-synchronised motion without spindle speed",
        implements: &["NGC220", "NGC338", "NGC506", "NGC808", "SW049"],
        origin: Runtime,
        default_enabled: true,
    }
}
