//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Diagnostic;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags G5.3 without an open G5.2 block, a control-point weight P ≤ 0, and a control point without both X and Y.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses these NURBS blocks and stops.
    ///
    /// ## Example
    /// ```gcode
    /// G5.3
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G1 X0 Y0 F100
    /// G5.2 X1 Y0 P1 L3
    /// X2 Y1 P1
    /// X3 Y0 P1
    /// G5.3
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC802
    pub static NURBS_BLOCK = {
        code: "A010",
        name: "nurbs-block",
        summary: "Malformed G5.2/G5.3 NURBS block",
        implements: &["NGC802"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// RS274/NGC: G5.3 without G5.2, and the words of NURBS control points.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let w = cx.w;
    let modal = cx.st.modal.motion;
    let mode = cx.motion_mode();
    // NURBS blocks.
    if w.has_g(53) && modal != 52 {
        return Err(cx.out.err(
            &NURBS_BLOCK,
            w.g_span(53),
            "Cannot use G5.3 without G5.2 first",
        ));
    }
    if mode == 52 && (w.has_g(52) || w.any_axis()) {
        if let Some(p) = w.get(b'P').filter(|p| *p <= 0.0) {
            return Err(cx.out.err(
                &NURBS_BLOCK,
                w.sp(b'P'),
                format!("NURBS weight P{p} must be positive"),
            ));
        }
        // The first control point may leave out X and Y (it is where the
        // tool is); any other needs both, and one without the other is
        // always an error.
        let span = cx.motion.map(|m| m.1).unwrap_or(cx.bspan);
        if w.has(b'X') != w.has(b'Y') {
            return Err(cx.out.err(
                &NURBS_BLOCK,
                span,
                "You must specify both X and Y coordinates for Control Points",
            ));
        }
        if !w.has(b'X') && w.get(b'P').is_some_and(|p| p > 0.0) && cx.nurbs_open {
            return Err(cx.out.err(
                &NURBS_BLOCK,
                span,
                "Can specify P without X and Y only for the first control point",
            ));
        }
    }
    Ok(())
}
