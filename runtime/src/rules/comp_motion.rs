//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).
//! `no_effect::check` also reports this code (NGC427 rotary motion, SW084 G41/G42
//! without a radius).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Dialect, Severity, Variant};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags an arc as the first move after G40 (RS274/NGC), and in ServoWorks an arc as the first or last move of tool radius compensation and any G code other than G00–G03, G04 and G40 while it is on. Also flags G41/G42 in a plane LinuxCNC cannot compensate in (G19; `emc2`: anything but G17). Hints (info) at rotary-axis motion under RS274/NGC compensation, and warns at ServoWorks G41/G42 with no D/H and no radius for the tool.
    ///
    /// ## Why is this bad?
    /// The control needs a straight move to build up or remove the offset; LinuxCNC stops, ServoWorks alarms.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.2
    /// G1 X1 F100
    /// G40
    /// G2 X2 Y0 R0.5
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X0 Y0
    /// G41.1 D0.2
    /// G1 X1 F100
    /// G40
    /// G1 X2
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, ServoWorks. Error.
    ///
    /// Implements: NGC217, SW082, SW083, NGC412, NGC427, SW084
    pub static COMP_MOTION = {
        code: "T004",
        name: "comp-motion",
        summary: "Cutter compensation started, ended or used where the control refuses",
        implements: &["NGC217", "SW082", "SW083", "NGC412", "NGC427", "SW084"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// Cutter compensation was just turned off and no motion has followed.
    pub(crate) after_g40: bool,
}

/// The error that stops the block, and whether the interpreter first turns
/// compensation off: rs274 releases the held-back moves before it rejects an arc
/// after G40, which only the executor can do.
pub(crate) struct Stop {
    pub(crate) error: Diagnostic,
    pub(crate) release_comp: bool,
}

impl Stop {
    fn error(error: Diagnostic) -> Stop {
        Stop {
            error,
            release_comp: false,
        }
    }
}

/// Motion rules at the start and end of cutter compensation.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Stop> {
    let (w, st) = (cx.w, cx.st);
    let d = cx.dialect;
    let comp_on = st.modal.comp != 400;
    let cancel = comp_on && w.has_g(400);
    let motion = cx.motion;
    let arc = matches!(motion, Some((20 | 30, _)));
    if d == Dialect::Rs274ngc {
        if let Some(&(g, s)) = w.g().iter().find(|g| matches!(g.0, 410 | 420 | 411 | 421)) {
            let plane = w
                .g()
                .iter()
                .find(|g| matches!(g.0, 170 | 180 | 190))
                .map(|g| g.0)
                .unwrap_or(st.modal.plane);
            let emc2 = cx.variant == Variant::Emc2;
            if (emc2 && plane != 170) || plane == 190 {
                return Err(Stop::error(cx.out.err(&COMP_MOTION, s, format!("cutter radius compensation (G{}) is not allowed in the G{} plane: LinuxCNC compensates only in {}", g / 10, plane / 10, if emc2 { "G17" } else { "G17 and G18" }))));
            }
        }
        if cancel {
            mem.after_g40 = true;
        }
        if mem.after_g40 {
            if let Some((g, s)) = motion {
                mem.after_g40 = false;
                if arc {
                    // rs274 turns compensation off (releasing the held-back
                    // moves) before it rejects the arc.
                    return Err(Stop {
                        release_comp: cancel && cx.ngc(),
                        error: cx.out.err(&COMP_MOTION, s, format!("G{} is the first move after G40: LinuxCNC needs a straight move to leave cutter compensation", g / 10)),
                    });
                }
            }
        }
        return Ok(());
    }
    if d != Dialect::Servoworks {
        return Ok(());
    }
    if let Some((g, s)) = motion {
        let first = w.g().iter().any(|x| matches!(x.0, 410 | 420)) || (comp_on && st.comp_first);
        if arc && (first || cancel) {
            let which = if cancel { "last" } else { "first" };
            cx.out.diag(&COMP_MOTION, Severity::Error, s, format!("the {which} motion of tool radius compensation cannot be G{:02}: use G00 or G01 to start and end it", g / 10));
        }
    }
    if comp_on && !cancel {
        if let Some(&(g, s)) = w
            .g()
            .iter()
            .find(|x| !matches!(x.0, 0 | 10 | 20 | 30 | 40 | 400 | 410 | 420))
        {
            let name = if g % 10 == 0 {
                format!("G{:02}", g / 10)
            } else {
                format!("G{}.{}", g / 10, g % 10)
            };
            cx.out.diag(&COMP_MOTION, Severity::Error, s, format!("{name} is not allowed in tool radius compensation mode (only G00–G03, G04, M, S, B and F): cancel with G40 first"));
        }
    }
    Ok(())
}
