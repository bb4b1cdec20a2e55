//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).
//! G37's calibration (`interp/exec/g37.rs`) reports its own faults.

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::{Cx, AXES};

declare_rule! {
    /// ## What it does
    /// Checks G43/G44/G49 and G37 against the machine's Tool Length Compensation Type (`machine.tlc_type`, default 0): type 0 (A) compensates and calibrates only Z, type 1 (B) only the axis perpendicular to the plane (G17 Z, G18 Y, G19 X), type 2 (C) any axis but needs G49 and H0 together to cancel and has no G37; G37 needs a preceding G43/G44 with a non-zero H; and a G37 whose measurement (`machine.g37_measured`, the dry run's stand-in for the sensor) falls outside the G37 Limit (`machine.g37_limit`).
    ///
    /// ## Why is this bad?
    /// ServoWorks raises an alarm or error for each of these.
    ///
    /// ## Example
    /// ```gcode
    /// G37 Z20.
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G43 H1
    /// G37 Z20.
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Error.
    ///
    /// Implements: SW077, SW078, SW079, SW092, SW093, SW094
    pub static TLC_TYPE = {
        code: "T005",
        name: "tlc-type",
        summary: "Length compensation or G37 not allowed for the TLC type",
        implements: &["SW077", "SW078", "SW079", "SW092", "SW093", "SW094"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// A G43/G44 with a non-zero H has been given and not cancelled.
    pub(crate) tlc_h: bool,
}

/// ServoWorks: the axis a G43/G44 length offset goes to, the G49 cancel and G37
/// calibration, by the machine's tool length compensation type.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) {
    let (w, st) = (cx.w, cx.st);
    let tlc_type = cx.input.machine.tlc_type.unwrap_or(0);
    // A plane code in the block applies before its G43/G37.
    let plane = w
        .g()
        .iter()
        .find(|g| matches!(g.0, 170 | 180 | 190))
        .map_or(st.modal.plane, |g| g.0);
    let perpendicular = match plane {
        180 => 1usize,
        190 => 0,
        _ => 2,
    };
    let axis_words: Vec<(usize, Span)> = AXES
        .iter()
        .enumerate()
        .filter(|(_, c)| w.has(**c))
        .map(|(i, c)| (i, w.sp(*c)))
        .chain(
            cx.items
                .bare_axes
                .iter()
                .filter_map(|(c, s)| AXES.iter().position(|a| a == c).map(|i| (i, *s))),
        )
        .collect();
    // G43/G44: which axis the length offset goes to, by TLC type.
    if let Some(&(g, _)) = w.g().iter().find(|(g, _)| matches!(g, 430 | 440)) {
        let h = w.get(b'H').map(|h| h.round() as i64);
        let allowed = if tlc_type == 1 { perpendicular } else { 2 };
        let has_allowed = axis_words.iter().any(|a| a.0 == allowed);
        for &(i, s) in axis_words
            .iter()
            .filter(|_| tlc_type != 2 && !has_allowed)
            .take(1)
        {
            let letter = AXES[i] as char;
            match tlc_type {
                0 if i != 2 => cx.out.diag(&TLC_TYPE, Severity::Error, s, format!("tool length compensation type 0 (A) compensates only Z: G{} {letter} raises an alarm; use Z or set machine.tlc_type", g / 10)),
                1 if i != perpendicular => cx.out.diag(&TLC_TYPE, Severity::Error, s, format!("tool length compensation type 1 (B) compensates the axis perpendicular to the plane ({}): G{} {letter} raises an alarm; select the matching plane first", AXES[perpendicular] as char, g / 10)),
                _ => {}
            }
        }
        match h {
            Some(0) => mem.tlc_h = false,
            Some(_) => mem.tlc_h = true,
            None => {}
        }
    }
    if w.has_g(490) {
        mem.tlc_h = false;
        // Type C cancels only with G49 and H0 in the same block.
        if tlc_type == 2 && w.get(b'H') != Some(0.0) {
            cx.out.diag(&TLC_TYPE, Severity::Error, w.g_span(490), "with tool length compensation type 2 (C) the cancel needs both G49 and H0: G49 alone raises an alarm; write G49 H0");
        }
    }
    // G37 automatic tool length calibration.
    if w.has_g(370) {
        let s = w.g_span(370);
        if tlc_type == 2 {
            cx.out.diag(&TLC_TYPE, Severity::Error, s, "G37 is not supported with tool length compensation type 2 (C): the control raises an error");
        } else if !mem.tlc_h {
            cx.out.diag(&TLC_TYPE, Severity::Error, s, "G37 needs a preceding G43 or G44 with a non-zero H: the calibrated offset has no tool to go to");
        }
        let allowed = if tlc_type == 1 { perpendicular } else { 2 };
        if tlc_type != 2 {
            if let Some(&(i, ws)) = axis_words.iter().find(|(i, _)| *i != allowed) {
                cx.out.diag(&TLC_TYPE, Severity::Error, ws, format!("G37 with {} is not allowed: with tool length compensation type {tlc_type} only {} can be calibrated", AXES[i] as char, AXES[allowed] as char));
            }
        }
    }
}
