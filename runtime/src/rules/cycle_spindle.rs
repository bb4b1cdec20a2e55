//! Flow-sensitive rule metadata. The check is the end of `spindle_stopped::check`
//! (`rules/spindle_stopped.rs`), which works out the same spindle state.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a drilling, boring or tapping cycle run while the spindle is stopped, a G84 with the spindle turning CCW (M04) and a G74 with it turning CW (M03). M03/M04 in the cycle block itself count.
    ///
    /// ## Why is this bad?
    /// The cycle would cut with a stopped spindle, or tap with the wrong hand and strip the thread.
    ///
    /// ## Example
    /// ```gcode
    /// M3 S500
    /// G90 G99 G74 X200 Y200 Z-100 R-20 P500 F200
    /// G80
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M4 S500
    /// G90 G99 G74 X200 Y200 Z-100 R-20 P500 F200
    /// G80
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, FANUC. Warning. (RS274/NGC refuses these cases: see C003.)
    ///
    /// Implements: SW119, SW120, FAN077, FAN078
    pub static CYCLE_SPINDLE = {
        code: "C005",
        name: "cycle-spindle",
        summary: "Canned cycle with the spindle stopped or reversed",
        implements: &["SW119", "SW120", "FAN077", "FAN078"],
        origin: Runtime,
        default_enabled: true,
    }
}
