//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags a G33 lead F outside 0.01–500 mm (metric; F1–F50000 without a decimal point) or 0.0001–9.9999 in (inch), and a spindle speed above (maximum cutting feed)/(lead) when `machine.max_cutting_feed` (mm/min) is set.
    ///
    /// ## Why is this bad?
    /// The control refuses the lead; above the speed limit the axis cannot follow the spindle and the thread is cut wrong.
    ///
    /// ## Example
    /// ```gcode
    /// S500 M03
    /// G33 Z-10. F60000
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S500 M03
    /// G33 Z-10. F1.5
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Error (lead), warning (speed).
    ///
    /// Implements: FAN055, FAN056
    pub static THREAD_LEAD = {
        code: "F018",
        name: "thread-lead",
        summary: "G33 lead out of range or spindle too fast for the lead",
        implements: &["FAN055", "FAN056"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// FANUC: a G33 block's lead and spindle speed (`motion` as `involute::check` answers it).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, motion: Option<(u32, Span)>) {
    if let Some((330, s)) = motion {
        lead(cx, s);
    }
}

/// G33 lead and spindle speed limits (FANUC).
fn lead(cx: &mut Cx<'_, '_>, s: Span) {
    let (w, st) = (cx.w, cx.st);
    let Some(f) = w.get(b'F') else { return };
    let point = w.point[(b'F' - b'A') as usize];
    let inch = st.modal.inch;
    let lead = if point {
        f
    } else if inch {
        f * 0.0001
    } else {
        f * 0.01
    };
    let (lo, hi, unit) = if inch {
        (0.0001, 9.9999, "in")
    } else {
        (0.01, 500.0, "mm")
    };
    if lead < lo - 1e-12 || lead > hi + 1e-9 {
        cx.out.diag(
            &THREAD_LEAD,
            Severity::Error,
            w.sp(b'F'),
            format!(
                "G33 lead {lead} {unit} is out of range: the control accepts {lo} to {hi} {unit}"
            ),
        );
        return;
    }
    let lead_mm = if inch { lead * 25.4 } else { lead };
    if let Some(fmax) = cx.input.machine.max_cutting_feed {
        let smax = fmax / lead_mm;
        if st.spindle > smax + 1e-9 {
            cx.out.diag(&THREAD_LEAD, Severity::Warning, s, format!("spindle speed S{} exceeds the threading limit {:.1} min⁻¹ (maximum feed {fmax} mm/min ÷ lead {lead_mm} mm): the axis cannot follow the spindle; lower S", st.spindle, smax));
        }
    }
}
