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
//!   the previous line, joining of nearly collinear G64 P moves (the "naive CAM"
//!   detector), the optimisation depth and lazy cut-off of the backward pass, and by
//!   default execution period by period with LinuxCNC's velocity update, ramps and
//!   split cycles ([`MachineProfile::servo_simulation`]). All 142 measured goldens
//!   in `tests/cycle_time` are reproduced within 1 ms.
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
pub mod profile;
mod servo;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::machine::{MachineProfile, PlannerModel};
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
    /// (0 = as much as the geometry allows). In the `linuxcnc` model a non-zero
    /// tolerance is also the naive-CAM tolerance (LinuxCNC's Q, which defaults to P):
    /// consecutive straight feed moves that stay within it are joined into one.
    Blend { tolerance: f64 },
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
    /// M3/M4: the spindle ramps up (profile `spindle_ramp_time`) before motion resumes.
    SpindleStart {
        block: u32,
    },
    /// M5: the spindle ramps down.
    SpindleStop {
        block: u32,
    },
    /// M0 (or M1 when `optional` and the optional stop switch is on).
    ProgramStop {
        optional: bool,
        block: u32,
    },
    /// Another M code that waits for a machine handshake (profile `m_code_time`).
    MCode {
        code: u32,
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
    /// Spindle ramps, M-code handshakes, program stops.
    pub other_s: f64,
    /// Path length travelled (blend arcs cut corners, so this can be a little less
    /// than the programmed length).
    pub distance_mm: f64,
    pub per_tool: BTreeMap<u32, ToolTotals>,
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
