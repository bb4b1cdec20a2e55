//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a G33 lead F outside 0.01–500 mm (metric; F1–F50000 without a decimal point) or 0.0001–9.9999 in (inch), and a spindle speed above (maximum cutting feed)/(lead) when `machine.max_cutting_feed` (mm/min) is set.
    ///
    /// ## Why is this bad?
    /// The control refuses the lead; above the speed limit the axis cannot follow the spindle and the thread is cut wrong.
    ///
    /// ## Example
    /// ```gcode
    /// S500 M03
    /// G33 Z-10. F60000
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S500 M03
    /// G33 Z-10. F1.5
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error (lead), warning (speed).
    ///
    /// Implements: FAN055, FAN056
    pub static THREAD_LEAD = {
        code: "F018",
        name: "thread-lead",
        summary: "G33 lead out of range or spindle too fast for the lead",
        implements: &["FAN055", "FAN056"],
        origin: Runtime,
        default_enabled: true,
    }
}
