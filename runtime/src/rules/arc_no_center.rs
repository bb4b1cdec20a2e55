//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a G2/G3 block with neither R nor I/J/K (or, in ServoWorks, with both).
    ///
    /// ## Why is this bad?
    /// The control cannot locate the centre and stops (`R, I, J and K words all missing for arc`).
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1
    /// G2 X10 Y0 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1
    /// G2 X10 Y0 R10 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error.
    ///
    /// After this error (RS274/NGC; R with I/J/K in ServoWorks) the dry run continues as if the arc had been skipped with the tool at its programmed end point (no motion, no time). FANUC and ServoWorks without R or I/J/K: the dry run makes a straight feed move to the end point.
    ///
    /// Reported by W003, not this rule, when both see an arc without R or I/J/K on the same text (one diagnostic per fault).
    ///
    /// Reported by W002, not this rule, when both see an arc with both R and I/J/K on the same text (one diagnostic per fault).
    ///
    /// Implements: SW031, SW032, NGC203, NGC204, NGC209
    pub static ARC_NO_CENTER = {
        code: "A005",
        name: "arc-missing-center",
        summary: "Arc without R or centre words, or with both",
        implements: &["SW031", "SW032", "NGC203", "NGC204", "NGC209"],
        origin: Runtime,
        default_enabled: true,
    }
}
