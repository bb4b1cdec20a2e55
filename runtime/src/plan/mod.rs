//! Velocity planning with look-ahead: from motion segments and machine events to
//! per-segment times and the cycle time.
//!
//! The planner is streaming: feed [`Event`]s one at a time with [`Planner::push`],
//! collect [`SegmentTiming`]s from the callback, and call [`Planner::finish`] for
//! the [`Totals`]. It keeps at most `lookahead + 2` segments in memory, and the
//! work per segment is O(lookahead), so a 20-million-line program is planned in
//! bounded memory and linear time. [`plan`] is the convenience wrapper that
//! collects everything into a [`PlanResult`].
//!
//! Units: mm, degrees (rotary axes), seconds; feeds in mm/s (deg/s for moves of
//! rotary axes only).
//!
//! Models (see [`PlannerModel`]):
//! * `linuxcnc` follows LinuxCNC 2.9's trajectory planner (`tp.c`, `blendmath.c`)
//!   and canonical layer (`emccanon.cc`): per-move velocity and acceleration limits
//!   derived from the axis limits, `[TRAJ]MAX_LINEAR_VELOCITY` capping the path
//!   speed (its acceleration cap is not applied, as measured), arcs keeping half the
//!   acceleration for the tangential direction until a following move finalises them,
//!   a 10 % acceleration cut ("kink ratio") on both moves of a corner that is not
//!   blended, G64 blend arcs for line-line, line-arc, arc-line and arc-arc corners (tolerance
//!   P, or a quarter of the shorter move without P) that may swallow a short rest of
//!   the previous line, joining of nearly collinear G64 moves within Q (the "naive
//!   CAM" detector; Q defaults to P), which also takes an XY arc whose chord lies
//!   within Q as two lines, the centripetal limit of helices on LinuxCNC's effective
//!   radius (the whole rise, not the rise per radian), the optimisation depth and
//!   lazy cut-off of the backward pass, and by default execution period by period
//!   with LinuxCNC's velocity update, ramps and split cycles
//!   ([`MachineProfile::servo_simulation`]). All 142 measured goldens in
//!   `tests/cycle_time` are reproduced within 1 ms, the 244 CAM-shaped runs of
//!   `tests/cycle_time/cam` with a median error of 0.03 % and at most 3.7 % (a G64
//!   corner from a line into a chain of tiny arcs out of the XY plane).
//! * `trapezoid` and `scurve` are generic look-ahead planners: corner speed from
//!   the blend tolerance (the largest arc that stays within it), full tangential
//!   acceleration on arcs with a centripetal cap, and for `scurve` the extra time of
//!   jerk-limited ramps.
//!
//! Known gaps of the `linuxcnc` model: corners next to `Path` curves use the
//! line-line blend construction on the tangents; helices at G64 corners get a
//! parabolic or tangent junction, never a blend arc (as in LinuxCNC, but not
//! checked against it); the closed-form execution approximates parabolic blends
//! (used when no blend arc can be built, e.g. with rotary axes) and ramp decisions;
//! spindle-synchronised motion (G33, G76, rigid tapping) and feed override changes
//! are not modelled.

mod engine;
pub mod explain;
pub mod profile;
mod servo;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::machine::{MachineProfile, PlannerModel, RapidPositioning};
pub use engine::Planner;

/// Position of all six program axes: X Y Z (mm) and A B C (degrees).
pub type Pose = [f64; 6];

/// Geometry of a motion segment.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum SegmentKind {
    /// Rapid positioning (G0): axis rapid rates, no programmed feed.
    Rapid,
    /// Straight feed move (G1).
    Line,
    /// Circular arc or helix (G2/G3). `normal` is a unit vector; a positive `sweep`
    /// turns counter-clockwise about it. `sweep` is the total angle in radians
    /// including extra full turns. The helical rise is `end − start` along `normal`.
    Arc {
        center: [f64; 3],
        normal: [f64; 3],
        radius: f64,
        sweep: f64,
    },
    /// Any other curve (NURBS, involute, exponential, polar…): known length,
    /// tangent directions at both ends and an upper bound of its curvature (1/mm).
    Path {
        start_tangent: [f64; 3],
        end_tangent: [f64; 3],
        max_curvature: f64,
    },
}

