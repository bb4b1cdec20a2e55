//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags, in inverse-time mode (G93), a G1/G2/G3 move without its own F word (error), an F word on a line without a feed move (ignored, info), and a canned cycle (error).
    ///
    /// ## Why is this bad?
    /// Under G93 the F word is the reciprocal of the move's time and applies to that move only; LinuxCNC refuses a feed move without F and refuses canned cycles in G93.
    ///
    /// ## Example
    /// ```gcode
    /// G93
    /// G1 X1 F10
    /// G1 X2
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G93
    /// G1 X1 F10
    /// G1 X2 F10
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error (info for an ignored F).
    ///
    /// Implements: NGC201, NGC202, NGC310
    pub static INVERSE_TIME = {
        code: "F009",
        name: "inverse-time-feed",
        summary: "Inverse-time feed (G93) misuse",
        implements: &["NGC201", "NGC202", "NGC310"],
        origin: Runtime,
        default_enabled: true,
    }
}
