//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags (RS274/NGC) a D, H, I, J, L, P, Q or R word, or a `$` spindle selector, that no code of the line (or the modal motion) uses, and a `$` beyond the configured spindles (`machine.spindles`, default 1).
    ///
    ///
    /// Also flags axis words on a line with no motion code while no motion mode is
    /// active: after G80, or before the program's first G0/G1 (LinuxCNC starts in
    /// G80). G10, G28, G30, G52, G92 and G43.1/G43.2 on the line use them. The same
    /// words with an explicit G80 on the line are W004's.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses the line ("P word with no G2 G3 G4 … to use it") and stops the program; the word is usually a typo or belongs to another line.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1 P2
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G4 P2
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops as in LinuxCNC.
    ///
    /// Reported by W002, not this rule, when both see a D peck clearance LinuxCNC 2.9 does not accept on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC108, NGC110, NGC814
    pub static WORD_UNUSED = {
        code: "X008",
        name: "word-unused",
        summary: "A word that no code of the line uses",
        implements: &["NGC108", "NGC110", "NGC814"],
        origin: Runtime,
        default_enabled: true,
    }
}