/// What the control does at the end of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum PathMode {
    /// Stop at the end of every segment (G61.1, G09, FANUC G61, rapids on most controls).
    ExactStop,
    /// LinuxCNC G61 ("exact path"): stop at corners, run through tangent joints.
    ExactPath,
    /// Continuous path (G64): round the corner within `tolerance` mm
    /// (0 = as much as the geometry allows). `naive` is the `linuxcnc` model's
    /// naive-CAM tolerance (LinuxCNC's Q, which defaults to P): consecutive straight
    /// feed moves that stay within it are joined into one; 0 joins nothing.
    Blend { tolerance: f64, naive: f64 },
}

impl PathMode {
    /// G64 P`tolerance` without Q: the naive-CAM tolerance is the same.
    pub const fn blend(tolerance: f64) -> PathMode {
        PathMode::Blend {
            tolerance,
            naive: tolerance,
        }
    }
}

/// One motion segment as produced by the interpreter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    pub kind: SegmentKind,
    pub start: Pose,
    pub end: Pose,
    /// Path length in mm (XYZ), or in degrees for moves of rotary axes only.
    /// Curves planned as lines (involutes, exponential moves) give their own
    /// length here, which the planner uses instead of the chord.
    pub length: f64,
    /// Programmed feed, mm/s (ignored for rapids).
    pub feed: f64,
    pub mode: PathMode,
    /// Index of the source block, reported back in the timings.
    pub block: u32,
    /// Tool in the spindle (0 = none).
    pub tool: u32,
}

impl Segment {
    /// A straight move from `start` to `end` (XYZ only) of the given kind.
    pub fn line(start: [f64; 3], end: [f64; 3], feed: f64, mode: PathMode) -> Segment {
        let s = [start[0], start[1], start[2], 0.0, 0.0, 0.0];
        let e = [end[0], end[1], end[2], 0.0, 0.0, 0.0];
        Segment {
            kind: SegmentKind::Line,
            start: s,
            end: e,
            length: dist3(&start, &end),
            feed,
            mode,
            block: 0,
            tool: 0,
        }
    }

    /// A rapid move from `start` to `end` (XYZ only).
    pub fn rapid(start: [f64; 3], end: [f64; 3], mode: PathMode) -> Segment {
        Segment {
            kind: SegmentKind::Rapid,
            ..Segment::line(start, end, 0.0, mode)
        }
    }

    /// An arc in a plane through `center` with unit `normal`, from `start` turning by
    /// `sweep` radians (positive = counter-clockwise about `normal`), rising by
    /// `rise` along the normal. The end point and length are computed.
    pub fn arc(
        start: [f64; 3],
        center: [f64; 3],
        normal: [f64; 3],
        sweep: f64,
        rise: f64,
        feed: f64,
        mode: PathMode,
    ) -> Segment {
        let r = sub3(&start, &center);
        let n = normal;
        // Radial part of the start vector (remove any component along the normal).
        let along = dot3(&r, &n);
        let radial = [
            r[0] - along * n[0],
            r[1] - along * n[1],
            r[2] - along * n[2],
        ];
        let radius = norm3(&radial);
        let b = cross3(&n, &radial);
        let (s, c) = sweep.sin_cos();
        let end = [
            center[0] + along * n[0] + radial[0] * c + b[0] * s + n[0] * rise,
            center[1] + along * n[1] + radial[1] * c + b[1] * s + n[1] * rise,
            center[2] + along * n[2] + radial[2] * c + b[2] * s + n[2] * rise,
        ];
        let planar = radius * sweep.abs();
        Segment {
            kind: SegmentKind::Arc {
                center,
                normal,
                radius,
                sweep,
            },
            start: [start[0], start[1], start[2], 0.0, 0.0, 0.0],
            end: [end[0], end[1], end[2], 0.0, 0.0, 0.0],
            length: (planar * planar + rise * rise).sqrt(),
            feed,
            mode,
            block: 0,
            tool: 0,
        }
    }

    /// Sets the source block index.
    pub fn with_block(mut self, block: u32) -> Segment {
        self.block = block;
        self
    }

    /// Sets the tool number.
    pub fn with_tool(mut self, tool: u32) -> Segment {
        self.tool = tool;
        self
    }
}

