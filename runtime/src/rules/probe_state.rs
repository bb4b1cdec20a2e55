//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).
//! The probe move itself (`interp/exec/motion.rs`) reports the rest.

use analyzer::declare_rule;
use analyzer::{Diagnostic, Variant};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags a G38.2–G38.5 probe move whose target is the current position, with cutter compensation on, or in feed-per-revolution mode (G95; `emc2` also G93).
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops: a probe needs a real move at a feed per minute along an uncompensated path.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0 Z0
    /// G38.2 Z0 F10
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0 Z0
    /// G38.2 Z-1 F10
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error.
    ///
    /// Reported by W003, not this rule, when both see a probe or motion code without axis words on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC226, NGC227, NGC229
    pub static PROBE_STATE = {
        code: "F011",
        name: "probe-state",
        summary: "Probe move in a state LinuxCNC refuses",
        implements: &["NGC226", "NGC227", "NGC229"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// Probe moves (LinuxCNC G38.2–G38.5).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    if !cx.ngc() {
        return Ok(());
    }
    let Some((g, s)) = cx.motion else {
        return Ok(());
    };
    if !(382..=385).contains(&g) {
        return Ok(());
    }
    if st.modal.comp != 400 && !w.has_g(400) {
        return Err(cx.out.err(
            &PROBE_STATE,
            s,
            "probing (G38) is not allowed with cutter radius compensation on: give G40 first",
        ));
    }
    let mode = if w.has_g(950) {
        950
    } else if w.has_g(930) {
        930
    } else if w.has_g(940) {
        940
    } else {
        st.modal.feed_mode
    };
    let emc2 = cx.variant == Variant::Emc2;
    if mode == 950 || (emc2 && mode == 930) {
        return Err(cx.out.err(
            &PROBE_STATE,
            s,
            "probing (G38) needs feed per minute: give G94 first",
        ));
    }
    Ok(())
}
