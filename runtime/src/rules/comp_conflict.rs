//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags codes given while cutter radius compensation (G41/G42) is on that the control refuses: in RS274/NGC G41/G42 again, G10 L2/L20 on the active system, G28/G30, G53, G92 and G52, G54–G59.3, M6 and a plane change (the `emc2` profile also G10 L1/L10/L11 and a units change); in FANUC a plane change and G45–G48. In RS274/NGC also G43/G43.1/G43.2/G49, G61/G61.1/G64, G98/G99, G28.1/G30.1, G5.1/G5.2, M48–M53 and M62–M68.
    ///
    /// ## Why is this bad?
    /// The compensated path depends on these settings; LinuxCNC stops with an error (for M6 the 2007 EMC2 only warns that the old radius stays in use), FANUC alarms PS0037/PS0042.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.4
    /// G1 X1 F100
    /// G28
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.4
    /// G1 X1 F100
    /// G40 G1 X2
    /// G28
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, FANUC. Error (M6 in the `emc2` profile: warning).
    ///
    /// Implements: NGC402, NGC403, NGC405, NGC407, NGC408, NGC411, NGC420, NGC423, NGC425, FAN153, FAN155, NGC421
    pub static COMP_CONFLICT = {
        code: "T002",
        name: "comp-conflict",
        summary: "Code not allowed while cutter compensation is on",
        implements: &["NGC402", "NGC403", "NGC405", "NGC407", "NGC408", "NGC411", "NGC420", "NGC423", "NGC425", "FAN153", "FAN155", "NGC421"],
        origin: Runtime,
        default_enabled: true,
    }
}
