//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::syntax::{Item, ItemKind};
use analyzer::{Severity, Span};

use super::check::{Cx, Sink};
use super::polar_interp;
use super::polar_interp::POLAR_INTERP;
use crate::interp::State;

declare_rule! {
    /// ## What it does
    /// Checks FANUC involute interpolation: start or end point inside the base circle, more than 100 turns from the involute's start, end point off the involute through the start by more than parameter 5610 (`machine.involute_tolerance`, default 0.01 mm), G40/G41/G42 or another G code than G04, G10, G17–G19, G65–G67, G90, G91 in involute mode, involute in cylindrical interpolation (G07.1), optional chamfer/corner R in involute mode, a cutter-compensated path that enters the base circle, and more than four additional helical axes.
    ///
    /// ## Why is this bad?
    /// The control alarms (PS0242/PS0243) or refuses the block.
    ///
    /// ## Example
    /// ```gcode
    /// G00 X-1. Y0
    /// G02.2 X1. Y10. I1. J0 R1. F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G00 X-1. Y0
    /// G02.2 X1. Y9.425 I1. J0 R1. F100
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error (cutter-compensated path into the base circle: warning).
    ///
    /// Implements: FAN043, FAN044, FAN045, FAN046, FAN047, FAN048, FAN049, FAN050, FAN051
    pub static INVOLUTE = {
        code: "A012",
        name: "involute",
        summary: "Invalid involute interpolation (G02.2/G03.2)",
        implements: &["FAN043", "FAN044", "FAN045", "FAN046", "FAN047", "FAN048", "FAN049", "FAN050", "FAN051"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// FANUC: cylindrical interpolation (G07.1) is on.
    pub(crate) cylindrical: bool,
}

/// FANUC: involute interpolation (G02.2/G03.2): the codes allowed in its mode, its
/// geometry, and not in cylindrical interpolation. Answers the block's motion with
/// the involute codes, which the motion list of `Cx::motion` leaves out.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Option<(u32, Span)> {
    let (w, st) = (cx.w, cx.st);
    let involute_mode = matches!(st.modal.motion, 22 | 32);
    // Modes that switch for the following blocks.
    if w.has_g(71) {
        mem.cylindrical = true;
    }
    // Involute mode restrictions.
    // Involute codes are not in the checks' motion list: find them here.
    let invol: Option<(u32, Span)> = w
        .g()
        .iter()
        .find(|g| matches!(g.0, 22 | 32))
        .copied()
        .or_else(|| {
            (involute_mode
                && w.any_axis()
                && !w.g().iter().any(|g| matches!(g.0, 0 | 10 | 20 | 30)))
            .then(|| {
                (
                    st.modal.motion,
                    w.g().first().map(|g| g.1).unwrap_or(cx.bspan),
                )
            })
        });
    let invol_block = invol.is_some();
    let motion = invol.or(cx.motion);
    if involute_mode || invol_block {
        for &(g, s) in w.g() {
            if matches!(g, 400 | 410 | 420) && involute_mode {
                cx.out.diag(&INVOLUTE, Severity::Error, s, format!("G{} cannot be commanded in involute interpolation mode: give G41/G42 before G02.2/G03.2 and G40 after leaving it", g / 10));
            } else if involute_mode
                && !matches!(
                    g,
                    22 | 32
                        | 40
                        | 100
                        | 170
                        | 180
                        | 190
                        | 650
                        | 660
                        | 670
                        | 900
                        | 910
                        | 0
                        | 10
                        | 20
                        | 30
                )
            {
                cx.out.diag(&INVOLUTE, Severity::Error, s, format!("G{} is not allowed in involute interpolation mode (only G04, G10, G17–G19, G65–G67, G90, G91)", analyzer::dialect::CodeNum(g).display()));
            }
        }
    }
    if let Some((m, s)) = motion {
        if matches!(m, 22 | 32) {
            if mem.cylindrical {
                cx.out.diag(&INVOLUTE, Severity::Error, s, "involute interpolation is not allowed in cylindrical interpolation (G07.1) mode");
            }
            geometry(cx, m == 32, s);
        }
    }
    motion
}

/// FANUC involute interpolation (G02.2/G03.2) in the XY plane: the start
/// and end must lie outside the base circle, on one involute, within 100 turns.
fn geometry(cx: &mut Cx<'_, '_>, ccw: bool, s: Span) {
    let (w, st) = (cx.w, cx.st);
    let (a, b) = cx.plane_axes();
    let (ia, ib) = (b"IJK"[a.min(2)], b"IJK"[b.min(2)]);
    let (Some(i), Some(j), Some(r)) = (w.get(ia), w.get(ib), w.get(b'R')) else {
        return;
    };
    let u = if st.modal.inch { 25.4 } else { 1.0 };
    let (i, j, r) = (i * u, j * u, r.abs() * u);
    if r <= 0.0 {
        return;
    }
    let start = [st.pos[a], st.pos[b]];
    let t = cx.target();
    let end = [t[a], t[b]];
    let c = [start[0] + i, start[1] + j];
    let rho = |p: [f64; 2]| (p[0] - c[0]).hypot(p[1] - c[1]);
    let (rs, re) = (rho(start), rho(end));
    let tol = 1e-6;
    if rs < r - tol || re < r - tol {
        let which = if rs < r - tol { "start" } else { "end" };
        cx.out.diag(&INVOLUTE, Severity::Error, s, format!("the involute's {which} point lies inside the base circle (radius {r}): the control alarms (PS0242)"));
        return;
    }
    // Unwinding angle of each point and the angle where its involute leaves the circle.
    let phi = |rr: f64| ((rr / r).powi(2) - 1.0).max(0.0).sqrt();
    let (ps, pe) = (phi(rs), phi(re));
    if ps.max(pe) > 100.0 * std::f64::consts::TAU {
        cx.out.diag(&INVOLUTE, Severity::Error, s, "the involute's start or end point is more than 100 turns from where the involute leaves the base circle: the control alarms (PS0242)");
        return;
    }
    // G03.2 turns counter-clockwise: outward the involute unwinds with the turn, inward against it.
    let dir = if ccw { 1.0 } else { -1.0 };
    let sense = if re >= rs { dir } else { -dir };
    let ang = |p: [f64; 2]| (p[1] - c[1]).atan2(p[0] - c[0]);
    let base = |p: [f64; 2], f: f64| ang(p) - sense * (f - f.atan());
    let mut d = base(end, pe) - base(start, ps);
    d = (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
    let dev = 2.0 * re * (d.abs() / 2.0).sin();
    let limit = cx.input.machine.involute_tolerance.unwrap_or(0.01);
    if dev > limit {
        cx.out.diag(&INVOLUTE, Severity::Error, s, format!("the end point is {dev:.4} mm off the involute through the start point, more than the allowed {limit} mm (parameter 5610): the control alarms (PS0243)"));
    }
    // Cutter compensation on the concave side shortens the unwound string by the radius.
    let inner = matches!((st.modal.comp, ccw), (410, true) | (420, false));
    let rc = st.comp_radius;
    if inner && rc > 0.0 && rc > r * ps.min(pe) {
        cx.out.diag(&INVOLUTE, Severity::Warning, s, format!("with cutter compensation (radius {rc}) the tool-centre involute enters the base circle near the start: the control alarms (PS0242); start farther from the base circle or use a smaller tool"));
    }
    let extra = b"XYZABCUVW"
        .iter()
        .enumerate()
        .filter(|(k, c)| *k != a && *k != b && w.has(**c))
        .count();
    if extra > 4 {
        cx.out.diag(
            &INVOLUTE,
            Severity::Error,
            s,
            format!(
                "a helical involute moves at most four additional axes; this block moves {extra}"
            ),
        );
    }
}

/// FANUC: optional chamfer / corner R (`,C` `,R`) in involute or polar
/// interpolation mode, found through the items (the word reader drops them).
/// Also reports K004 (polar-interp) in polar mode.
#[inline(always)]
pub(crate) fn comma_words(
    items: &[Item],
    st: &State,
    polar_interp: &polar_interp::Mem,
    out: &mut Sink<'_>,
) {
    let involute = matches!(st.modal.motion, 22 | 32);
    for it in items {
        let ItemKind::Word(wd) = &it.kind else {
            continue;
        };
        if !wd.comma {
            continue;
        }
        let g_here: Vec<u32> = items
            .iter()
            .filter_map(|x| match &x.kind {
                ItemKind::Word(g) if g.letter == b'G' => g
                    .num()
                    .and_then(|n| analyzer::dialect::CodeNum::from_value(n.value))
                    .map(|c| c.0),
                _ => None,
            })
            .collect();
        let inv_here = involute && !g_here.iter().any(|g| matches!(g, 0 | 10 | 20 | 30))
            || g_here.iter().any(|g| matches!(g, 22 | 32));
        if inv_here {
            out.diag(
                &INVOLUTE,
                Severity::Error,
                it.span,
                "optional chamfering or corner R cannot be used in involute interpolation mode",
            );
        } else if polar_interp.on || st.modal.polar {
            out.diag(
                &POLAR_INTERP,
                Severity::Error,
                it.span,
                "optional chamfering or corner R cannot be used in polar coordinate mode",
            );
        }
    }
}