/// Input to the planner: motion, or something that takes time without moving.
// Most events are motions, so boxing the motion would cost an allocation per
// segment to save the few bytes the other variants leave unused.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Event {
    Motion(Segment),
    /// G4: motion stops first, then the control waits.
    Dwell {
        seconds: f64,
        block: u32,
    },
    /// M6: motion stops, the changer runs for the profile's tool-change time.
    ToolChange {
        tool: u32,
        block: u32,
    },
    /// M3/M4, or an S word while the spindle turns: the spindle ramps to `rpm`
    /// (positive clockwise, negative counter-clockwise) before motion resumes, in
    /// `spindle_ramp_time` plus `spindle_ramp_per_1000rpm` per 1000 rpm of change.
    SpindleStart {
        rpm: f64,
        block: u32,
    },
    /// M5: the spindle ramps down from its speed.
    SpindleStop {
        block: u32,
    },
    /// M0 (or M1 when `optional` and the optional stop switch is on).
    ProgramStop {
        optional: bool,
        block: u32,
    },
    /// Another M code: `code` is its number × 10 (190 for M19). M19 takes
    /// `spindle_orient_time`, M7/M8/M9 `coolant_time`, the pallet change code
    /// `pallet_change_time`, any other `m_code_times` or `m_code_time`. A code
    /// whose time is 0 does not stop the motion.
    MCode {
        code: u32,
        block: u32,
    },
    /// A T word that only selects the next tool (profile `tool_select_time`; 0
    /// does not stop the motion).
    ToolSelect {
        tool: u32,
        block: u32,
    },
}

/// Timing of one executed planner element. Blend arcs inserted by the `linuxcnc`
/// model appear as their own elements, tagged with the block of the move they
/// round off; short moves the blend swallowed entirely have no element.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SegmentTiming {
    pub block: u32,
    pub tool: u32,
    pub rapid: bool,
    /// True for a blend arc the planner inserted.
    pub blend: bool,
    pub start_s: f64,
    pub end_s: f64,
    /// Path speed when the element starts, mm/s.
    pub entry_speed: f64,
    /// Highest path speed on the element, mm/s.
    pub peak_speed: f64,
    /// Path speed when the element ends, mm/s.
    pub exit_speed: f64,
    /// Length actually travelled on this element, mm.
    pub length: f64,
    /// Where this element's time went; the parts sum to the time it added to
    /// `motion_s`.
    pub causes: Causes,
}

/// Motion time by cause, s, read off the planner's velocity profile of each
/// element: the time the element would take at its programmed feed, the time a
/// speed cap below that feed adds (by which cap), and the time its ramps add
/// below the cap, charged to the corner (blend, exact stop, corner speed) when
/// the junction's corner limit set the speed there and to acceleration
/// otherwise (a start from rest, or a move too short to reach speed). Rapids
/// are one cause. The parts of an element sum to its time.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Causes {
    /// Cutting at the programmed feed (with the feed override).
    pub feed_s: f64,
    /// Ramps limited by acceleration: starts and stops, moves too short to reach speed.
    pub accel_s: f64,
    /// Ramps to a corner's speed (blend, exact stop, tangent kink) and blend arcs
    /// slower than the feed.
    pub corner_s: f64,
    /// An axis velocity limit below the feed.
    pub axis_cap_s: f64,
    /// `[TRAJ]MAX_LINEAR_VELOCITY` (the path speed cap) below the feed.
    pub traj_cap_s: f64,
    /// The centripetal limit of an arc or curve below the feed.
    pub curve_cap_s: f64,
    /// A move so short that it cannot run in fewer servo periods at the feed.
    pub servo_cap_s: f64,
    /// Rapid positioning.
    pub rapid_s: f64,
}

impl Causes {
    /// The sum of every cause.
    pub fn total_s(&self) -> f64 {
        self.feed_s
            + self.accel_s
            + self.corner_s
            + self.axis_cap_s
            + self.traj_cap_s
            + self.curve_cap_s
            + self.servo_cap_s
            + self.rapid_s
    }

    /// Adds `o` cause by cause.
    pub fn add(&mut self, o: &Causes) {
        self.feed_s += o.feed_s;
        self.accel_s += o.accel_s;
        self.corner_s += o.corner_s;
        self.axis_cap_s += o.axis_cap_s;
        self.traj_cap_s += o.traj_cap_s;
        self.curve_cap_s += o.curve_cap_s;
        self.servo_cap_s += o.servo_cap_s;
        self.rapid_s += o.rapid_s;
    }
}

