//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/modal.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a G code outside the manual's whitelist while 3D dynamic look-ahead contour control is on (`G05 P10000` or `G08 P1`).
    ///
    /// ## Why is this bad?
    /// The control alarms; turn look-ahead off with `G08 P0` first. The whitelist: G00–G04, G17–G21, G28–G30, G50/G51, G50.1/G51.1, G52–G59, G54.1, G61, G64, G64.1, G65, G90–G92, G310, G311.
    ///
    /// ## Example
    /// ```gcode
    /// G05 P10000
    /// G81 X0 Y0 Z-1 R1 F100
    /// G08 P0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G05 P10000
    /// G01 X10 F100
    /// G08 P0
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
