//! The streaming planner: a queue of planner elements ("tc"s, after LinuxCNC's
//! trajectory components), junction set-up when an element is queued, a backward
//! pass over the look-ahead window after every addition, and execution of the
//! oldest element once the window is full.

use std::collections::VecDeque;
use std::f64::consts::PI;

use super::profile::{scurve_penalty, trapezoid};
use super::servo::{self, Run, View};

mod blend;
mod chain;
mod optimize;
use super::{
    cross3, dist3, dot3, norm3, sub3, unit3, Causes, Event, MachineProfile, PathMode, PlannerModel,
    RapidPositioning, Segment, SegmentKind, SegmentTiming, Totals,
};
use blend::{start_accel_dir, Circ};
use chain::Chain;

/// Share of the acceleration arcs keep for the tangential direction until LinuxCNC
/// finalises them (`BLEND_ACC_RATIO_TANGENTIAL`).
const ACC_RATIO_TAN: f64 = 0.5;
/// Gap cycles below which a blend arc swallows the rest of the previous line.
const GAP_CYCLES: f64 = 4.0;
/// Short tangent segments below this duration use a linear velocity ramp
/// (1 / `ARC_BLEND_RAMP_FREQ`).
const RAMP_CUTOFF_S: f64 = 0.01;
/// Minimum number of servo cycles per optimised segment (`TP_MIN_SEGMENT_CYCLES`).
const MIN_SEGMENT_CYCLES: f64 = 1.02;
const POS_EPS: f64 = 1e-12;
/// Longest element (in servo periods at its target speed) run period by period.
const MAX_SERVO_CYCLES: f64 = 1e7;
const ANGLE_EPS: f64 = 1e-6;

