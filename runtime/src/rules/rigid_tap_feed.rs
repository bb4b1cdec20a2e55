//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags rigid tapping (M29 with G84/G74) with F0, and with a feed above `machine.max_cutting_feed` (mm/min) when it is set.
    ///
    /// ## Why is this bad?
    /// F0 gives a zero lead (PS0201); a feed above the upper limit alarms.
    ///
    /// ## Example
    /// ```gcode
    /// S500 M29
    /// G84 X0 Y0 Z-10. R2. F0
    /// G80
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S500 M29
    /// G84 X0 Y0 Z-10. R2. F500
    /// G80
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Reported by this rule, not F001, when both see rigid tapping with F0 on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN105, FAN106
    pub static RIGID_TAP_FEED = {
        code: "C009",
        name: "rigid-tap-feed",
        summary: "Rigid-tap feed zero or above the cutting-feed limit",
        implements: &["FAN105", "FAN106"],
        origin: Runtime,
        default_enabled: true,
    }
}
