//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Severity};

use super::check::{is_feed_motion, Cx};
use super::cycle_spindle::CYCLE_SPINDLE;
use crate::interp::is_cycle;

declare_rule! {
    /// ## What it does
    /// Flags G33/G76 with the spindle not turning, a feed-per-revolution (G95) move with spindle speed 0, and (RS274/NGC) M3/M4 with S0.
    ///
    /// ## Why is this bad?
    /// Motion synchronised to the spindle cannot proceed with the spindle stopped: LinuxCNC stops on G33/G76 and a G95 move at S0 never finishes; ServoWorks computes a zero feed.
    ///
    /// ## Example
    /// ```gcode
    /// G95 F0.1
    /// G1 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// S1000 M3
    /// G95 F0.1
    /// G1 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error in RS274/NGC (warning for M3/M4 with S0); warning in ServoWorks.
    ///
    /// Implements: NGC220, NGC338, NGC506, NGC808, SW049
    pub static SPINDLE_STOPPED = {
        code: "F010",
        name: "spindle-stopped",
        summary: "Spindle-synchronised motion without spindle speed",
        implements: &["NGC220", "NGC338", "NGC506", "NGC808", "SW049"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// An M3/M4 at S0 was reported and no S word has come since: the next ones
    /// are the same fault (a sprayer's program turns M3/M5 on every pass).
    s0_reported: bool,
}

/// Spindle state against spindle-synchronised motion and canned cycles.
/// Also reports C005 (cycle-spindle) for FANUC and ServoWorks cycles.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Diagnostic> {
    let (w, st) = (cx.w, cx.st);
    if w.has(b'S') {
        mem.s0_reported = false;
    }
    let ngc = cx.ngc();
    let speed = w.get(b'S').unwrap_or(st.spindle);
    let dir = if w.has_m(30) {
        1
    } else if w.has_m(40) {
        -1
    } else if w.has_m(50) {
        0
    } else {
        st.spindle_dir
    };
    if ngc && speed <= 0.0 && !mem.s0_reported {
        if let Some(m) = [30u32, 40].into_iter().find(|m| w.has_m(*m)) {
            mem.s0_reported = true;
            let s = w.m_span(m);
            cx.out.diag(
                &SPINDLE_STOPPED,
                Severity::Warning,
                s,
                format!(
                    "M{} starts the spindle with speed S0: program S before or with M{} (later M3/M4 before an S word are the same fault and not reported again)",
                    m / 10,
                    m / 10
                ),
            );
        }
    }
    let motion = cx.motion;
    let Some((g, s)) = motion else {
        return Ok(());
    };
    let feed_mode = if w.has_g(950) {
        950
    } else if w.has_g(930) || w.has_g(940) {
        0
    } else {
        st.modal.feed_mode
    };
    if ngc {
        if matches!(g, 330 | 760) && dir == 0 {
            return Err(cx.out.err(
                &SPINDLE_STOPPED,
                s,
                format!(
                    "G{} needs the spindle turning (M3 or M4): LinuxCNC stops",
                    g / 10
                ),
            ));
        }
        if feed_mode == 950 && is_feed_motion(g) && speed <= 0.0 {
            return Err(cx.out.err(&SPINDLE_STOPPED, s, "feed per revolution (G95) with spindle speed 0: the move would never finish; program S"));
        }
        return Ok(());
    }
    if feed_mode == 950 && is_feed_motion(g) && speed <= 0.0 {
        cx.out.diag(
            &SPINDLE_STOPPED,
            Severity::Warning,
            s,
            "feed per revolution (G95) with no spindle speed: the feed is zero; program S",
        );
    }
    // Rigid tapping (M29) turns the spindle itself, in position control.
    let rigid = st.modal.rigid_tap && matches!(g, 740 | 840);
    if is_cycle(g) {
        if dir == 0 && !rigid {
            cx.out.diag(
                &CYCLE_SPINDLE,
                Severity::Warning,
                s,
                format!(
                    "G{} drills with the spindle stopped: start it with M03/M04 and S first",
                    g / 10
                ),
            );
        } else if g == 840 && dir == -1 {
            cx.out.diag(
                &CYCLE_SPINDLE,
                Severity::Warning,
                s,
                "G84 taps with the spindle turning CCW (M04): right-hand tapping needs M03",
            );
        } else if g == 740 && dir == 1 {
            cx.out.diag(
                &CYCLE_SPINDLE,
                Severity::Warning,
                s,
                "G74 taps with the spindle turning CW (M03): left-hand tapping needs M04",
            );
        }
    }
    Ok(())
}
