//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags the lathe cycles G70, G71 and G72 (and their .1/.2 forms) outside the XZ plane (G18), without Q (the profile subroutine), and G71/G72 while cutter radius compensation is on.
    /// The interpreter runs the cycle as LinuxCNC does and reports the profile errors LinuxCNC
    /// stops on under this code too: a profile that is not monotonic, a corner (A/C) that cannot
    /// be finished, an arc without I/K, U/W in G91, an I that is not positive.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses them ("G71.0 can only be used in XZ plane (G18)") and stops.
    ///
    /// ## Example
    /// ```gcode
    /// G71 X1 Z1 D1 Q1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G18
    /// G71 X1 Z1 D1 Q1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC822
    pub static LATHE_CYCLE = {
        code: "C007",
        name: "lathe-cycle",
        summary: "G70–G72 outside G18, without Q, or under cutter compensation",
        implements: &["NGC822"],
        origin: Runtime,
        default_enabled: true,
    }
}
