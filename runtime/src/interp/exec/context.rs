//! RS274/NGC modal state save and restore: M70 (save), M71 (invalidate), M72 (restore),
//! M73 (save, restored automatically when the subroutine returns).
//!
//! LinuxCNC keeps one saved context per call level.  A restore compares the saved state
//! with the current one and runs the G/M codes that bring the current state back, so the
//! canonical calls are those the codes themselves produce: units first (as a block of
//! its own), then one block with F, S, the differing modal G codes and the first
//! differing M code, then one block per further M code.

use super::*;
use crate::rules::flow::FLOW;

/// The state M70/M73 saves, in LinuxCNC's own terms (`active_g_codes` slots as ten
/// times the G number, `active_m_codes` slots, `active_settings`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SavedContext {
    inch: bool,
    /// Plane, cutter compensation, distance, feed mode, coordinate system, tool length
    /// offset, retract mode, spindle mode, IJK mode, lathe diameter mode, G92 applied.
    g: [u32; 11],
    /// G61 (610), G61.1 (611) or G64 (640).
    control: u32,
    /// Feed (mm/min, or the raw value in inverse time) and spindle speed.
    feed: f64,
    speed: f64,
    /// G64 P and Q, program units as written.
    tol: f64,
    naive: f64,
    /// Spindle (3/4/5), mist (7/9/-1) and flood (8/-1), as LinuxCNC's
    /// `write_m_codes` reports them.
    m: [i32; 3],
    /// M73: restore when the subroutine returns.
    pub(super) auto: bool,
}

impl Interp<'_, '_> {
    fn current_context(&self) -> SavedContext {
        let md = &self.st.modal;
        let u = self.unit();
        // LinuxCNC reports G43 whenever a tool offset is in effect, whatever code set it.
        let tlo = if self.st.tlo.iter().any(|v| *v != 0.0) {
            430
        } else {
            490
        };
        let origin = match md.origin {
            o @ 1..=6 => 530 + 10 * o as u32,
            o @ 7..=9 => 584 + o as u32,
            _ => 540,
        };
        let g92 = if self.param(5210) != 0.0 { 923 } else { 922 };
        SavedContext {
            inch: md.inch,
            g: [
                md.plane,
                md.comp,
                if md.incremental { 910 } else { 900 },
                md.feed_mode,
                origin,
                tlo,
                if md.retract_old_z { 980 } else { 990 },
                if md.css { 960 } else { 970 },
                if md.ijk_abs { 901 } else { 911 },
                if md.diameter { 70 } else { 80 },
                g92,
            ],
            control: md.path,
            feed: self.st.feed,
            speed: self.st.spindle,
            tol: md.path_tol.unwrap_or(0.0) / u,
            naive: self.naive_tol,
            m: [
                match self.st.spindle_dir {
                    0 => 5,
                    d if d > 0 => 3,
                    _ => 4,
                },
                if self.st.mist {
                    7
                } else if self.st.flood {
                    -1
                } else {
                    9
                },
                if self.st.flood { 8 } else { -1 },
            ],
            auto: false,
        }
    }

    /// The saved context of the current call level.
    fn context_slot(&mut self) -> &mut Option<SavedContext> {
        match self.frames.last_mut() {
            Some(f) => &mut f.context,
            None => &mut self.top_context,
        }
    }

    /// M70–M73 of a block, at their place in the order of execution (with the
    /// spindle codes, before coolant).
    pub(super) fn exec_context_codes(&mut self, w: &Words) -> Result<(), Diagnostic> {
        if w.has_m(700) || w.has_m(730) {
            let mut c = self.current_context();
            // M73 at the top level has nothing to return to; LinuxCNC stores it anyway.
            c.auto = w.has_m(730) && !self.frames.is_empty();
            *self.context_slot() = Some(c);
        } else if w.has_m(710) {
            *self.context_slot() = None;
        } else if w.has_m(720) {
            let Some(saved) = self.context_slot().clone() else {
                return Err(self.err(
                    &FLOW,
                    w.m.iter()
                        .find(|(m, _)| *m == 720)
                        .map(|x| x.1)
                        .unwrap_or_default(),
                    "Cannot restore context from invalid stack frame - missing M70/M73?",
                ));
            };
            self.restore_context(&saved)?;
        }
        Ok(())
    }

    /// Called when a subroutine frame is left: an M73 context comes back.
    pub(super) fn auto_restore(&mut self, saved: Option<SavedContext>) -> Result<(), Diagnostic> {
        match saved {
            Some(c) if c.auto => self.restore_context(&c),
            _ => Ok(()),
        }
    }

    fn restore_context(&mut self, saved: &SavedContext) -> Result<(), Diagnostic> {
        let (fi, bi) = self.cur;
        let p = self.files[fi].prog.clone();
        let span = p
            .blocks
            .get(bi as usize)
            .map(|b| b.span)
            .unwrap_or_default();
        let run = |it: &mut Self, w: &Words| it.exec_words(fi, bi, &p, w, &[], span).map(|_| ());
        if self.st.modal.inch != saved.inch {
            let mut w = Words::default();
            w.push_g(if saved.inch { 200 } else { 210 }, span);
            run(self, &w)?;
        }
        let now = self.current_context();
        let mut w = Words::default();
        let set = |w: &mut Words, c: u8, v: f64| w.set(c, v);
        let u = self.unit();
        if saved.feed != now.feed {
            // LinuxCNC writes the feed with one decimal (`F%.1f`).
            let f = if saved.g[3] == 930 {
                saved.feed
            } else {
                saved.feed / u
            };
            set(&mut w, b'F', (f * 10.0).round() / 10.0);
        }
        if saved.speed != now.speed {
            set(&mut w, b'S', saved.speed.round());
        }
        for (k, (s, n)) in saved.g.iter().zip(now.g.iter()).enumerate() {
            // Cutter compensation comes back only as G40: G41/G42 would need the
            // tool and side LinuxCNC does not save either.
            if s != n && !(k == 1 && *s != 400) {
                w.push_g(*s, span);
            }
        }
        // Our tolerance is kept in mm and converted back, LinuxCNC keeps it as
        // written: round-off is not a difference.
        let differs = |a: f64, b: f64| (a - b).abs() > 1e-9 * a.abs().max(1.0);
        let g64 = differs(saved.tol, now.tol) || differs(saved.naive, now.naive);
        if saved.control != now.control && saved.control != 640 {
            w.push_g(saved.control, span);
        }
        if saved.control == 640 && (g64 || saved.control != now.control) {
            w.push_g(640, span);
            set(&mut w, b'P', saved.tol);
            set(&mut w, b'Q', saved.naive);
        }
        let mut ms = saved
            .m
            .iter()
            .zip(now.m.iter())
            .filter(|(s, n)| s != n && **s != -1)
            .map(|(s, _)| *s as u32 * 10);
        if let Some(m) = ms.next() {
            w.m.push((m, span));
        }
        let rest: Vec<u32> = ms.collect();
        if w.is_empty() {
            return Ok(());
        }
        run(self, &w)?;
        for m in rest {
            let mut w = Words::default();
            w.m.push((m, span));
            run(self, &w)?;
        }
        Ok(())
    }
}
