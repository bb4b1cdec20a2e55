//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/motion.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Reports an R-format arc that ServoWorks runs as a half circle about the chord's midpoint because |R| is short of half the chord by no more than the circle error allowance.
    ///
    /// ## Why is this bad?
    /// The path differs from the programmed radius: the control uses radius = half chord, so the part comes out slightly different from what the program says.
    ///
    /// ## Example
    /// ```gcode
    /// G91 G0 X0 Y0
    /// G2 X100 R49 F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G91 G0 X0 Y0
    /// G2 X100 R50 F100
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Warning. Example: with `circle_error_allowance = 1.5`, `G2 X100 R49` runs with radius 50 about (50, 0).
    ///
    /// Implements: SW037
    pub static ARC_CORRECTED_R = {
        code: "A003",
        name: "arc-corrected-half-circle",
        summary: "R-format arc corrected to a half circle within the circle error allowance",
        implements: &["SW037"],
        origin: Runtime,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Reports an I/J/K arc whose start and end radii differ by no more than the circle error allowance: ServoWorks runs it with radius (r1 + r2)/2 about a centre on the chord's perpendicular bisector (the one nearest the programmed centre).
    ///
    /// ## Why is this bad?
    /// The centre moves: `G2 X100 Y0 J-100` from the origin runs with radius 120.7 about (50, −109.87) instead of radius 100 about (0, −100).
    ///
    /// ## Example
    /// ```gcode
    /// G91 G0 X0 Y0
    /// G2 X100 I49 F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G91 G0 X0 Y0
    /// G2 X100 I50 F100
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Warning.
    ///
    /// Implements: SW039
    pub static ARC_CORRECTED_IJK = {
        code: "A004",
        name: "arc-corrected-average-radius",
        summary: "Centre-format arc corrected to the average radius within the circle error allowance",
        implements: &["SW039"],
        origin: Runtime,
        default_enabled: true,
    }
}