fn acc_ratio_normal() -> f64 {
    (1.0 - ACC_RATIO_TAN * ACC_RATIO_TAN).sqrt()
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Term {
    Stop,
    Exact,
    Parabolic,
    Tangent,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TcType {
    Line,
    Circle,
    Blend,
    Path,
}

#[derive(Debug, Clone)]
struct Tc {
    ty: TcType,
    rapid: bool,
    rotary: bool,
    pure_rotary: bool,
    u_start: [f64; 3],
    u_end: [f64; 3],
    radius: f64,
    /// Geometry of a planar arc (None for lines, helices and blends).
    circ: Option<Circ>,
    target: f64,
    nominal: f64,
    reqvel: f64,
    maxvel: f64,
    maxaccel: f64,
    term: Term,
    tolerance: f64,
    kink_vel: f64,
    kink_reduce: f64,
    kink_reduce_prev: f64,
    blend_prev: bool,
    acc_ratio_tan: f64,
    finalized: bool,
    finalvel: f64,
    block: u32,
    tool: u32,
    /// LinuxCNC model: a parabolic junction on either side halves the acceleration.
    halve_parabolic: bool,
    /// The backward pass found this element's final speed capped by a speed limit
    /// rather than by the look-ahead (LinuxCNC never clears the flag).
    at_max: bool,
    /// The backward pass has set `finalvel` at least once.
    optimized: bool,
    /// Highest target speed (when queued) of this element and the older ones
    /// joined to it by tangent junctions: a `finalvel` at or above it is spent
    /// only as that speed, by this element and every older one of the run.
    run_vmax: f64,
    /// A rapid whose axes move independently (dog-leg): limits of its slowest
    /// axis scaled to the line, no path speed cap, a stop at both ends.
    dogleg: bool,
    /// Path length travelled, when it differs from `target` (dog-leg rapids).
    travel: Option<f64>,
    /// Programmed feed, mm/s (infinite without one): what the time causes
    /// measure the element against.
    feed: f64,
    /// The speed the axis velocity limits alone allow, mm/s (an arc's
    /// centripetal limit can be lower).
    axis_vel: f64,
    /// Servo-period execution state.
    run: Run,
}

impl Tc {
    fn overall_accel(&self) -> f64 {
        let mut s = 1.0 - self.kink_reduce.max(self.kink_reduce_prev);
        if self.halve_parabolic && (self.blend_prev || self.term == Term::Parabolic) {
            s *= 0.5;
        }
        self.maxaccel * s
    }

    fn tangential_accel(&self) -> f64 {
        let a = self.overall_accel();
        match self.ty {
            TcType::Circle | TcType::Blend | TcType::Path => a * self.acc_ratio_tan,
            TcType::Line => a,
        }
    }

    /// Highest target speed with feed override at most 1 (`tcGetMaxTargetVel`).
    fn max_target_vel(&self) -> f64 {
        self.reqvel.min(self.maxvel)
    }
}

/// The streaming planner. See the module documentation of [`super`].
pub struct Planner {
    p: MachineProfile,
    model: PlannerModel,
    vel: [f64; 6],
    /// Per-axis rapid rates (G0), X Y Z A B C.
    rapid: [f64; 6],
    acc: [f64; 6],
    cycle: f64,
    depth: usize,
    queue: VecDeque<Tc>,
    v_cur: f64,
    t: f64,
    run_start: f64,
    /// Time the next element may start before the previous one ends (parabolic blend).
    overlap: f64,
    totals: Totals,
    /// Straight feed moves held back by the `linuxcnc` model's naive-CAM detector.
    chain: Chain,
    /// Spindle speed, rpm: positive clockwise, negative counter-clockwise.
    spindle_rpm: f64,
    /// The speed where the last executed element ended was set by a corner.
    entry_corner: bool,
}

impl Planner {
    pub fn new(profile: &MachineProfile) -> Planner {
        let (vel, acc) = profile.xyzabc_limits();
        let rapid: [f64; 6] = std::array::from_fn(|i| {
            profile
                .axis(['X', 'Y', 'Z', 'A', 'B', 'C'][i])
                .map(|a| a.rapid_rate)
                .unwrap_or(0.0)
        });
        let cycle = if profile.servo_period > 0.0 {
            profile.servo_period
        } else {
            0.001
        };
        Planner {
            p: profile.clone(),
            model: profile.planner,
            vel,
            rapid,
            acc,
            cycle,
            depth: profile.lookahead.max(1) as usize,
            queue: VecDeque::new(),
            v_cur: 0.0,
            t: 0.0,
            run_start: 0.0,
            overlap: 0.0,
            totals: Totals::default(),
            chain: Chain::default(),
            spindle_rpm: 0.0,
            entry_corner: false,
        }
    }

    fn lcnc(&self) -> bool {
        self.model == PlannerModel::Linuxcnc
    }

    /// Feeds one event; timings of elements that leave the look-ahead window are
    /// passed to `out`.
    pub fn push(&mut self, ev: Event, out: &mut dyn FnMut(SegmentTiming)) {
        match ev {
            Event::Motion(seg) => {
                if self.lcnc() {
                    if let Some(halves) = arc_as_lines(&seg) {
                        for half in halves {
                            self.push(Event::Motion(half), out);
                        }
                        return;
                    }
                }
                if self.lcnc() && chainable(&seg) {
                    if !self.chain.is_empty() && !self.chain.linkable(&seg) {
                        self.flush_chain(out);
                    }
                    self.chain.push(seg);
                } else {
                    self.flush_chain(out);
                    self.add_segment(&seg, out);
                }
            }
            Event::Dwell { seconds, .. } => {
                self.flush(out);
                let s = seconds.max(0.0);
                self.totals.dwell_s += s;
            }
            Event::ToolChange { .. } => {
                self.flush(out);
                let t = self.p.tool_change_time;
                self.totals.tool_change_s += t;
                self.totals.aux.tool_change_s += t;
                self.totals.aux.tool_changes += 1;
            }
            Event::ToolSelect { .. } => {
                let t = self.p.tool_select_time;
                if t > 0.0 {
                    self.flush(out);
                    self.totals.aux.tool_select_s += t;
                    self.totals.other_s += t;
                }
            }
            Event::SpindleStart { rpm, .. } => {
                self.flush(out);
                let from = self.spindle_rpm;
                // A reversal runs down to rest and up again.
                let change = if from * rpm < 0.0 {
                    from.abs() + rpm.abs()
                } else {
                    (rpm - from).abs()
                };
                self.spindle_rpm = rpm;
                if change > 0.0 && change.is_finite() {
                    self.spindle_time(change);
                }
            }
            Event::SpindleStop { .. } => {
                self.flush(out);
                let from = std::mem::take(&mut self.spindle_rpm).abs();
                if from > 0.0 && from.is_finite() {
                    self.spindle_time(from);
                }
            }
            Event::ProgramStop { .. } => {
                self.flush(out);
                let t = self.p.program_stop_time;
                self.totals.other_s += t;
                self.totals.aux.program_stop_s += t;
                self.totals.aux.program_stops += 1;
            }
            Event::MCode { code, .. } => {
                let aux = &mut self.totals.aux;
                let (t, slot) = match code {
                    190 => (self.p.spindle_orient_time, &mut aux.orient_s),
                    70 | 80 | 90 => (self.p.coolant_time, &mut aux.coolant_s),
                    c if c == self.p.pallet_change_m.saturating_mul(10) => {
                        (self.p.pallet_change_time, &mut aux.pallet_change_s)
                    }
                    c => (self.p.m_code_seconds(c), &mut aux.m_code_s),
                };
                if t > 0.0 {
                    *slot += t;
                    self.totals.other_s += t;
                    self.flush(out);
                }
                if code == 190 {
                    // The spindle stops to orient.
                    self.spindle_rpm = 0.0;
                }
            }
        }
    }

    /// Charges a spindle speed change of `change` rpm.
    fn spindle_time(&mut self, change: f64) {
        let t = self.p.spindle_ramp_time + self.p.spindle_ramp_per_1000rpm * change / 1000.0;
        self.totals.aux.spindle_s += t;
        self.totals.other_s += t;
    }

    /// The totals so far: motion time counts only the elements executed yet.
    pub fn totals(&self) -> &Totals {
        &self.totals
    }

    /// Runs out the queue and returns the totals.
    pub fn finish(mut self, out: &mut dyn FnMut(SegmentTiming)) -> Totals {
        self.flush_chain(out);
        self.flush(out);
        let t = &mut self.totals;
        t.cycle_time_s = t.motion_s + t.dwell_s + t.tool_change_s + t.other_s;
        self.totals
    }

    fn add_segment(&mut self, seg: &Segment, out: &mut dyn FnMut(SegmentTiming)) {
        if let Some(tc) = self.build(seg) {
            self.add(tc, out);
        }
    }

    /// Sends the held-back moves on as one straight move.
    fn flush_chain(&mut self, out: &mut dyn FnMut(SegmentTiming)) {
        let Some((first, last)) = self.chain.take() else {
            return;
        };
        let mut seg = last;
        seg.start = first.start;
        let b = [first.start[0], first.start[1], first.start[2]];
        let e = [last.end[0], last.end[1], last.end[2]];
        seg.length = norm3(&sub3(&e, &b));
        self.add_segment(&seg, out);
    }

    /// Brings motion to a stop at the end of the queued path and executes it.
    fn flush(&mut self, out: &mut dyn FnMut(SegmentTiming)) {
        self.flush_chain(out);
        // LinuxCNC leaves the last move's junction type alone (a G64 move keeps its
        // halved acceleration); its final speed is zero either way.
        if !self.lcnc() {
            if let Some(back) = self.queue.back_mut() {
                back.term = Term::Stop;
            }
        }
        self.optimize();
        while !self.queue.is_empty() {
            self.execute_front(out);
        }
    }

    // ------------------------------------------------------------------ building

    /// Converts a segment into a planner element with the velocity and acceleration
    /// limits LinuxCNC's canonical layer derives from the axis limits.
    fn build(&self, seg: &Segment) -> Option<Tc> {
        let d: [f64; 6] = std::array::from_fn(|i| seg.end[i] - seg.start[i]);
        let dxyz = [d[0], d[1], d[2]];
        let xyz_len = norm3(&dxyz);
        let abc_len = (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]).sqrt();
        let cart = xyz_len > 1e-9;
        let ang = abc_len > 1e-9;
        let lcnc = self.lcnc();
        let (term, tolerance) = match seg.mode {
            PathMode::ExactStop => (Term::Stop, 0.0),
            PathMode::ExactPath => (Term::Exact, 0.0),
            PathMode::Blend { tolerance, .. } => {
                let tol = if tolerance > 0.0 {
                    tolerance
                } else {
                    self.p.default_blend_tolerance.max(0.0)
                };
                (Term::Parabolic, tol)
            }
        };
        let rapid = matches!(seg.kind, SegmentKind::Rapid);
        // Straight-move limits: the time the slowest axis needs at its own limit.
        let axis_time = |lim: &[f64; 6], sel: &dyn Fn(usize) -> bool| -> f64 {
            let mut t: f64 = 0.0;
            for i in 0..6 {
                if sel(i) && lim[i] > 0.0 && d[i] != 0.0 {
                    t = t.max(d[i].abs() / lim[i]);
                }
            }
            t
        };
        let sel: &dyn Fn(usize) -> bool = if cart && !ang {
            &|i| i < 3
        } else if ang && !cart {
            &|i| i >= 3
        } else {
            &|_| true
        };
        let mut tc = Tc {
            ty: TcType::Line,
            rapid,
            rotary: ang,
            pure_rotary: ang && !cart,
            u_start: unit3(&dxyz),
            u_end: unit3(&dxyz),
            radius: 0.0,
            circ: None,
            target: 0.0,
            nominal: 0.0,
            reqvel: 0.0,
            maxvel: 0.0,
            maxaccel: 0.0,
            term,
            tolerance,
            kink_vel: -1.0,
            kink_reduce: 0.0,
            kink_reduce_prev: 0.0,
            blend_prev: false,
            acc_ratio_tan: 1.0,
            finalized: false,
            finalvel: 0.0,
            block: seg.block,
            tool: seg.tool,
            halve_parabolic: lcnc,
            at_max: false,
            optimized: false,
            run_vmax: 0.0,
            dogleg: false,
            travel: None,
            feed: if seg.feed > 0.0 && !rapid {
                seg.feed
            } else {
                f64::INFINITY
            },
            axis_vel: f64::INFINITY,
            run: Run::default(),
        };
        let feed_cap = |v: f64| if v > 0.0 { v } else { f64::INFINITY };
        match seg.kind {
            SegmentKind::Rapid | SegmentKind::Line => {
                if !cart && !ang {
                    return None;
                }
                // Curves planned as lines (involutes, exponential moves) bring their
                // own path length, longer than the chord.
                let dtot = if cart {
                    xyz_len.max(seg.length)
                } else {
                    abc_len
                };
                // G0 runs each axis at most at its rapid rate (LinuxCNC: the same as
                // its maximum velocity).
                let tv = axis_time(if rapid { &self.rapid } else { &self.vel }, sel);
                let ta = axis_time(&self.acc, sel);
                let vmax = if tv > 0.0 {
                    dtot / tv
                } else {
                    feed_cap(seg.feed)
                };
                let amax = if ta > 0.0 {
                    dtot / ta
                } else {
                    self.p.traj_max_acceleration
                };
                tc.target = dtot;
                tc.maxvel = vmax;
                tc.axis_vel = vmax;
                tc.reqvel = if rapid {
                    vmax
                } else {
                    vmax.min(feed_cap(seg.feed))
                };
                tc.maxaccel = amax;
                if rapid && self.p.rapid_positioning == RapidPositioning::Independent {
                    self.dogleg(&mut tc, seg, dtot);
                }
            }
            SegmentKind::Arc {
                center,
                normal,
                radius,
                sweep,
            } => {
                let n = unit3(&normal);
                if norm3(&n) == 0.0 || radius <= 0.0 || sweep == 0.0 {
                    return None;
                }
                let s3 = [seg.start[0], seg.start[1], seg.start[2]];
                let e3 = [seg.end[0], seg.end[1], seg.end[2]];
                let rise = dot3(&dxyz, &n);
                let planar = radius * sweep.abs();
                let total = (planar * planar + rise * rise).sqrt();
                if total < POS_EPS {
                    return None;
                }
                // The two axes of the arc's plane: the ones the normal does not point along.
                let k = (0..3)
                    .max_by(|a, b| n[*a].abs().total_cmp(&n[*b].abs()))
                    .unwrap_or(2);
                let (i1, i2) = ((k + 1) % 3, (k + 2) % 3);
                let present = |lim: &[f64; 6], i: usize| {
                    if lim[i] > 0.0 {
                        lim[i]
                    } else {
                        f64::INFINITY
                    }
                };
                let v_axes = present(&self.vel, i1).min(present(&self.vel, i2));
                let a_axes = present(&self.acc, i1).min(present(&self.acc, i2));
                let a_normal = a_axes * 3f64.sqrt() / 2.0;
                let v_radial = (a_normal * radius).sqrt();
                let v_planar = v_radial.min(v_axes);
                let t_motion = axis_time(&self.vel, &|_| true);
                let t_spiral = planar / v_planar;
                let t_max = t_motion.max(t_spiral);
                let vmax = if t_max > 0.0 { total / t_max } else { v_planar };
                let t_axes = t_motion.max(planar / v_axes);
                tc.axis_vel = if t_axes > 0.0 { total / t_axes } else { v_axes };
                let tt_motion = axis_time(&self.acc, &|_| true);
                let tt_spiral = planar / a_axes;
                let tt = tt_motion.max(tt_spiral);
                let amax = if tt > 0.0 { total / tt } else { a_axes };
                tc.ty = TcType::Circle;
                tc.radius = if lcnc {
                    helix_effective_radius(radius, &sub3(&e3, &center), &n, rise, sweep)
                } else {
                    radius
                };
                tc.target = total;
                tc.maxvel = vmax;
                tc.reqvel = vmax.min(feed_cap(seg.feed));
                tc.maxaccel = amax;
                tc.acc_ratio_tan = ACC_RATIO_TAN;
                let sign = if sweep >= 0.0 { 1.0 } else { -1.0 };
                let in_plane = |p: &[f64; 3]| -> [f64; 3] {
                    let r = sub3(p, &center);
                    let along = dot3(&r, &n);
                    [
                        r[0] - along * n[0],
                        r[1] - along * n[1],
                        r[2] - along * n[2],
                    ]
                };
                // LinuxCNC runs an arc whose end is off its circle (rounded
                // coordinates) as a spiral, and its tangents lean by the change of
                // radius; chained arcs then meet at a small kink it plans for.
                let spiral = if lcnc {
                    norm3(&in_plane(&e3)) - norm3(&in_plane(&s3))
                } else {
                    0.0
                };
                let tangent = |p: &[f64; 3]| -> [f64; 3] {
                    let r = in_plane(p);
                    let t = unit3(&cross3(&n, &r));
                    let u = unit3(&r);
                    let turn = if lcnc {
                        norm3(&r) * sweep.abs()
                    } else {
                        planar
                    };
                    let mut v = [0.0; 3];
                    for i in 0..3 {
                        v[i] = t[i] * sign * turn + n[i] * rise + u[i] * spiral;
                    }
                    unit3(&v)
                };
                tc.u_start = tangent(&s3);
                tc.u_end = tangent(&e3);
                if rise.abs() < 1e-9 {
                    let n_eff = if sweep >= 0.0 {
                        n
                    } else {
                        [-n[0], -n[1], -n[2]]
                    };
                    let r0 = sub3(&s3, &center);
                    let along = dot3(&r0, &n);
                    let c_plane = [
                        center[0] + along * n[0],
                        center[1] + along * n[1],
                        center[2] + along * n[2],
                    ];
                    tc.circ = Some(Circ {
                        center: c_plane,
                        normal: n_eff,
                        start: s3,
                        angle: sweep.abs(),
                        radius: norm3(&in_plane(&s3)),
                        spiral,
                    });
                }
                if !lcnc {
                    tc.acc_ratio_tan = 1.0;
                    tc.maxaccel = tc.maxaccel.min(a_axes);
                    tc.maxvel = tc.maxvel.min((a_axes * radius).sqrt());
                    tc.reqvel = tc.reqvel.min(tc.maxvel);
                }
            }
            SegmentKind::Path {
                start_tangent,
                end_tangent,
                max_curvature,
            } => {
                if seg.length < POS_EPS {
                    return None;
                }
                let v_axes = (0..3)
                    .filter(|i| self.vel[*i] > 0.0)
                    .map(|i| self.vel[i])
                    .fold(f64::INFINITY, f64::min);
                let a_axes = (0..3)
                    .filter(|i| self.acc[*i] > 0.0)
                    .map(|i| self.acc[i])
                    .fold(f64::INFINITY, f64::min);
                let v_curv = if max_curvature > 0.0 {
                    (a_axes * acc_ratio_normal() / max_curvature).sqrt()
                } else {
                    f64::INFINITY
                };
                tc.ty = TcType::Path;
                tc.target = seg.length;
                tc.axis_vel = v_axes;
                tc.maxvel = v_axes.min(v_curv);
                tc.reqvel = tc.maxvel.min(feed_cap(seg.feed));
                tc.maxaccel = a_axes;
                tc.acc_ratio_tan = if lcnc { ACC_RATIO_TAN } else { 1.0 };
                tc.u_start = unit3(&start_tangent);
                tc.u_end = unit3(&end_tangent);
            }
        }
        if !tc.maxvel.is_finite() {
            tc.maxvel = self.p.traj_max_velocity;
        }
        if !tc.maxaccel.is_finite() || tc.maxaccel <= 0.0 {
            tc.maxaccel = self.p.traj_max_acceleration.min(1e6);
        }
        if !lcnc && !tc.dogleg {
            // The generic models honour the path acceleration cap.
            tc.maxaccel = tc.maxaccel.min(self.p.traj_max_acceleration);
        }
        tc.nominal = tc.target;
        // Every segment takes at least one servo period.
        tc.maxvel = tc.maxvel.min(tc.target / self.cycle);
        Some(tc)
    }

    /// Makes `tc` a dog-leg rapid of path length `dtot`: each axis runs its own
    /// trapezoid, so the move lasts as long as the slowest axis's. Scaling that
    /// axis's rapid rate and acceleration by `dtot / dᵢ` gives a path trapezoid of
    /// exactly that duration (a trapezoid's time does not change when distance,
    /// speed and acceleration scale together), run from rest to rest.
    fn dogleg(&self, tc: &mut Tc, seg: &Segment, dtot: f64) {
        // A rapid override above 100 % cannot pass the axes' rates.
        let ovr = self.p.rapid_override.clamp(0.0, 1.0);
        let mut slowest: Option<(f64, usize)> = None;
        for i in 0..6 {
            let d = (seg.end[i] - seg.start[i]).abs();
            let (v, a) = (self.rapid[i] * ovr, self.acc[i]);
            if d == 0.0 || v <= 0.0 || a <= 0.0 {
                continue;
            }
            let t = trapezoid(d, 0.0, v, 0.0, a).time;
            if slowest.is_none_or(|(ts, _)| t > ts) {
                slowest = Some((t, i));
            }
        }
        let Some((_, i)) = slowest else {
            return;
        };
        let k = dtot / (seg.end[i] - seg.start[i]).abs();
        tc.maxvel = self.rapid[i] * k;
        tc.reqvel = tc.maxvel;
        tc.maxaccel = self.acc[i] * k;
        tc.term = Term::Stop;
        tc.dogleg = true;
        if !tc.pure_rotary {
            let rate: [f64; 6] = std::array::from_fn(|j| self.rapid[j] * ovr);
            let path = super::dogleg_path(&seg.start, &seg.end, &rate, &self.acc);
            tc.travel = Some(super::polyline_length(&path));
        }
    }

    // ------------------------------------------------------------------ queueing

    fn add(&mut self, mut tc: Tc, out: &mut dyn FnMut(SegmentTiming)) {
        // Rapid and feed moves are never blended, and every axis of a dog-leg
        // rapid starts from rest.
        let stop = |prev: &Tc, tc: &Tc| prev.rapid != tc.rapid || tc.dogleg;
        // The newest element is set up where it is (an element is several hundred
        // bytes); the junctions read no other element.
        let mut queue = std::mem::take(&mut self.queue);
        if let Some(prev) = queue.back_mut() {
            if stop(prev, &tc) {
                set_term(prev, Some(&mut tc), Term::Stop);
            }
            if self.lcnc() {
                // A blend arc may swallow the older element, and goes after it.
                let (blend, consumed) = self.lcnc_junction(prev, &mut tc);
                if consumed {
                    queue.pop_back();
                } else {
                    self.finalize(prev);
                }
                if let Some(b) = blend {
                    queue.push_back(b);
                }
            } else {
                self.generic_junction(prev, &mut tc);
                self.finalize(prev);
            }
        }
        self.queue = queue;
        let v = self.real_target_vel(&tc);
        tc.run_vmax = match self.queue.back() {
            Some(prev) if prev.term == Term::Tangent => prev.run_vmax.max(v),
            _ => v,
        };
        self.queue.push_back(tc);
        self.optimize();
        while self.queue.len() > self.depth + 2 {
            self.execute_front(out);
        }
    }

    /// `tcFinalizeLength`: the element's length can no longer change.
    fn finalize(&self, tc: &mut Tc) {
        if tc.finalized {
            return;
        }
        tc.maxvel = tc.maxvel.min(tc.target / self.cycle);
        if tc.ty == TcType::Circle && self.lcnc() {
            let a_max = tc.overall_accel();
            let a_n_cut = acc_ratio_normal() * a_max;
            let r = tc.radius.max(1e-12);
            let a_n_vmax = tc.maxvel * tc.maxvel / r;
            if a_n_vmax > a_n_cut {
                tc.maxvel = (a_n_cut * r).sqrt();
            } else if a_max > 0.0 {
                tc.acc_ratio_tan = (1.0 - (a_n_vmax / a_max).powi(2)).max(0.0).sqrt();
            }
        }
        tc.finalized = true;
    }

    /// LinuxCNC junction set-up (`tpSetupTangent`, `tpHandleBlendArc`). Returns the
    /// blend arc to insert and whether `prev` was swallowed by it.
    fn lcnc_junction(&self, prev: &mut Tc, tc: &mut Tc) -> (Option<Tc>, bool) {
        if tc.rotary || prev.rotary || prev.term == Term::Stop {
            return (None, false);
        }
        let u1 = prev.u_end;
        let u2 = tc.u_start;
        let sum = [u1[0] + u2[0], u1[1] + u2[1], u1[2] + u2[2]];
        let sharp = (PI * 2.0 / 180.0).powi(2);
        if dot3(&sum, &sum) < sharp {
            set_term(prev, Some(tc), Term::Stop);
            return (None, false);
        }
        let v_max = prev.max_target_vel().min(tc.max_target_vel());
        let a_inst = v_max / self.cycle + tc.maxaccel;
        let mut scale: f64 = 0.0;
        for i in 0..3 {
            if self.acc[i] > 0.0 {
                scale = scale.max((a_inst * (u2[i] - u1[i]) / self.acc[i]).abs());
            }
        }
        if prev.ty == TcType::Circle || tc.ty == TcType::Circle {
            scale /= ACC_RATIO_TAN;
        }
        // LinuxCNC bounds the ratio to [0.001, 0.7071].
        let kink = self
            .p
            .tangent_kink_ratio
            .clamp(0.001, std::f64::consts::FRAC_1_SQRT_2);
        if scale < kink {
            set_term(prev, Some(tc), Term::Tangent);
            set_kink(prev, tc, v_max, scale);
            return (None, false);
        }
        set_kink(prev, tc, v_max * kink / scale, kink);
        if prev.term != Term::Parabolic {
            // Exact path: the corner stops, but both moves keep the reduced acceleration.
            return (None, false);
        }
        if !prev.finalized && !tc.finalized {
            if let Some(b) = self.blend_arc(prev, tc) {
                let perf_arc = b.arc.maxvel;
                let perf_par = self.parabolic_performance(prev, tc) / 2.0;
                let perf_tan = prev.kink_vel;
                if perf_arc > perf_par && perf_arc > perf_tan {
                    remove_kink(prev, tc);
                    tc.target = (tc.target - b.trim_next).max(0.0);
                    if let Some(c) = b.next_circ {
                        tc.circ = Some(c);
                        tc.u_start = c.tangent(0.0);
                    }
                    set_term(prev, Some(tc), Term::Tangent);
                    if !b.consume {
                        prev.target = (prev.target - b.trim_prev).max(0.0);
                        if let Some(c) = b.prev_circ {
                            prev.circ = Some(c);
                            prev.u_end = c.tangent(c.angle);
                        }
                    }
                    return (Some(b.arc), b.consume);
                }
            }
        }
        // No arc: the better of a parabolic blend and an approximate tangent.
        let perf_par = self.parabolic_performance(prev, tc) / 2.0;
        if perf_par >= prev.kink_vel {
            remove_kink(prev, tc);
            set_term(prev, Some(tc), Term::Parabolic);
        } else {
            set_term(prev, Some(tc), Term::Tangent);
        }
        (None, false)
    }

    /// `estimateParabolicBlendPerformance`: net speed through a parabolic blend.
    fn parabolic_performance(&self, prev: &Tc, tc: &Tc) -> f64 {
        let (vb1, vb2, theta) = self.parabolic_blend_vel(prev, tc);
        theta.sin() * (vb1 + vb2) / 2.0
    }

    /// `tpComputeBlendVelocity`: the speeds at which a parabolic blend starts on
    /// each side, and the intersection half-angle.
    fn parabolic_blend_vel(&self, a: &Tc, b: &Tc) -> (f64, f64, f64) {
        let acc1 = a.tangential_accel().max(1e-9);
        let acc2 = b.tangential_accel().max(1e-9);
        let tv1 = self.real_target_vel(a);
        let tv2 = self.real_target_vel(b);
        let tri = |t: &Tc| {
            let l = if t.finalized {
                t.target
            } else {
                t.target / 2.0
            };
            (t.tangential_accel() * l).sqrt()
        };
        let vr1 = tri(a).min(tv1).max(1e-9);
        let vr2 = tri(b).min(tv2).max(1e-9);
        let t_reach = (a.target / vr1).min(b.target / vr2);
        let t_blend = t_reach.min((vr1 / acc1).max(vr2 / acc2));
        let mut v1 = vr1.min(t_blend * acc1);
        let mut v2 = vr2.min(t_blend * acc2);
        let theta = (-dot3(&a.u_end, &start_accel_dir(b)))
            .clamp(-1.0, 1.0)
            .acos()
            / 2.0;
        if a.tolerance > 0.0 {
            let c = theta.cos();
            if c > (PI / 2.0 - 1e-3).cos() {
                let tb = 2.0 * (acc1 * a.tolerance / c).sqrt();
                v1 = v1.min(tb);
                v2 = v2.min(tb);
            }
        }
        (v1, v2, theta)
    }

    /// Generic models: corner speed from the blend tolerance.
    fn generic_junction(&self, prev: &mut Tc, tc: &mut Tc) {
        if prev.term == Term::Stop {
            return;
        }
        let u1 = prev.u_end;
        let u2 = tc.u_start;
        let c = dot3(&u1, &u2).clamp(-1.0, 1.0);
        if prev.term == Term::Exact {
            // Exact path: run through joints that are tangent within 1°.
            if c > (PI / 180.0).cos() {
                set_term(prev, Some(tc), Term::Tangent);
            } else {
                set_term(prev, Some(tc), Term::Stop);
            }
            return;
        }
        let theta = (-c).acos() / 2.0;
        if theta < ANGLE_EPS {
            set_term(prev, Some(tc), Term::Stop);
            return;
        }
        let v_corner = if PI / 2.0 - theta < ANGLE_EPS {
            f64::INFINITY
        } else {
            let tol = if prev.tolerance > 0.0 {
                prev.tolerance
            } else {
                prev.nominal.min(tc.nominal) * 0.25
            };
            let s = theta.sin();
            let r_tol = tol * s / (1.0 - s);
            let r_len = theta.tan() * prev.nominal.min(tc.nominal) * 0.5;
            let a = prev.maxaccel.min(tc.maxaccel);
            (a * r_tol.min(r_len)).sqrt()
        };
        set_term(prev, Some(tc), Term::Tangent);
        prev.kink_vel = v_corner;
    }

    // ------------------------------------------------------------------ planning

    /// `tpGetRealTargetVel` with the profile's overrides.
    fn real_target_vel(&self, tc: &Tc) -> f64 {
        let scale = if tc.rapid {
            self.p.rapid_override
        } else {
            self.p.feed_override
        };
        let mut v = (tc.reqvel * scale).min(tc.maxvel);
        // A dog-leg rapid has no path speed to cap.
        if !tc.pure_rotary && !tc.dogleg {
            v = v.min(self.p.traj_max_velocity);
        }
        v.max(0.0)
    }

    fn view(&self, tc: &Tc) -> View {
        View {
            target: tc.target,
            v_target: self.real_target_vel(tc),
            finalvel: tc.finalvel,
            tangent: tc.term == Term::Tangent,
            stop: matches!(tc.term, Term::Stop | Term::Exact),
            accel: tc.tangential_accel().max(1e-9),
        }
    }

    /// Executes the oldest queued element.
    fn execute_front(&mut self, out: &mut dyn FnMut(SegmentTiming)) {
        // Servo periods cost machine time; an absurdly slow move (a feed of a few
        // µm/min over metres) would take billions of them, so it runs in closed form.
        let servo_ok = self.queue.front().is_some_and(|tc| {
            let v = self.real_target_vel(tc);
            v > 0.0 && tc.target / v / self.cycle < MAX_SERVO_CYCLES
        });
        if self.lcnc() && self.p.servo_simulation && servo_ok {
            self.execute_front_servo(out);
        } else {
            self.execute_front_analytic(out);
        }
    }

    /// LinuxCNC model, period by period (see [`servo`]).
    fn execute_front_servo(&mut self, out: &mut dyn FnMut(SegmentTiming)) {
        let Some(mut tc) = self.queue.pop_front() else {
            return;
        };
        let cycle = self.cycle;
        let start = self.t;
        if !tc.run.active && tc.run.progress == 0.0 && tc.run.currentvel == 0.0 {
            // Entered from a closed-form element (or from rest).
            tc.run.currentvel = self.v_cur;
        }
        let v0 = tc.run.currentvel;
        let view = self.view(&tc);
        // A move that cannot move (zero feed) is skipped rather than run forever.
        let budget = if view.v_target > 0.0 {
            let pr = trapezoid(tc.target, 0.0, view.v_target, 0.0, view.accel);
            (pr.time * 4.0 / cycle) as u64 + 10_000
        } else {
            0
        };
        let mut cycles: u64 = 0;
        loop {
            if tc.run.remove || cycles >= budget {
                if tc.run.remove {
                    cycles += 1;
                }
                break;
            }
            if !tc.run.active {
                tc.run.active = true;
                let dist = tc.target - tc.run.progress;
                let denom = tc.run.currentvel + tc.finalvel.min(view.v_target);
                let seg_time = if denom > 0.0 {
                    2.0 * dist / denom
                } else {
                    f64::INFINITY
                };
                tc.run.ramp = seg_time < RAMP_CUTOFF_S
                    && !tc.rapid
                    && tc.term == Term::Tangent
                    && dist != 0.0;
            }
            if tc.run.splitting {
                // The element ends inside this period; the next one gets the rest.
                let next2 = self.queue.get(1).map(|n| self.real_target_vel(n));
                let next_view = self.queue.front().map(|n| self.view(n));
                if let (Some(next), Some(nv)) = (self.queue.front_mut(), next_view) {
                    if tc.term == Term::Tangent {
                        next.run.cycle_time = cycle - tc.run.cycle_time;
                        next.run.currentvel = tc.run.term_vel;
                    } else if next.run.cycle_time == 0.0 {
                        next.run.cycle_time = cycle;
                    }
                    servo::update_cycle(&mut next.run, &nv, next2, cycle);
                }
                cycles += 1;
                break;
            }
            tc.run.cycle_time = cycle;
            let next_t = self.queue.front().map(|n| self.real_target_vel(n));
            // Once a parabolic blend has started the next element moves in the same
            // periods, so they are not skipped.
            if !tc.run.blending_next {
                cycles += servo::cruise(&mut tc.run, &view, next_t, cycle, budget - cycles);
                if cycles >= budget {
                    continue;
                }
            }
            servo::update_cycle(&mut tc.run, &view, next_t, cycle);
            cycles += 1;
            if tc.term == Term::Parabolic {
                // Parabolic blend: once this element decelerates below the blend
                // speed, the next one starts moving in the same periods.
                if let Some(next) = self.queue.front() {
                    let (blend_vel, _, _) = self.parabolic_blend_vel(&tc, next);
                    tc.run.blending_next |= tc.run.on_final_decel && tc.run.currentvel < blend_vel;
                    if tc.run.blending_next {
                        let nv = self.view(next);
                        if let Some(next) = self.queue.front_mut() {
                            if next.run.cycle_time == 0.0 {
                                next.run.cycle_time = cycle;
                            }
                            servo::update_cycle(&mut next.run, &nv, None, cycle);
                        }
                    }
                }
            }
            if tc.run.remove {
                break;
            }
        }
        // A control that needs a minimum time per block cannot run shorter elements.
        let time = (cycles as f64 * cycle).max(self.p.block_processing_time);
        let end = start + time;
        self.t = end;
        let v_end = if tc.term == Term::Tangent {
            tc.run.term_vel
        } else {
            0.0
        };
        self.v_cur = v_end;
        if v_end <= 0.0 {
            self.run_start = end;
        }
        self.account(&tc, start, end, time, v0, tc.run.peak, v_end, out);
    }

    /// Executes the oldest queued element with closed-form profiles.
    fn execute_front_analytic(&mut self, out: &mut dyn FnMut(SegmentTiming)) {
        let Some(tc) = self.queue.pop_front() else {
            return;
        };
        let lcnc = self.lcnc();
        let v_target = self.real_target_vel(&tc);
        let next_target = self
            .queue
            .front()
            .map(|n| self.real_target_vel(n))
            .unwrap_or(0.0);
        let v_final = if tc.term == Term::Tangent {
            tc.finalvel.min(v_target).min(next_target)
        } else {
            0.0
        };
        let a = tc.tangential_accel().max(1e-9);
        let v0 = self.v_cur.min(v_target);
        let l = tc.target;
        let ramp_time = {
            let denom = v0 + tc.finalvel.min(v_target);
            if denom > 0.0 {
                2.0 * l / denom
            } else {
                f64::INFINITY
            }
        };
        let (time, v_end, v_peak) = if lcnc
            && !tc.rapid
            && tc.term == Term::Tangent
            && ramp_time < RAMP_CUTOFF_S
            && v_final > 0.0
        {
            // Short segment: linear velocity ramp from v0 to the final speed.
            let lo = (v0 * v0 - 2.0 * a * l).max(0.0).sqrt();
            let hi = (v0 * v0 + 2.0 * a * l).sqrt();
            let ve = v_final.clamp(lo, hi);
            let t = if v0 + ve > 0.0 {
                2.0 * l / (v0 + ve)
            } else {
                0.0
            };
            (t, ve, v0.max(ve))
        } else {
            let pr = trapezoid(l, v0, v_target, v_final, a);
            let mut t = pr.time;
            if self.model == PlannerModel::Scurve {
                let j = self.jerk();
                t += scurve_penalty(v0, pr.v_peak, pr.v_end, a, j);
            }
            (t, pr.v_end, pr.v_peak)
        };
        // A control that needs a minimum time per block cannot run shorter elements.
        let time = time.max(self.p.block_processing_time);
        // A parabolic blend lets this element start while the previous one is
        // still decelerating.
        let start = self.t - self.overlap.min(time);
        self.overlap = 0.0;
        if tc.term == Term::Parabolic {
            if let Some(next) = self.queue.front() {
                let (vb1, _, _) = self.parabolic_blend_vel(&tc, next);
                self.overlap = (vb1 / a).min(time);
            }
        }
        let mut end = start + time;
        if v_end <= 0.0 && self.overlap == 0.0 {
            if lcnc {
                // The servo loop finishes a stop-to-stop run on a period boundary.
                let run = end - self.run_start;
                let cycles = (run / self.cycle - 1e-6).ceil().max(0.0);
                let quantized = cycles * self.cycle;
                end = self.run_start + quantized.max(run);
            }
            self.run_start = end;
        }
        // The clock advances by the element's time less the shared overlap.
        let added = (end - self.t).max(0.0);
        self.t = end;
        self.v_cur = v_end;
        self.account(&tc, start, end, added, v0, v_peak, v_end, out);
        if v_end <= 0.0 && self.overlap == 0.0 && self.p.in_position_time > 0.0 {
            // Settling into the in-position window before the next block starts.
            self.t += self.p.in_position_time;
            self.run_start = self.t;
            self.totals.other_s += self.p.in_position_time;
            self.totals.aux.in_position_s += self.p.in_position_time;
        }
    }

    /// Adds an executed element to the totals and reports it.
    #[allow(clippy::too_many_arguments)]
    fn account(
        &mut self,
        tc: &Tc,
        start: f64,
        end: f64,
        added: f64,
        v0: f64,
        v_peak: f64,
        v_end: f64,
        out: &mut dyn FnMut(SegmentTiming),
    ) {
        let l = tc.target;
        let travelled = tc.travel.unwrap_or(l);
        let causes = self.attribute(tc, added, v0, v_peak, v_end);
        let tot = &mut self.totals;
        tot.causes.add(&causes);
        tot.motion_s += added;
        if tc.rapid {
            tot.rapid_s += added;
        } else {
            tot.cutting_s += added;
        }
        tot.distance_mm += if tc.pure_rotary { 0.0 } else { travelled };
        let tt = tot.per_tool.entry(tc.tool).or_default();
        tt.motion_s += added;
        if tc.rapid {
            tt.rapid_s += added;
        } else {
            tt.cutting_s += added;
        }
        tt.distance_mm += if tc.pure_rotary { 0.0 } else { travelled };
        out(SegmentTiming {
            block: tc.block,
            tool: tc.tool,
            rapid: tc.rapid,
            blend: tc.ty == TcType::Blend,
            start_s: start,
            end_s: end,
            entry_speed: v0,
            peak_speed: v_peak,
            exit_speed: v_end,
            length: l,
            causes,
        });
    }

    /// Splits the `added` seconds of an executed element by cause (see
    /// [`super::Causes`]) from its profile: entry speed `v0`, peak `v_peak`,
    /// exit `v_end`, and the planner's own target speed and acceleration.
    /// The element is no longer in the queue; its successor is at the front.
    fn attribute(&mut self, tc: &Tc, added: f64, v0: f64, v_peak: f64, v_end: f64) -> Causes {
        let mut c = Causes::default();
        let exit_corner = self.exit_corner(tc, v_end);
        let entry_corner = std::mem::replace(&mut self.entry_corner, exit_corner);
        if tc.rapid {
            c.rapid_s = added;
            return c;
        }
        let l = tc.target;
        let v = self.real_target_vel(tc);
        let t = added.max(0.0);
        if !(v > 0.0 && l > 0.0 && t.is_finite()) {
            c.accel_s = t;
            return c;
        }
        // Without a programmed feed the target speed is all there is to reach.
        let f = if tc.feed.is_finite() {
            (tc.feed * self.p.feed_override).max(v)
        } else {
            v
        };
        // A cap below the feed costs time only where the element reaches it;
        // below it the ramps are measured against the feed itself.
        let reached = v_peak >= v * (1.0 - 1e-3);
        let v_ref = if reached { v } else { f };
        let cap = if reached {
            (l / v - l / f).clamp(0.0, t)
        } else {
            0.0
        };
        // Rounding leaves a trace of a cap where there is none.
        let cap = if cap > t * 1e-9 { cap } else { 0.0 };
        let ramp = (t - l / v_ref).clamp(0.0, t - cap);
        c.feed_s = t - cap - ramp;
        let counts = &mut self.totals.cause_counts;
        if cap > 0.0 {
            let slot = if tc.ty == TcType::Blend {
                &mut c.corner_s
            } else if !tc.pure_rotary && !tc.dogleg && v >= self.p.traj_max_velocity {
                counts.traj_cap += 1;
                &mut c.traj_cap_s
            } else if v * self.cycle <= l * (1.0 + 1e-9)
                && v * self.cycle * MIN_SEGMENT_CYCLES >= l * (1.0 - 1e-9)
            {
                counts.servo_cap += 1;
                &mut c.servo_cap_s
            } else if v < tc.axis_vel * (1.0 - 1e-9) {
                counts.curve_cap += 1;
                &mut c.curve_cap_s
            } else {
                counts.axis_cap += 1;
                &mut c.axis_cap_s
            };
            *slot += cap;
        }
        if ramp > 0.0 {
            // Time each ramp takes beyond running its distance at the target speed.
            let a = tc.tangential_accel().max(1e-9);
            let vp = v_peak.min(v);
            let lost = |u: f64| {
                let u = u.clamp(0.0, vp);
                (vp - u) / a * (1.0 - (vp + u) / (2.0 * v_ref))
            };
            let (ls, le) = (lost(v0), lost(v_end));
            // Clamped: rounding must not leave the other ramp a negative share.
            let start = if ls + le > 0.0 {
                (ramp * ls / (ls + le)).min(ramp)
            } else {
                ramp
            };
            let corner = |at_corner: bool| at_corner || tc.ty == TcType::Blend;
            let (cs, as_) = if corner(entry_corner) {
                (start, 0.0)
            } else {
                (0.0, start)
            };
            let end = (ramp - start).max(0.0);
            let (ce, ae) = if corner(exit_corner) {
                (end, 0.0)
            } else {
                (0.0, end)
            };
            c.corner_s += cs + ce;
            c.accel_s += as_ + ae;
            if as_ + ae > 0.0 {
                counts.accel += 1;
            }
            if cs + ce > 0.0 || (tc.ty == TcType::Blend && cap > 0.0) {
                counts.corner += 1;
            }
        } else if tc.ty == TcType::Blend && cap > 0.0 {
            counts.corner += 1;
        }
        if tc.ty != TcType::Blend && !reached {
            let first = counts.short == 0;
            counts.short += 1;
            counts.short_s += t;
            counts.short_max_mm = counts.short_max_mm.max(l);
            counts.short_feed_min = if first {
                f
            } else {
                counts.short_feed_min.min(f)
            };
            counts.short_feed_max = counts.short_feed_max.max(f);
        }
        c
    }

    /// Whether the speed at the end of `tc` (just executed) was set by a corner:
    /// an exact stop or exact-path stop between two feed moves, a parabolic
    /// blend, a tangent junction held at its corner speed, or a blend arc.
    /// A stop where motion ends or turns into a rapid is not a corner.
    fn exit_corner(&self, tc: &Tc, v_end: f64) -> bool {
        let Some(next) = self.queue.front() else {
            return false;
        };
        if tc.ty == TcType::Blend {
            return true;
        }
        match tc.term {
            Term::Stop | Term::Exact => !(next.rapid != tc.rapid || next.dogleg || tc.dogleg),
            Term::Parabolic => true,
            Term::Tangent => {
                let at = v_end * (1.0 + 1e-6) + 1e-9;
                let kink = tc.kink_vel >= 0.0
                    && tc.kink_vel <= at
                    && tc.kink_vel < self.real_target_vel(tc) * (1.0 - 1e-9);
                kink || (next.ty == TcType::Blend && self.real_target_vel(next) <= at)
            }
        }
    }

    fn jerk(&self) -> f64 {
        self.p
            .axes
            .iter()
            .filter(|a| a.jerk > 0.0)
            .map(|a| a.jerk)
            .fold(f64::INFINITY, f64::min)
    }
}

/// The radius LinuxCNC's planner takes for an arc's centripetal speed limit
/// (`pmCircleEffectiveMinRadius`): the spiral's flattened radius plus the square of
/// the whole helical rise over it. The rise is not divided by the angle, so a
/// helix of several turns runs faster than its curvature allows; measured so.
fn helix_effective_radius(
    radius: f64,
    end_from_center: &[f64; 3],
    n: &[f64; 3],
    rise: f64,
    sweep: f64,
) -> f64 {
    let along = dot3(end_from_center, n);
    let radial = [
        end_from_center[0] - along * n[0],
        end_from_center[1] - along * n[1],
        end_from_center[2] - along * n[2],
    ];
    let dr = (norm3(&radial) - radius) / sweep.abs();
    let inner = dr * dr + radius * radius;
    let r_spiral = (inner * inner * inner).sqrt() / (inner + dr * dr);
    rise * rise / r_spiral + r_spiral
}

/// LinuxCNC's canonical layer feeds an XY arc whose chord deviates less than the
/// naive-CAM tolerance to the naive-CAM detector as two lines through the arc's
/// middle (`ARC_FEED`, `chord_deviation`). The deviation is taken over the arc's
/// last turn only, as there.
fn arc_as_lines(seg: &Segment) -> Option<[Segment; 2]> {
    let SegmentKind::Arc {
        center,
        normal,
        sweep,
        ..
    } = seg.kind
    else {
        return None;
    };
    let PathMode::Blend { naive, .. } = seg.mode else {
        return None;
    };
    if naive <= 0.0 || normal[0] != 0.0 || normal[1] != 0.0 || seg.start[3..] != seg.end[3..] {
        return None;
    }
    let (sx, sy) = (seg.start[0] - center[0], seg.start[1] - center[1]);
    let r = sx.hypot(sy);
    let ccw = (sweep >= 0.0) == (normal[2] >= 0.0);
    let th1 = sy.atan2(sx);
    let th2 = (seg.end[1] - center[1]).atan2(seg.end[0] - center[0]);
    // The angle from start to end the way the arc turns, in (1e-5, 2π + 1e-5].
    let mut dth = th2 - th1;
    for _ in 0..2 {
        if ccw && dth <= 1e-5 {
            dth += std::f64::consts::TAU;
        } else if !ccw && dth >= -1e-5 {
            dth -= std::f64::consts::TAU;
        }
    }
    let included = dth.abs();
    let deviation = r * (1.0 - (included / 2.0).cos());
    // A NaN deviation (degenerate arc) keeps the arc.
    if deviation.is_nan() || deviation >= naive {
        return None;
    }
    let mid_angle = th1 + dth / 2.0;
    let mut mid = seg.start;
    mid[0] = center[0] + r * mid_angle.cos();
    mid[1] = center[1] + r * mid_angle.sin();
    mid[2] = (seg.start[2] + seg.end[2]) / 2.0;
    let half = |a: [f64; 6], b: [f64; 6]| Segment {
        kind: SegmentKind::Line,
        start: a,
        end: b,
        length: dist3(&[a[0], a[1], a[2]], &[b[0], b[1], b[2]]),
        ..*seg
    };
    Some([half(seg.start, mid), half(mid, seg.end)])
}

/// A straight feed move of the linear axes in G64 with a tolerance.
fn chainable(seg: &Segment) -> bool {
    matches!(seg.kind, SegmentKind::Line)
        && matches!(seg.mode, PathMode::Blend { naive, .. } if naive > 0.0)
        && seg.start[3..] == seg.end[3..]
}

fn set_term(prev: &mut Tc, tc: Option<&mut Tc>, term: Term) {
    if let Some(tc) = tc {
        tc.blend_prev = term == Term::Parabolic;
    }
    prev.term = term;
}

fn set_kink(prev: &mut Tc, tc: &mut Tc, kink_vel: f64, reduce: f64) {
    prev.kink_vel = kink_vel;
    prev.kink_reduce = prev.kink_reduce.max(reduce);
    tc.kink_reduce_prev = tc.kink_reduce_prev.max(reduce);
}

fn remove_kink(prev: &mut Tc, tc: &mut Tc) {
    prev.kink_vel = -1.0;
    prev.kink_reduce = 0.0;
    tc.kink_reduce_prev = 0.0;
}

/// Two distinct mutable elements `i < j` of a `VecDeque`'s slices.
fn pair_mut<'a>(
    head: &'a mut [Tc],
    tail: &'a mut [Tc],
    i: usize,
    j: usize,
) -> (&'a mut Tc, &'a mut Tc) {
    let h = head.len();
    if j < h {
        let (a, b) = head.split_at_mut(j);
        (&mut a[i], &mut b[0])
    } else if i >= h {
        let (a, b) = tail.split_at_mut(j - h);
        (&mut a[i - h], &mut b[0])
    } else {
        (&mut head[i], &mut tail[j - h])
    }
}
