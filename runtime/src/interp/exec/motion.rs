//! Motion: the block's end point, straight moves (G0/G1), arcs and helices
//! (G2/G3, with LinuxCNC's radius-error checks), the feed rules a move obeys, the
//! curve moves that become sampled or special motions (involute, exponential,
//! G5/G5.1 splines, G5.2 NURBS) and threading (G33, G33.1, G76).

use super::*;
use crate::rules::{
    arc_corrected::{ARC_CORRECTED_IJK, ARC_CORRECTED_R},
    arc_no_center::ARC_NO_CENTER,
    arc_polar_ijk::ARC_POLAR_IJK,
    arc_radius_mismatch::ARC_RADIUS_MISMATCH,
    arc_radius_too_small::ARC_RADIUS_TOO_SMALL,
    arc_same_end_r::ARC_SAME_END_R,
    cycle_state::CYCLE_STATE,
    interp::INTERP,
    probe_state::PROBE_STATE,
    zero_feed::ZERO_FEED,
};

impl Interp<'_, '_> {
    /// The end point of a straight move from the block's axis words.
    pub(super) fn target(&self, w: &Words) -> [f64; 6] {
        target_of(&self.st, self.ngc(), w)
    }

    /// Normal direction control after the block's motion (at index `i`): the
    /// in-place turn of the tool axis goes in before it and arcs turn the axis
    /// by their sweep. Blocks that made other than one G01/G02/G03 motion, and
    /// moves held back by radius compensation, are left alone.
    pub(super) fn ndc_after_motion(&mut self, i: usize, left: bool) {
        if self.out.motions.len() != i + 1
            || !self.st.comp_queue.is_empty()
            || !matches!(self.st.modal.motion, 10 | 20 | 30)
        {
            return;
        }
        let cfg = self.cfg.ndc;
        let a = cfg.axis;
        let Some(m) = self.out.motions.get(i) else {
            return;
        };
        let Some(step) = crate::interp::ndc::step(m, m.start[a], left, &cfg) else {
            return;
        };
        let turn = step.turn.unwrap_or(0.0);
        if turn != 0.0 {
            let mut r = m.clone();
            r.kind = MotionKind::Feed;
            r.end = r.start;
            r.end[a] += turn;
            r.feed = cfg.rotation_feed;
            r.inverse_time = None;
            self.out.motions.insert(i, r);
        }
        if let Some(m) = self.out.motions.last_mut() {
            m.start[a] += turn;
            m.end[a] += turn + step.along;
        }
        self.st.pos[a] += turn + step.along;
        self.st.mpos[a] += turn + step.along;
    }

    /// ServoWorks `G10 L20`: axis types, as `P<axis> R<type>` or as axis words
    /// holding the types (`G10 L20 X2 Y10`). Type 12 makes a torque axis; the
    /// other types (1 normal, 2 rotary, 3 rotary single-turn, 10 PLC) leave the
    /// axis positioned by the program. Axes past C are not modelled.
    pub(super) fn servoworks_axis_types(&mut self, w: &Words, p: i64) {
        let mut set = |axis: usize, ty: f64| {
            if axis < 6 {
                if ty.round() == 12.0 {
                    self.st.torque_axes |= 1 << axis;
                } else {
                    self.st.torque_axes &= !(1 << axis);
                }
            }
        };
        if let Some(r) = w.get(b'R') {
            if (1..=8).contains(&p) {
                set((p - 1) as usize, r);
            }
            return;
        }
        for (i, c) in [b'X', b'Y', b'Z', b'A', b'B', b'C'].into_iter().enumerate() {
            if let Some(v) = w.get(c) {
                set(i, v);
            }
        }
    }

    /// A motion from internal-unit geometry; converts lengths to mm.
    pub(super) fn motion_base(
        &self,
        kind: MotionKind,
        start: [f64; 6],
        end: [f64; 6],
        feed: f64,
    ) -> Motion {
        // A FANUC G00 always decelerates to a stop at its end (spec/fanuc.md §5.3),
        // whichever way its axes move.
        let fanuc_rapid = matches!(kind, MotionKind::Rapid)
            && self.input.program.dialect == analyzer::Dialect::Fanuc;
        let exact = matches!(self.st.modal.path, 610 | 611) || self.block_exact || fanuc_rapid;
        let lu = self.lu();
        let mm = |p: [f64; 6]| [p[0] * lu, p[1] * lu, p[2] * lu, p[3], p[4], p[5]];
        let kind = match kind {
            MotionKind::Arc {
                center,
                normal,
                turns,
                radius,
            } => MotionKind::Arc {
                center: [center[0] * lu, center[1] * lu, center[2] * lu],
                normal,
                turns,
                radius: radius * lu,
            },
            k => k,
        };
        // Feed per revolution (G95) becomes mm/min at the programmed spindle speed;
        // threads keep their pitch (mm/rev).
        let feed = if self.st.modal.feed_mode == 950
            && !matches!(kind, MotionKind::Thread | MotionKind::Rapid)
        {
            feed * lu * self.st.spindle
        } else {
            feed * lu
        };
        let feed = if matches!(kind, MotionKind::Feed)
            && self.input.program.dialect == analyzer::Dialect::Servoworks
            && !self.st.modal.feed_linear_only
        {
            rotary_feed::g310_linear_feed(feed, &start, &end)
        } else {
            feed
        };
        let blend_tolerance = match self.st.modal.path_tol {
            Some(t) if self.st.modal.path == 640 => t * lu,
            _ => 0.0,
        };
        Motion {
            kind,
            start: mm(start),
            end: mm(end),
            feed,
            inverse_time: if self.st.modal.feed_mode == 930 && !matches!(kind, MotionKind::Rapid) {
                Some(self.st.feed)
            } else {
                None
            },
            exact_stop: exact,
            exact_path: self.st.modal.path == 610
                && !self.block_exact
                && self.input.program.dialect == analyzer::Dialect::Rs274ngc,
            blend_tolerance,
            naive_tolerance: if self.st.modal.path == 640 && self.ngc() {
                self.naive_tol * lu
            } else {
                blend_tolerance
            },
            file: self.file_id(),
            block: self.cur.1,
            line: self.cur_line,
            tool: self.st.tool,
            spindle_rpm: self.st.spindle,
        }
    }

