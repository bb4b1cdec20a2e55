//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G codes outside the manual's allowed list while 3D dynamic look-ahead (G05) is on.
    ///
    /// ## Why is this bad?
    /// The control alarms; turn look-ahead off with G08 first.
    ///
    /// ## Example
    /// ```gcode
    /// G05
    /// G81 X0 Y0 Z-1 R1 F100
    /// G08
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G05
    /// G01 X10 F100
    /// G08
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Error.
    ///
    /// Implements: SW056
    pub static DLACC_INCOMPATIBLE = {
        code: "D001",
        name: "dlacc-incompatible-code",
        summary: "G code not allowed while 3D-DLACC is on",
        implements: &["SW056"],
        origin: Runtime,
        default_enabled: true,
    }
}
