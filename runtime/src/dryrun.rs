//! The dry run: interpreter output → planner input → cycle time and toolpath.
//!
//! This is the glue every host uses (`partscope run`, the language server's
//! preview and code lens), so the conversion of the interpreter's motions into
//! planner segments lives in one place.

use std::collections::BTreeMap;
use std::ops::ControlFlow;

use analyzer::config::MachineConfig;
use analyzer::Dialect;
use serde::Serialize;

use crate::interp::{Event as IEvent, EventKind, Motion, MotionKind, RunOutput};
use crate::machine::{MachineProfile, RapidPositioning};
use crate::plan::{
    self, cross3, dist3, dot3, sub3, Causes, PathMode, Segment, SegmentKind, SegmentTiming, Totals,
};

/// The planner profile from a `[machine]` table: the dialect's defaults with the
/// table's planner keys applied (the interpreter reads its keys from the same table).
pub fn profile_from_table(machine: &MachineConfig, dialect: Dialect) -> MachineProfile {
    MachineProfile::default_for(dialect).with(machine)
}

/// One toolpath polyline for previews: a motion sampled at a chord tolerance.
#[derive(Debug, Clone, Serialize)]
pub struct ToolpathSegment {
    /// `rapid`, `feed` or `arc`.
    pub kind: &'static str,
    /// 0-based source line (in `file`).
    pub line: u32,
    /// 0 = the main file; otherwise an index into the run's files + 1.
    pub file: u32,
    /// Programmed feed in mm/min (0 for rapids).
    pub feed: f64,
    pub tool: u32,
    pub points: Vec<[f64; 3]>,
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct Toolpath {
    pub segments: Vec<ToolpathSegment>,
    pub bounds: Bounds,
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct Bounds {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// Timing of one source block (main file) or of a subprogram block.
#[derive(Debug, Clone, Serialize)]
pub struct BlockTime {
    pub file: u32,
    pub line: u32,
    pub start_s: f64,
    pub end_s: f64,
    /// Time spent moving in this block, summed over every execution (loops, calls).
    pub duration_s: f64,
    pub length_mm: f64,
    /// Highest path speed reached in the block, mm/min.
    pub peak_feed: f64,
    /// The block's share of the cycle time: its motion time by cause (parabolic
    /// blends overlap moves, so this can be less than `duration_s`) plus its
    /// dwell and auxiliary time.
    pub time_s: f64,
    pub causes: Causes,
    pub dwell_s: f64,
    /// Auxiliary time of the block's events (tool change, spindle, M codes, stops).
    pub aux_s: f64,
}

/// What a dry run computes.
#[derive(Debug, Clone, Default)]
pub struct DryRun {
    pub totals: Totals,
    /// Per executed motion (index = motion index): start and end on the
    /// program's clock (dwell and auxiliary time included), and peak speed.
    pub motion_times: Vec<(f64, f64, f64)>,
    /// Program time at which each interpreter event happens (same order as `RunOutput::events`).
    pub event_times: Vec<f64>,
    /// Seconds each interpreter event takes (dwell, auxiliary), same order as
    /// `RunOutput::events`.
    pub event_seconds: Vec<f64>,
    /// Per-block times and causes ([`block_times`]).
    pub blocks: Vec<BlockTime>,
}

/// The sweep angle (radians, signed: + counter-clockwise about `normal`) of an arc motion.
fn arc_sweep(m: &Motion, center: [f64; 3], normal: [f64; 3], turns: i32) -> f64 {
    // Project both radius vectors on the arc plane.
    let proj = |v: [f64; 3]| {
        let d = dot3(&v, &normal);
        [
            v[0] - d * normal[0],
            v[1] - d * normal[1],
            v[2] - d * normal[2],
        ]
    };
    let s = proj(sub3(&xyz(&m.start), &center));
    let e = proj(sub3(&xyz(&m.end), &center));
    let sin = dot3(&cross3(&s, &e), &normal);
    let cos = dot3(&s, &e);
    let mut angle = sin.atan2(cos);
    let d = sub3(&e, &s);
    let chord = dot3(&d, &d).sqrt();
    if chord > 1e-6 {
        // Distinct ends: never a full circle, however small the angle (`R1e12`).
        if angle <= 0.0 {
            angle += std::f64::consts::TAU;
        }
    } else if angle <= 1e-12 {
        // Counter-clockwise about the normal: a zero angle is a full circle.
        angle += std::f64::consts::TAU;
    }
    angle + std::f64::consts::TAU * turns.max(0) as f64
}

fn xyz(p: &[f64; 6]) -> [f64; 3] {
    [p[0], p[1], p[2]]
}

/// Rise of a helix: the end point's offset from the start along the arc normal.
fn helix_rise(m: &Motion, normal: &[f64; 3]) -> f64 {
    dot3(&sub3(&xyz(&m.end), &xyz(&m.start)), normal)
}

/// A motion's planner kind and path length, before an exponential move's own
/// measure: what `segment_of` and `length_of` share.
fn kind_and_length(m: &Motion) -> (SegmentKind, f64) {
    let (kind, length) = match m.kind {
        MotionKind::Arc {
            center,
            normal,
            turns,
            radius,
        } => {
            let sweep = arc_sweep(m, center, normal, turns);
            let rise = helix_rise(m, &normal);
            let planar = radius * sweep;
            (
                SegmentKind::Arc {
                    center,
                    normal,
                    radius,
                    sweep,
                },
                (planar * planar + rise * rise).sqrt(),
            )
        }
        MotionKind::Involute { curve, .. } => (SegmentKind::Line, curve.length()),
        MotionKind::Rapid => (SegmentKind::Rapid, dist3(&xyz(&m.start), &xyz(&m.end))),
        _ => (SegmentKind::Line, dist3(&xyz(&m.start), &xyz(&m.end))),
    };
    if length > 1e-12 {
        return (kind, length);
    }
    let rot = ((m.end[3] - m.start[3]).powi(2)
        + (m.end[4] - m.start[4]).powi(2)
        + (m.end[5] - m.start[5]).powi(2))
    .sqrt();
    (kind, rot)
}

/// An exponential move's integrated X–A length and its feed in mm/s (the one
/// that gives the integrated time of the feed running from F to Q), when the
/// move has one.
fn exponential_measure(m: &Motion) -> Option<(f64, f64)> {
    let (MotionKind::Exponential { curve, end_feed }, None) = (m.kind, m.inverse_time) else {
        return None;
    };
    let e = curve.measure(m.feed, end_feed);
    (e.length > 1e-12 && e.minutes > 0.0 && e.minutes.is_finite())
        .then(|| (e.length, e.length / (e.minutes * 60.0)))
}

/// The path length of `segment_of(m, _)`, without building the segment.
pub fn length_of(m: &Motion) -> f64 {
    match exponential_measure(m) {
        Some((length, _)) => length,
        None => kind_and_length(m).1,
    }
}

/// The planner segment of a motion; `index` is stored as the segment's block so
/// timings map back to motions.
pub fn segment_of(m: &Motion, index: u32) -> Segment {
    let mode = if m.exact_path {
        PathMode::ExactPath
    } else if m.exact_stop {
        PathMode::ExactStop
    } else {
        PathMode::Blend {
            tolerance: m.blend_tolerance,
            naive: m.naive_tolerance,
        }
    };
    let (kind, length) = kind_and_length(m);
    // Feed in mm/s: inverse time gives the move's duration; per-revolution feeds
    // (G95, threads) scale with the spindle speed.
    let (length, feed) = exponential_measure(m).unwrap_or_else(|| {
        let feed = match (m.inverse_time, m.kind) {
            (_, MotionKind::Rapid) => 0.0,
            (Some(inv), _) if inv > 0.0 => length * inv / 60.0,
            (_, MotionKind::Thread) => m.feed * m.spindle_rpm / 60.0,
            _ => m.feed / 60.0,
        };
        (length, feed)
    });
    Segment {
        kind,
        start: m.start,
        end: m.end,
        length,
        feed,
        mode,
        block: index,
        tool: m.tool,
    }
}

/// Interleaves the interpreter's motions and events into planner events.
pub fn planner_events(out: &RunOutput) -> Vec<plan::Event> {
    let mut evs = Vec::with_capacity(out.motions.len() + out.events.len());
    interleave(&out.motions, &out.events, 0, &mut |e| evs.push(e));
    evs
}

/// The planner event of an interpreter event, if it takes machine time; its
/// `block` is `index`, the event's place in the list it came from.
fn planner_event(ev: &IEvent, index: usize) -> Option<plan::Event> {
    let block = index as u32;
    Some(match &ev.kind {
        EventKind::Dwell(s) => plan::Event::Dwell {
            seconds: s.max(0.0),
            block,
        },
        EventKind::ToolChange { tool } => plan::Event::ToolChange { tool: *tool, block },
        EventKind::Spindle { dir, rpm } => {
            if *dir == 0 {
                plan::Event::SpindleStop { block }
            } else {
                plan::Event::SpindleStart {
                    rpm: rpm.abs() * f64::from(*dir),
                    block,
                }
            }
        }
        EventKind::Coolant { .. } => plan::Event::MCode { code: 80, block },
        EventKind::MCode { code } => plan::Event::MCode { code: *code, block },
        EventKind::ToolSelect { tool } => plan::Event::ToolSelect { tool: *tool, block },
        EventKind::Stop { optional } => plan::Event::ProgramStop {
            optional: *optional,
            block,
        },
        _ => return None,
    })
}

/// Passes motions (as segments numbered from `first_index`) and the events between
/// them to `emit` in execution order; an event's `motion_index` is relative to `motions`.
fn interleave(
    motions: &[Motion],
    events: &[IEvent],
    first_index: usize,
    emit: &mut dyn FnMut(plan::Event),
) {
    interleave_while(motions, events, first_index, &mut |e| {
        emit(e);
        true
    });
}

/// [`interleave`] until `emit` returns false; whether it went to the end.
fn interleave_while(
    motions: &[Motion],
    events: &[IEvent],
    first_index: usize,
    emit: &mut dyn FnMut(plan::Event) -> bool,
) -> bool {
    interleave_at(motions, events, first_index, 0, 0, emit)
}

/// [`interleave_while`] for a chunk of a run whose events count motions from
/// the run's first (`motions[0]` is motion `first_index`, `events[0]` event
/// `first_event`).
fn interleave_from(
    motions: &[Motion],
    events: &[IEvent],
    first_index: usize,
    first_event: usize,
    emit: &mut dyn FnMut(plan::Event) -> bool,
) -> bool {
    interleave_at(motions, events, first_index, first_index, first_event, emit)
}

/// The interleaving: an event's `motion_index` less `base` is its place in
/// `motions`; events are numbered from `first_event`.
fn interleave_at(
    motions: &[Motion],
    events: &[IEvent],
    first_index: usize,
    base: usize,
    first_event: usize,
    emit: &mut dyn FnMut(plan::Event) -> bool,
) -> bool {
    let mut e = events
        .iter()
        .enumerate()
        .map(|(k, ev)| (first_event + k, ev))
        .peekable();
    for (i, m) in motions.iter().enumerate() {
        while let Some((k, ev)) = e.next_if(|(_, ev)| ev.motion_index.saturating_sub(base) <= i) {
            if let Some(pe) = planner_event(ev, k) {
                if !emit(pe) {
                    return false;
                }
            }
        }
        if !emit(plan::Event::Motion(segment_of(m, (first_index + i) as u32))) {
            return false;
        }
    }
    for (k, ev) in e {
        if let Some(pe) = planner_event(ev, k) {
            if !emit(pe) {
                return false;
            }
        }
    }
    true
}

/// Motion time above which the planner uses closed-form profiles instead of servo periods.
pub const SERVO_SIMULATION_LIMIT_S: f64 = 4.0 * 3600.0;

/// Length over feed (rapids at the path speed cap): a lower bound of the motion time.
fn naive_seconds(events: &[plan::Event], profile: &MachineProfile) -> f64 {
    let rapid = profile.traj_max_velocity.max(1e-9);
    events
        .iter()
        .map(|e| naive_event_seconds(e, rapid))
        .filter(|t| t.is_finite())
        .sum()
}

/// One event's share of [`naive_seconds`]; `rapid` is the path speed cap.
fn naive_event_seconds(e: &plan::Event, rapid: f64) -> f64 {
    match e {
        plan::Event::Motion(s) if matches!(s.kind, SegmentKind::Rapid) => s.length / rapid,
        plan::Event::Motion(s) if s.feed > 0.0 => s.length / s.feed.min(rapid),
        _ => 0.0,
    }
}

/// Plans a run whose motions arrive in chunks ([`crate::interp::run_streaming`]) and
/// returns only the totals, in memory that does not grow with the program. The
/// totals equal those of [`plan_run`].
///
/// `plan_run` chooses closed-form execution when the whole program's naive motion
/// time exceeds [`SERVO_SIMULATION_LIMIT_S`], which is known only at the end. One
/// planner runs, as the profile asks; when a profile that simulates servo periods
/// passes the limit, the planner is dropped and [`StreamPlan::finish`] returns
/// `None`: the run must be streamed again into [`StreamPlan::closed_form`]
/// ([`stream_totals`] does both). Running a closed-form planner alongside instead
/// would double the planning cost of every program to save a second interpreter
/// pass for the few that run longer than four hours.
///
/// To spare that second pass, a servo-period plan keeps a copy of the chunks it
/// was given, up to [`REPLAY_BYTES`]: when it passes the limit with the copy
/// whole, it plans the copy closed-form and goes on so. A run whose first four
/// hours of motion need more than that is still run twice.
pub struct StreamPlan {
    planner: Option<plan::Planner>,
    /// The planner simulates servo periods, so the limit applies.
    servo: bool,
    /// The chunks so far, while the limit may still be passed and they fit.
    replay: Option<Replay>,
    profile: MachineProfile,
    naive_s: f64,
    rapid: f64,
    motions: usize,
    /// Per-block figures, when asked for ([`StreamPlan::with_blocks`]).
    blocks: Option<StreamBlocks>,
}

/// What [`StreamPlan`] needs to put the planner's elements on their blocks:
/// the motions the planner holds, by index, file and line, and the dwell and
/// auxiliary time so far (the planner's clock counts motion only).
#[derive(Debug, Default)]
struct StreamBlocks {
    acc: BlockAcc,
    /// (motion index, file, line, length).
    pending: std::collections::VecDeque<(u32, u32, u32, f64)>,
    offset: f64,
    last_end: f64,
}

impl StreamBlocks {
    /// An element's timing: its motion is the first pending one of its index
    /// (elements come in motion order; motions without one were joined into
    /// a later element).
    fn element(&mut self, t: &SegmentTiming) {
        while let Some(&(i, file, line, mm)) = self.pending.front() {
            if i > t.block {
                break;
            }
            self.pending.pop_front();
            if i == t.block {
                self.acc.element(file, line, t, self.offset);
            }
            // Lengths as `plan_run` adds them: a motion without an element
            // of its own is placed where the next element starts.
            let at = t.start_s + self.offset;
            self.acc.length(file, line, mm, at);
            if i == t.block {
                // Blend arcs report on the motion they round off: keep it.
                self.pending.push_front((i, file, line, 0.0));
                self.last_end = self.last_end.max(t.end_s + self.offset);
                break;
            }
        }
    }

    /// Motions no element reported on (the end of the run).
    fn drain(&mut self) {
        while let Some((_, file, line, mm)) = self.pending.pop_front() {
            let at = self.last_end;
            self.acc.length(file, line, mm, at);
        }
    }
}

/// Bytes of motions and events a [`StreamPlan`] keeps to plan again
/// closed-form (about 150 000 motions).
pub const REPLAY_BYTES: usize = 32 << 20;

/// The chunks a [`StreamPlan`] was given, in order.
#[derive(Debug)]
struct Replay {
    chunks: Vec<(Vec<Motion>, Vec<IEvent>)>,
    bytes: usize,
    limit: usize,
}

impl Replay {
    fn new(limit: usize) -> Replay {
        Replay {
            chunks: Vec::new(),
            bytes: 0,
            limit,
        }
    }

    /// Keeps a copy of a chunk; false when it would pass the limit.
    fn keep(&mut self, motions: &[Motion], events: &[IEvent]) -> bool {
        self.bytes += std::mem::size_of_val(motions) + std::mem::size_of_val(events);
        if self.bytes > self.limit {
            return false;
        }
        self.chunks.push((motions.to_vec(), events.to_vec()));
        true
    }
}

impl StreamPlan {
    /// Plans with `profile` as given.
    pub fn new(profile: &MachineProfile) -> StreamPlan {
        StreamPlan {
            planner: Some(plan::Planner::new(profile)),
            servo: profile.servo_simulation,
            replay: profile.servo_simulation.then(|| Replay::new(REPLAY_BYTES)),
            profile: profile.clone(),
            naive_s: 0.0,
            rapid: profile.traj_max_velocity.max(1e-9),
            motions: 0,
            blocks: None,
        }
    }

    /// Plans with closed-form profiles whatever `profile` says, as [`plan_run`] does
    /// beyond the servo-simulation limit.
    pub fn closed_form(profile: &MachineProfile) -> StreamPlan {
        let mut cf = profile.clone();
        cf.servo_simulation = false;
        StreamPlan::new(&cf)
    }

    /// Keeps at most `bytes` of the run to plan again (instead of
    /// [`REPLAY_BYTES`]); 0 for a host that would rather run the program twice.
    pub fn with_replay_bytes(mut self, bytes: usize) -> StreamPlan {
        if let Some(r) = self.replay.as_mut() {
            r.limit = bytes;
        }
        self
    }

    /// Also gathers the per-block figures of [`block_times`] (memory grows with
    /// the program's line count, not with its motions).
    pub fn with_blocks(mut self) -> StreamPlan {
        self.blocks = Some(StreamBlocks::default());
        self
    }

    /// Feeds the next chunk of the run (see [`crate::interp::MotionSink`]).
    pub fn push(&mut self, motions: &[Motion], events: &[IEvent]) {
        if self
            .replay
            .as_mut()
            .is_some_and(|r| !r.keep(motions, events))
        {
            self.replay = None;
        }
        if !self.push_planned(motions, events) {
            return;
        }
        // Past the limit: the whole run is planned closed-form, from the kept
        // chunks when there are all of them, or by the host's second run.
        let Some(replay) = self.replay.take() else {
            return;
        };
        let mut again = StreamPlan::closed_form(&self.profile);
        if self.blocks.is_some() {
            again = again.with_blocks();
        }
        for (m, e) in &replay.chunks {
            again.push(m, e);
        }
        *self = again;
    }

    /// Plans a chunk; true when it passed the servo-simulation limit (the
    /// planner is then dropped).
    fn push_planned(&mut self, motions: &[Motion], events: &[IEvent]) -> bool {
        let first = self.motions;
        self.motions += motions.len();
        let Self {
            planner,
            servo,
            naive_s,
            rapid,
            blocks,
            ..
        } = self;
        let Some(p) = planner.as_mut() else {
            return false;
        };
        let mut over = false;
        interleave(motions, events, first, &mut |e| {
            if over {
                return;
            }
            if *servo {
                let t = naive_event_seconds(&e, *rapid);
                if t.is_finite() {
                    *naive_s += t;
                }
                if *naive_s > SERVO_SIMULATION_LIMIT_S {
                    over = true;
                    return;
                }
            }
            let Some(b) = blocks.as_mut() else {
                p.push(e, &mut |_| {});
                return;
            };
            let index = event_block(&e);
            match e {
                plan::Event::Motion(seg) => {
                    if let Some(m) = index.checked_sub(first).and_then(|i| motions.get(i)) {
                        b.pending
                            .push_back((seg.block, m.file.0, m.line, seg.length));
                    }
                    p.push(e, &mut |t| b.element(&t));
                }
                _ => {
                    let before = non_motion_s(p.totals());
                    p.push(e, &mut |t| b.element(&t));
                    let now = non_motion_s(p.totals());
                    b.offset = now;
                    if let Some(ev) = events.get(index) {
                        let s = now - before;
                        let t = p.totals();
                        let at = t.motion_s + t.aux.in_position_s + before;
                        let dwell = matches!(ev.kind, EventKind::Dwell(_));
                        b.acc.event(ev.file.0, ev.line, dwell, at, s);
                        b.last_end = b.last_end.max(at + s);
                    }
                }
            }
        });
        if over {
            *planner = None;
        }
        over
    }

    /// The totals, or `None` when the run passed the servo-simulation limit and must
    /// be planned again with [`StreamPlan::closed_form`].
    pub fn finish(self) -> Option<Totals> {
        self.finish_with_blocks().map(|(t, _)| t)
    }

    /// [`StreamPlan::finish`] with the per-block figures (empty unless
    /// [`StreamPlan::with_blocks`]).
    pub fn finish_with_blocks(self) -> Option<(Totals, Vec<BlockTime>)> {
        let p = self.planner?;
        match self.blocks {
            Some(mut b) => {
                let totals = p.finish(&mut |t| b.element(&t));
                b.drain();
                Some((totals, b.acc.finish()))
            }
            None => Some((p.finish(&mut |_| {}), Vec::new())),
        }
    }
}

/// Streams a run through [`StreamPlan`]: `run` executes the program, handing its
/// motions to the sink it is given, and is called a second time only when the run
/// passes the servo-simulation limit. Returns the output of the last run and the
/// totals, equal to those of [`plan_run`].
pub fn stream_totals<R>(
    profile: &MachineProfile,
    mut run: impl FnMut(&mut crate::interp::MotionSink<'_>) -> R,
) -> (R, Totals) {
    let mut plan = StreamPlan::new(profile);
    let out = run(&mut |m, e| plan.push(m, e));
    if let Some(totals) = plan.finish() {
        return (out, totals);
    }
    let mut plan = StreamPlan::closed_form(profile);
    let out = run(&mut |m, e| plan.push(m, e));
    // A closed-form planner has no limit to pass.
    let totals = plan.finish().unwrap_or_default();
    (out, totals)
}

/// A change to the machine or the program that a what-if estimate plans.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WhatIfKind {
    /// The feed override at [`WHAT_IF_FEED_OVERRIDE`] times the profile's.
    FeedOverride,
    /// `G64 P`[`WHAT_IF_BLEND_TOLERANCE`] on every move (RS274/NGC).
    Blend,
    /// Every axis and the path accelerating [`WHAT_IF_ACCELERATION`] times faster.
    Acceleration,
}

/// Feed override factor of [`WhatIfKind::FeedOverride`].
pub const WHAT_IF_FEED_OVERRIDE: f64 = 1.2;
/// Blend tolerance of [`WhatIfKind::Blend`], mm.
pub const WHAT_IF_BLEND_TOLERANCE: f64 = 0.05;
/// Acceleration factor of [`WhatIfKind::Acceleration`].
pub const WHAT_IF_ACCELERATION: f64 = 2.0;

/// A what-if estimate: the program planned again with one change.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WhatIf {
    /// `feed_override`, `blend` or `acceleration`.
    pub key: &'static str,
    pub label: String,
    pub cycle_time_s: f64,
    pub motion_s: f64,
}

impl WhatIfKind {
    pub const ALL: [WhatIfKind; 3] = [
        WhatIfKind::FeedOverride,
        WhatIfKind::Blend,
        WhatIfKind::Acceleration,
    ];

    /// Whether the change means something on `dialect`'s control: `G64 P` is
    /// RS274/NGC's.
    pub fn applies(self, dialect: Dialect) -> bool {
        self != WhatIfKind::Blend || dialect == Dialect::Rs274ngc
    }
}

/// Plans `events` (from [`planner_events`]) again with one change and
/// returns the totals' cycle and motion time. This costs one planner run.
pub fn what_if(events: &[plan::Event], profile: &MachineProfile, kind: WhatIfKind) -> WhatIf {
    let mut p = profile.clone();
    let (key, label) = match kind {
        WhatIfKind::FeedOverride => {
            p.feed_override *= WHAT_IF_FEED_OVERRIDE;
            (
                "feed_override",
                format!("feed override {:.0} %", p.feed_override * 100.0),
            )
        }
        WhatIfKind::Blend => (
            "blend",
            format!("G64 P{WHAT_IF_BLEND_TOLERANCE} (mm) on every move"),
        ),
        WhatIfKind::Acceleration => {
            for a in &mut p.axes {
                a.max_acceleration *= WHAT_IF_ACCELERATION;
            }
            p.traj_max_acceleration *= WHAT_IF_ACCELERATION;
            (
                "acceleration",
                format!("{WHAT_IF_ACCELERATION}× acceleration on every axis"),
            )
        }
    };
    if p.servo_simulation && naive_seconds(events, &p) > SERVO_SIMULATION_LIMIT_S {
        p.servo_simulation = false;
    }
    let mut planner = plan::Planner::new(&p);
    let mut ignore = |_: SegmentTiming| {};
    for ev in events {
        let mut ev = *ev;
        if let (WhatIfKind::Blend, plan::Event::Motion(seg)) = (kind, &mut ev) {
            seg.mode = PathMode::blend(WHAT_IF_BLEND_TOLERANCE);
        }
        planner.push(ev, &mut ignore);
    }
    let totals = planner.finish(&mut ignore);
    WhatIf {
        key,
        label,
        cycle_time_s: totals.cycle_time_s,
        motion_s: totals.motion_s,
    }
}

/// Plans a run.
pub fn plan_run(out: &RunOutput, profile: &MachineProfile) -> DryRun {
    plan_run_stoppable(out, profile, &|| false).0
}

/// [`plan_run`] for a host that may stop it: `None` when `stop` returned
/// true (it is polled every 64 planner events).
pub fn plan_run_until(
    out: &RunOutput,
    profile: &MachineProfile,
    stop: &dyn Fn() -> bool,
) -> Option<DryRun> {
    match plan_run_stoppable(out, profile, stop) {
        (_, true) => None,
        (plan, false) => Some(plan),
    }
}

/// The plan, and whether `stop` cut it short.
fn plan_run_stoppable(
    out: &RunOutput,
    profile: &MachineProfile,
    stop: &dyn Fn() -> bool,
) -> (DryRun, bool) {
    // Period-by-period execution costs time in proportion to machine time; beyond
    // SERVO_SIMULATION_LIMIT_S of (naively estimated) motion the closed-form profiles,
    // within a few milliseconds of it per move, keep long jobs fast. The whole run
    // is at hand, so a cheap first pass decides instead of a servo-period plan
    // that stops at the limit.
    let mut profile = profile.clone();
    if profile.servo_simulation {
        let rapid = profile.traj_max_velocity.max(1e-9);
        let mut naive = 0.0;
        interleave_while(&out.motions, &out.events, 0, &mut |e| {
            let t = naive_event_seconds(&e, rapid);
            if t.is_finite() {
                naive += t;
            }
            naive <= SERVO_SIMULATION_LIMIT_S
        });
        if naive > SERVO_SIMULATION_LIMIT_S {
            profile.servo_simulation = false;
        }
    }
    let mut plan = RunPlan::new(&profile);
    // The first pass decided: the limit cannot be passed again.
    plan.servo_limit = false;
    plan.push(&out.motions, &out.events, stop);
    plan.finish_stopped(&out.events)
}

/// [`plan_run`] fed chunk by chunk while the interpreter runs
/// ([`crate::interp::run_checkpointed_observed`]): the same plan, element for
/// element, once [`RunPlan::finish`] has the run's events.
///
/// `plan_run` chooses closed-form execution when the whole program's naive motion
/// time exceeds [`SERVO_SIMULATION_LIMIT_S`], which a stream knows only when it
/// passes it: the plan then stops ([`RunPlan::over_limit`]) and the finished run
/// must be planned with [`plan_run`] instead.
pub struct RunPlan {
    planner: plan::Planner,
    /// The planner simulates servo periods, so the limit applies.
    servo_limit: bool,
    naive_s: f64,
    rapid: f64,
    over: bool,
    stopped: bool,
    /// Planner events pushed (the stop is polled every 64: under the servo
    /// simulation one event can be thousands of periods).
    pushed: usize,
    /// Per motion so far: file and line, and length.
    motions: Vec<(u32, u32)>,
    lengths: Vec<f64>,
    events: usize,
    motion_times: Vec<(f64, f64, f64)>,
    event_seconds: Vec<f64>,
    blocks: BlockAcc,
    /// The dwell and auxiliary time so far (the planner's clock counts motion only).
    offset: f64,
}

impl RunPlan {
    /// Plans with `profile` as given (servo periods until the limit, when it
    /// simulates them).
    pub fn new(profile: &MachineProfile) -> RunPlan {
        RunPlan {
            planner: plan::Planner::new(profile),
            servo_limit: profile.servo_simulation,
            naive_s: 0.0,
            rapid: profile.traj_max_velocity.max(1e-9),
            over: false,
            stopped: false,
            pushed: 0,
            motions: Vec::new(),
            lengths: Vec::new(),
            events: 0,
            motion_times: Vec::new(),
            event_seconds: Vec::new(),
            blocks: BlockAcc::default(),
            offset: 0.0,
        }
    }

    /// Makes room for the figures of `motions` motions on as many lines of
    /// the main file (a program's block count is a good guess): tables grown
    /// by doubling leave their old copies as holes in the allocator's heap.
    pub fn reserve(&mut self, motions: usize) {
        let motions = motions.min(RESERVED_MOTIONS);
        self.motions.reserve(motions);
        self.lengths.reserve(motions);
        self.motion_times.reserve(motions);
        self.blocks.main.reserve(motions);
        self.blocks.by_line.reserve(motions);
    }

    /// Whether the run passed the servo-simulation limit (nothing more is planned).
    pub fn over_limit(&self) -> bool {
        self.over
    }

    /// Whether `stop` cut the plan short.
    pub fn stopped(&self) -> bool {
        self.stopped
    }

    /// Plans the next motions and events of the run ([`crate::interp::MotionObserver`]:
    /// an event's `motion_index` counts from the run's first motion). `stop` is
    /// polled every 64 planner events.
    pub fn push(&mut self, motions: &[Motion], events: &[IEvent], stop: &dyn Fn() -> bool) {
        let first = self.motions.len();
        let first_event = self.events;
        self.motions
            .extend(motions.iter().map(|m| (m.file.0, m.line)));
        self.lengths.resize(self.motions.len(), 0.0);
        self.events += events.len();
        self.motion_times
            .resize(self.motions.len(), (0.0, 0.0, 0.0));
        self.event_seconds.resize(self.events, 0.0);
        if self.over || self.stopped {
            return;
        }
        let RunPlan {
            planner,
            servo_limit,
            naive_s,
            rapid,
            over,
            stopped,
            pushed,
            motions: lines,
            lengths,
            motion_times,
            event_seconds,
            blocks,
            offset,
            ..
        } = self;
        let off_now = std::cell::Cell::new(*offset);
        let mut record = |t: SegmentTiming| {
            let off = off_now.get();
            if let Some(slot) = motion_times.get_mut(t.block as usize) {
                if slot.1 == 0.0 {
                    slot.0 = t.start_s + off;
                }
                slot.1 = slot.1.max(t.end_s + off);
                slot.2 = slot.2.max(t.peak_speed);
            }
            if let Some(&(file, line)) = lines.get(t.block as usize) {
                blocks.element(file, line, &t, off);
            }
        };
        interleave_from(motions, events, first, first_event, &mut |ev| {
            if pushed.is_multiple_of(64) && stop() {
                *stopped = true;
                return false;
            }
            *pushed += 1;
            if *servo_limit {
                let t = naive_event_seconds(&ev, *rapid);
                if t.is_finite() {
                    *naive_s += t;
                }
                if *naive_s > SERVO_SIMULATION_LIMIT_S {
                    *over = true;
                    return false;
                }
            }
            let before = match ev {
                plan::Event::Motion(seg) => {
                    // The length the per-block table adds at the end.
                    if let Some(slot) = lengths.get_mut(seg.block as usize) {
                        *slot = seg.length;
                    }
                    None
                }
                _ => Some(non_motion_s(planner.totals())),
            };
            let index = event_block(&ev);
            planner.push(ev, &mut record);
            if let Some(before) = before {
                let now = non_motion_s(planner.totals());
                off_now.set(now);
                if let Some(slot) = event_seconds.get_mut(index) {
                    *slot += now - before;
                }
            }
            true
        });
        *offset = off_now.get();
    }

    /// The plan of the run whose `events` (all of them) were pushed; `None` when
    /// it passed the servo-simulation limit or `stop` cut it short.
    pub fn finish(self, events: &[IEvent]) -> Option<DryRun> {
        if self.over {
            return None;
        }
        match self.finish_stopped(events) {
            (_, true) => None,
            (plan, false) => Some(plan),
        }
    }

    fn finish_stopped(self, events: &[IEvent]) -> (DryRun, bool) {
        let RunPlan {
            planner,
            stopped,
            motions: lines,
            lengths,
            motion_times: mut times,
            event_seconds,
            mut blocks,
            offset,
            ..
        } = self;
        let totals = planner.finish(&mut |t: SegmentTiming| {
            if let Some(slot) = times.get_mut(t.block as usize) {
                if slot.1 == 0.0 {
                    slot.0 = t.start_s + offset;
                }
                slot.1 = slot.1.max(t.end_s + offset);
                slot.2 = slot.2.max(t.peak_speed);
            }
            if let Some(&(file, line)) = lines.get(t.block as usize) {
                blocks.element(file, line, &t, offset);
            }
        });
        let motion_times = times;
        // Events happen at the end of the motion before them (the planner stops
        // first), after the events before them there.
        let mut event_times = Vec::with_capacity(events.len());
        let mut last_end: f64 = 0.0;
        // The latest end of the motions before the event (a joined or empty motion
        // has no time of its own).
        let mut seen = 0;
        let mut motion_end: f64 = 0.0;
        for (i, ev) in events.iter().enumerate() {
            while seen < ev.motion_index.min(motion_times.len()) {
                motion_end = motion_end.max(motion_times[seen].1);
                seen += 1;
            }
            // Motion ends are on the program clock already; an event right after
            // another one starts when that one ends.
            let at = motion_end.max(last_end);
            let s = event_seconds.get(i).copied().unwrap_or(0.0);
            event_times.push(at);
            blocks.event(
                ev.file.0,
                ev.line,
                matches!(ev.kind, EventKind::Dwell(_)),
                at,
                s,
            );
            last_end = at + s;
        }
        // A motion without an element of its own (joined into a later one, or
        // empty) is placed where the next element starts.
        let mut at = motion_times.iter().map(|t| t.1).fold(0.0, f64::max);
        for ((&(file, line), &mm), t) in lines.iter().zip(&lengths).zip(&motion_times).rev() {
            if t.1 > 0.0 {
                at = t.0;
            }
            blocks.length(file, line, mm, at);
        }
        (
            DryRun {
                totals,
                motion_times,
                event_times,
                event_seconds,
                blocks: blocks.finish(),
            },
            stopped,
        )
    }
}

/// Time spent outside motion so far: dwell and auxiliary time (in-position
/// settling belongs to the motion, whose clock it advances).
fn non_motion_s(t: &Totals) -> f64 {
    t.dwell_s + t.tool_change_s + t.other_s - t.aux.in_position_s
}

/// Per-block figures gathered as the planner reports elements: the main
/// file's blocks in the order they first ran, found by line through an index
/// (4 bytes a line, not an empty figure's 144), other files' in a map.
#[derive(Debug, Default)]
pub struct BlockAcc {
    main: Vec<BlockTime>,
    /// Per line of the main file: its place in `main`, or `NO_BLOCK`.
    by_line: Vec<u32>,
    other: BTreeMap<(u32, u32), BlockTime>,
}

/// The most motions a run's tables make room for before they fill: a file of
/// empty lines has millions of blocks and no motion, and address space is not
/// free either.
pub const RESERVED_MOTIONS: usize = 1 << 21;

/// A main-file line without figures in [`BlockAcc`].
const NO_BLOCK: u32 = u32::MAX;

impl BlockAcc {
    fn slot(&mut self, file: u32, line: u32, at: f64) -> &mut BlockTime {
        let fresh = || BlockTime {
            file,
            line,
            start_s: at,
            end_s: at,
            duration_s: 0.0,
            length_mm: 0.0,
            peak_feed: 0.0,
            time_s: 0.0,
            causes: Causes::default(),
            dwell_s: 0.0,
            aux_s: 0.0,
        };
        if file == 0 {
            let i = line as usize;
            if self.by_line.len() <= i {
                self.by_line.resize(i + 1, NO_BLOCK);
            }
            let k = match self.by_line[i] {
                NO_BLOCK => {
                    self.by_line[i] = self.main.len() as u32;
                    self.main.push(fresh());
                    self.main.len() - 1
                }
                k => k as usize,
            };
            &mut self.main[k]
        } else {
            self.other.entry((file, line)).or_insert_with(fresh)
        }
    }

    /// A planner element of a motion on (`file`, `line`); `offset` moves its
    /// times from the planner's motion clock to the program's.
    pub fn element(&mut self, file: u32, line: u32, t: &SegmentTiming, offset: f64) {
        let (start, end) = (t.start_s + offset, t.end_s + offset);
        let b = self.slot(file, line, start);
        b.start_s = b.start_s.min(start);
        b.end_s = b.end_s.max(end);
        b.duration_s += (end - start).max(0.0);
        b.peak_feed = b.peak_feed.max(t.peak_speed * 60.0);
        b.causes.add(&t.causes);
        b.time_s += t.causes.total_s();
    }

    /// An event of `s` seconds starting at `at` (dwell, or auxiliary time).
    pub fn event(&mut self, file: u32, line: u32, dwell: bool, at: f64, s: f64) {
        if s <= 0.0 {
            return;
        }
        let b = self.slot(file, line, at);
        b.start_s = b.start_s.min(at);
        b.end_s = b.end_s.max(at + s);
        if dwell {
            b.dwell_s += s;
        } else {
            b.aux_s += s;
        }
        b.time_s += s;
    }

    /// A motion's programmed length, also for one the planner joined into a
    /// later element; `at` is where a block that gets no element starts.
    pub fn length(&mut self, file: u32, line: u32, mm: f64, at: f64) {
        self.slot(file, line, at).length_mm += mm;
    }

    /// The blocks in the order they first ran (blocks that start together by
    /// file and line).
    pub fn finish(self) -> Vec<BlockTime> {
        let mut v = self.main;
        v.extend(self.other.into_values());
        // File and line are unique, so the order is the same whatever the
        // order the blocks were gathered in.
        v.sort_unstable_by(|a, b| {
            a.start_s
                .total_cmp(&b.start_s)
                .then(a.file.cmp(&b.file))
                .then(a.line.cmp(&b.line))
        });
        v
    }
}

/// The `block` of a planner event: the motion index of a motion, the
/// interpreter event's index of anything else.
fn event_block(ev: &plan::Event) -> usize {
    let b = match ev {
        plan::Event::Motion(s) => s.block,
        plan::Event::Dwell { block, .. }
        | plan::Event::ToolChange { block, .. }
        | plan::Event::SpindleStart { block, .. }
        | plan::Event::SpindleStop { block }
        | plan::Event::ProgramStop { block, .. }
        | plan::Event::MCode { block, .. }
        | plan::Event::ToolSelect { block, .. } => *block,
    };
    b as usize
}

/// Samples motions into polylines with at most `chord` mm deviation on arcs;
/// rapids are straight lines (see [`toolpath_on`] for a machine's real G0 path).
pub fn toolpath(out: &RunOutput, chord: f64) -> Toolpath {
    toolpath_with(out, chord, None)
}

/// [`toolpath`] on a machine: where `profile` moves G0 axes independently, each
/// rapid is drawn as the dog-leg its axes make ([`plan::dogleg_path`]).
pub fn toolpath_on(out: &RunOutput, chord: f64, profile: &MachineProfile) -> Toolpath {
    toolpath_with(out, chord, Some(profile))
}

/// Rapid rates (with the rapid override, at most 100 %) and accelerations of X Y Z
/// A B C when `profile` moves G0 axes independently.
fn dogleg_limits(profile: Option<&MachineProfile>) -> Option<([f64; 6], [f64; 6])> {
    let p = profile.filter(|p| p.rapid_positioning == RapidPositioning::Independent)?;
    let ovr = p.rapid_override.clamp(0.0, 1.0);
    let (_, acc) = p.xyzabc_limits();
    let rate = std::array::from_fn(|i| {
        p.axis(['X', 'Y', 'Z', 'A', 'B', 'C'][i])
            .map(|a| a.rapid_rate * ovr)
            .unwrap_or(0.0)
    });
    Some((rate, acc))
}

fn toolpath_with(out: &RunOutput, chord: f64, profile: Option<&MachineProfile>) -> Toolpath {
    let mut tp = Toolpath::default();
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for_each_toolpath_segment(out, chord, profile, |m, kind, points| {
        for p in points {
            for i in 0..3 {
                if p[i].is_finite() {
                    min[i] = min[i].min(p[i]);
                    max[i] = max[i].max(p[i]);
                }
            }
        }
        tp.segments.push(ToolpathSegment {
            kind,
            line: m.line,
            file: m.file.0,
            feed: m.feed,
            tool: m.tool,
            points: points.to_vec(),
        });
        ControlFlow::Continue(())
    });
    if min[0].is_finite() {
        tp.bounds = Bounds { min, max };
    }
    tp
}

/// The polyline of every motion, in order, as [`toolpath_on`] samples it
/// (`profile`: `None` draws rapids straight), handed to `f` with the motion
/// and its kind (`rapid`, `feed`, `arc`) in one reused buffer: a host that
/// keeps its own form of the toolpath allocates nothing per motion. `f`
/// returns [`ControlFlow::Break`] to stop early (a cancelled request).
pub fn for_each_toolpath_segment(
    out: &RunOutput,
    chord: f64,
    profile: Option<&MachineProfile>,
    mut f: impl FnMut(&Motion, &'static str, &[[f64; 3]]) -> ControlFlow<()>,
) {
    let chord = if chord > 0.0 { chord } else { 0.01 };
    let dogleg = dogleg_limits(profile);
    let mut points = Vec::new();
    for m in &out.motions {
        points.clear();
        points.push([m.start[0], m.start[1], m.start[2]]);
        let kind = match m.kind {
            MotionKind::Rapid => "rapid",
            MotionKind::Arc { .. } => "arc",
            _ => "feed",
        };
        if let MotionKind::Arc {
            center,
            normal,
            turns,
            radius,
        } = m.kind
        {
            let sweep = arc_sweep(m, center, normal, turns);
            let r = radius.max(1e-9);
            let step = if chord < r {
                2.0 * (1.0 - chord / r).acos()
            } else {
                std::f64::consts::FRAC_PI_2
            };
            let n = ((sweep / step.max(1e-3)).ceil() as usize).clamp(2, 2048);
            let s = sub3(&xyz(&m.start), &center);
            let along = dot3(&s, &normal);
            let radial = [
                s[0] - along * normal[0],
                s[1] - along * normal[1],
                s[2] - along * normal[2],
            ];
            let b = cross3(&normal, &radial);
            let rise = helix_rise(m, &normal);
            for k in 1..n {
                let f = k as f64 / n as f64;
                let (sn, cs) = (sweep * f).sin_cos();
                points.push([
                    center[0] + (along + rise * f) * normal[0] + radial[0] * cs + b[0] * sn,
                    center[1] + (along + rise * f) * normal[1] + radial[1] * cs + b[1] * sn,
                    center[2] + (along + rise * f) * normal[2] + radial[2] * cs + b[2] * sn,
                ]);
            }
        }
        if let MotionKind::Involute { curve, axes } = m.kind {
            // The tangent turns by dφ per step, on a radius of curvature of at
            // most R·φ: steps that keep the chord within `chord` of the curve.
            let rho = curve.base_radius * curve.phi_start.max(curve.phi_end);
            let step = if chord < rho {
                2.0 * (1.0 - chord / rho).acos()
            } else {
                std::f64::consts::FRAC_PI_2
            };
            let span = curve.phi_end - curve.phi_start;
            let n = ((span.abs() / step.max(1e-3)).ceil() as usize).clamp(2, 2048);
            let (a, b) = (usize::from(axes[0]).min(2), usize::from(axes[1]).min(2));
            for k in 1..n {
                let f = k as f64 / n as f64;
                let q = curve.point(curve.phi_start + span * f);
                let mut p = [
                    m.start[0] + (m.end[0] - m.start[0]) * f,
                    m.start[1] + (m.end[1] - m.start[1]) * f,
                    m.start[2] + (m.end[2] - m.start[2]) * f,
                ];
                p[a] = q[0];
                p[b] = q[1];
                points.push(p);
            }
        }
        if let (MotionKind::Rapid, Some((rate, acc))) = (m.kind, &dogleg) {
            let path = plan::dogleg_path(&m.start, &m.end, rate, acc);
            points.extend(path.iter().skip(1).map(|p| [p[0], p[1], p[2]]));
        } else {
            points.push([m.end[0], m.end[1], m.end[2]]);
        }
        if f(m, kind, &points).is_break() {
            return;
        }
    }
}

/// Per-block times (summed over the motions and events of each (file, line)),
/// on the program's clock, in the order the blocks first ran; a block appears
/// when it moves or its events take time.
pub fn block_times(_out: &RunOutput, dry: &DryRun) -> Vec<BlockTime> {
    dry.blocks.clone()
}
