//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Severity;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags H (with G43/G44/G49) or D (with G41/G42) beyond the available offsets (`machine.offset_count`, default 400), and G10 with a missing or unknown L, tool-offset data without P, or G10 L2 with P outside 0–6.
    ///
    /// ## Why is this bad?
    /// The control alarms (PS0030, PS0031).
    ///
    /// ## Example
    /// ```gcode
    /// G43 H500 Z10.
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G43 H5 Z10.
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error.
    ///
    /// Reported by W007, not this rule, when both see a negative offset number on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN156, FAN161
    pub static OFFSET_NUMBER = {
        code: "T007",
        name: "offset-number",
        summary: "Offset number beyond the offsets, or illegal G10 data kind",
        implements: &["FAN156", "FAN161"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// FANUC: H/D offset numbers and G10 data kinds.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>) {
    let w = cx.w;
    // Offset numbers and G10 data.
    let count = cx.input.machine.offset_count.unwrap_or(400.0);
    for c in [b'H', b'D'] {
        if let Some(v) = w.get(c) {
            let uses = if c == b'H' {
                w.g().iter().any(|g| matches!(g.0, 430 | 440 | 490))
            } else {
                w.g().iter().any(|g| matches!(g.0, 410 | 420))
            };
            if uses && (v < 0.0 || v > count) {
                cx.out.diag(&OFFSET_NUMBER, Severity::Error, w.sp(c), format!("offset number {}{v} is beyond the {count} offsets of this control (PS0030): use 0 to {count}", c as char));
            }
        }
    }
    if w.has_g(100) {
        let l = w.get(b'L').map(|l| l.round() as i64);
        let ok_l = matches!(l, Some(1 | 2 | 3 | 10 | 11 | 12 | 13 | 20 | 50 | 52));
        if !ok_l {
            let span = if w.has(b'L') {
                w.sp(b'L')
            } else {
                w.g_span(100)
            };
            cx.out.diag(&OFFSET_NUMBER, Severity::Error, span, format!("G10 {}: the data kind L is missing or not one the control knows (PS0031); use L1/L10–L13 tool offsets, L2/L20 work offsets", l.map(|l| format!("L{l}")).unwrap_or_else(|| "without L".into())));
        } else if matches!(l, Some(1 | 10 | 11 | 12 | 13)) && !w.has(b'P') {
            cx.out.diag(
                &OFFSET_NUMBER,
                Severity::Error,
                w.g_span(100),
                "G10 tool offset data without P (the offset number): the control alarms (PS0031)",
            );
        } else if l == Some(2) && w.get(b'P').is_some_and(|p| !(0.0..=6.0).contains(&p)) {
            cx.out.diag(
                &OFFSET_NUMBER,
                Severity::Error,
                w.sp(b'P'),
                "G10 L2 takes P0 (external) to P6 (G59): other P values are illegal (PS0031)",
            );
        }
    }
}