    pub(super) fn rapid_to(&mut self, t: [f64; 6]) {
        if self.canon.is_some() {
            let s = self.canon_pos(&t);
            canon!(self, "STRAIGHT_TRAVERSE({s})");
        }
        let end = self.to_machine(t);
        let m = self.motion_base(MotionKind::Rapid, self.st.mpos, end, 0.0);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
    }

    pub(super) fn feed_to(&mut self, t: [f64; 6], span: Span) -> Result<(), Diagnostic> {
        if let Err(e) = self.check_feed(span) {
            // A feed move without F leaves the tool at its end (`recover.rs`).
            self.recover_to = Some(recover::Recover::SetPos(t));
            return Err(e);
        }
        if self.st.modal.feed_mode == 930 && !std::mem::take(&mut self.inv_rate_set) {
            let len = dist(&self.st.pos, &t);
            // LinuxCNC gives a zero-length move a nominal rate of 0.1 (its issue 2410).
            let rate = if len == 0.0 {
                0.1
            } else {
                len * self.st.feed / self.unit()
            };
            canon!(self, "SET_FEED_RATE({})", f4(rate));
        }
        if self.canon.is_some() {
            let s = self.canon_pos(&t);
            canon!(self, "STRAIGHT_FEED({s})");
        }
        let end = self.to_machine(t);
        let feed = self.effective_feed(dist(&self.st.mpos, &end));
        let m = self.motion_base(MotionKind::Feed, self.st.mpos, end, feed);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
        Ok(())
    }

    pub(super) fn effective_feed(&self, len: f64) -> f64 {
        match self.st.modal.feed_mode {
            930 => len * self.st.feed,
            _ => self.st.feed,
        }
    }

    pub(super) fn check_feed(&mut self, span: Span) -> Result<(), Diagnostic> {
        // `F#650` with a value only the machine knows (`machine_vars.rs`).
        let machine_feed = self.st.tainted.iter().any(|k| k == "F");
        if self.st.feed <= 0.0 && !machine_feed {
            let msg = match self.dialect {
                Dialect::Rs274ngc => {
                    "cannot feed with zero feed rate: program F before the first feed move"
                }
                Dialect::Fanuc => {
                    "feed rate is zero (F0) on a cutting move: the control alarms (PS0011)"
                }
                Dialect::Servoworks => {
                    "feed rate is zero on a cutting move: program F before the first G01/G02/G03"
                }
            };
            let e = self.err(&ZERO_FEED, span, msg);
            if self.ngc() {
                return Err(e);
            }
            self.out.diagnostics.push(e);
        }
        Ok(())
    }

    /// Leaving cycle mode: FANUC/ServoWorks forget the drilling data;
    /// LinuxCNC keeps P/Q/R for the next cycle and only forgets the initial level.
    pub(super) fn clear_cycle(&mut self) {
        if self.ngc() {
            self.st.cycle.initial = None;
        } else {
            self.st.cycle = CycleMem::default();
        }
    }

    /// FANUC/ServoWorks G31 skip function: a one-shot straight feed move at F that
    /// stops where the skip signal comes (here: at the target, no contact is
    /// simulated). The modal motion is not changed.
    fn exec_skip(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let t = self.target(w);
        self.check_feed(bspan)?;
        let end = self.to_machine(t);
        let m = self.motion_base(MotionKind::Probe, self.st.mpos, end, self.st.feed);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
        Ok(())
    }

