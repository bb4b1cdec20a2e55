//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).
//! Running the cycle (`interp/exec/g7x.rs`) reports the profile's own faults.

use analyzer::declare_rule;
use analyzer::Diagnostic;

use super::check::Cx;

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

/// RS274/NGC: lathe roughing/finishing cycles, checked in LinuxCNC's order and words.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    // Lathe roughing/finishing cycles, checked in LinuxCNC's order and words.
    if let Some(&(g, s)) = w
        .g()
        .iter()
        .find(|(g, _)| matches!(g, 700 | 710 | 711 | 712 | 720 | 721 | 722))
    {
        let name = format!("G{}.{}", g / 10, g % 10);
        if !w.has(b'Q') {
            return Err(cx.out.err(&LATHE_CYCLE, s, "G7x.x  requires a Q word"));
        }
        if g != 700 && st.modal.comp != 400 {
            return Err(cx.out.err(
                &LATHE_CYCLE,
                s,
                format!("{name} cannot be used with cutter compensation enabled"),
            ));
        }
        if st.modal.plane != 180 && !w.has_g(180) {
            return Err(cx.out.err(
                &LATHE_CYCLE,
                s,
                format!("{name} can only be used in XZ plane (G18)"),
            ));
        }
    }
    Ok(())
}