/// How many feed elements each cause touched, and the feed elements that never
/// reach their target speed, for sentences like "1,842 segments shorter than
/// 0.05 mm never reach F2000".
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct CauseCounts {
    /// Elements with acceleration time.
    pub accel: u64,
    /// Elements with corner time.
    pub corner: u64,
    pub axis_cap: u64,
    pub traj_cap: u64,
    pub curve_cap: u64,
    pub servo_cap: u64,
    /// Feed elements whose peak speed stays below their target speed.
    pub short: u64,
    /// Their time, s.
    pub short_s: f64,
    /// The longest of them, mm.
    pub short_max_mm: f64,
    /// The lowest and highest programmed feed among them (with the override), mm/s.
    pub short_feed_min: f64,
    pub short_feed_max: f64,
}

/// Per-tool breakdown.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ToolTotals {
    pub motion_s: f64,
    pub rapid_s: f64,
    pub cutting_s: f64,
    pub distance_mm: f64,
}

/// Program totals. `cycle_time_s` = `motion_s` + `dwell_s` + `tool_change_s` + `other_s`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Totals {
    pub cycle_time_s: f64,
    /// Time with at least one axis moving.
    pub motion_s: f64,
    pub rapid_s: f64,
    pub cutting_s: f64,
    pub dwell_s: f64,
    pub tool_change_s: f64,
    /// Every other auxiliary time: the sum of the [`Auxiliary`] categories
    /// other than the tool change.
    pub other_s: f64,
    /// Auxiliary (non-motion) time by category.
    pub aux: Auxiliary,
    /// Path length travelled (blend arcs cut corners, so this can be a little less
    /// than the programmed length; dog-leg rapids are longer than the line).
    pub distance_mm: f64,
    pub per_tool: BTreeMap<u32, ToolTotals>,
    /// Motion time by cause (sums to `motion_s`).
    pub causes: Causes,
    pub cause_counts: CauseCounts,
}

/// Auxiliary time by category, s, and how many events made it.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Auxiliary {
    /// M6 (ServoWorks: T), also in [`Totals::tool_change_s`].
    pub tool_change_s: f64,
    pub tool_changes: u32,
    /// T words that only select a tool.
    pub tool_select_s: f64,
    /// Spindle starts, stops and speed changes.
    pub spindle_s: f64,
    /// M19.
    pub orient_s: f64,
    /// M7, M8, M9.
    pub coolant_s: f64,
    pub pallet_change_s: f64,
    /// Other M codes.
    pub m_code_s: f64,
    /// In-position settling at exact stops.
    pub in_position_s: f64,
    /// M0 and M1: operator time.
    pub program_stop_s: f64,
    pub program_stops: u32,
}

impl Auxiliary {
    /// The sum of every category.
    pub fn total_s(&self) -> f64 {
        self.tool_change_s
            + self.tool_select_s
            + self.spindle_s
            + self.orient_s
            + self.coolant_s
            + self.pallet_change_s
            + self.m_code_s
            + self.in_position_s
            + self.program_stop_s
    }
}

/// Everything [`plan`] computes.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct PlanResult {
    pub timings: Vec<SegmentTiming>,
    pub totals: Totals,
}

/// Plans a whole event sequence and collects the timings.
pub fn plan<I: IntoIterator<Item = Event>>(profile: &MachineProfile, events: I) -> PlanResult {
    let mut timings = Vec::new();
    let mut planner = Planner::new(profile);
    for ev in events {
        planner.push(ev, &mut |t| timings.push(t));
    }
    let totals = planner.finish(&mut |t| timings.push(t));
    PlanResult { timings, totals }
}

/// The naive estimate (length / feed, rapids at the TRAJ or axis rate, no
/// acceleration) that the validation report compares against.
pub fn naive_motion_time(profile: &MachineProfile, segments: &[Segment]) -> f64 {
    let mut t = 0.0;
    for s in segments {
        let v = match s.kind {
            SegmentKind::Rapid => profile.traj_max_velocity.min(
                profile
                    .axes
                    .iter()
                    .map(|a| a.rapid_rate)
                    .fold(f64::INFINITY, f64::min),
            ),
            _ => s.feed,
        };
        if v > 0.0 && v.is_finite() {
            t += s.length / v;
        }
    }
    t
}

