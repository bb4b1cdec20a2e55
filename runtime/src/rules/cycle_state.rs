//! Flow-sensitive rule metadata. The words of G33/G33.1/G76 are checked at the start
//! of `cycle_hygiene::check` (`rules/cycle_hygiene.rs`); the other cases are part of
//! running the cycle or move, in `interp/exec/cycles.rs`, `motion.rs` and `offsets.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a canned cycle with cutter compensation on, L0 repeats, or R below Z; a tapping cycle with the spindle turning the wrong way; and G76 with compensation on, rotary words, bad depths (I = 0, J ≤ 0, K ≤ J) or a taper E longer than half the thread (a warning in LinuxCNC 2.9, which runs it; the `emc2` profile also refuses X/Y words and planes other than G18).
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses each case.
    ///
    /// ## Example
    /// ```gcode
    /// G0 Z5
    /// G81 X1 Z2 R1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 Z5
    /// G81 X1 Z-2 R1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error.
    ///
    /// Reported by W003, not this rule, when both see a canned cycle without a word it needs (G76 without P, …) on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC303, NGC304, NGC311, NGC313, NGC315, FAN024, NGC330, NGC331, NGC335, NGC336, NGC337
    pub static CYCLE_STATE = {
        code: "C003",
        name: "cycle-state",
        summary: "Canned cycle in an impossible state",
        implements: &["NGC303", "NGC304", "NGC311", "NGC313", "NGC315", "FAN024", "NGC330", "NGC331", "NGC335", "NGC336", "NGC337"],
        origin: Runtime,
        default_enabled: true,
    }
}