    pub(super) fn exec_motion(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let mut motion = None;
        for (g, _) in w.g() {
            if matches!(
                g,
                0 | 10
                    | 20
                    | 30
                    | 23
                    | 33
                    | 22
                    | 32
                    | 330
                    | 331
                    | 382
                    | 383
                    | 384
                    | 385
                    | 800
                    | 760
                    | 730
                    | 740
                    | 810..=890
            ) || (self.ngc() && matches!(g, 50..=53 | 700 | 710..=712 | 720..=722))
            {
                // rs274 lets any other group-1 code in the block win over G80
                // (`G0 G40 G49 G80` is a rapid with no axis words).
                if !(self.ngc() && *g == 800 && motion.is_some()) {
                    motion = Some(*g);
                }
            }
        }
        if let Some(m) = motion {
            if m == 53 {
                // G5.3 closes a NURBS block: one curve through the collected points.
                return self.finish_nurbs(bspan);
            }
            if m == 800 {
                self.st.modal.motion = 800;
                self.clear_cycle();
                self.canon_comment("interpreter: motion mode set to none");
                return Ok(());
            }
            if !is_cycle(m) {
                // A group-01 code cancels the cycle and its data, as G80 does.
                self.clear_cycle();
            }
        }
        let mode = motion.unwrap_or(self.st.modal.motion);
        let has_axes = w.any_axis() || (is_cycle(mode) && w.has(b'R'));
        if motion.is_none() && !has_axes {
            return Ok(());
        }
        if w.has_g(310) && !self.ngc() && w.any_axis() {
            return self.exec_skip(w, bspan);
        }
        if w.has_g(530) {
            // Machine coordinates for this block only.
            let letters = [b'X', b'Y', b'Z', b'A', b'B', b'C'];
            let mut m = self.st.mpos;
            for (i, v) in m.iter_mut().enumerate() {
                if let Some(x) = w.get(letters[i]) {
                    *v = if i < 3 { self.lin(x) } else { x };
                }
            }
            let t = self.to_program(m);
            // The block's G0/G1 stays the motion mode (`G53 G0 Z0`, then `X0 Y0`
            // is another rapid).
            if matches!(mode, 0 | 10) {
                self.st.modal.motion = mode;
            }
            if mode == 10 {
                self.feed_to(t, bspan)?;
            } else {
                self.rapid_to(t);
            }
            return Ok(());
        }
        match mode {
            0 => {
                self.st.modal.motion = 0;
                // LinuxCNC commands a zero-length move for a bare G0/G1.
                if has_axes || (self.ngc() && motion.is_some()) {
                    let t = self.target(w);
                    self.comp_move(t, true, bspan)?;
                }
            }
            10 => {
                self.st.modal.motion = 10;
                // A G01 whose axis words all name torque axes only sets torques.
                let torque_only = self.st.torque_axes != 0
                    && b"XYZABCUVW"
                        .iter()
                        .enumerate()
                        .all(|(i, c)| !w.has(*c) || (i < 6 && self.st.torque_axes & (1 << i) != 0));
                if (has_axes && !torque_only) || (self.ngc() && motion.is_some()) {
                    let t = self.target(w);
                    self.comp_move(t, false, bspan)?;
                }
            }
            20 | 30 => {
                self.st.modal.motion = mode;
                if has_axes || w.has(b'I') || w.has(b'J') || w.has(b'K') {
                    if let Err(e) = self.exec_arc(w, mode == 20, bspan) {
                        // An arc off its circle goes straight to its end; any other
                        // arc that cannot be made leaves the tool at its end.
                        let t = self.target(w);
                        self.recover_to = Some(if e.code == ARC_RADIUS_MISMATCH.code {
                            recover::Recover::Feed(t)
                        } else {
                            recover::Recover::SetPos(t)
                        });
                        return Err(e);
                    }
                }
            }
            50 | 51 if self.ngc() => {
                self.st.modal.motion = mode;
                self.exec_spline(w, mode == 51, bspan)?;
            }
            52 if self.ngc() => {
                self.st.modal.motion = 52;
                // A block without coordinates adds no control point: the first
                // one (where the tool is) is implied, as in LinuxCNC.
                if w.any_axis() {
                    let t = self.target(w);
                    let wgt = w.get(b'P').unwrap_or(1.0);
                    self.nurbs.push((t, wgt));
                }
            }
            760 if self.ngc() => {
                self.st.modal.motion = 760;
                self.exec_threading(w, bspan)?;
            }
            330 => {
                self.st.modal.motion = 330;
                let t = self.target(w);
                let k = w.get(b'K').map(|v| self.lin(v)).unwrap_or(0.0);
                canon!(self, "START_SPEED_FEED_SYNC({:.6},0)", k / self.unit());
                let s = self.canon_pos(&t);
                canon!(self, "STRAIGHT_FEED({s})");
                self.canon("STOP_SPEED_FEED_SYNCH()");
                let end = self.to_machine(t);
                let m = self.motion_base(MotionKind::Thread, self.st.mpos, end, k);
                self.out.motions.push(m);
                self.st.mpos = end;
                self.st.pos = t;
            }
            331 if self.ngc() => {
                self.st.modal.motion = 331;
                if self.st.spindle_dir == 0 {
                    return Err(self.err(&INTERP, bspan, "Spindle not turning in G33.1"));
                }
                let t = self.target(w);
                let k = w.get(b'K').map(|v| self.lin(v)).unwrap_or(0.0);
                let u = self.unit();
                canon!(self, "START_SPEED_FEED_SYNC({:.6},0)", k / u);
                canon!(
                    self,
                    "RIGID_TAP({}, {}, {})",
                    f4(t[0] / u),
                    f4(t[1] / u),
                    f4(t[2] / u)
                );
                self.canon("STOP_SPEED_FEED_SYNCH()");
                // The tap feeds in and reverses out: rs274 leaves the current point
                // where the block started.
                let start = self.st.mpos;
                let end = self.to_machine(t);
                let m = self.motion_base(MotionKind::Thread, start, end, k);
                self.out.motions.push(m);
                let m = self.motion_base(MotionKind::Thread, end, start, k);
                self.out.motions.push(m);
            }
            382..=385 => {
                if self.ngc() && !w.any_axis() {
                    return Err(self.err(&PROBE_STATE, bspan, "All axes missing with motion code"));
                }
                let t = self.target(w);
                // G38.3 and G38.5 report a failed probe in #5070 instead of
                // stopping, so LinuxCNC lets them start at their target.
                if self.ngc() && matches!(mode, 382 | 384) && dist(&self.st.pos, &t) == 0.0 {
                    return Err(self.err(&PROBE_STATE, bspan, "Start point too close to probe point: a G38.2/G38.4 move needs a target away from the current position"));
                }
                self.check_feed(bspan)?;
                self.canon("TURN_PROBE_ON()");
                let s = self.canon_pos(&t);
                canon!(self, "STRAIGHT_PROBE({s})");
                self.canon("TURN_PROBE_OFF()");
                let start = self.st.pos;
                let end = self.to_machine(t);
                let m = self.motion_base(MotionKind::Probe, self.st.mpos, end, self.st.feed);
                self.out.motions.push(m);
                // The probe trips at the target (no contact is simulated) and backs
                // off 0.254 mm / 0.01 in toward the start, as LinuxCNC's rs274 does.
                let d: f64 = (0..3)
                    .map(|i| (start[i] - t[i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let mut stop = t;
                if d > 0.0 && self.ngc() {
                    let back = if self.st.modal.inch { 0.01 } else { 0.254 };
                    for i in 0..3 {
                        stop[i] = t[i] + back * (start[i] - t[i]) / d;
                    }
                }
                self.st.mpos = self.to_machine(stop);
                self.st.pos = stop;
                // #5061… hold the trip point itself.
                for (k, v) in t.iter().enumerate() {
                    self.set_param(5061 + k, Some(*v));
                }
                // #5070 (probe tripped) reads 0 after every probe move in the
                // standalone rs274, so `while [#5070 NE 0]` retry loops end.
                if self.ngc() {
                    self.set_param(5070, Some(0.0));
                }
            }
            23 | 33 | 22 | 32 => {
                self.st.modal.motion = mode;
                let mut t = self.target(w);
                self.check_feed(bspan)?;
                let end = self.to_machine(t);
                let kind = if mode == 23 || mode == 33 {
                    self.exponential_kind(w, &mut t)
                } else {
                    self.involute_kind(w, &end, mode == 32)
                };
                let end = self.to_machine(t);
                let m = self.motion_base(kind, self.st.mpos, end, self.st.feed);
                self.out.motions.push(m);
                self.st.mpos = end;
                self.st.pos = t;
            }
            700 | 710..=712 | 720..=722 if self.ngc() => self.exec_g7x(mode, w, bspan)?,
            m if is_cycle(m) && (motion.is_some() || has_axes) => {
                if let Err(e) = self.exec_cycle(m, w, bspan) {
                    // A cycle that cannot run leaves the tool over its hole, at the
                    // height it had.
                    let mut t = self.target(w);
                    let n = self.normal_axis();
                    t[n] = self.st.pos[n];
                    self.recover_to = Some(recover::Recover::SetPos(t));
                    return Err(e);
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// The motion kind of a G02.2/G03.2 block ending at machine point `end`: the
    /// involute of the base circle (radius R, centre start + I/J/K in the plane)
    /// through the start. Undefined curves (the checks report them) leave a
    /// straight move.
    pub(super) fn involute_kind(&self, w: &Words, end: &[f64; 6], ccw: bool) -> MotionKind {
        let (a, b) = self.plane_axes();
        let (la, lb) = (b"IJK"[a.min(2)], b"IJK"[b.min(2)]);
        let (Some(i), Some(j), Some(r)) = (w.get(la), w.get(lb), w.get(b'R')) else {
            return MotionKind::Feed;
        };
        let lu = self.lu();
        let (i, j, r) = (self.lin(i) * lu, self.lin(j) * lu, self.lin(r).abs() * lu);
        let s = [self.st.mpos[a] * lu, self.st.mpos[b] * lu];
        let e = [end[a] * lu, end[b] * lu];
        match crate::interp::involute::InvoluteCurve::new(s, e, [s[0] + i, s[1] + j], r, ccw) {
            Some(curve) => MotionKind::Involute {
                curve,
                axes: [a as u8, b as u8],
            },
            None => MotionKind::Feed,
        }
    }

    /// The motion kind of a G02.3/G03.3 block, with A's end in `t`: A turns by
    /// the exponential curve's rotation (the format has no A word). Undefined
    /// curves (SW045 reports them) leave a straight move.
    pub(super) fn exponential_kind(&mut self, w: &Words, t: &mut [f64; 6]) -> MotionKind {
        let lu = self.lu();
        let (i, j, r) = (w.get(b'I'), w.get(b'J'), w.get(b'R'));
        let curve = match (i, j, r) {
            (Some(i), Some(j), Some(r)) => crate::interp::exponential::ExpCurve::new(
                i,
                j,
                r * lu,
                self.st.pos[0] * lu,
                t[0] * lu,
                self.st.modal.motion == 33,
            ),
            _ => None,
        };
        let Some(curve) = curve else {
            return MotionKind::Feed;
        };
        t[3] = self.st.pos[3] + curve.a_travel();
        let end_feed = w.get(b'Q').map(|q| q * lu).unwrap_or(self.st.feed * lu);
        MotionKind::Exponential { curve, end_feed }
    }

    /// G5 (cubic) / G5.1 (quadratic) splines in the XY plane. The canonical
    /// output is LinuxCNC's `NURBS_FEED(n, ...)`; the motion is sampled.
    pub(super) fn exec_spline(
        &mut self,
        w: &Words,
        quadratic: bool,
        span: Span,
    ) -> Result<(), Diagnostic> {
        self.check_feed(span)?;
        let s0 = self.st.pos;
        let t = self.target(w);
        let (i, j) = (
            w.get(b'I').map(|v| self.lin(v)),
            w.get(b'J').map(|v| self.lin(v)),
        );
        let ctrl: Vec<[f64; 2]> = if quadratic {
            let c = [s0[0] + i.unwrap_or(0.0), s0[1] + j.unwrap_or(0.0)];
            vec![[s0[0], s0[1]], c, [t[0], t[1]]]
        } else {
            // Without I/J the first control point mirrors the previous spline's second one.
            let (pi, pj) = match (i, j) {
                (Some(a), Some(b)) => (a, b),
                _ => (-self.spline_pq.0, -self.spline_pq.1),
            };
            let p = w.get(b'P').map(|v| self.lin(v)).unwrap_or(0.0);
            let q = w.get(b'Q').map(|v| self.lin(v)).unwrap_or(0.0);
            self.spline_pq = (p, q);
            vec![
                [s0[0], s0[1]],
                [s0[0] + pi, s0[1] + pj],
                [t[0] + p, t[1] + q],
                [t[0], t[1]],
            ]
        };
        canon!(self, "NURBS_FEED({}, ...)", if quadratic { 3 } else { 4 });
        self.sampled_curve(&ctrl, t);
        Ok(())
    }

    pub(super) fn finish_nurbs(&mut self, span: Span) -> Result<(), Diagnostic> {
        let pts = std::mem::take(&mut self.nurbs);
        self.st.modal.motion = 800;
        if pts.is_empty() {
            return Ok(());
        }
        self.check_feed(span)?;
        canon!(self, "NURBS_FEED({}, ...)", pts.len() + 1);
        // Follow the control polygon: a close enough length for cycle time.
        let mut ctrl = vec![[self.st.pos[0], self.st.pos[1]]];
        ctrl.extend(pts.iter().map(|(p, _)| [p[0], p[1]]));
        let end = pts.last().map(|p| p.0).unwrap_or(self.st.pos);
        self.sampled_curve(&ctrl, end);
        Ok(())
    }

    /// Feed motions along a Bézier curve with these control points (de Casteljau).
    pub(super) fn sampled_curve(&mut self, ctrl: &[[f64; 2]], end: [f64; 6]) {
        const N: usize = 16;
        let start = self.st.pos;
        for k in 1..=N {
            let u = k as f64 / N as f64;
            let mut pts = ctrl.to_vec();
            while pts.len() > 1 {
                pts = pts
                    .windows(2)
                    .map(|w| {
                        [
                            w[0][0] + (w[1][0] - w[0][0]) * u,
                            w[0][1] + (w[1][1] - w[0][1]) * u,
                        ]
                    })
                    .collect();
            }
            let mut p = end;
            p[0] = pts[0][0];
            p[1] = pts[0][1];
            for i in 2..6 {
                p[i] = start[i] + (end[i] - start[i]) * u;
            }
            let m_end = self.to_machine(p);
            let feed = self.effective_feed(0.0);
            let m = self.motion_base(MotionKind::Feed, self.st.mpos, m_end, feed);
            self.out.motions.push(m);
            self.st.mpos = m_end;
        }
        self.st.pos = end;
        self.st.mpos = self.to_machine(end);
    }

    /// LinuxCNC's G76 threading cycle (lathe, XZ): passes at depths
    /// `I + J·pass^(1/R)` with compound angle Q, spring passes H, tapers E/L.
    pub(super) fn exec_threading(&mut self, w: &Words, span: Span) -> Result<(), Diagnostic> {
        use std::f64::consts::PI;
        if self.st.modal.comp != 400 {
            return Err(self.err(
                &CYCLE_STATE,
                span,
                "cannot use G76 threading cycle with cutter radius compensation on",
            ));
        }
        // The 2007 EMC2 limited G76 to G18 without X or Y and E up to half the
        // thread; LinuxCNC 2.9 runs all of these (checked against its rs274).
        let emc2 = self.variant == Variant::Emc2;
        if emc2 && self.st.modal.plane != 180 {
            return Err(self.err(
                &CYCLE_STATE,
                span,
                "G76 threading works only in the XZ plane: select G18 first",
            ));
        }
        let refused: &[u8] = if emc2 { b"XYABC" } else { b"ABC" };
        if let Some(c) = refused.iter().copied().find(|c| w.has(*c)) {
            return Err(self.err(
                &CYCLE_STATE,
                w.sp(c),
                format!(
                    "G76 does not accept {}: the thread runs along Z from the current position",
                    c as char
                ),
            ));
        }
        let i = w.get(b'I').map(|v| self.lin(v)).unwrap_or(0.0);
        let j = w.get(b'J').map(|v| self.lin(v)).unwrap_or(0.0);
        let k = w.get(b'K').map(|v| self.lin(v)).unwrap_or(0.0);
        if let Some(e) = w.get(b'E') {
            let e = self.lin(e);
            let zabs = self.target(w)[2];
            let half = (zabs - self.st.pos[2]).abs() / 2.0;
            if e > half + 1e-9 {
                let msg = "G76 taper length E is longer than half the thread: shorten E";
                if emc2 {
                    return Err(self.err(&CYCLE_STATE, w.sp(b'E'), msg));
                }
                self.diag(&CYCLE_STATE, Severity::Warning, w.sp(b'E'), msg);
            }
        }
        if i == 0.0 {
            return Err(self.err(&CYCLE_STATE, span, "in G76, I must not be 0"));
        }
        if j <= 0.0 {
            return Err(self.err(&CYCLE_STATE, span, "in G76, J must be greater than 0"));
        }
        if k <= j {
            return Err(self.err(&CYCLE_STATE, span, "in G76, K must be greater than J"));
        }
        // In diameter mode (G7) rs274 halves I, J and K after checking them, as it halves X:
        // they are diameters too.
        let (i, j, k) = if self.st.modal.diameter {
            (i / 2.0, j / 2.0, k / 2.0)
        } else {
            (i, j, k)
        };
        let end = self.target(w);
        let start = self.st.pos;
        let boring = i > 0.0;
        let safe_x = start[0];
        let full_dia_depth = i.abs();
        let start_depth = i.abs() + j.abs();
        let cut_increment = j.abs();
        let full_threadheight = k.abs();
        let end_depth = k.abs() + i.abs();
        let pitch = w.get(b'P').map(|v| self.lin(v)).unwrap_or(0.0);
        let mut compound = w.get(b'Q').unwrap_or(0.0) * PI / 180.0;
        if end[2] > start[2] {
            compound = -compound;
        }
        let spring = w.get(b'H').map(|h| h.max(0.0) as u32).unwrap_or(0);
        let degression = w.get(b'R').filter(|r| *r >= 1.0).unwrap_or(1.0);
        let mut taper = w.get(b'E').map(|v| self.lin(v)).unwrap_or(0.0).max(0.0);
        let taper_pitch = if taper > 0.0 {
            pitch * taper.hypot(full_threadheight) / taper
        } else {
            pitch
        };
        if end[2] > start[2] {
            taper = -taper;
        }
        let flags = w.get(b'L').map(|l| l.max(0.0) as u32).unwrap_or(0);
        let (entry, exit) = (flags & 1 != 0, flags & 2 != 0);
        let target_z = end[2] + k.abs() * compound.tan();
        let u = self.unit();
        let x_at = |d: f64| if boring { safe_x + d } else { safe_x - d };
        let pt = |x: f64, z: f64| {
            let mut p = start;
            p[0] = x;
            p[2] = z;
            p
        };
        let sync = |s: &mut Self, p: f64| canon!(s, "START_SPEED_FEED_SYNC({:.6},0)", p / u);
        let mut pass_no = 1.0f64;
        let mut depth = start_depth;
        let mut guard = 0;
        let mut passes: Vec<f64> = Vec::new();
        while depth < end_depth && guard < 100_000 {
            guard += 1;
            passes.push(depth);
            pass_no += 1.0;
            depth = full_dia_depth + cut_increment * pass_no.powf(1.0 / degression);
        }
        for _ in 0..=spring {
            passes.push(end_depth);
        }
        for depth in passes {
            let zoff = (depth - full_dia_depth) * compound.tan();
            self.rapid_to(pt(x_at(depth - end_depth), start[2] - zoff));
            if taper != 0.0 && entry {
                self.canon("DISABLE_FEED_OVERRIDE()");
                sync(self, taper_pitch);
                self.thread_to(
                    pt(x_at(depth - full_threadheight), start[2] - zoff),
                    taper_pitch,
                );
                self.thread_to(pt(x_at(depth), start[2] - zoff - taper), taper_pitch);
                sync(self, pitch);
            } else {
                self.rapid_to(pt(x_at(depth), start[2] - zoff));
                self.canon("DISABLE_FEED_OVERRIDE()");
                sync(self, pitch);
            }
            if taper != 0.0 && exit {
                self.thread_to(pt(x_at(depth), target_z - zoff + taper), pitch);
                sync(self, taper_pitch);
                self.thread_to(
                    pt(x_at(depth - full_threadheight), target_z - zoff),
                    taper_pitch,
                );
            } else {
                self.thread_to(pt(x_at(depth), target_z - zoff), pitch);
            }
            self.canon("STOP_SPEED_FEED_SYNCH()");
            self.rapid_to(pt(x_at(depth - end_depth), target_z - zoff));
            self.canon("ENABLE_FEED_OVERRIDE()");
        }
        self.rapid_to(end);
        Ok(())
    }

    /// A spindle-synchronised straight move (pitch in mm/rev).
    pub(super) fn thread_to(&mut self, t: [f64; 6], pitch: f64) {
        if self.canon.is_some() {
            let s = self.canon_pos(&t);
            canon!(self, "STRAIGHT_FEED({s})");
        }
        let end = self.to_machine(t);
        let m = self.motion_base(MotionKind::Thread, self.st.mpos, end, pitch);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
    }

    pub(super) fn exec_arc(&mut self, w: &Words, cw: bool, bspan: Span) -> Result<(), Diagnostic> {
        let (a, b) = self.plane_axes();
        let n = self.normal_axis();
        let t = self.target(w);
        let ijk = [b'I', b'J', b'K'];
        let (ca, cb) = (ijk[a], ijk[b]);
        let s2 = [self.st.pos[a], self.st.pos[b]];
        let e2 = [t[a], t[b]];
        let has_r = w.has(b'R');
        let has_c = w.has(ca) || w.has(cb);
        let span = w
            .g()
            .iter()
            .find(|(g, _)| *g == 20 || *g == 30)
            .map(|x| x.1)
            .unwrap_or(bspan);
        if self.st.modal.polar && !self.ngc() && has_c {
            self.diag(
                &ARC_POLAR_IJK,
                Severity::Error,
                span,
                "I/J/K centre words cannot be used in polar coordinate mode (G16): use R",
            );
        }
        if !has_r && !has_c {
            if self.ngc() {
                return Err(self.err(
                    &ARC_NO_CENTER,
                    span,
                    "R, I, J and K words all missing for arc",
                ));
            }
            self.diag(
                &ARC_NO_CENTER,
                Severity::Error,
                span,
                "arc without R or centre words (I/J/K)",
            );
            self.feed_to(t, bspan)?;
            return Ok(());
        }
        if has_r && has_c && self.ngc() && self.canon.is_some() {
            return Err(self.err(
                &ARC_NO_CENTER,
                w.sp(b'R'),
                "Mixed radius ijk format for arc",
            ));
        }
        if has_r && has_c && self.dialect == Dialect::Servoworks {
            return Err(self.err(
                &ARC_NO_CENTER,
                w.sp(b'R'),
                "R and I/J/K in one arc block: the control reports an error",
            ));
        }
        let spec = if has_r {
            ArcSpec::R(self.lin(w.get(b'R').unwrap_or(0.0)))
        } else {
            let oa = w.get(ca).map(|v| self.lin(v)).unwrap_or(0.0);
            let ob = w.get(cb).map(|v| self.lin(v)).unwrap_or(0.0);
            if self.st.modal.ijk_abs {
                ArcSpec::Center([oa, ob])
            } else {
                ArcSpec::Center([s2[0] + oa, s2[1] + ob])
            }
        };
        let inch = self.st.modal.inch;
        let result = match self.dialect {
            Dialect::Rs274ngc => {
                arc::solve_ngc(s2, e2, spec, cw, inch, self.variant == Variant::Emc2)
            }
            Dialect::Fanuc => arc::solve_fanuc(s2, e2, spec, cw, self.cfg.arc_radius_tolerance),
            Dialect::Servoworks => {
                let mu = self.cfg.machine_unit;
                let tol = self.cfg.circle_error_allowance.max((2.0 * mu * mu).sqrt());
                arc::solve_servoworks(s2, e2, spec, cw, tol)
            }
        };
        let sol = match result {
            Ok(s) => s,
            Err(e) => return Err(self.arc_error(e, s2, e2, spec, span)),
        };
        // A mismatch within the machine-unit bound √(m1² + m2²) is what rounding end points and
        // centres to the machine unit leaves (CAM output); the manual (§6.3.3 Limitations) runs
        // such arcs without complaint, so only a correction beyond it is worth a warning.
        let resolution = (2.0 * self.cfg.machine_unit * self.cfg.machine_unit).sqrt();
        if sol.corrected && self.dialect == Dialect::Servoworks && sol.mismatch > resolution {
            let rule = if has_r {
                &ARC_CORRECTED_R
            } else {
                &ARC_CORRECTED_IJK
            };
            self.diag(
                rule,
                Severity::Warning,
                span,
                format!(
                    "arc corrected within the circle error allowance (mismatch {:.4} mm): radius {:.4}, centre ({:.4}, {:.4})",
                    sol.mismatch, sol.radius, sol.center[0], sol.center[1]
                ),
            );
        }
        self.check_feed(bspan)?;
        let turns = match w.get(b'P') {
            Some(p) if self.ngc() || self.dialect == Dialect::Fanuc && w.has(b'L') => {
                (p.round() as i32).max(1)
            }
            _ => w
                .get(b'L')
                .filter(|_| self.dialect == Dialect::Fanuc)
                .map(|l| (l.round() as i32).max(1))
                .unwrap_or(1),
        };
        // Canon: ARC_FEED(first_end, second_end, first_centre, second_centre, rotation, normal_end, a, b, c).
        let u = self.unit();
        if self.st.modal.feed_mode == 930 {
            let len = arc_len(
                s2,
                e2,
                sol.center,
                sol.radius,
                cw,
                turns - 1,
                t[n] - self.st.pos[n],
            );
            canon!(self, "SET_FEED_RATE({})", f4(len * self.st.feed / u));
        }
        let rot = if cw { -turns } else { turns };
        let pe = e2;
        let ca = self.comp_arc(t, e2, sol.center, sol.radius, rot, span)?;
        let (e2, t, radius, center) = (ca.end, ca.target, ca.radius, ca.center);
        // A lathe tool's controlled point is its origin, not the centre of its nose radius.
        let shift = self.lathe_origin([0.0; 6]);
        let t_out = self.lathe_origin(t);
        // Adding a zero shift would turn a -0 (which rs274 prints as -0.0000) into +0.
        let sh = |v: f64, d: f64| if d == 0.0 { v } else { v + d };
        let e2_out = [sh(e2[0], shift[a]), sh(e2[1], shift[b])];
        let center_out = [sh(center[0], shift[a]), sh(center[1], shift[b])];
        if self.canon.is_some() {
            canon!(
                self,
                "ARC_FEED({}, {}, {}, {}, {}, {}, {}, {}, {})",
                f4(e2_out[0] / u),
                f4(e2_out[1] / u),
                f4(center_out[0] / u),
                f4(center_out[1] / u),
                rot,
                f4(t[n] / u),
                f4(t[3]),
                f4(t[4]),
                f4(t[5])
            );
        }
        // Machine-frame geometry.
        let mut c3 = self.st.pos;
        c3[a] = center_out[0];
        c3[b] = center_out[1];
        let cm = self.to_machine(c3);
        // Counter-clockwise in each plane's (first, second) axes turns about the
        // positive normal axis, including G18's (Z, X).
        let mut normal = [0.0; 3];
        normal[n] = 1.0;
        let mirrored = self.st.modal.mirror && {
            let m = self.st.mirror.0;
            (m[a] as u8 + m[b] as u8) % 2 == 1
        };
        if cw != mirrored {
            for x in normal.iter_mut() {
                *x = -*x;
            }
        }
        let scale = if self.st.modal.scaling {
            self.st.scale.1[a]
        } else {
            1.0
        };
        let end = self.to_machine(t_out);
        let feed = self.effective_feed(0.0);
        let m = self.motion_base(
            MotionKind::Arc {
                center: [cm[0], cm[1], cm[2]],
                normal,
                turns: turns - 1,
                radius: radius * scale,
            },
            self.st.mpos,
            end,
            feed,
        );
        self.out.motions.push(m);
        self.st.mpos = end;
        if self.st.modal.comp != 400 && self.st.comp_radius > 0.0 {
            // The programmed point stays on the contour; the tool tip is offset.
            self.comp_hold(2, [0.0; 2], center, rot, ca.sweep);
            self.st.comp_tip = t;
            self.st.pos[a] = pe[0];
            self.st.pos[b] = pe[1];
            for i in 0..6 {
                if i != a && i != b {
                    self.st.pos[i] = t[i];
                }
            }
        } else {
            self.st.pos = t;
        }
        Ok(())
    }

    pub(super) fn arc_error(
        &self,
        e: ArcError,
        s: [f64; 2],
        en: [f64; 2],
        spec: ArcSpec,
        span: Span,
    ) -> Diagnostic {
        let d = self.dialect;
        match e {
            ArcError::SameEndR => {
                let msg = match d {
                    Dialect::Rs274ngc => "current point same as end point of arc: an R-format arc cannot be a full circle; use I/J/K".to_string(),
                    _ => "R-format arc with the end point equal to the start point: use I/J/K for a full circle".to_string(),
                };
                self.err(&ARC_SAME_END_R, span, msg)
            }
            ArcError::RadiusTooSmall(gap) => {
                let msg = match d {
                    Dialect::Rs274ngc => "arc radius too small to reach end point".to_string(),
                    Dialect::Fanuc => format!("arc radius too small to reach the end point by {gap:.4} mm (PS0020)"),
                    Dialect::Servoworks => format!(
                        "Invalid center point for circular interpolation: |R| is {gap:.4} mm shorter than half the chord, more than the circle error allowance ({:.4} mm)",
                        self.cfg.circle_error_allowance
                    ),
                };
                self.err(&ARC_RADIUS_TOO_SMALL, span, msg)
            }
            ArcError::RadiusMismatch(r1, r2) => {
                let c = match spec {
                    ArcSpec::Center(c) => c,
                    ArcSpec::R(_) => [0.0, 0.0],
                };
                let u = self.unit();
                let msg = match d {
                    Dialect::Rs274ngc => {
                        let (a, b) = match self.st.modal.plane {
                            180 => ('Z', 'X'),
                            190 => ('Y', 'Z'),
                            _ => ('X', 'Y'),
                        };
                        let abs_err = (r1 - r2).abs() / u;
                        format!(
                            "Radius to end of arc differs from radius to start: start=({a}{:.4},{b}{:.4}) center=({a}{:.4},{b}{:.4}) end=({a}{:.4},{b}{:.4}) r1={:.4} r2={:.4} abs_err={} rel_err={:.4}%",
                            s[0] / u,
                            s[1] / u,
                            c[0] / u,
                            c[1] / u,
                            en[0] / u,
                            en[1] / u,
                            r1 / u,
                            r2 / u,
                            fmt_g4(abs_err),
                            abs_err / (r1.max(r2) / u) * 100.0
                        )
                    }
                    Dialect::Fanuc => format!(
                        "end-point radius differs from start radius by {:.4} mm, more than parameter 3410 ({:.4} mm) (PS0020)",
                        (r1 - r2).abs(),
                        self.cfg.arc_radius_tolerance
                    ),
                    Dialect::Servoworks => format!(
                        "Invalid center point for circular interpolation: r1 = {r1:.4}, r2 = {r2:.4}, |r1 - r2| = {:.4} mm exceeds the circle error allowance ({:.4} mm)",
                        (r1 - r2).abs(),
                        self.cfg.circle_error_allowance
                    ),
                };
                self.err(&ARC_RADIUS_MISMATCH, span, msg)
            }
            ArcError::ZeroRadius => match (d, spec) {
                (Dialect::Rs274ngc, ArcSpec::Center(c)) => {
                    let u = self.unit();
                    let (a, b) = match self.st.modal.plane {
                        180 => ('Z', 'X'),
                        190 => ('Y', 'Z'),
                        _ => ('X', 'Y'),
                    };
                    let r1 = (s[0] - c[0]).hypot(s[1] - c[1]) / u;
                    let r2 = (en[0] - c[0]).hypot(en[1] - c[1]) / u;
                    let msg = format!(
                        "Zero-radius arc: start=({a}{:.4},{b}{:.4}) center=({a}{:.4},{b}{:.4}) end=({a}{:.4},{b}{:.4}) r1={r1:.4} r2={r2:.4}",
                        s[0] / u,
                        s[1] / u,
                        c[0] / u,
                        c[1] / u,
                        en[0] / u,
                        en[1] / u,
                    );
                    self.err(&ARC_RADIUS_MISMATCH, span, msg)
                }
                _ => self.err(&ARC_RADIUS_MISMATCH, span, "zero-radius arc"),
            },
        }
    }
}

fn arc_len(s: [f64; 2], e: [f64; 2], c: [f64; 2], r: f64, cw: bool, turns: i32, dz: f64) -> f64 {
    let sw = arc::sweep(s, e, c, cw, turns);
    (sw * r).hypot(dz)
}

/// C's `%.4g`.
fn fmt_g4(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exp = v.abs().log10().floor() as i32;
    if !(-4..4).contains(&exp) {
        let s = format!("{v:.3e}");
        // Rust prints `1.235e-5`; C prints `1.235e-05` and drops trailing zeros.
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        let e: i32 = e.parse().unwrap_or(0);
        return format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs());
    }
    let decimals = (3 - exp).max(0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The end point of a straight move from the block's axis words.
pub(crate) fn target_of(st: &State, ngc: bool, w: &Words) -> [f64; 6] {
    let lin = |v: f64| v * unit_of(ngc, st.modal.inch);
    let letters = [b'X', b'Y', b'Z', b'A', b'B', b'C'];
    let mut t = st.pos;
    let inc = st.modal.incremental;
    if ngc && (w.polar_r.is_some() || w.polar_a.is_some()) {
        // LinuxCNC polar words: radius/angle about the origin of the plane.
        let (a, b) = st.modal.plane_axes();
        let (x, y) = (t[a], t[b]);
        let (r0, th0) = (x.hypot(y), y.atan2(x));
        let (r, th) = if inc {
            (
                r0 + w.polar_r.map(lin).unwrap_or(0.0),
                th0 + w.polar_a.unwrap_or(0.0).to_radians(),
            )
        } else {
            (
                w.polar_r.map(lin).unwrap_or(r0),
                w.polar_a.map(f64::to_radians).unwrap_or(th0),
            )
        };
        t[a] = r * th.cos();
        t[b] = r * th.sin();
        let n = st.modal.normal_axis();
        for i in [n, 3, 4, 5] {
            if let Some(v) = w.get(letters[i]) {
                let v = if i < 3 { lin(v) } else { v };
                t[i] = if inc { t[i] + v } else { v };
            }
        }
        return t;
    }
    if st.modal.polar && !ngc {
        let (a, b) = st.modal.plane_axes();
        let pl = [b'X', b'Y', b'Z'];
        if w.has(pl[a]) || w.has(pl[b]) {
            let (r0, t0) = (
                st.pos[a].hypot(st.pos[b]),
                st.pos[b].atan2(st.pos[a]).to_degrees(),
            );
            let r = w
                .get(pl[a])
                .map(lin)
                .map(|v| if inc { r0 + v } else { v })
                .unwrap_or(r0);
            let th = w
                .get(pl[b])
                .map(|v| if inc { t0 + v } else { v })
                .unwrap_or(t0);
            t[a] = r * th.to_radians().cos();
            t[b] = r * th.to_radians().sin();
        }
        let n = st.modal.normal_axis();
        if let Some(v) = w.get(pl[n]) {
            let v = lin(v);
            t[n] = if inc { t[n] + v } else { v };
        }
        return t;
    }
    for i in 0..6 {
        if st.torque_axes & (1 << i) != 0 {
            continue;
        }
        if let Some(v) = w.get(letters[i]) {
            let v = if i < 3 { lin(v) } else { v };
            t[i] = if inc { t[i] + v } else { v };
        }
    }
    // FANUC/ServoWorks incremental addresses U V W on lathes are not modelled.
    t
}
