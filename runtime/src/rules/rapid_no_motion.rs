//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a G0 with axis words whose target is where the tool already is (after the first motion).
    /// A block that runs more than once (in a subprogram or a loop) is flagged only if it never
    /// moves the tool on any pass. A subprogram's first motion is never flagged: it positions the
    /// tool for each call, wherever one caller already stands.
    ///
    /// ## Why is this bad?
    /// The block does nothing but costs a block; it often hides a wrong coordinate.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1 Y1
    /// G0 X1 Y1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1 Y1
    /// G0 X2 Y1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Info.
    ///
    /// Implements: NGC230
    pub static RAPID_NO_MOTION = {
        code: "F014",
        name: "rapid-no-motion",
        summary: "Rapid to the current position",
        implements: &["NGC230"],
        origin: Runtime,
        default_enabled: true,
    }
}
