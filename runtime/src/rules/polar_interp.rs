//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G00 in polar coordinate interpolation (G12.1) and optional chamfering or corner R (`,C` `,R`) in polar coordinate modes (G12.1, G16).
    ///
    /// ## Why is this bad?
    /// Polar coordinate interpolation allows only G01, G02, G03, G02.2 and G03.2 (the FANUC alarm list); chamfering and corner R are not allowed in polar coordinate mode.
    ///
    /// ## Example
    /// ```gcode
    /// G12.1
    /// G00 X10.
    /// G13.1
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G12.1
    /// G01 X10. F100
    /// G13.1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Warning (G00), error (chamfer/corner R).
    ///
    /// Implements: FAN158, FAN061
    pub static POLAR_INTERP = {
        code: "K004",
        name: "polar-interp",
        summary: "G00 or chamfer/corner R in polar modes",
        implements: &["FAN158", "FAN061"],
        origin: Runtime,
        default_enabled: true,
    }
}
