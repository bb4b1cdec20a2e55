//! Interpreter state at a block boundary. Cloning is cheap: the parameter
//! tables are `Arc`-shared and copied only on write.

use analyzer::{FileId, Span};
use std::collections::HashMap;
use std::sync::Arc;

/// Modal codes, as G numbers in tenths (`G1` = 10, `G61.1` = 611).
#[derive(Debug, Clone, PartialEq)]
pub struct Modal {
    pub motion: u32,
    pub plane: u32,
    pub inch: bool,
    pub incremental: bool,
    /// 930, 940 or 950.
    pub feed_mode: u32,
    /// 1..=9 for G54..G59.3; 100 + n for G54.1 Pn.
    pub origin: usize,
    /// 400, 410, 420.
    pub comp: u32,
    /// 490, 430, 440, 432 (TCP).
    pub tlo_mode: u32,
    /// 610, 611, 640, 641.
    pub path: u32,
    pub path_tol: Option<f64>,
    /// G98 (true) or G99.
    pub retract_old_z: bool,
    pub polar: bool,
    pub scaling: bool,
    pub rotation: bool,
    pub mirror: bool,
    pub dlacc: bool,
    /// G96 constant surface speed.
    pub css: bool,
    /// FANUC rigid tapping requested with M29.
    pub rigid_tap: bool,
    /// G90.1: arc centres are absolute.
    pub ijk_abs: bool,
    /// RS274/NGC G7: X words are diameters.
    pub diameter: bool,
    /// ServoWorks G311: the feed is along the linear axes only (G310, the
    /// default, spreads it over the rotary axes too).
    pub feed_linear_only: bool,
    /// ServoWorks normal direction control: G41.1 (tool left, `Some(true)`),
    /// G42.1 (`Some(false)`) or G40.1 (`None`).
    pub ndc: Option<bool>,
}

