//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Dialect, Severity, Variant};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags codes given while cutter radius compensation (G41/G42) is on that the control refuses: in RS274/NGC G41/G42 again, G10 L2/L20 on the active system, G28/G30, G53, G92 and G52, G54–G59.3, M6 and a plane change (the `emc2` profile also G10 L1/L10/L11 and a units change); in FANUC a plane change and G45–G48. In RS274/NGC also G43/G43.1/G43.2/G49, G61/G61.1/G64, G98/G99, G28.1/G30.1, G5.1/G5.2, M48–M53 and M62–M68.
    ///
    /// ## Why is this bad?
    /// The compensated path depends on these settings; LinuxCNC stops with an error (for M6 the 2007 EMC2 only warns that the old radius stays in use), FANUC alarms PS0037/PS0042.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.4
    /// G1 X1 F100
    /// G28
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.4
    /// G1 X1 F100
    /// G40 G1 X2
    /// G28
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, FANUC. Error (M6 in the `emc2` profile: warning).
    ///
    /// Implements: NGC402, NGC403, NGC405, NGC407, NGC408, NGC411, NGC420, NGC423, NGC425, FAN153, FAN155, NGC421
    pub static COMP_CONFLICT = {
        code: "T002",
        name: "comp-conflict",
        summary: "Code not allowed while cutter compensation is on",
        implements: &["NGC402", "NGC403", "NGC405", "NGC407", "NGC408", "NGC411", "NGC420", "NGC423", "NGC425", "FAN153", "FAN155", "NGC421"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// Codes LinuxCNC (and FANUC, for planes and G45–G48) refuse while cutter
/// radius compensation is on.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    if st.modal.comp == 400 {
        return Ok(());
    }
    let plane = w
        .g()
        .iter()
        .find(|g| matches!(g.0, 170 | 180 | 190))
        .copied();
    if cx.dialect == Dialect::Fanuc {
        if let Some((p, s)) = plane {
            if p != st.modal.plane {
                cx.out.diag(&COMP_CONFLICT, Severity::Error, s, "the plane cannot be changed while cutter compensation (G41/G42) is on: the control alarms (PS0037); cancel with G40 first");
            }
        }
        if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 450 | 460 | 470 | 480)) {
            cx.out.diag(&COMP_CONFLICT, Severity::Error, s, format!("G{} tool position offset cannot be used while cutter compensation (G41/G42) is on: the control alarms (PS0042); cancel with G40 first", g / 10));
        }
        return Ok(());
    }
    if !cx.ngc() {
        return Ok(());
    }
    let emc2 = cx.variant == Variant::Emc2;
    let msg_tail =
        "while cutter radius compensation is on: LinuxCNC stops; cancel it with G40 first";
    // Plane and units are applied before G40 in LinuxCNC's order of execution.
    if let Some((p, s)) = plane {
        let bad = if emc2 { p != 170 } else { p != st.modal.plane };
        if bad {
            return Err(cx.out.err(
                &COMP_CONFLICT,
                s,
                format!("cannot change the plane to G{} {msg_tail}", p / 10),
            ));
        }
    }
    // LinuxCNC 2.9 accepts a units change under compensation; the 2007 EMC2 refused it.
    for (code, inch) in [(200u32, true), (210, false)] {
        if emc2 && w.has_g(code) && inch != st.modal.inch {
            return Err(cx.out.err(
                &COMP_CONFLICT,
                w.g_span(code),
                format!("cannot change units {msg_tail}"),
            ));
        }
    }
    if w.has_g(400) {
        return Ok(());
    }
    if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 410 | 420 | 411 | 421)) {
        return Err(cx.out.err(
            &COMP_CONFLICT,
            s,
            format!(
                "G{}{} turns cutter radius compensation on when it is already on: LinuxCNC stops; give G40 first",
                g / 10,
                if g % 10 == 1 { ".1" } else { "" }
            ),
        ));
    }
    let modes: [(u32, &str); 13] = [
        (430, "change the tool length offset (G43)"),
        (431, "change the tool length offset (G43.1)"),
        (432, "change the tool length offset (G43.2)"),
        (490, "change the tool length offset (G49)"),
        (610, "change the path control mode (G61)"),
        (611, "change the path control mode (G61.1)"),
        (640, "change the path control mode (G64)"),
        (980, "change the retract mode (G98)"),
        (990, "change the retract mode (G99)"),
        (281, "set the G28 reference point"),
        (301, "set the G30 reference point"),
        (51, "run a spline (G5.1)"),
        (52, "run a NURBS block (G5.2)"),
    ];
    if let Some((code, what)) = modes.iter().find(|(c, _)| w.has_g(*c)) {
        return Err(cx.out.err(
            &COMP_CONFLICT,
            w.g_span(*code),
            format!("cannot {what} {msg_tail}"),
        ));
    }
    if let Some(&(m, s)) =
        w.m.iter()
            .find(|m| (480..=530).contains(&m.0) || (620..=680).contains(&m.0))
    {
        return Err(cx.out.err(
            &COMP_CONFLICT,
            s,
            format!(
                "M{} (overrides or motion I/O) cannot be used {msg_tail}",
                m / 10
            ),
        ));
    }
    if w.has_g(100) {
        let l = w.get(b'L').map(|l| l.round() as i64).unwrap_or(-1);
        let p = w.get(b'P').map(|p| p.round() as usize).unwrap_or(0);
        let active = p == 0 || p == st.modal.origin;
        // LinuxCNC 2.9 refuses only a change of the active system; EMC2 also tool data.
        if (emc2 && matches!(l, 1 | 10 | 11)) || (matches!(l, 2 | 20) && active) {
            return Err(cx.out.err(
                &COMP_CONFLICT,
                w.g_span(100),
                format!("G10 L{l} changes an offset in use {msg_tail}"),
            ));
        }
    }
    for (code, what) in [
        (280u32, "G28 reference return"),
        (300, "G30 reference return"),
        (530, "G53 machine-coordinate move"),
        (920, "G92 offset"),
        (520, "G52 offset"),
    ] {
        if w.has_g(code) {
            return Err(cx.out.err(
                &COMP_CONFLICT,
                w.g_span(code),
                format!("cannot use {what} {msg_tail}"),
            ));
        }
    }
    if let Some(&(g, s)) = w.g().iter().find(|g| (540..=593).contains(&g.0)) {
        let name = if g % 10 == 0 {
            format!("G{}", g / 10)
        } else {
            format!("G{}.{}", g / 10, g % 10)
        };
        return Err(cx.out.err(
            &COMP_CONFLICT,
            s,
            format!("cannot change the coordinate system to {name} {msg_tail}"),
        ));
    }
    if w.has_m(60) {
        let s = w.m_span(60);
        if emc2 {
            cx.out.diag(&COMP_CONFLICT, Severity::Warning, s, "tool change while cutter radius compensation is on: the old tool's radius stays in use; give G40 before M6");
        } else {
            return Err(cx
                .out
                .err(&COMP_CONFLICT, s, format!("cannot change tools {msg_tail}")));
        }
    }
    Ok(())
}