/// One axis moving rest to rest over `d` at most at `v` with acceleration `a`:
/// the trapezoid's duration and the times its acceleration ends and its
/// deceleration starts.
fn axis_ramp(d: f64, v: f64, a: f64) -> (f64, f64, f64) {
    let total = profile::trapezoid(d, 0.0, v, 0.0, a).time;
    let ramp = (v / a).min(total / 2.0);
    (total, ramp, total - ramp)
}

/// Distance an axis of [`axis_ramp`] has covered at time `t`.
fn axis_position(d: f64, v: f64, a: f64, t: f64) -> f64 {
    let (total, ramp, decel) = axis_ramp(d, v, a);
    if t >= total {
        d
    } else if t <= ramp {
        0.5 * a * t * t
    } else if t <= decel {
        0.5 * a * ramp * ramp + a * ramp * (t - ramp)
    } else {
        d - 0.5 * a * (total - t) * (total - t)
    }
}

/// The path of a G0 whose axes move independently (FANUC non-linear
/// positioning, ServoWorks G00 without linear interpolation): every axis starts
/// at once and runs its own trapezoid at its rapid rate `rate[i]` and acceleration
/// `acc[i]`, so the tool leaves the straight line where the first axis arrives.
/// Returns points from `start` to `end`: every moment an axis changes phase, and
/// between them eight steps where the path bends. Each axis moves monotonically,
/// so every point lies in the box the end points span. An axis with no rate or
/// acceleration (not on the machine) moves at once.
pub fn dogleg_path(start: &Pose, end: &Pose, rate: &[f64; 6], acc: &[f64; 6]) -> Vec<Pose> {
    let moving = |i: usize| rate[i] > 0.0 && acc[i] > 0.0 && end[i] != start[i];
    let d: [f64; 6] = std::array::from_fn(|i| (end[i] - start[i]).abs());
    let mut times = vec![0.0];
    for i in (0..6).filter(|i| moving(*i)) {
        let (total, ramp, decel) = axis_ramp(d[i], rate[i], acc[i]);
        times.extend([ramp, decel, total]);
    }
    times.retain(|t| t.is_finite());
    times.sort_by(f64::total_cmp);
    times.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    let at = |t: f64| -> Pose {
        std::array::from_fn(|i| {
            if !moving(i) {
                return end[i];
            }
            let x = axis_position(d[i], rate[i], acc[i], t);
            start[i] + x.copysign(end[i] - start[i])
        })
    };
    let mut points = vec![*start];
    for w in times.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        let mid = 0.5 * (t0 + t1);
        // The path bends where two axes move and one of them changes speed.
        let movers = (0..6)
            .filter(|i| moving(*i) && axis_ramp(d[*i], rate[*i], acc[*i]).0 > mid)
            .count();
        let ramping = (0..6).any(|i| {
            let (total, ramp, decel) = axis_ramp(d[i], rate[i], acc[i]);
            moving(i) && mid < total && (mid < ramp || mid > decel)
        });
        let steps = if movers > 1 && ramping { 8 } else { 1 };
        for k in 1..=steps {
            points.push(at(t0 + (t1 - t0) * k as f64 / steps as f64));
        }
    }
    // The last sample is the end point up to rounding: make it exact.
    if points.len() > 1 {
        points.pop();
    }
    points.push(*end);
    points
}

/// Length of a polyline through the XYZ of `points`, mm.
pub fn polyline_length(points: &[Pose]) -> f64 {
    points
        .windows(2)
        .map(|w| dist3(&[w[0][0], w[0][1], w[0][2]], &[w[1][0], w[1][1], w[1][2]]))
        .sum()
}

pub(crate) fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn sub3(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn cross3(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn norm3(a: &[f64; 3]) -> f64 {
    dot3(a, a).sqrt()
}

pub(crate) fn dist3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    norm3(&sub3(a, b))
}

pub(crate) fn unit3(a: &[f64; 3]) -> [f64; 3] {
    let n = norm3(a);
    if n > 0.0 {
        [a[0] / n, a[1] / n, a[2] / n]
    } else {
        [0.0; 3]
    }
}
