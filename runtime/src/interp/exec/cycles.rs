//! Canned cycles: drilling, boring, tapping and peck cycles (G73–G89 and the
//! FANUC/ServoWorks variants), their modal memory (`State::cycle`), repeats (L/K),
//! retract planes (G98/G99) and the G76/G87 shift.

use super::*;
use crate::rules::{
    cycle_missing::CYCLE_MISSING, cycle_q::CYCLE_Q, cycle_state::CYCLE_STATE, interp::INTERP,
    rigid_tap::RIGID_TAP, step_budget::STEP_BUDGET,
};

/// Pecks per hole after which a peck cycle finishes the hole in one move.
const MAX_PECKS: u32 = 1_000;

impl Interp<'_, '_> {
    /// The G76/G87 shift of `q` as a plane-axis displacement (index, signed amount).
    pub(super) fn drill_shift_vec(&self, q: f64) -> Option<(usize, f64)> {
        let (which, sign) = self.cfg.drill_shift?;
        let (a, b) = self.plane_axes();
        Some((if which == 0 { a } else { b }, sign * q.abs()))
    }

    pub(super) fn exec_cycle(
        &mut self,
        mode: u32,
        w: &Words,
        bspan: Span,
    ) -> Result<(), Diagnostic> {
        let ngc = self.ngc();
        let span = w
            .g()
            .iter()
            .find(|(g, _)| is_cycle(*g))
            .map(|x| x.1)
            .unwrap_or(bspan);
        // LinuxCNC's canned cycles move only X, Y and Z.
        if ngc && mode != 800 {
            for c in [b'A', b'B', b'C'] {
                if w.has(c) {
                    return Err(self.err(
                        &INTERP,
                        w.sp(c),
                        format!(
                            "Cannot put a{} {} in canned cycle",
                            if c == b'A' { "n" } else { "" },
                            char::from(c.to_ascii_lowercase())
                        ),
                    ));
                }
            }
        }
        let same = self.st.modal.motion == mode;
        let (a, b) = self.plane_axes();
        let n = self.normal_axis();
        let letters = [b'X', b'Y', b'Z'];
        let zl = letters[n];
        if self.st.feed <= 0.0 && mode != 800 {
            self.check_feed(span)?;
        }
        if self.st.modal.comp != 400 && ngc {
            return Err(self.err(
                &CYCLE_STATE,
                span,
                "cannot use canned cycles with cutter compensation on",
            ));
        }
        // FANUC/ServoWorks: a cycle block without a position or R makes no hole
        // (SW117, reported by the hygiene check), so missing R/Z levels are not
        // an error yet (servoworks.md TV-63).
        if !ngc && !w.any_axis() && !w.has(b'R') {
            return Ok(());
        }
        let mut cyc = self.st.cycle.clone();
        if let Some(r) = w.get(b'R') {
            cyc.r = Some(self.lin(r));
            self.rules.cycle_r_seen = true;
        }
        if let Some(z) = w.get(zl) {
            cyc.z = Some(self.lin(z));
        }
        if ngc && (cyc.r.is_none() || (!same && !w.has(b'R'))) {
            return Err(self.err(
                &CYCLE_MISSING,
                span,
                "R clearance plane unspecified in cycle",
            ));
        }
        if cyc.r.is_none() && self.dialect == Dialect::Servoworks {
            return Err(self.err(
                &CYCLE_MISSING,
                span,
                "canned cycle without R (point R level)",
            ));
        }
        if cyc.r.is_none() {
            // FANUC (FAN090): with no point R the cycle starts its feed at the
            // initial level, which the dry run then uses as R. After a G80 that
            // cleared an R the programmer may expect the old one (a warning); a
            // program that never gave R chose to start from where the tool is.
            let (sev, why) = if self.rules.cycle_r_seen {
                (
                    Severity::Warning,
                    "the R of the earlier cycle was cleared by the cancel",
                )
            } else {
                (Severity::Info, "no R has been given in this program")
            };
            self.diag(
                &CYCLE_MISSING,
                sev,
                span,
                format!("canned cycle without R (point R level), {why}: the cycle feeds from the initial level. Give R to start the feed closer to the work"),
            );
            cyc.r = Some(self.st.cycle.initial.unwrap_or(self.st.pos[n]));
        }
        if cyc.z.is_none() || (ngc && !same && !w.has(zl)) {
            return Err(self.err(
                &CYCLE_MISSING,
                span,
                format!("{} value unspecified in canned cycle", zl as char),
            ));
        }
        if let Some(p) = w.get(b'P') {
            cyc.p = Some(if ngc { p } else { p / 1000.0 });
        }
        if let Some(q) = w.get(b'Q') {
            let q = self.lin(q);
            if matches!(mode, 730 | 830) && q <= 0.0 {
                let msg = if ngc {
                    "negative or zero Q value used in G73/G83 peck cycle"
                } else {
                    "peck depth Q must be positive"
                };
                if ngc {
                    return Err(self.err(&CYCLE_Q, w.sp(b'Q'), msg));
                }
                self.diag(&CYCLE_Q, Severity::Warning, w.sp(b'Q'), msg);
            }
            // ServoWorks ignores a negative G73/G83 Q and keeps the modal one
            // (SW122; servoworks.md TV-64 recommends it).
            let ignored = self.dialect == Dialect::Servoworks
                && matches!(mode, 730 | 830)
                && q <= 0.0
                && cyc.q.is_some();
            if !ignored {
                cyc.q = Some(q.abs());
            }
        }
        for (c, slot) in [(b'I', 0), (b'J', 1), (b'K', 2)] {
            if let Some(v) = w.get(c) {
                let v = self.lin(v);
                match slot {
                    0 => cyc.i = Some(v),
                    1 => cyc.j = Some(v),
                    _ => cyc.k = Some(v),
                }
            }
        }
        // rs274 checks the cycle's own words only after climbing to R and
        // switching to exact path; the others stop before any output.
        let missing_q = matches!(mode, 730 | 830) && cyc.q.is_none();
        let missing_p = matches!(mode, 820 | 860 | 880 | 890) && ngc && cyc.p.is_none();
        if missing_q && !ngc {
            return Err(self.err(&CYCLE_Q, span, "Q word missing with G73/G83"));
        }
        // Rigid tapping (FANUC M29) checks.
        if self.dialect == Dialect::Fanuc
            && matches!(mode, 740 | 840)
            && self.st.modal.rigid_tap
            && self.st.spindle <= 0.0
        {
            self.diag(
                &RIGID_TAP,
                Severity::Error,
                span,
                "rigid tapping (M29) needs a spindle speed S (PS0203)",
            );
        }
        if ngc && mode == 840 && self.st.spindle_dir != 1 {
            return Err(self.err(&CYCLE_STATE, span, "spindle not turning clockwise in G84"));
        }
        if ngc && mode == 740 && self.st.spindle_dir != -1 {
            return Err(self.err(
                &CYCLE_STATE,
                span,
                "spindle not turning counterclockwise in G74",
            ));
        }
        if ngc && matches!(mode, 860 | 870 | 880) && self.st.spindle_dir == 0 {
            return Err(self.err(
                &CYCLE_STATE,
                span,
                format!("spindle not turning in G{}", mode / 10),
            ));
        }
        let repeats = if ngc {
            let l = w.get(b'L').unwrap_or(1.0).round() as i64;
            if l == 0 {
                return Err(self.err(&CYCLE_STATE, span, "cannot do zero repeats of cycle"));
            }
            l.max(1)
        } else {
            w.raw_k.map(|k| k.round() as i64).unwrap_or(1).max(0)
        };
        self.st.modal.motion = mode;
        let old_z = if ngc {
            match self.st.cycle.initial {
                Some(z) => z,
                None => self.st.pos[n],
            }
        } else {
            self.st.cycle.initial.unwrap_or(self.st.pos[n])
        };
        cyc.initial = Some(old_z);
        let inc = self.st.modal.incremental;
        let (r, bottom) = if ngc {
            if inc {
                let r = old_z + cyc.r.unwrap_or(0.0);
                (r, r + cyc.z.unwrap_or(0.0))
            } else {
                (cyc.r.unwrap_or(0.0), cyc.z.unwrap_or(0.0))
            }
        } else {
            // FANUC/ServoWorks keep the levels absolute once resolved; only words of this
            // block are read incrementally (R from the initial level, Z from R).
            let r = match w.get(b'R') {
                Some(v) if inc => old_z + self.lin(v),
                Some(v) => self.lin(v),
                None => cyc.r_abs.unwrap_or(cyc.r.unwrap_or(0.0)),
            };
            let z = match w.get(zl) {
                Some(v) if inc => r + self.lin(v),
                Some(v) => self.lin(v),
                None => cyc.z_abs.unwrap_or(cyc.z.unwrap_or(0.0)),
            };
            (r, z)
        };
        cyc.r_abs = Some(r);
        cyc.z_abs = Some(bottom);
        self.st.cycle = cyc.clone();
        if r < bottom && ngc {
            return Err(self.err(
                &CYCLE_STATE,
                span,
                match self.st.modal.plane {
                    180 => "R less than y in cycle in xz plane",
                    190 => "R less than x in cycle in yz plane",
                    _ => "R less than z in cycle in xy plane",
                },
            ));
        }
        if repeats == 0 {
            return Ok(());
        }
        let save_path = self.st.modal.path;
        let mut cur_z = self.st.pos[n];
        let clear = if self.st.modal.retract_old_z {
            old_z.max(r)
        } else {
            r
        };
        // NGC: climb to R first when below it.
        let start_z = cur_z;
        if ngc && old_z < r {
            let mut p = self.st.pos;
            p[n] = r;
            self.rapid_to(p);
            cur_z = r;
        }
        if ngc && save_path != 610 {
            self.canon("SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
        }
        if missing_q {
            return Err(self.err(
                &CYCLE_Q,
                span,
                format!("Q word missing with g{}", mode / 10),
            ));
        }
        if missing_p {
            return Err(self.err(
                &CYCLE_MISSING,
                span,
                format!("dwell time P word missing with G{}", mode / 10),
            ));
        }
        let mut pa = self.st.pos[a];
        let mut pb = self.st.pos[b];
        let mut da = w.get(letters[a]).map(|v| self.lin(v));
        let mut db = w.get(letters[b]).map(|v| self.lin(v));
        if !ngc && self.st.modal.polar {
            // Polar hole positions: resolve radius/angle once, then step by the difference.
            let t = self.target(w);
            if inc {
                da = Some(t[a] - pa);
                db = Some(t[b] - pb);
            } else {
                da = Some(t[a]);
                db = Some(t[b]);
            }
        }
        // Each repetition counts against the step budget, so `L1000000000` stays bounded.
        let left = self.input.step_budget.saturating_sub(self.steps);
        let repeats = if repeats as u64 > left {
            self.diag(&STEP_BUDGET, Severity::Warning, span, format!("{repeats} cycle repetitions exceed the remaining step budget; only {left} are simulated (raise it with --step-budget)"));
            left as i64
        } else {
            repeats
        };
        self.steps += repeats.max(0) as u64;
        // LinuxCNC polar words (`@` radius, `^` angle) in a cycle: each
        // repetition in G91 turns and extends from the last hole, so
        // `G91 G81 … ^60 L6` drills six holes 60 degrees apart.
        let polar = (ngc && (w.polar_r.is_some() || w.polar_a.is_some())).then(|| {
            (
                w.polar_r.map(|v| self.lin(v)),
                w.polar_a.map(f64::to_radians),
            )
        });
        for k in 0..repeats {
            if self.motion_budget_reached(span) {
                break;
            }
            if let Some((dr, dth)) = polar {
                let (r0, th0) = (pa.hypot(pb), pb.atan2(pa));
                let (r, th) = if inc {
                    (r0 + dr.unwrap_or(0.0), th0 + dth.unwrap_or(0.0))
                } else {
                    (dr.unwrap_or(r0), dth.unwrap_or(th0))
                };
                pa = r * th.cos();
                pb = r * th.sin();
            } else if inc {
                pa += da.unwrap_or(0.0);
                pb += db.unwrap_or(0.0);
            } else {
                pa = da.unwrap_or(pa);
                pb = db.unwrap_or(pb);
            }
            let at = |s: &Self, z: f64| {
                let mut p = s.st.pos;
                p[a] = pa;
                p[b] = pb;
                p[n] = z;
                p
            };
            if ngc {
                if k == 0 && cur_z > r {
                    self.rapid_to(at(self, cur_z));
                    self.rapid_to(at(self, r));
                } else {
                    self.rapid_to(at(self, clear));
                    if clear > r {
                        self.rapid_to(at(self, r));
                    }
                }
            } else {
                let z0 = if k == 0 { start_z } else { self.st.pos[n] };
                self.rapid_to(at(self, z0));
                if (self.st.pos[n] - r).abs() > 1e-12 {
                    self.rapid_to(at(self, r));
                }
            }
            self.cycle_body(mode, &cyc, r, bottom, clear, &at, bspan)?;
            cur_z = self.st.pos[n];
        }
        let _ = cur_z;
        if ngc && save_path != 610 {
            let tol = self.st.modal.path_tol.unwrap_or(0.0) / self.unit();
            match save_path {
                611 => self.canon("SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)"),
                _ => {
                    canon!(self, "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, {tol:.6})");
                    canon!(self, "SET_NAIVECAM_TOLERANCE({})", f4(tol));
                }
            }
        }
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn cycle_body(
        &mut self,
        mode: u32,
        cyc: &CycleMem,
        r: f64,
        bottom: f64,
        clear: f64,
        at: &dyn Fn(&Self, f64) -> [f64; 6],
        span: Span,
    ) -> Result<(), Diagnostic> {
        let ngc = self.ngc();
        let dwell = cyc.p.unwrap_or(0.0);
        let fanuc_ret = |s: &Self| if s.st.modal.retract_old_z { clear } else { r };
        let ret = if ngc { clear } else { fanuc_ret(self) };
        let dwell_ev = |s: &mut Self| {
            if dwell > 0.0 || ngc {
                canon!(s, "DWELL({})", f4(dwell));
                s.event(EventKind::Dwell(dwell));
            }
        };
        match mode {
            810 => {
                self.feed_to(at(self, bottom), span)?;
                self.rapid_to(at(self, ret));
            }
            820 => {
                self.feed_to(at(self, bottom), span)?;
                dwell_ev(self);
                self.rapid_to(at(self, ret));
            }
            730 | 830 => {
                // A missing or non-positive Q is reported (C002); the hole is then drilled
                // in one peck rather than in millions of zero-depth ones.
                let q = cyc
                    .q
                    .filter(|q| *q > 0.0)
                    .unwrap_or((r - bottom).abs().max(1e-6));
                let g73 = mode == 730;
                // LinuxCNC's peck clearance is 0.01 inch in either unit system.
                let d = if ngc {
                    if self.st.modal.inch {
                        0.01
                    } else {
                        0.254
                    }
                } else if g73 {
                    self.cfg.g73_retract
                } else {
                    self.cfg.g83_clearance
                };
                let mut depth = r - q;
                let mut guard = 0;
                // More than MAX_PECKS pecks per hole is not a real program: the rest of
                // the hole is drilled in one move so output stays bounded.
                while depth > bottom && guard < MAX_PECKS {
                    guard += 1;
                    self.feed_to(at(self, depth), span)?;
                    if g73 {
                        self.rapid_to(at(self, depth + d));
                    } else {
                        self.rapid_to(at(self, r));
                        self.rapid_to(at(self, depth + d));
                    }
                    depth -= q;
                }
                self.feed_to(at(self, bottom), span)?;
                self.rapid_to(at(self, ret));
            }
            740 | 840 if ngc => {
                // LinuxCNC: overrides off, reverse the spindle at the bottom, feed out to the clear level.
                let (rev, fwd) = if mode == 840 {
                    (
                        "START_SPINDLE_COUNTERCLOCKWISE(0)",
                        "START_SPINDLE_CLOCKWISE(0)",
                    )
                } else {
                    (
                        "START_SPINDLE_CLOCKWISE(0)",
                        "START_SPINDLE_COUNTERCLOCKWISE(0)",
                    )
                };
                // LinuxCNC 2.9 passes the coordinates to its feed helper in a rotated
                // order in the XZ and YZ planes; reproduce the points it really commands.
                let (a, b) = self.plane_axes();
                let tap = |s: &Self, level: f64| {
                    let base = at(s, level);
                    let (pa, pb) = (base[a], base[b]);
                    let mut p = base;
                    match s.st.modal.plane {
                        180 => {
                            p[0] = level;
                            p[1] = pa;
                            p[2] = pb;
                        }
                        190 => {
                            p[0] = pb;
                            p[1] = level;
                            p[2] = pa;
                        }
                        _ => {}
                    }
                    p
                };
                self.canon("DISABLE_FEED_OVERRIDE()");
                self.canon("DISABLE_SPEED_OVERRIDE(0)");
                self.feed_to(tap(self, bottom), span)?;
                self.canon("STOP_SPINDLE_TURNING(0)");
                self.canon(rev);
                dwell_ev(self);
                self.feed_to(tap(self, clear), span)?;
                // The interpreter records the hole position at the clear level.
                self.st.pos = at(self, clear);
                self.canon("STOP_SPINDLE_TURNING(0)");
                self.canon(fwd);
                self.canon("ENABLE_FEED_OVERRIDE()");
                self.canon("ENABLE_SPEED_OVERRIDE(0)");
            }
            740 | 840 => {
                self.feed_to(at(self, bottom), span)?;
                dwell_ev(self);
                // The spindle reverses to back the tap out and turns the original way
                // again at R (ServoWorks §6.3.29: "dwell, CW, feed up, back to CCW").
                let (rpm, dir) = (self.st.spindle, self.st.spindle_dir);
                if dir != 0 {
                    self.event(EventKind::Spindle { rpm, dir: -dir });
                }
                self.feed_to(at(self, r), span)?;
                // ServoWorks rigid tapping dwells P again at R (§6.3.30, §6.3.37).
                if self.dialect == Dialect::Servoworks && self.st.modal.rigid_tap {
                    dwell_ev(self);
                }
                if dir != 0 {
                    self.event(EventKind::Spindle { rpm, dir });
                }
                if ret > r {
                    self.rapid_to(at(self, ret));
                }
            }
            850 => {
                self.feed_to(at(self, bottom), span)?;
                self.feed_to(at(self, r), span)?;
                if ret > r || ngc {
                    self.rapid_to(at(self, ret));
                }
            }
            860 => {
                self.feed_to(at(self, bottom), span)?;
                dwell_ev(self);
                self.canon("STOP_SPINDLE_TURNING(0)");
                self.rapid_to(at(self, ret));
                self.canon(if self.st.spindle_dir < 0 {
                    "START_SPINDLE_COUNTERCLOCKWISE(0)"
                } else {
                    "START_SPINDLE_CLOCKWISE(0)"
                });
            }
            880 => {
                self.feed_to(at(self, bottom), span)?;
                dwell_ev(self);
                self.canon("STOP_SPINDLE_TURNING(0)");
                self.canon("PROGRAM_STOP()");
                self.event(EventKind::Stop { optional: false });
                self.canon("START_SPINDLE_CLOCKWISE(0)");
                if !ngc {
                    self.rapid_to(at(self, ret));
                }
            }
            890 => {
                self.feed_to(at(self, bottom), span)?;
                dwell_ev(self);
                if ngc {
                    self.feed_to(at(self, clear), span)?;
                } else {
                    self.feed_to(at(self, r), span)?;
                    if ret > r {
                        self.rapid_to(at(self, ret));
                    }
                }
            }
            760 => {
                // FANUC fine boring: shift away by Q at the bottom, rapid out, shift back.
                self.feed_to(at(self, bottom), span)?;
                dwell_ev(self);
                let q = cyc.q.unwrap_or(0.0);
                let mut p = at(self, bottom);
                if let Some((a, d)) = self.drill_shift_vec(q) {
                    p[a] += d;
                    self.rapid_to(p);
                }
                p[self.normal_axis()] = ret;
                self.rapid_to(p);
                self.rapid_to(at(self, ret));
            }
            870 => {
                if ngc {
                    let (i, j, k) = (
                        cyc.i.unwrap_or(0.0),
                        cyc.j.unwrap_or(0.0),
                        cyc.k.unwrap_or(0.0),
                    );
                    let mut off = at(self, r);
                    let (a, b) = self.plane_axes();
                    off[a] += i;
                    off[b] += j;
                    let middle = if self.st.modal.incremental {
                        bottom + k
                    } else {
                        k
                    };
                    // The tool passes the bore with the spindle stopped and oriented
                    // (rs274's direction codes: 2 clockwise, 3 counterclockwise).
                    let ccw = self.st.spindle_dir < 0;
                    let orient = format!("ORIENT_SPINDLE(0, 0.0000, {})", if ccw { 3 } else { 2 });
                    let start = if ccw {
                        "START_SPINDLE_COUNTERCLOCKWISE(0)"
                    } else {
                        "START_SPINDLE_CLOCKWISE(0)"
                    };
                    self.rapid_to(off);
                    self.canon("STOP_SPINDLE_TURNING(0)");
                    self.canon(&orient);
                    let mut o2 = off;
                    o2[self.normal_axis()] = bottom;
                    self.rapid_to(o2);
                    self.rapid_to(at(self, bottom));
                    self.canon(start);
                    self.feed_to(at(self, middle), span)?;
                    self.feed_to(at(self, bottom), span)?;
                    self.canon("STOP_SPINDLE_TURNING(0)");
                    self.canon(&orient);
                    self.rapid_to(o2);
                    let mut o3 = o2;
                    o3[self.normal_axis()] = clear;
                    self.rapid_to(o3);
                    self.rapid_to(at(self, clear));
                    self.canon(start);
                } else {
                    // Back boring: the R point is the hole bottom. The tool passes the
                    // bore shifted away from the wall (oriented spindle), comes back on
                    // centre to cut upwards, and leaves shifted again.
                    let init = self.st.cycle.initial.unwrap_or(clear);
                    let shift = self.drill_shift_vec(cyc.q.unwrap_or(0.0));
                    let shifted = |s: &Self, level: f64| {
                        let mut p = at(s, level);
                        if let Some((a, d)) = shift {
                            p[a] += d;
                        }
                        p
                    };
                    if shift.is_some() {
                        self.rapid_to(shifted(self, init));
                        self.rapid_to(shifted(self, r));
                    }
                    self.rapid_to(at(self, r));
                    self.feed_to(at(self, bottom), span)?;
                    dwell_ev(self);
                    if shift.is_some() {
                        self.rapid_to(shifted(self, bottom));
                        self.rapid_to(shifted(self, init));
                    } else {
                        self.rapid_to(at(self, r));
                    }
                    self.rapid_to(at(self, init));
                }
            }
            _ => {}
        }
        Ok(())
    }
}
