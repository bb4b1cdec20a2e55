//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).
//! `no_effect::check` also reports this code (SW112 G68 centre words).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Dialect, Severity, Variant};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags G53 with a motion other than G0/G1 or in G91 (RS274/NGC), and in ServoWorks G29 with no earlier G28/G30, G20/G21 after motion, G52 in G91, cutter compensation with scaling or mirror, scaling and mirror together, and the order G51 → G68 → G41 / G69 before G50. Also G10 without a valid L (LinuxCNC 2.9: L0, L1, L2, L10, L11, L20; `emc2`: L2) and G10 L0 while a tool is loaded. Warns at a ServoWorks G68 centre word on the axis normal to the plane.
    ///
    /// ## Why is this bad?
    /// The control refuses the block, ignores it, or transforms the path in an order the manual does not support.
    ///
    /// ## Example
    /// ```gcode
    /// G91
    /// G53 G0 X0
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G90
    /// G53 G0 X0
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error (ServoWorks G29, G52 and ordering: warning; units after motion: info).
    ///
    /// Implements: NGC404, NGC406, SW072, SW074, SW081, SW103, SW107, SW113, NGC400, NGC821, SW112
    pub static COORDINATE_MODE = {
        code: "K003",
        name: "coordinate-mode",
        summary: "Coordinate, unit or transformation command in a refused or ignored state",
        implements: &["NGC404", "NGC406", "SW072", "SW074", "SW081", "SW103", "SW107", "SW113", "NGC400", "NGC821", "SW112"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// G53, G29, G52 and unit changes, and (ServoWorks) the order of scaling,
/// mirror, rotation and cutter compensation.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    let d = cx.dialect;
    let m = &st.modal;
    if d == Dialect::Rs274ngc && w.has_g(530) {
        let s = w.g_span(530);
        if let Some((g, _)) = cx.motion {
            if !matches!(g, 0 | 10) {
                return Err(cx.out.err(
                    &COORDINATE_MODE,
                    s,
                    "G53 works only with G0 or G1: LinuxCNC stops",
                ));
            }
        }
        if (m.incremental && !w.has_g(900)) || w.has_g(910) {
            return Err(cx.out.err(
                &COORDINATE_MODE,
                s,
                "G53 cannot be used in incremental mode (G91): give G90 on the line",
            ));
        }
    }
    if d == Dialect::Rs274ngc && w.has_g(100) {
        let s = w.g_span(100);
        let l = w.get(b'L').map(|l| l.round() as i64);
        let valid: &[i64] = if cx.variant == Variant::Emc2 {
            &[2]
        } else {
            &[0, 1, 2, 10, 11, 20]
        };
        if !l.is_some_and(|l| valid.contains(&l)) {
            let list = valid
                .iter()
                .map(|v| format!("L{v}"))
                .collect::<Vec<_>>()
                .join(", ");
            return Err(cx.out.err(
                &COORDINATE_MODE,
                s,
                format!("G10 needs one of {list}: LinuxCNC stops"),
            ));
        }
        if l == Some(0) && st.tool != 0 {
            return Err(cx.out.err(&COORDINATE_MODE, s, format!("G10 L0 (reload the tool table) is not allowed while tool {} is loaded: unload it with T0 M6 first", st.tool)));
        }
    }
    if d != Dialect::Servoworks {
        return Ok(());
    }
    if w.has_g(290) && st.g28_mid.is_none() {
        cx.out.diag(&COORDINATE_MODE, Severity::Warning, w.g_span(290), "G29 without an earlier G28/G30: there is no intermediate point, so the move goes straight to the target");
    }
    for (code, inch) in [(200u32, true), (210, false)] {
        if w.has_g(code) && inch != m.inch && cx.any_motion() {
            cx.out.diag(&COORDINATE_MODE, Severity::Info, w.g_span(code), "units change after motion has been programmed: positions, offsets and feeds given earlier are not converted; set G20/G21 once at the top");
        }
    }
    if w.has_g(520) && ((m.incremental && !w.has_g(900)) || w.has_g(910)) {
        cx.out.diag(
            &COORDINATE_MODE,
            Severity::Warning,
            w.g_span(520),
            "G52 in incremental mode (G91) is ignored: give it in G90",
        );
    }
    let comp_on = m.comp != 400 && !w.has_g(400);
    if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 410 | 420)) {
        if m.scaling || m.mirror || w.has_g(510) || w.has_g(511) {
            cx.out.diag(&COORDINATE_MODE, Severity::Error, s, format!("G{} cannot be combined with scaling (G51) or mirror image (G51.1): cancel them first", g / 10));
        }
    }
    if w.has_g(510) && (m.mirror || w.has_g(511)) {
        cx.out.diag(
            &COORDINATE_MODE,
            Severity::Error,
            w.g_span(510),
            "scaling (G51) cannot be active together with mirror image (G51.1)",
        );
    }
    if w.has_g(511) && (m.scaling || w.has_g(510)) {
        cx.out.diag(
            &COORDINATE_MODE,
            Severity::Error,
            w.g_span(511),
            "mirror image (G51.1) cannot be active together with scaling (G51)",
        );
    }
    if w.has_g(510) && (m.rotation || comp_on) {
        cx.out.diag(
            &COORDINATE_MODE,
            Severity::Warning,
            w.g_span(510),
            "G51 after G68 or G41/G42: the order must be G51, then G68, then G41/G42",
        );
    }
    if w.has_g(680) && comp_on {
        cx.out.diag(
            &COORDINATE_MODE,
            Severity::Warning,
            w.g_span(680),
            "G68 after G41/G42: the order must be G51, then G68, then G41/G42",
        );
    }
    if w.has_g(500) && m.rotation && !w.has_g(690) {
        cx.out.diag(
            &COORDINATE_MODE,
            Severity::Warning,
            w.g_span(500),
            "G50 while rotation (G68) is on: cancel rotation with G69 before scaling",
        );
    }
    Ok(())
}
