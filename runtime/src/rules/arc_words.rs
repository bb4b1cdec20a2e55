//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Dialect, Severity, Variant};

use super::arc_ill_conditioned::ARC_ILL_CONDITIONED;
use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags a centre offset along the axis normal to the plane (K under G17), a radius-format arc with no in-plane end point (RS274/NGC; `emc2` also centre format), G90.1 absolute centres with one offset missing, and in ServoWorks an arc whose axis words do not match the plane or that moves more than two helical axes.
    ///
    /// ## Why is this bad?
    /// The control cannot build the arc the words describe: LinuxCNC stops, ServoWorks alarms.
    ///
    /// ## Example
    /// ```gcode
    /// G17 G0 X0 Y0
    /// G2 X1 Y1 K1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G17 G0 X0 Y0
    /// G2 X1 Y1 J1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error.
    ///
    /// After this error the dry run continues as if the arc had been skipped with the tool at its programmed end point (no motion, no time).
    ///
    /// Implements: NGC205, NGC208, NGC210, NGC216, SW033, SW034, SW042
    pub static ARC_WORDS = {
        code: "A008",
        name: "arc-words",
        summary: "Arc words that do not fit the active plane",
        implements: &["NGC205", "NGC208", "NGC210", "NGC216", "SW033", "SW034", "SW042"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// Arc words against the active plane, and radius-format arcs whose centre
/// is ill-defined (sweep near 180° or 360°).
/// Also reports A009 (arc-ill-conditioned).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    let Some((g, span)) = cx.motion else {
        return Ok(());
    };
    if !matches!(g, 20 | 30) {
        return Ok(());
    }
    let d = cx.dialect;
    let ngc = d == Dialect::Rs274ngc;
    // A plane code on the arc's own line applies before the arc.
    let plane = w
        .g()
        .iter()
        .find(|g| matches!(g.0, 170 | 180 | 190))
        .map(|g| g.0)
        .unwrap_or(st.modal.plane);
    let (a, b, n) = match plane {
        180 => (2, 0, 1),
        190 => (1, 2, 0),
        _ => (0, 1, 2),
    };
    let axes = [b'X', b'Y', b'Z'];
    let ijk = [b'I', b'J', b'K'];
    let has_r = w.has(b'R');
    let has_c = w.has(ijk[a]) || w.has(ijk[b]);
    let plane = format!("G{}", plane / 10);
    if d != Dialect::Fanuc && w.has(ijk[n]) && !(ngc && g == 20 && w.has_g(330)) {
        let msg = format!(
            "{} is the centre offset along the axis normal to the {plane} plane: an arc in {plane} takes {} and {}",
            ijk[n] as char, ijk[a] as char, ijk[b] as char
        );
        if ngc {
            return Err(cx.out.err(&ARC_WORDS, w.sp(ijk[n]), msg));
        }
        cx.out.diag(&ARC_WORDS, Severity::Error, w.sp(ijk[n]), msg);
    }
    let in_plane_end = w.has(axes[a]) || w.has(axes[b]);
    if ngc && !in_plane_end {
        let emc2 = cx.variant == Variant::Emc2;
        if has_r {
            return Err(cx.out.err(&ARC_WORDS, span, format!("a radius-format arc needs an end point in the {plane} plane ({} or {}): without one there is no arc", axes[a] as char, axes[b] as char)));
        }
        if emc2 && has_c {
            return Err(cx.out.err(
                &ARC_WORDS,
                span,
                format!(
                    "a centre-format arc needs an end point in the {plane} plane ({} or {})",
                    axes[a] as char, axes[b] as char
                ),
            ));
        }
    }
    if ngc && !has_r && st.modal.ijk_abs && has_c && !(w.has(ijk[a]) && w.has(ijk[b])) {
        return Err(cx.out.err(
            &ARC_WORDS,
            span,
            format!(
                "with absolute arc centres (G90.1) both {} and {} are needed",
                ijk[a] as char, ijk[b] as char
            ),
        ));
    }
    if d == Dialect::Servoworks {
        if w.has(axes[n]) && (w.has(axes[a]) != w.has(axes[b])) {
            cx.out.diag(&ARC_WORDS, Severity::Error, span, format!("the arc's axis words do not match the {plane} plane: give both {} and {} (or neither) with a helical {}", axes[a] as char, axes[b] as char, axes[n] as char));
        }
        let extra = b"XYZABCUVW"
            .iter()
            .filter(|c| **c != axes[a] && **c != axes[b] && w.has(**c))
            .count();
        if extra > 2 {
            cx.out.diag(&ARC_WORDS, Severity::Error, span, format!("{extra} axes outside the {plane} plane move with this arc: at most two helical axes are allowed"));
        }
    }
    // Radius format: the sweep follows from the chord and |R|.
    if d == Dialect::Servoworks || !has_r {
        return Ok(());
    }
    let Some(r) = w.get(b'R').map(|v| cx.lin(v)) else {
        return Ok(());
    };
    let t = cx.target();
    let chord = (t[a] - st.pos[a]).hypot(t[b] - st.pos[b]);
    if r == 0.0 || chord == 0.0 || chord > 2.0 * r.abs() {
        return Ok(());
    }
    if r.abs() > 1e6 * chord {
        let sagitta = chord * chord / (8.0 * r.abs());
        let shape = if r > 0.0 {
            format!("it differs from a straight line by {sagitta:.1e} mm; program G1")
        } else {
            "as a negative radius it is an almost full circle of that size; check the sign and the radius".to_string()
        };
        cx.out.diag(&ARC_ILL_CONDITIONED, Severity::Warning, w.sp(b'R'), format!("radius {} is over a million times the chord ({chord:.4}): the centre lies too far away to be computed exactly, and {shape}", r.abs()));
        return Ok(());
    }
    let half = (chord / (2.0 * r.abs())).min(1.0).asin().to_degrees();
    let sweep = if r > 0.0 {
        2.0 * half
    } else {
        360.0 - 2.0 * half
    };
    let near_half = (165.0..=195.0).contains(&sweep);
    let near_full = ngc && sweep >= 345.0;
    if near_half || near_full {
        cx.out.diag(&ARC_ILL_CONDITIONED, Severity::Info, w.sp(b'R'), format!("this radius-format arc sweeps {sweep:.1}°: near {}° a tiny change of the end point moves the centre a lot; program the centre with {}/{}", if near_full { 360 } else { 180 }, ijk[a] as char, ijk[b] as char));
    }
    Ok(())
}
