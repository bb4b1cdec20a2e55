//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Dialect, Severity};

use super::check::Cx;
use super::cycle_state::CYCLE_STATE;
use crate::interp::is_cycle;

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

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// The cycle (tenths) whose block last stored Q (FANUC/ServoWorks).
    pub(crate) q_from: Option<u32>,
}

/// Canned-cycle modal hygiene: cancelling by group-01 codes, plane changes,
/// blocks that make no hole, repeats on one spot, retract levels.
/// Also reports C003 (cycle-state) for the words of G33/G33.1/G76, first.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    let d = cx.dialect;
    let ngc = d == Dialect::Rs274ngc;
    // rs274 checks the words of spindle-synchronised motions with the rest of the block,
    // before anything in it runs (and before the spindle and plane checks of the move).
    if let Some((m @ (330 | 331 | 760), span)) = cx.motion.filter(|_| ngc) {
        let missing = if m == 760 {
            if !w.has(b'P') {
                Some("P word missing with G76")
            } else if !(w.has(b'I') && w.has(b'J') && w.has(b'K')) {
                Some("I J or K words missing with G76")
            } else {
                None
            }
        } else if !w.has(b'K') {
            Some("K word missing with g33/g33.1")
        } else if w.has(b'F') {
            Some("F word used with a g33/g33.1")
        } else {
            None
        };
        if let Some(msg) = missing {
            return Err(cx.out.err(&CYCLE_STATE, span, msg));
        }
    }
    let modal = st.modal.modal_cycle() && !w.has_g(800);
    if modal && !ngc {
        if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 0 | 10 | 20 | 30)) {
            let (sev, msg) = if d == Dialect::Fanuc {
                (
                    Severity::Info,
                    format!(
                        "G{:02} while canned cycle G{} is modal cancels the cycle, as G80 would",
                        g / 10,
                        st.modal.motion / 10
                    ),
                )
            } else {
                (Severity::Warning, format!("G{:02} while canned cycle G{} is modal: the manual does not say what happens (assumed to cancel the cycle); give G80 first", g / 10, st.modal.motion / 10))
            };
            cx.out.diag(&CYCLE_HYGIENE, sev, s, msg);
        }
        if let Some(&(p, s)) = w.g().iter().find(|g| matches!(g.0, 170 | 180 | 190)) {
            if p != st.modal.plane {
                let sev = if d == Dialect::Fanuc {
                    Severity::Warning
                } else {
                    Severity::Error
                };
                cx.out.diag(&CYCLE_HYGIENE, sev, s, "the plane (drilling axis) changes while a canned cycle is modal: cancel the cycle with G80 first");
            }
        }
    }
    if w.has_g(800) {
        mem.q_from = None;
    }
    let explicit = w.g().iter().find(|g| is_cycle(g.0)).copied();
    if modal && !ngc && explicit.is_none() {
        let fanuc = d == Dialect::Fanuc;
        let kept: &[u8] = if fanuc { b"QP" } else { b"QR" };
        if !w.any_axis() {
            if let Some(c) = kept.iter().copied().find(|c| w.has(*c)) {
                cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, w.sp(c), format!("{} in a canned-cycle block that makes no hole is not stored as cycle data: give it with the hole position", c as char));
            }
        }
        if fanuc {
            let inc = st.modal.incremental;
            let changes = (w.has_g(900) && inc) || (w.has_g(910) && !inc);
            let zl = [b'X', b'Y', b'Z'][cx.normal_axis()];
            // Absolute R, Z = r, z; incremental R = I + r, Z = R + z: with the
            // initial level I and r both zero the two readings agree.
            let c = &st.cycle;
            let initial = c.initial.unwrap_or(st.pos[cx.normal_axis()]);
            let same_either_way = initial.abs() < 1e-9 && c.r.is_none_or(|r| r.abs() < 1e-9);
            if changes && !(w.has(b'R') && w.has(zl)) && !same_either_way {
                let s = w.g_span(if w.has_g(900) { 900 } else { 910 });
                cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, s, "G90/G91 changes in canned-cycle mode without R and Z on the line: the stored R and Z are now read in the other mode; give R and Z again");
            }
            if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 430 | 440 | 490)) {
                cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, s, format!("G{} in canned-cycle mode: the new length offset takes effect at the positioning to point R, not at once", g / 10));
            }
            if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 450 | 460 | 470 | 480)) {
                cx.out.diag(
                    &CYCLE_HYGIENE,
                    Severity::Warning,
                    s,
                    format!(
                        "G{} tool position offset is ignored in canned-cycle mode",
                        g / 10
                    ),
                );
            }
        }
    }
    if !ngc && (modal || explicit.is_some()) {
        let mode = explicit.map(|e| e.0).unwrap_or(st.modal.motion);
        let class = |m: u32| match m {
            730 | 830 => Some("peck depth"),
            760 | 870 => Some("shift amount"),
            _ => None,
        };
        if w.has(b'Q') {
            mem.q_from = Some(mode);
        } else if let (Some(from), Some(now)) = (mem.q_from, class(mode)) {
            if let Some(before) = class(from) {
                if before != now && (w.any_axis() || explicit.is_some()) {
                    let s = explicit.map(|e| e.1).unwrap_or_default();
                    cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, s, format!("G{} reuses Q stored by G{}: the {before} becomes the {now}; give Q on this block", mode / 10, from / 10));
                    mem.q_from = Some(mode);
                }
            }
        }
    }
    let Some((mode, span)) = explicit else {
        return Ok(());
    };
    if d == Dialect::Servoworks && st.modal.comp != 400 && !w.has_g(400) {
        cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, span, "tool radius compensation is ignored inside canned cycles: the holes are drilled at the programmed points");
    }
    let n = cx.normal_axis();
    let zl = [b'X', b'Y', b'Z'][n];
    if !ngc && !w.any_axis() && !w.has(b'R') {
        cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, span, "a canned-cycle block without X/Y/Z/R or other axis words makes no hole: it only stores the cycle data");
    }
    let absolute = if w.has_g(910) {
        false
    } else {
        w.has_g(900) || !st.modal.incremental
    };
    // LinuxCNC's G76 is a threading cycle whose L word selects the tapers.
    let repeats = if ngc && mode == 760 {
        None
    } else if ngc {
        w.get(b'L').map(|l| l.round() as i64)
    } else if d == Dialect::Fanuc {
        w.raw_k.map(|k| k.round() as i64)
    } else {
        None
    };
    if let Some(k) = repeats {
        if k >= 2 && absolute {
            let which = if ngc { "L" } else { "K" };
            cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, w.sp(if ngc { b'L' } else { b'K' }), format!("{which}{k} repeats the cycle in absolute mode (G90): every repeat drills the same hole; use G91 to step between holes"));
        }
    }
    let g98 = if w.has_g(990) {
        false
    } else {
        w.has_g(980) || st.modal.retract_old_z
    };
    if mode == 870 && !g98 && !ngc {
        let (sev, msg) = if d == Dialect::Fanuc {
            (
                Severity::Warning,
                "G87 with G99: the back-boring cycle returns to the initial level, not to point R",
            )
        } else {
            (
                Severity::Error,
                "G87 works only with G98: G99 is an error; use G98",
            )
        };
        cx.out.diag(&CYCLE_HYGIENE, sev, span, msg);
    }
    if !absolute {
        return Ok(());
    }
    let init = if st.modal.modal_cycle() {
        st.cycle.initial.unwrap_or(st.pos[n])
    } else {
        st.pos[n]
    };
    let r = w
        .get(b'R')
        .map(|v| cx.lin(v))
        .or(if ngc { st.cycle.r } else { st.cycle.r_abs });
    let z = w
        .get(zl)
        .map(|v| cx.lin(v))
        .or(if ngc { st.cycle.z } else { st.cycle.z_abs });
    let eps = 1e-9;
    if ngc {
        if let Some(r) = r {
            if g98 && init < r - eps {
                cx.out.diag(&CYCLE_HYGIENE, Severity::Info, span, format!("G98 has no effect here: the start height {} is below R {}, so the cycle retracts to R", fmt_len(init / cx.unit()), fmt_len(r / cx.unit())));
            }
        }
        return Ok(());
    }
    let (Some(r), Some(z)) = (r, z) else {
        return Ok(());
    };
    let u = if st.modal.inch { 25.4 } else { 1.0 };
    if mode == 870 {
        if r > z + eps {
            cx.out.diag(&CYCLE_HYGIENE, Severity::Warning, span, format!("in G87 point R ({}) must lie beyond point Z ({}): the back-boring cycle starts below the hole", fmt_len(r / u), fmt_len(z / u)));
        }
    } else if r > init + eps {
        // Advice, not a fault: the cycle rapids up to R and drills from there,
        // and real programs run that way (FAN081; the tool moves away from the work).
        cx.out.diag(&CYCLE_HYGIENE, Severity::Info, span, format!("point R ({}) is above the initial level ({}): the tool retracts upward to R before drilling", fmt_len(r / u), fmt_len(init / u)));
    } else if z > r + eps {
        cx.out.diag(
            &CYCLE_HYGIENE,
            Severity::Warning,
            span,
            format!(
                "point Z ({}) is above point R ({}): R must lie between the initial level and Z",
                fmt_len(z / u),
                fmt_len(r / u)
            ),
        );
    }
    Ok(())
}

/// A length for a message: up to four decimals, no trailing zeros.
fn fmt_len(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}
