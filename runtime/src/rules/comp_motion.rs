//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags an arc as the first move after G40 (RS274/NGC), and in ServoWorks an arc as the first or last move of tool radius compensation and any G code other than G00–G03, G04 and G40 while it is on. Also flags G41/G42 in a plane LinuxCNC cannot compensate in (G19; `emc2`: anything but G17). Hints (info) at rotary-axis motion under RS274/NGC compensation, and warns at ServoWorks G41/G42 with no D/H and no radius for the tool.
    ///
    /// ## Why is this bad?
    /// The control needs a straight move to build up or remove the offset; LinuxCNC stops, ServoWorks alarms.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.2
    /// G1 X1 F100
    /// G40
    /// G2 X2 Y0 R0.5
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.2
    /// G1 X1 F100
    /// G40
    /// G1 X2
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error.
    ///
    /// Implements: NGC217, SW082, SW083, NGC412, NGC427, SW084
    pub static COMP_MOTION = {
        code: "T004",
        name: "comp-motion",
        summary: "Cutter compensation started, ended or used where the control refuses",
        implements: &["NGC217", "SW082", "SW083", "NGC412", "NGC427", "SW084"],
        origin: Runtime,
        default_enabled: true,
    }
}
