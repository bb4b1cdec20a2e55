//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Dialect, Severity};

use super::check::Cx;
use super::{comp_motion::COMP_MOTION, coordinate_mode::COORDINATE_MODE};
use crate::interp::moves_to_axis_words;

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

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// FANUC: rigid tapping was cancelled and no S has been given since.
    pub(crate) rigid_s_cleared: bool,
}

/// Hints that never stop the run: moves that do nothing, axis words taken
/// by a non-modal code, polar-mode subtleties, redundant mode switches.
/// Also reports T004 (comp-motion: NGC427, SW084) and K003 (coordinate-mode: SW112).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) {
    let (w, st) = (cx.w, cx.st);
    let d = cx.dialect;
    let motion = cx.motion;
    // NGC107: axis words taken by a group-0 code while a motion mode is only modal.
    if d == Dialect::Rs274ngc && w.any_axis() {
        let explicit = w.g().iter().any(|g| moves_to_axis_words(g.0));
        if let Some(&(g, s)) = w
            .g()
            .iter()
            .find(|g| matches!(g.0, 100 | 280 | 300 | 520 | 920))
        {
            if !explicit && st.modal.motion != 800 {
                let name = analyzer::dialect::CodeNum(g).display();
                cx.out.diag(&NO_EFFECT, Severity::Info, s, format!("the axis words of this line belong to G{name}: the modal motion G{} does not run here", analyzer::dialect::CodeNum(st.modal.motion).display()));
            }
        }
    }
    // NGC427: rotary axis motion under cutter compensation.
    if d == Dialect::Rs274ngc && st.modal.comp != 400 && !w.has_g(400) && motion.is_some() {
        if let Some(c) = b"ABC".iter().copied().find(|c| w.has(*c)) {
            cx.out.diag(&COMP_MOTION, Severity::Info, w.sp(c), format!("{} moves while cutter radius compensation is on: the offset is computed in the plane only, so check the path", c as char));
        }
    }
    // SW084: G41/G42 with no D/H and no radius for the current tool.
    if d == Dialect::Servoworks {
        if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 410 | 420)) {
            if !w.has(b'D') && !w.has(b'H') && cx.tool_diameter() == 0.0 {
                cx.out.diag(&COMP_MOTION, Severity::Warning, s, format!("G{} without D or H and no radius for tool {}: the compensation offset is zero", g / 10, st.tool));
            }
        }
        // SW112: G68 centre words outside the plane.
        if w.has_g(680) {
            let n = [b'X', b'Y', b'Z'][cx.normal_axis()];
            if w.has(n) {
                cx.out.diag(&COORDINATE_MODE, Severity::Warning, w.sp(n), format!("{} is not in the G{} plane: the G68 rotation centre takes only the plane's two axes", n as char, st.modal.plane / 10));
            }
        }
        // SW059: G05 P10000 / G08 P1 while on, or P0 while off.
        for code in [50u32, 80] {
            if w.has_g(code) {
                if let Some(p) = w.get(b'P') {
                    let on = p != 0.0;
                    if on == st.modal.dlacc {
                        cx.out.diag(
                            &NO_EFFECT,
                            Severity::Info,
                            w.g_span(code),
                            format!(
                                "3D-DLACC is already {}: this G{:02} changes nothing",
                                if on { "on" } else { "off" },
                                code / 10
                            ),
                        );
                    }
                }
            }
        }
    }
    if d != Dialect::Fanuc {
        return;
    }
    // FAN060 / FAN062: polar coordinate mode (G16).
    if st.modal.polar && !w.has_g(150) {
        if let Some(&(g, s)) = w
            .g()
            .iter()
            .find(|g| matches!(g.0, 40 | 100 | 520 | 920 | 530 | 220 | 680 | 510))
        {
            if w.any_axis() {
                cx.out.diag(&NO_EFFECT, Severity::Info, s, format!("in polar mode (G16) the axis words of G{:02} are Cartesian, not radius and angle", g / 10));
            }
        }
        if let Some((g, s)) = motion {
            let (a, b) = cx.plane_axes();
            let axes = [b'X', b'Y', b'Z'];
            if matches!(g, 0 | 10 | 20 | 30) && w.has(axes[b]) && !w.has(axes[a]) {
                cx.out.diag(&NO_EFFECT, Severity::Warning, s, format!("polar radius ({}) omitted: the current distance from the workpiece origin is used as the radius", axes[a] as char));
            }
        }
    }
    // FAN107: S is cleared when rigid tapping is cancelled.
    if w.has(b'S') {
        mem.rigid_s_cleared = false;
    }
    if mem.rigid_s_cleared {
        if let Some(&(m, s)) = w.m.iter().find(|m| matches!(m.0, 30 | 40)) {
            mem.rigid_s_cleared = false;
            cx.out.diag(&NO_EFFECT, Severity::Info, s, format!("M{:02} after rigid tapping was cancelled: S was cleared to S0, so give S again", m / 10));
        }
    }
    if st.modal.rigid_tap && (w.has_g(800) || w.g().iter().any(|g| matches!(g.0, 0 | 10 | 20 | 30)))
    {
        mem.rigid_s_cleared = true;
    }
}
