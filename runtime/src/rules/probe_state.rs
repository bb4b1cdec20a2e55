//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a G38.2–G38.5 probe move whose target is the current position, with cutter compensation on, or in feed-per-revolution mode (G95; `emc2` also G93).
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops: a probe needs a real move at a feed per minute along an uncompensated path.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0 Z0
    /// G38.2 Z0 F10
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0 Z0
    /// G38.2 Z-1 F10
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error.
    ///
    /// Reported by W003, not this rule, when both see a probe or motion code without axis words on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC226, NGC227, NGC229
    pub static PROBE_STATE = {
        code: "F011",
        name: "probe-state",
        summary: "Probe move in a state LinuxCNC refuses",
        implements: &["NGC226", "NGC227", "NGC229"],
        origin: Runtime,
        default_enabled: true,
    }
}
