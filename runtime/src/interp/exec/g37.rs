//! ServoWorks G37 automatic tool length calibration (servoworks.md D§5.4,
//! manual §6.3.14).
//!
//! The axis word is the theoretical surface position. The axis runs the first
//! `g37_ratio` of the distance at rapid and the rest at the G37 Speed until
//! the surface-detection signal triggers; the calibration (trigger − surface)
//! is added to the tool length offset of that axis. A dry run has no sensor:
//! the trigger comes `g37_measured` from the surface (default 0, the tool is
//! exactly as long as its offset says), so programs can be timed and their
//! G37 Limit checked for an assumed measurement.

use super::*;
use crate::rules::tlc_type::TLC_TYPE;

/// The `[machine]` keys of G37.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct G37Cfg {
    ratio: f64,
    /// mm/min.
    speed: f64,
    limit: Option<f64>,
    measured: f64,
}

impl G37Cfg {
    pub(in crate::interp) fn read(m: &analyzer::config::MachineConfig) -> G37Cfg {
        G37Cfg {
            ratio: m.g37_ratio.unwrap_or(0.0),
            speed: m.g37_speed.unwrap_or(100.0),
            limit: m.g37_limit.map(f64::abs),
            measured: m.g37_measured.unwrap_or(0.0),
        }
    }
}

impl Interp<'_, '_> {
    /// Runs `G37 <axis><surface>`: the approach motions, then the offset update.
    /// Without exactly one X/Y/Z word nothing moves (the checks report it).
    pub(super) fn exec_g37(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let words: Vec<usize> = (0..3).filter(|i| w.has([b'X', b'Y', b'Z'][*i])).collect();
        let [axis] = words[..] else {
            return Ok(());
        };
        let letter = [b'X', b'Y', b'Z'][axis];
        let Some(v) = w.get(letter) else {
            return Ok(());
        };
        let cfg = self.cfg.g37;
        let surface = {
            let v = self.lin(v);
            if self.st.modal.incremental {
                self.st.pos[axis] + v
            } else {
                v
            }
        };
        let start = self.st.pos[axis];
        let trigger = surface + cfg.measured;
        let at = |s: &mut Self, p: f64, rapid: bool| {
            let mut t = s.st.pos;
            t[axis] = p;
            let end = s.to_machine(t);
            let kind = if rapid {
                MotionKind::Rapid
            } else {
                MotionKind::Feed
            };
            let mut m = s.motion_base(kind, s.st.mpos, end, if rapid { 0.0 } else { cfg.speed });
            m.inverse_time = None;
            if !rapid {
                m.feed = cfg.speed * s.lu();
            }
            s.out.motions.push(m);
            s.st.mpos = end;
            s.st.pos = t;
        };
        let fast = start + cfg.ratio * (surface - start);
        if fast != start {
            at(self, fast, true);
        }
        if trigger != fast {
            at(self, trigger, false);
        }
        let calibration = trigger - surface;
        if let Some(l) = cfg.limit {
            if calibration.abs() >= l {
                return Err(self.err(
                    &TLC_TYPE,
                    w.sp(letter),
                    format!("G37 measured {calibration:+.4} from the surface position, outside the G37 Limit ±{l}: the control stops with an error"),
                ));
            }
        }
        // The tool now touches the surface: the offset grows by the calibration and
        // the programmed point reads the surface position.
        self.st.tlo[axis] += calibration;
        self.st.pos = self.to_program(self.st.mpos);
        Ok(())
    }
}
