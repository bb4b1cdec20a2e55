//! Flow-sensitive rule metadata. The check is the last part of `arc_words::check`
//! (`rules/arc_words.rs`), which reads the same plane and words.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags an R-format arc whose sweep is between 165° and 195° (and in RS274/NGC 345° or more).
    ///
    /// ## Why is this bad?
    /// Near a half or full circle the centre moves a long way for a tiny change of the end point, so rounding puts the arc somewhere unexpected; the manuals advise I/J/K there.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G2 X1.99 Y0 R1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G2 X1 Y-1 R1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, FANUC. Information for the sweep: the controls run such arcs, and a
    /// CAM post's exact half circle (`G3 X0 Y10 R5` from X0 Y0) is common and right;
    /// the advice matters where end points are rounded. Warning for a radius over a
    /// million times the chord, whose centre cannot be computed exactly at all.
    ///
    /// Implements: NGC213, FAN034
    pub static ARC_ILL_CONDITIONED = {
        code: "A009",
        name: "arc-ill-conditioned",
        summary: "Radius-format arc sweeping nearly 180° or 360°",
        implements: &["NGC213", "FAN034"],
        origin: Runtime,
        default_enabled: true,
    }
}
