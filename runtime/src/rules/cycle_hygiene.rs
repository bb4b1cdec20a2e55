//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags canned-cycle usage that the manuals warn about: a group-01 code (G00–G03) or a plane change while a cycle is modal, a cycle block with no position (no hole), repeats (K/L ≥ 2) in absolute mode, G87 with G99, point R above the initial level or Z above R (G87: R below Z), and in RS274/NGC G98 with the start height below R. Also: Q/R (FANUC Q/P) on a cycle block that makes no hole (not stored), Q inherited between peck cycles (G73/G83) and shift cycles (G76/G87), cutter compensation on a ServoWorks cycle (ignored), and in FANUC G90/G91 changed without R and Z, G43/G44/G49 (applied at point R) and G45–G48 (ignored) in cycle mode. The plane-change check also covers FANUC rigid tapping (PS0206).
    ///
    /// ## Why is this bad?
    /// Each one gives a hole in the wrong place, no hole, or a retract that is not what the program seems to say.
    ///
    /// ## Example
    /// ```gcode
    /// G90 G0 Z10
    /// G81 X0 Y0 Z-5 R2 K3 F100
    /// G80
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G90 G0 Z10
    /// G81 X0 Y0 Z-5 R2 F100
    /// X10
    /// G80
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, FANUC; RS274/NGC for L > 1 in G90 and G98 below R. Warning (plane change in ServoWorks and G87 with G99 in ServoWorks: error; FANUC group-01 cancel, NGC G98: info).
    ///
    /// Implements: SW115, SW117, SW118, SW127, SW134, NGC316, NGC319, FAN023, FAN025, FAN070, FAN075, FAN079, FAN080, FAN081, SW124, SW125, SW131, FAN071, FAN082, FAN084, FAN085, FAN088, FAN102
    pub static CYCLE_HYGIENE = {
        code: "C006",
        name: "cycle-hygiene",
        summary: "Canned cycle used in a way that misbehaves",
        implements: &["SW115", "SW117", "SW118", "SW127", "SW134", "NGC316", "NGC319", "FAN023", "FAN025", "FAN070", "FAN075", "FAN079", "FAN080", "FAN081", "SW124", "SW125", "SW131", "FAN071", "FAN082", "FAN084", "FAN085", "FAN088", "FAN102"],
        origin: Runtime,
        default_enabled: true,
    }
}
