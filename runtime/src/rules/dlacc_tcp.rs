//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/modal.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags turning 3D-DLACC on while tool centre point control (G43.2) is active, or G43.2 while DLACC is on.
    ///
    /// ## Why is this bad?
    /// The manual forbids the combination.
    ///
    /// ## Example
    /// ```gcode
    /// G43.2 H1
    /// G05 P10000
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G05 P10000
    /// G08 P0
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
