//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Hints at blocks whose effect differs from how they read: axis words taken by G10/G28/G30/G52/G92 while a motion mode is modal (RS274/NGC), G05/G08 switching 3D-DLACC to the state it already has (ServoWorks), Cartesian axis words of G04/G10/G52/G92/G53/G22/G68/G51 in polar mode, an omitted polar radius, and M03/M04 after rigid tapping cleared S (FANUC).
    ///
    /// ## Why is this bad?
    /// The program does not do what its author probably meant: a modal motion that does not run, a spindle started at S0.
    ///
    /// ## Example
    /// ```gcode
    /// G1 X1 F100
    /// G92 X0
    /// G92.1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G1 X1 F100
    /// G80
    /// G92 X0
    /// G92.1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Info (FANUC omitted polar radius: warning).
    ///
    /// Implements: NGC107, SW059, FAN060, FAN062, FAN107
    pub static NO_EFFECT = {
        code: "F012",
        name: "no-effect",
        summary: "A move or word that does nothing, or not what it seems",
        implements: &["NGC107", "SW059", "FAN060", "FAN062", "FAN107"],
        origin: Runtime,
        default_enabled: true,
    }
}