/// Memory of a canned cycle's modal data (program frame, mm).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CycleMem {
    pub r: Option<f64>,
    pub z: Option<f64>,
    pub p: Option<f64>,
    pub q: Option<f64>,
    pub i: Option<f64>,
    pub j: Option<f64>,
    pub k: Option<f64>,
    /// Initial level captured when the cycle mode began.
    pub initial: Option<f64>,
    /// FANUC/ServoWorks: R and Z levels resolved to absolute values.
    pub r_abs: Option<f64>,
    pub z_abs: Option<f64>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct State {
    pub modal: Modal,
    /// Programmed point (program frame, before scaling/mirror/rotation), mm/deg.
    pub pos: [f64; 6],
    /// Machine position, mm/deg.
    pub mpos: [f64; 6],
    pub g92: [f64; 6],
    pub g52: [f64; 6],
    /// Tool length offset (Z) and X offset, mm.
    pub tlo: [f64; 6],
    pub comp_radius: f64,
    /// Cutter compensation: the lathe tool orientation (0 and 9: no origin shift).
    pub comp_orientation: u8,
    /// Cutter compensation: the next move is the entry move.
    pub comp_first: bool,
    /// Cutter compensation: the tool tip (program frame), when it differs from `pos`.
    pub comp_tip: [f64; 6],
    /// Cutter compensation: the moves LinuxCNC still holds back (its canon queue),
    /// whose end points the next corner may move.
    pub comp_queue: Vec<CompQueued>,
    /// Cutter compensation: where the first held-back move starts, when known
    /// (LinuxCNC's `endpoint`; it checks pulled-back moves for reversal against it).
    pub comp_endpoint: Option<[f64; 2]>,
    /// Programmed feed (mm/min, or mm/rev under G95; inverse-time value under G93).
    pub feed: f64,
    pub spindle: f64,
    pub spindle_dir: i8,
    pub tool: u32,
    pub next_tool: u32,
    pub mist: bool,
    pub flood: bool,
    /// Numbered parameters (None = vacant).
    pub params: Arc<Vec<Option<f64>>>,
    /// Global named parameters (RS274/NGC).
    pub named: Arc<HashMap<String, f64>>,
    pub cycle: CycleMem,
    /// Scaling centre and factors.
    pub scale: ([f64; 3], [f64; 3]),
    /// Mirror axes and centre.
    pub mirror: ([bool; 3], [f64; 3]),
    /// Rotation centre (plane coordinates) and angle (degrees).
    pub rotation: ([f64; 2], f64),
    pub ended: bool,
    /// ServoWorks: axes switched to torque control (`G10 L20 … R12`), one bit
    /// per axis X…C. Their motion words are torques in % of the rated torque,
    /// not positions, so they do not move the axis in the dry run.
    pub torque_axes: u8,
    /// ServoWorks G43.2: arm length + tool length (mm), from the tip to the
    /// tool base point the linear axes carry.
    pub tcp_length: f64,
    /// Intermediate point of the last G28/G30 (for FANUC/ServoWorks G29).
    pub g28_mid: Option<[f64; 6]>,
    /// 1-based line of the block being executed (`#<_line>`).
    pub line: u32,
    /// FANUC G66 modal macro call: program and arguments.
    pub g66: Option<(String, Arc<Vec<Option<f64>>>)>,
    /// Parameters whose value an earlier runtime error left unknown (`exec/recover.rs`):
    /// numbered ones as `#n`, named ones by their key. Usually empty.
    pub tainted: Vec<String>,
    /// Runtime errors reported and recovered from so far (the cap stops floods).
    pub runtime_errors: u32,
    /// Code and message of each recovered error: a repeat of one (the same fault
    /// on a later block, e.g. every feed move of a program without F) is folded
    /// into the first report and does not count towards the cap.
    pub recovered: Arc<HashMap<(FileId, &'static str, String), Repeated>>,
    /// A call was skipped because its subroutine was not found or not read: the
    /// globals it would have set are unknown, not undefined, and the run's figures
    /// leave out what it runs (`RunOutput::skipped_calls`).
    pub skipped_call: bool,
}

/// A recovered error and its repeats (`exec/recover.rs`).
#[derive(Debug, Clone, PartialEq)]
pub struct Repeated {
    /// Where the first report is in the run's diagnostics.
    pub index: usize,
    /// Later blocks with the same fault.
    pub count: u32,
    /// The first few of them.
    pub spans: Vec<(FileId, Span)>,
}

impl Modal {
    pub fn power_on(servoworks: bool, fanuc: bool) -> Modal {
        Modal {
            // LinuxCNC starts with G80 (no motion mode); FANUC and ServoWorks with G00.
            motion: if servoworks || fanuc { 0 } else { 800 },
            plane: 170,
            inch: false,
            incremental: false,
            feed_mode: 940,
            origin: 1,
            comp: 400,
            tlo_mode: 490,
            path: 640,
            path_tol: None,
            retract_old_z: servoworks || fanuc,
            polar: false,
            scaling: false,
            rotation: false,
            mirror: false,
            dlacc: false,
            css: false,
            rigid_tap: false,
            ijk_abs: false,
            diameter: false,
            feed_linear_only: false,
            ndc: None,
        }
    }

    /// The codes in force, as strings.
    pub fn codes(&self, ngc: bool) -> Vec<String> {
        let g = |t: u32| {
            if t.is_multiple_of(10) {
                format!("G{}", t / 10)
            } else {
                format!("G{}.{}", t / 10, t % 10)
            }
        };
        let mut v = vec![
            g(self.motion),
            g(self.plane),
            if self.inch {
                "G20".into()
            } else {
                "G21".into()
            },
        ];
        v.push(if self.incremental {
            "G91".into()
        } else {
            "G90".into()
        });
        v.push(g(self.feed_mode));
        v.push(match self.origin {
            1..=6 => format!("G5{}", 3 + self.origin),
            7..=9 => format!("G59.{}", self.origin - 6),
            n => format!("G54.1 P{}", n.saturating_sub(100)),
        });
        v.push(g(self.comp));
        v.push(g(self.tlo_mode));
        v.push(g(self.path));
        if ngc || self.modal_cycle() {
            v.push(if self.retract_old_z {
                "G98".into()
            } else {
                "G99".into()
            });
        }
        if self.polar {
            v.push("G16".into());
        }
        if self.scaling {
            v.push("G51".into());
        }
        if self.mirror {
            v.push("G51.1".into());
        }
        if self.rotation {
            v.push("G68".into());
        }
        if self.dlacc {
            v.push("G05".into());
        }
        v
    }

    /// The in-plane axes (indices into X, Y, Z) of the selected plane.
    pub(crate) fn plane_axes(&self) -> (usize, usize) {
        match self.plane {
            180 => (2, 0),
            190 => (1, 2),
            _ => (0, 1),
        }
    }

    /// The axis (index into X, Y, Z) normal to the selected plane.
    pub(crate) fn normal_axis(&self) -> usize {
        match self.plane {
            180 => 1,
            190 => 0,
            _ => 2,
        }
    }

    pub fn modal_cycle(&self) -> bool {
        is_cycle(self.motion)
    }
}

/// Whether a motion code (tenths) is a canned cycle.
pub fn is_cycle(m: u32) -> bool {
    matches!(m, 730 | 740 | 760 | 810..=890)
}

/// Modal group 1 (motion) of RS274/NGC, codes × 10: G0–G3, the splines
/// G5–G5.3, G33/G33.1, the probes G38.2–G38.5, the lathe cycles G70–G72,
/// G80 and the canned cycles.
pub fn is_group_1(g: u32) -> bool {
    matches!(
        g,
        0 | 10 | 20 | 30 | 50..=53 | 330 | 331 | 382..=385 | 700 | 710..=712 | 720..=722 | 800
    ) || is_cycle(g)
}

/// The group-1 codes that move to the block's axis words as its end point.
/// The splines and the lathe cycles read their words their own way, and G80
/// moves nothing.
pub fn moves_to_axis_words(g: u32) -> bool {
    is_group_1(g) && !matches!(g, 50..=53 | 700..=722 | 800)
}

/// One held-back move of cutter compensation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompQueued {
    /// Index of its canonical line.
    pub canon: usize,
    /// Index of its motion.
    pub motion: usize,
    /// 0 feed, 1 rapid, 2 arc.
    pub kind: u8,
    /// Straight moves: the direction LinuxCNC checks a pulled-back end against.
    pub dir: [f64; 2],
    /// Arcs: the (compensated) centre in plane coordinates.
    pub center: [f64; 2],
    /// Arcs: signed turn count (positive counter-clockwise).
    pub turn: i32,
    /// Arcs: the sweep (radians, signed) of the programmed arc; 0 for inserted corner arcs.
    pub sweep: f64,
}
