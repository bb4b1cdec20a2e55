//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags G05 while G43.2 (TCP) is on.
    ///
    /// ## Why is this bad?
    /// The manual forbids the combination.
    ///
    /// ## Example
    /// ```gcode
    /// G43.2 H1
    /// G05
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G05
    /// G08
    /// G43.2 H1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks S-140M. Error.
    ///
    /// Implements: SW057
    pub static DLACC_TCP = {
        code: "D002",
        name: "dlacc-with-tcp",
        summary: "3D-DLACC together with tool centre point control",
        implements: &["SW057"],
        origin: Runtime,
        default_enabled: true,
    }
}
