//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Dialect, Severity, Span, Variant};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags M6 with no T since the start, a T replaced before any M6 used it, G43 with a negative H or an H other than the tool in the spindle, LinuxCNC's G43 without H before any tool change (it applies the tool in the spindle: tool 0, offset zero, when none is loaded), an M6 under G43 followed by Z motion without a new G43, and (ServoWorks) G43/G44 while TCP is on or a T change while length compensation is on without H.
    ///
    /// ## Why is this bad?
    /// The machine cuts with a length offset that belongs to another tool, or the control refuses the block.
    ///
    /// ## Example
    /// ```gcode
    /// G43 H-1
    /// G0 Z1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// T1 M6
    /// G43 H1
    /// G0 Z1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error for G43 H-1 and G43/G44 under TCP; warning for M6 with no tool (LinuxCNC 2.9 runs it); info for the hints.
    ///
    /// Implements: NGC414, NGC415, NGC504, NGC505, NGC510, SW096, SW146
    pub static TOOL_OFFSET_STATE = {
        code: "T003",
        name: "tool-offset-state",
        summary: "Tool selection or length offset in an inconsistent state",
        implements: &["NGC414", "NGC415", "NGC504", "NGC505", "NGC510", "SW096", "SW146"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// A T word has been given since the start.
    pub(crate) t_seen: bool,
    /// A T word was given and no M6 has used it yet (line span of that T).
    pub(crate) t_unused: Option<Span>,
    /// An M6 left the tool length offset of the old tool while G43 was in use.
    pub(crate) m6_without_g43: bool,
}

/// Tool selection and length offsets.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    let d = cx.dialect;
    let ngc = d == Dialect::Rs274ngc;
    if d == Dialect::Servoworks {
        if st.modal.tlo_mode == 432 {
            for code in [430u32, 440] {
                if w.has_g(code) {
                    cx.out.diag(&TOOL_OFFSET_STATE, Severity::Error, w.g_span(code), format!("G{} cannot be given while tool centre point control (G43.2) is on: cancel it with G49 first", code / 10));
                }
            }
        }
        if w.has(b'T') && matches!(st.modal.tlo_mode, 430 | 440) && !w.has(b'H') {
            cx.out.diag(&TOOL_OFFSET_STATE, Severity::Info, w.sp(b'T'), "the tool changes while length compensation is on: the old length offset stays until G43/G44 with an explicit H");
        }
        return Ok(());
    }
    if !ngc {
        return Ok(());
    }
    if w.has_g(430) {
        if let Some(h) = w.get(b'H') {
            if h < 0.0 {
                return Err(cx.out.err(&TOOL_OFFSET_STATE, w.sp(b'H'), format!("G43 H{h}: negative tool numbers do not exist; use G43.1 for a dynamic offset")));
            }
            let h = h.round() as u32;
            if h != st.tool {
                cx.out.diag(
                    &TOOL_OFFSET_STATE,
                    Severity::Info,
                    w.sp(b'H'),
                    format!(
                        "G43 H{h} applies the length of tool {h}, but tool {} is in the spindle",
                        st.tool
                    ),
                );
            }
        } else if st.tool == 0
            && cx.variant != Variant::Emc2
            && !w.has_m(60)
            && cx.cfg.tools.get(&0).is_none_or(|t| t.length == 0.0)
        {
            // LinuxCNC's G43 without H takes the tool in the spindle (spec/rs274ngc.md
            // 3.12); before any M6 (or after M61 Q0) that is tool 0, whose length is zero.
            // A program may expect the tool already in the spindle: a note, not a warning.
            cx.out.diag(&TOOL_OFFSET_STATE, Severity::Info, w.g_span(430), "G43 without H applies the length of the tool in the spindle, and none is loaded (tool 0): the offset is zero; load the tool first (T… M6) or give H");
        }
    }
    if w.has(b'T') {
        if let Some(prev) = mem.t_unused {
            if !w.has_m(60) {
                let _ = prev;
                cx.out.diag(&TOOL_OFFSET_STATE, Severity::Info, w.sp(b'T'), "this T replaces an earlier T that no M6 used: only the last selected tool is loaded");
            }
        }
        mem.t_seen = true;
        mem.t_unused = Some(w.sp(b'T'));
    }
    if w.has_m(60) {
        let s = w.m_span(60);
        // LinuxCNC 2.9 (its rs274) loads tool 0 without complaint: a warning only.
        if !mem.t_seen {
            cx.out.diag(
                &TOOL_OFFSET_STATE,
                Severity::Warning,
                s,
                "M6 with no tool selected: the spindle gets tool 0 (no tool); give T before M6",
            );
        }
        mem.t_unused = None;
        if st.modal.tlo_mode == 430 && !w.has_g(430) && !w.has_g(490) {
            mem.m6_without_g43 = true;
        }
    }
    if w.has_g(430) || w.has_g(490) {
        mem.m6_without_g43 = false;
    } else if mem.m6_without_g43 && w.has(b'Z') && !w.has_m(60) {
        mem.m6_without_g43 = false;
        cx.out.diag(&TOOL_OFFSET_STATE, Severity::Info, w.sp(b'Z'), "M6 loaded a new tool but the length offset is still the old tool's: give G43 (H of the new tool) before moving Z");
    }
    Ok(())
}
