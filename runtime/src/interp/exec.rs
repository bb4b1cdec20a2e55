//! Block execution.

// Axis arrays are indexed in parallel (program, machine, offsets), which reads
// more clearly with indices than with zipped iterators.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;
use std::sync::Arc;

use analyzer::syntax::{
    BlockKind, CommentKind, Expr, ExprId, ItemKind, MacroStmt, OKeyword, OLabel, Program, WordValue,
};
use analyzer::{Diagnostic, Dialect, FileId, Severity, Span, Variant};

use super::arc::{self, ArcError, ArcSpec};
use super::expr::{self, EvalError, Val, VarSource};
use super::files::{label_key, FileEntry, ProgRef};
use super::machine_cfg::{parse_tool_table, parse_var_file, MachineCfg};
use super::rotary_feed;
use super::state::{is_cycle, CompQueued, CycleMem, Modal, State};
use super::types::*;

mod budget;
mod context;
mod g37;
mod g7x;
mod g7x_geom;
pub(super) use g37::G37Cfg;
mod resume;
use crate::canon::{f4, Canon};
use crate::rules::codes;
pub use resume::{rerun, run_checkpointed, Checkpoints};

#[path = "checks.rs"]
mod checks;
#[path = "fast.rs"]
mod fast;
#[path = "spec_checks.rs"]
mod spec_checks;

const NUM_PARAMS: usize = 20_000;

/// Blocks of the main file that get a [`BlockSnapshot`]; beyond this the
/// snapshots stay `None` so that multi-million-line programs fit in memory.
pub const SNAPSHOT_LIMIT: usize = 2_000_000;

/// Pecks per hole after which a peck cycle finishes the hole in one move.
const MAX_PECKS: u32 = 1_000;

/// Runs a program. Never panics; bounded by `step_budget` and the call depth.
pub fn run(input: &RunInput<'_>) -> RunOutput {
    run_with_snapshots(input, true)
}

/// Like [`run`]; with `snapshots` false no per-block state is kept (batch hosts that
/// only need motions and diagnostics save about 500 bytes per block).
pub fn run_with_snapshots(input: &RunInput<'_>, snapshots: bool) -> RunOutput {
    let mut it = Interp::new(input, snapshots);
    it.run_main();
    it.finish()
}

/// Like [`run_with_snapshots`] with every block on the general path: the reference
/// the fast path for plain motion blocks is tested against.
#[doc(hidden)]
pub fn run_without_fast_path(input: &RunInput<'_>, snapshots: bool) -> RunOutput {
    let mut it = Interp::new(input, snapshots);
    it.fast_path = false;
    it.run_main();
    it.finish()
}

/// The 2007 EMC2 interpreter refuses every concave corner under cutter radius
/// compensation (rs274ngc.md NGC416); LinuxCNC 2.9 stops the tool short instead.
const EMC2_CONCAVE: &str = "Concave corner with cutter radius comp";

/// Motions a streaming run hands to its sink at a time: big enough that the sink's
/// per-call cost vanishes, small enough that memory stays flat.
const STREAM_CHUNK: usize = 4096;

/// A receiver of a run's motions and events in order, chunk by chunk. An event's
/// `motion_index` counts from the first motion of the chunk it arrives with, so an
/// event with index `k` happens before `motions[k]` of that chunk (or after all of
/// them when `k == motions.len()`).
pub type MotionSink<'s> = dyn FnMut(&[Motion], &[Event]) + 's;

/// A [`MotionSink`] that receives the interpreter's own buffers: it may take their
/// contents (swapping in empty vectors it has recycled) instead of copying them.
/// Whatever it leaves in them is dropped.
pub type OwnedMotionSink<'s> = dyn FnMut(&mut Vec<Motion>, &mut Vec<Event>) + 's;

/// Like [`run_with_snapshots`] without snapshots, but motions and events go to `sink`
/// while the program runs instead of accumulating in the output: hosts that only
/// need totals (cycle time) or nothing at all (lint) run in memory that does not grow
/// with the program. The returned output has empty `motions` and `events`.
pub fn run_streaming(input: &RunInput<'_>, sink: &mut MotionSink<'_>) -> RunOutput {
    run_streaming_owned(input, &mut |m, e| sink(m, e))
}

/// [`run_streaming`] handing over the buffers themselves ([`OwnedMotionSink`]).
pub fn run_streaming_owned(input: &RunInput<'_>, sink: &mut OwnedMotionSink<'_>) -> RunOutput {
    let mut it = Interp::new(input, false);
    it.run_main_with(Some(sink));
    let mut out = it.finish();
    if !out.motions.is_empty() || !out.events.is_empty() {
        sink(&mut out.motions, &mut out.events);
    }
    out.motions = Vec::new();
    out.events = Vec::new();
    out
}

/// Where control goes after a block.
enum Flow {
    Next,
    Goto(usize, u32),
    Stop,
}

#[derive(Debug, Clone)]
enum FrameKind {
    /// RS274/NGC `o… call`.
    NgcSub,
    /// FANUC/ServoWorks M98 (shares locals) or G65 (new locals); `repeat` left.
    Sub { start: u32, repeat: u32 },
}

#[derive(Debug, Clone)]
struct Frame {
    kind: FrameKind,
    ret_file: usize,
    ret_block: u32,
    /// Caller's local parameters, restored on return.
    saved: Option<Vec<Option<f64>>>,
    named_locals: HashMap<String, f64>,
    call_span: Span,
    /// Called by a G66 modal call (no nested modal calls inside it).
    modal_call: bool,
    /// RS274/NGC: the state saved by M70/M73 at this call level.
    context: Option<context::SavedContext>,
}

/// The evaluated words of one block.
#[derive(Default)]
struct Words {
    v: [Option<f64>; 26],
    span: [Span; 26],
    point: [bool; 26],
    g: Vec<(u32, Span)>,
    m: Vec<(u32, Span)>,
    pname: Option<String>,
    n: Option<i64>,
    ijk_order: Vec<(u8, f64)>,
    /// The N number as written.
    n_text: Option<String>,
    /// RS274/NGC polar words `@` (radius) and `^` (angle, degrees).
    polar_r: Option<f64>,
    polar_a: Option<f64>,
    /// K as written (a repeat count in FANUC/ServoWorks cycles).
    raw_k: Option<f64>,
}

impl Words {
    fn get(&self, c: u8) -> Option<f64> {
        self.v.get((c - b'A') as usize).copied().flatten()
    }
    fn has(&self, c: u8) -> bool {
        self.get(c).is_some()
    }
    fn sp(&self, c: u8) -> Span {
        self.span
            .get((c - b'A') as usize)
            .copied()
            .unwrap_or_default()
    }
    fn has_g(&self, t: u32) -> bool {
        self.g.iter().any(|(g, _)| *g == t)
    }
    fn g_span(&self, t: u32) -> Span {
        self.g
            .iter()
            .find(|(g, _)| *g == t)
            .map(|(_, s)| *s)
            .unwrap_or_default()
    }
    fn has_m(&self, t: u32) -> bool {
        self.m.iter().any(|(m, _)| *m == t)
    }
    fn any_axis(&self) -> bool {
        b"XYZABCUVW".iter().any(|c| self.has(*c))
            || self.polar_r.is_some()
            || self.polar_a.is_some()
    }
}

struct Vars<'s> {
    st: &'s State,
    locals: Option<&'s HashMap<String, f64>>,
    dialect: Dialect,
    /// Tool-table offsets (X Y Z) and diameter of the tool in the spindle, in the tool
    /// table's units.
    tool: [f64; 4],
}

impl VarSource for Vars<'_> {
    fn get_num(&self, n: i64, span: Span) -> Result<Val, EvalError> {
        if n < 0 || n as usize >= NUM_PARAMS {
            let code = if self.dialect == Dialect::Rs274ngc {
                "X006"
            } else {
                "X007"
            };
            return Err(EvalError {
                span,
                message: format!("parameter number #{n} out of range"),
                code,
            });
        }
        if self.dialect == Dialect::Rs274ngc && (5401..=5403).contains(&n) {
            return Ok(Some(self.tool[(n - 5401) as usize]));
        }
        if self.dialect == Dialect::Rs274ngc && n == 5410 {
            return Ok(Some(self.tool[3]));
        }
        if let Some(v) = system_var(self.st, self.dialect, n) {
            return Ok(Some(v));
        }
        let v = self.st.params.get(n as usize).copied().flatten();
        Ok(if self.dialect == Dialect::Rs274ngc {
            Some(v.unwrap_or(0.0))
        } else {
            v
        })
    }
    fn get_named(&self, name: &str, span: Span) -> Result<Val, EvalError> {
        if let Some(v) = self.locals.and_then(|l| l.get(name)) {
            return Ok(Some(*v));
        }
        if let Some(v) = self.st.named.get(name) {
            return Ok(Some(*v));
        }
        if let Some(v) = predefined(self.st, name) {
            return Ok(Some(v));
        }
        Err(EvalError {
            span,
            message: format!("named parameter #<{name}> not defined"),
            code: "X006",
        })
    }
    fn named_exists(&self, name: &str) -> bool {
        self.locals.is_some_and(|l| l.contains_key(name))
            || self.st.named.contains_key(name)
            || predefined(self.st, name).is_some()
    }
}

/// Read-only system variables computed from the state: FANUC/ServoWorks
/// #4001… modal codes, #5001… end point, #5021… machine, #5041… work
/// position; LinuxCNC #5420… current position.
fn system_var(st: &State, d: Dialect, n: i64) -> Option<f64> {
    // RS274/NGC keeps lengths in program units already.
    let u = if st.modal.inch && d != Dialect::Rs274ngc {
        25.4
    } else {
        1.0
    };
    let axis = |v: &[f64; 6], i: usize| if i < 3 { v[i] / u } else { v[i] };
    match d {
        Dialect::Rs274ngc => match n {
            5420..=5425 => Some(axis(&st.pos, (n - 5420) as usize)),
            5400 => Some(f64::from(st.tool)),
            _ => None,
        },
        _ => match n {
            4001 => Some(f64::from(st.modal.motion) / 10.0),
            4002 => Some(f64::from(st.modal.plane) / 10.0),
            4003 => Some(if st.modal.incremental { 91.0 } else { 90.0 }),
            4005 => Some(f64::from(st.modal.feed_mode) / 10.0),
            4006 => Some(if st.modal.inch { 20.0 } else { 21.0 }),
            4007 => Some(f64::from(st.modal.comp) / 10.0),
            4008 => Some(f64::from(st.modal.tlo_mode) / 10.0),
            4009 => Some(if st.modal.modal_cycle() {
                f64::from(st.modal.motion) / 10.0
            } else {
                80.0
            }),
            4010 => Some(if st.modal.retract_old_z { 98.0 } else { 99.0 }),
            4014 => Some(match st.modal.origin {
                o @ 1..=6 => 53.0 + o as f64,
                _ => 54.1,
            }),
            4109 => Some(st.feed / u),
            4119 => Some(st.spindle),
            4120 => Some(f64::from(st.tool)),
            5001..=5006 | 5041..=5046 => Some(axis(&st.pos, ((n - 1) % 20) as usize)),
            5021..=5026 => Some(axis(&st.mpos, (n - 5021) as usize)),
            5081..=5086 => Some(axis(&st.tlo, (n - 5081) as usize)),
            _ => None,
        },
    }
}

/// LinuxCNC read-only named parameters, in program units.
fn predefined(st: &State, name: &str) -> Option<f64> {
    // Only RS274/NGC has named parameters, and it keeps program units.
    let u = 1.0;
    let axes = ["x", "y", "z", "a", "b", "c"];
    for (i, a) in axes.iter().enumerate() {
        if name.strip_prefix('_') == Some(a) {
            return Some(if i < 3 { st.pos[i] / u } else { st.pos[i] });
        }
        if name == format!("_abs_{a}") {
            return Some(if i < 3 { st.mpos[i] / u } else { st.mpos[i] });
        }
    }
    Some(match name {
        "_metric" => f64::from(u8::from(!st.modal.inch)),
        "_imperial" => f64::from(u8::from(st.modal.inch)),
        "_lathe_diameter_mode" => f64::from(u8::from(st.modal.diameter)),
        "_lathe_radius_mode" => f64::from(u8::from(!st.modal.diameter)),
        "_absolute" => f64::from(u8::from(!st.modal.incremental)),
        "_incremental" => f64::from(u8::from(st.modal.incremental)),
        "_feed" => st.feed / u,
        "_rpm" => st.spindle,
        "_current_tool" => f64::from(st.tool),
        "_selected_tool" => f64::from(st.next_tool),
        "_coord_system" => 530.0 + 10.0 * st.modal.origin as f64,
        "_motion_mode" => f64::from(st.modal.motion),
        "_plane" => f64::from(st.modal.plane),
        "_value" | "_value_returned" => 0.0,
        "_line" => f64::from(st.line),
        _ => return None,
    })
}

struct Interp<'a, 'i> {
    input: &'i RunInput<'a>,
    dialect: Dialect,
    variant: Variant,
    cfg: MachineCfg,
    files: Vec<FileEntry<'a>>,
    file_names: HashMap<String, usize>,
    st: State,
    frames: Vec<Frame>,
    repeats: Vec<(usize, u32, i64)>,
    out: RunOutput,
    canon: Option<Canon>,
    steps: u64,
    /// Where the interpreter is: file index and block.
    cur: (usize, u32),
    cur_line: u32,
    /// RS274/NGC: the file opened with `%`.
    percent_open: bool,
    saw_end: bool,
    /// Last arc for snapshots / rules.
    nblocks_main: usize,
    after_end_reported: bool,
    /// Locals of the main level (RS274/NGC named parameters without `_`).
    main_locals: HashMap<String, f64>,
    limit_reports: u32,
    /// G09 in the current block (FANUC/ServoWorks one-shot exact stop).
    block_exact: bool,
    /// Memory of the state checks (tool words, G40, motion seen).
    chk: checks::Mem,
    modal_cache: Option<(Modal, Vec<String>)>,
    /// Motions already handed to a streaming sink.
    motions_drained: usize,
    /// P/Q of the last G5 (the next G5 without I/J mirrors them).
    spline_pq: (f64, f64),
    /// Control points of an open G5.2 NURBS block.
    nurbs: Vec<([f64; 6], f64)>,
    /// Memory of the spec-ledger checks (`spec_checks.rs`).
    spec: spec_checks::SpecMem,
    /// RS274/NGC canon: how far tool-length-offset changes have moved the programmed
    /// point since the last move.  rs274's standalone canon tracks the last commanded
    /// point without tool offsets, and a tool change (M6, M61) makes the interpreter
    /// re-read its position from there, undoing these shifts.
    tlo_drift: [f64; 6],
    /// RS274/NGC: the feed override is switched off (M49, M50 P0); the program end
    /// switches it back on.
    feed_override_off: bool,
    /// The block's inverse-time rate is already out: rs274 sets it once per
    /// compensated move, from the programmed path, before any corner arc.
    inv_rate_set: bool,
    /// Plain motion blocks take `fast::fast_motion_block` (off only to test it).
    fast_path: bool,
    /// The fast path's words, kept between blocks: a `Words` is several hundred
    /// bytes, and clearing the four letters the fast path writes is cheaper than
    /// building a new one for every line.
    fast_words: Option<Box<Words>>,
    /// RS274/NGC: the state saved by M70 outside any subroutine.
    top_context: Option<context::SavedContext>,
    /// G64 Q (naive CAM tolerance) as written; M70 saves it.
    naive_tol: f64,
    /// LinuxCNC's `doing_break`: set by a break out of a while or repeat loop and
    /// consumed by the next `do` loop's closing `while`.
    pending_break: bool,
    /// Checkpoints and rerun state (`resume.rs`); `None` for plain runs.
    resume: Option<resume::Resume>,
    /// RS274/NGC: the profile of a G70-G72 cycle being read from its subroutine.
    g7x: Option<g7x::Capture>,
}

fn v6(v: [f64; 6]) -> [f64; 6] {
    v
}

impl<'a, 'i> Interp<'a, 'i> {
    /// `snapshots` false: no per-block state is kept (and the table of 100-byte slots,
    /// one per block, is never allocated).
    fn new(input: &'i RunInput<'a>, snapshots: bool) -> Interp<'a, 'i> {
        let dialect = input.settings.dialect;
        let mut cfg = MachineCfg::read(input.machine, dialect);
        if let Some(t) = input.tool_table {
            // Tool-table values stay in machine units; `pfac` converts at use.
            parse_tool_table(t, 1.0, &mut cfg.tools, &mut cfg.tool_order);
        }
        let mut params = vec![None; NUM_PARAMS];
        if dialect == Dialect::Rs274ngc {
            for p in params.iter_mut().take(5602) {
                *p = Some(0.0);
            }
            params[5220] = Some(1.0);
            // (DEBUG,) output is on until a program clears #5599.
            params[5599] = Some(1.0);
        }
        if let Some(v) = input.var_file {
            for (n, val) in parse_var_file(v) {
                if n < NUM_PARAMS {
                    params[n] = Some(val);
                }
            }
        }
        for (idx, vals) in &cfg.work_offsets {
            for (k, v) in vals.iter().enumerate() {
                params[5201 + 20 * idx + k] = Some(*v / cfg.param_unit);
            }
        }
        let sw = dialect == Dialect::Servoworks;
        let mut modal = Modal::power_on(sw, dialect == Dialect::Fanuc);
        // RS274/NGC starts in the coordinate system #5220 names (1 = G54 …
        // 9 = G59.3); a value out of range is a start-up fault in the 2007
        // semantics and G54 in LinuxCNC 2.9.
        let mut bad_origin = None;
        if dialect == Dialect::Rs274ngc {
            let n = params[5220].unwrap_or(1.0);
            if n.fract() == 0.0 && (1.0..=9.0).contains(&n) {
                modal.origin = n as usize;
            } else {
                bad_origin = Some(n);
            }
        }
        let st = State {
            modal,
            pos: [0.0; 6],
            mpos: [0.0; 6],
            g92: [0.0; 6],
            g52: [0.0; 6],
            tlo: [0.0; 6],
            comp_radius: 0.0,
            comp_orientation: 0,
            comp_first: true,
            comp_tip: [0.0; 6],
            comp_queue: Vec::new(),
            comp_endpoint: None,
            feed: 0.0,
            spindle: 0.0,
            spindle_dir: 0,
            tool: 0,
            next_tool: 0,
            mist: false,
            flood: false,
            params: Arc::new(params),
            named: Arc::new(HashMap::new()),
            cycle: CycleMem::default(),
            scale: ([0.0; 3], [1.0; 3]),
            mirror: ([false; 3], [0.0; 3]),
            rotation: ([0.0; 2], 0.0),
            ended: false,
            torque_axes: 0,
            tcp_length: 0.0,
            g28_mid: None,
            line: 0,
            g66: None,
        };
        let main = FileEntry::new(ProgRef::Borrowed(input.program), FileId(0));
        let emit = input.emit_canon && dialect == Dialect::Rs274ngc;
        let mut it = Interp {
            input,
            dialect,
            variant: input.settings.variant,
            cfg,
            files: vec![main],
            file_names: HashMap::new(),
            st,
            frames: Vec::new(),
            repeats: Vec::new(),
            out: RunOutput {
                snapshots: if snapshots {
                    vec![None; input.program.blocks.len()]
                } else {
                    Vec::new()
                },
                ..RunOutput::default()
            },
            canon: if emit { Some(Canon::default()) } else { None },
            steps: 0,
            cur: (0, 0),
            cur_line: 0,
            percent_open: false,
            saw_end: false,
            nblocks_main: if snapshots {
                input.program.blocks.len()
            } else {
                0
            },
            after_end_reported: false,
            main_locals: HashMap::new(),
            limit_reports: 0,
            block_exact: false,
            chk: checks::Mem::default(),
            modal_cache: None,
            spline_pq: (0.0, 0.0),
            nurbs: Vec::new(),
            spec: Default::default(),
            motions_drained: 0,
            tlo_drift: [0.0; 6],
            feed_override_off: false,
            inv_rate_set: false,
            fast_path: true,
            fast_words: Some(Box::default()),
            top_context: None,
            naive_tol: 0.0,
            pending_break: false,
            g7x: None,
            resume: None,
        };
        if let Some(n) = bad_origin {
            if it.variant == Variant::Emc2 {
                it.diag(
                    codes::INTERP,
                    Severity::Error,
                    Span::default(),
                    format!("parameter #5220 is {n}: the start-up coordinate system must be a whole number 1 to 9 (G54 to G59.3); the control faults"),
                );
            }
        }
        // The current position starts at the machine origin.
        it.st.pos = it.to_program(it.st.mpos);
        let (g5x, g92, origin) = (it.g5x_prog(), it.st.g92, it.st.modal.origin);
        let u = it.unit();
        let rot = it.rotation_of(1);
        if let Some(c) = it.canon.as_mut() {
            let g = g5x.map(|v| v);
            c.preamble(origin, &scale6(g, u), &scale6(g92, u), rot);
        }
        it
    }

    /// Internal length units per program unit. RS274/NGC keeps lengths in
    /// program units as LinuxCNC does (so canonical output rounds identically);
    /// the other dialects keep millimetres.
    fn unit(&self) -> f64 {
        if self.ngc() || !self.st.modal.inch {
            1.0
        } else {
            25.4
        }
    }

    /// Millimetres per internal length unit.
    fn lu(&self) -> f64 {
        if self.ngc() && self.st.modal.inch {
            25.4
        } else {
            1.0
        }
    }

    /// Internal units per parameter/tool-table unit.
    fn pfac(&self) -> f64 {
        let lu = self.lu();
        if self.cfg.param_unit == lu {
            1.0
        } else if lu == 1.0 {
            self.cfg.param_unit
        } else {
            self.cfg.param_unit / lu
        }
    }

    /// Switches RS274/NGC program units, converting the stored lengths as
    /// LinuxCNC does.
    fn switch_units(&mut self, inch: bool) {
        if inch == self.st.modal.inch {
            return;
        }
        let f = if inch { 1.0 / 25.4 } else { 25.4 };
        if self.ngc() {
            let st = &mut self.st;
            for v in [
                &mut st.pos,
                &mut st.mpos,
                &mut st.g92,
                &mut st.g52,
                &mut st.tlo,
                &mut st.comp_tip,
            ] {
                for x in v.iter_mut().take(3) {
                    *x *= f;
                }
            }
            st.comp_radius *= f;
            st.feed *= f;
            st.modal.path_tol = st.modal.path_tol.map(|t| t * f);
            for x in [
                &mut st.cycle.r,
                &mut st.cycle.z,
                &mut st.cycle.q,
                &mut st.cycle.i,
                &mut st.cycle.j,
                &mut st.cycle.k,
                &mut st.cycle.initial,
            ] {
                if let Some(v) = x.as_mut() {
                    *v *= f;
                }
            }
        }
        self.st.modal.inch = inch;
    }

    fn ngc(&self) -> bool {
        self.dialect == Dialect::Rs274ngc
    }

    fn param(&self, n: usize) -> f64 {
        self.st.params.get(n).copied().flatten().unwrap_or(0.0)
    }

    fn set_param(&mut self, n: usize, v: Option<f64>) {
        if n < NUM_PARAMS {
            Arc::make_mut(&mut self.st.params)[n] = v;
        }
    }

    /// Work offset of the active origin, mm.
    fn g5x_prog(&self) -> [f64; 6] {
        self.g5x_of(self.st.modal.origin)
    }

    fn g5x_of(&self, origin: usize) -> [f64; 6] {
        let base = if origin >= 100 {
            7001 + 20 * origin.saturating_sub(101)
        } else {
            5201 + 20 * origin
        };
        // Every move asks for this: one slice of the parameters, one unit factor. The
        // highest origin (G54.1 P300) ends far below `NUM_PARAMS`; an unset or missing
        // parameter reads 0, as `param` reads it.
        let raw = self.st.params.get(base..base + 6).unwrap_or(&[None; 6]);
        let f = self.pfac();
        let mut o = [0.0; 6];
        for (k, (v, r)) in o.iter_mut().zip(raw).enumerate() {
            let r = r.unwrap_or(0.0);
            *v = if k < 3 { r * f } else { r };
        }
        o
    }

    /// Program-frame commanded point → machine.
    fn to_machine(&self, p: [f64; 6]) -> [f64; 6] {
        let mut q = self.transform(p);
        for i in 0..6 {
            q[i] += self.st.g92[i] + self.st.g52[i];
        }
        let rot = self.xy_rotation();
        if rot != 0.0 {
            // LinuxCNC rotates the offset point about the work origin (G10 L2 R).
            let (s, c) = rot.to_radians().sin_cos();
            let (x, y) = (q[0], q[1]);
            q[0] = x * c - y * s;
            q[1] = x * s + y * c;
        }
        let o = self.g5x_prog();
        let mut m = [0.0; 6];
        for i in 0..6 {
            m[i] = q[i] + o[i] + self.st.tlo[i];
            if rot != 0.0 && m[i].abs() < 1e-12 {
                // Round-off from the rotation would print as -0.000000.
                m[i] = 0.0;
            }
        }
        m
    }

    fn to_program(&self, m: [f64; 6]) -> [f64; 6] {
        let o = self.g5x_prog();
        let mut q = [0.0; 6];
        for i in 0..6 {
            q[i] = m[i] - o[i] - self.st.tlo[i];
        }
        let rot = self.xy_rotation();
        if rot != 0.0 {
            let (s, c) = (-rot).to_radians().sin_cos();
            let (x, y) = (q[0], q[1]);
            // Round-off from the rotation would print as -0.000000.
            let snap = |v: f64| if v.abs() < 1e-12 { 0.0 } else { v };
            q[0] = snap(x * c - y * s);
            q[1] = snap(x * s + y * c);
        }
        for i in 0..6 {
            q[i] -= self.st.g92[i] + self.st.g52[i];
        }
        self.untransform(q)
    }

    /// Inverse of [`Self::transform`]: rotation, then scaling, then mirror undone.
    fn untransform(&self, p: [f64; 6]) -> [f64; 6] {
        let mut q = p;
        let m = &self.st.modal;
        if m.rotation {
            let (a, b) = self.plane_axes();
            let (c, ang) = self.st.rotation;
            let (s, co) = (-ang).to_radians().sin_cos();
            let (x, y) = (q[a] - c[0], q[b] - c[1]);
            q[a] = c[0] + x * co - y * s;
            q[b] = c[1] + x * s + y * co;
        }
        if m.scaling {
            for i in 0..3 {
                let f = self.st.scale.1[i];
                if f != 0.0 {
                    q[i] = self.st.scale.0[i] + (q[i] - self.st.scale.0[i]) / f;
                }
            }
        }
        if m.mirror {
            for i in 0..3 {
                if self.st.mirror.0[i] {
                    q[i] = 2.0 * self.st.mirror.1[i] - q[i];
                }
            }
        }
        q
    }

    /// XY rotation (degrees) of the active RS274/NGC coordinate system.
    fn xy_rotation(&self) -> f64 {
        self.rotation_of(self.st.modal.origin)
    }

    fn rotation_of(&self, origin: usize) -> f64 {
        if self.ngc() && (1..=9).contains(&origin) {
            self.param(5210 + 20 * origin)
        } else {
            0.0
        }
    }

    fn rotation_canon(&self, origin: usize) -> String {
        format!("SET_XY_ROTATION({})", f4(self.rotation_of(origin)))
    }

    /// Mirror, scaling and rotation (FANUC/ServoWorks).
    fn transform(&self, p: [f64; 6]) -> [f64; 6] {
        let mut q = p;
        let m = &self.st.modal;
        if m.mirror {
            for i in 0..3 {
                if self.st.mirror.0[i] {
                    q[i] = 2.0 * self.st.mirror.1[i] - q[i];
                }
            }
        }
        if m.scaling {
            for i in 0..3 {
                q[i] = self.st.scale.0[i] + (q[i] - self.st.scale.0[i]) * self.st.scale.1[i];
            }
        }
        if m.rotation {
            let (a, b) = self.plane_axes();
            let (c, ang) = self.st.rotation;
            let (s, co) = ang.to_radians().sin_cos();
            let (x, y) = (q[a] - c[0], q[b] - c[1]);
            q[a] = c[0] + x * co - y * s;
            q[b] = c[1] + x * s + y * co;
        }
        q
    }

    /// Whether the tool runs left of the path under G41/G42 (the machine's
    /// `trc_g41_side` decides which code means left).
    fn comp_left(&self) -> bool {
        (self.st.modal.comp == 410) != self.cfg.g41_right
    }

    /// The G76/G87 shift of `q` as a plane-axis displacement (index, signed amount).
    fn drill_shift_vec(&self, q: f64) -> Option<(usize, f64)> {
        let (which, sign) = self.cfg.drill_shift?;
        let (a, b) = self.plane_axes();
        Some((if which == 0 { a } else { b }, sign * q.abs()))
    }

    fn plane_axes(&self) -> (usize, usize) {
        match self.st.modal.plane {
            180 => (2, 0),
            190 => (1, 2),
            _ => (0, 1),
        }
    }

    fn normal_axis(&self) -> usize {
        match self.st.modal.plane {
            180 => 1,
            190 => 0,
            _ => 2,
        }
    }

    fn file_id(&self) -> FileId {
        self.files.get(self.cur.0).map(|f| f.id).unwrap_or_default()
    }

    fn diag(&mut self, code: &'static str, sev: Severity, span: Span, msg: impl Into<String>) {
        let d = Diagnostic::new(code, sev, span, msg).in_file(self.file_id());
        self.out.diagnostics.push(d);
    }

    fn event(&mut self, kind: EventKind) {
        let e = Event {
            kind,
            motion_index: self.out.motions.len(),
            file: self.file_id(),
            block: self.cur.1,
            line: self.cur_line,
        };
        self.out.events.push(e);
    }

    fn canon(&mut self, s: impl AsRef<str>) {
        if let Some(c) = self.canon.as_mut() {
            c.call(s);
        }
    }

    pub(super) fn canon_comment(&mut self, s: &str) {
        if let Some(c) = self.canon.as_mut() {
            c.comment(s);
        }
    }

    /// Program-frame coordinates in program units, for canon lines.
    fn canon_pos(&self, p: &[f64; 6]) -> String {
        let u = self.unit();
        let v = [p[0] / u, p[1] / u, p[2] / u, p[3], p[4], p[5]];
        Canon::six(&v)
    }

    // ----------------------------------------------------------------- main loop

    fn run_main(&mut self) {
        self.run_main_with(None);
    }

    /// Hands the motions and events so far to `sink`, unless a compensated move is
    /// still pending (it may yet be moved, so it must stay in the buffer).
    fn drain_to(&mut self, sink: &mut OwnedMotionSink<'_>) {
        if !self.st.comp_queue.is_empty() {
            return;
        }
        self.motions_drained += self.out.motions.len();
        sink(&mut self.out.motions, &mut self.out.events);
        self.out.motions.clear();
        self.out.events.clear();
    }

    /// Whether any motion has been produced (also those already streamed out).
    fn any_motion(&self) -> bool {
        self.motions_drained > 0 || !self.out.motions.is_empty()
    }

    fn run_main_with(&mut self, mut sink: Option<&mut OwnedMotionSink<'_>>) {
        // A restored rerun has the input files' diagnostics from before.
        if !self.resume.as_ref().is_some_and(|r| r.restored) {
            self.spec_input_files();
        }
        let p = self.files[0].prog.clone();
        if self.ngc() {
            if let Some(b) = p
                .blocks
                .iter()
                .find(|b| !p.items_of(b).is_empty() || b.kind == BlockKind::Percent)
            {
                self.percent_open = b.kind == BlockKind::Percent;
            }
        }
        let budget = self.input.step_budget.max(1);
        loop {
            let (fi, bi) = self.cur;
            let nblocks = self.files.get(fi).map(|f| f.prog.blocks.len()).unwrap_or(0);
            if bi as usize >= nblocks {
                if self.frames.is_empty() || fi == 0 {
                    self.end_of_file();
                    break;
                }
                // A subprogram file ran out without M99: return to the caller.
                if !self.ret_from_sub(None) {
                    break;
                }
                continue;
            }
            if self.resume.is_some() && self.resume_point(fi, bi) {
                break;
            }
            self.steps += 1;
            if self.steps > budget {
                let span = self.block_span(fi, bi);
                self.diag(
                    codes::STEP_BUDGET,
                    Severity::Warning,
                    span,
                    format!("execution stopped after {budget} blocks: the step budget was reached and the rest of the program is not simulated; raise it with --step-budget"),
                );
                break;
            }
            let first_motion = self.out.motions.len();
            let result = self.exec_block(fi, bi);
            self.check_limits(fi, bi, first_motion);
            if self.motion_budget_reached(self.block_span(fi, bi)) {
                break;
            }
            match result {
                Ok(Flow::Next) => self.cur = (self.cur.0, self.cur.1 + 1),
                Ok(Flow::Goto(f, b)) => self.cur = (f, b),
                Ok(Flow::Stop) => break,
                Err(d) => {
                    // rs274 never prints the calls cutter compensation still holds back
                    // when it stops at an error.
                    let held = self.st.comp_queue.first().map(|q| q.canon);
                    if let (Some(first), Some(c)) = (held, self.canon.as_mut()) {
                        c.lines.truncate(first);
                    }
                    if self.canon.is_some() && self.out.canon_error.is_none() {
                        let line = self.line_text(self.cur.0, self.cur.1);
                        // An expression the parser could not read: rs274 names the `#`.
                        let msg = Some(&line)
                            .filter(|_| {
                                self.ngc()
                                    && d.message
                                        .eq_ignore_ascii_case("expression could not be parsed")
                            })
                            .and_then(|l| rs274_parameter_message(l))
                            .unwrap_or_else(|| rs274_message(&d.message));
                        self.out.canon_error = Some(format!("{msg}\n{line}"));
                    }
                    self.out.diagnostics.push(d);
                    break;
                }
            }
            if fi == 0 && (bi as usize) < self.nblocks_main.min(SNAPSHOT_LIMIT) {
                let snap = self.snapshot();
                if let Some(s) = self.out.snapshots.get_mut(bi as usize) {
                    *s = Some(snap);
                }
            }
            if self.out.motions.len() >= STREAM_CHUNK {
                if let Some(sink) = sink.as_deref_mut() {
                    self.drain_to(sink);
                }
            }
        }
        if let Some(c) = self.canon.as_mut() {
            c.line_number = None;
            c.call("ON_RESET()");
            c.call("ON_RESET()");
        }
    }

    /// Soft limits: end points of the block's motions against the profile's travel.
    fn check_limits(&mut self, fi: usize, bi: u32, first: usize) {
        if self.cfg.limits.iter().all(Option::is_none) || self.limit_reports >= 100 {
            return;
        }
        let mut hit = [false; 6];
        // Under ServoWorks TCP the linear axes carry the tool base point.
        let tcp = (self.dialect == Dialect::Servoworks && self.st.modal.tlo_mode == 432)
            .then_some(self.st.tcp_length);
        for m in self.out.motions.iter().skip(first) {
            let mut end = m.end;
            if let Some(l) = tcp {
                let b = super::tcp::base_point([end[0], end[1], end[2]], end[4], end[5], l);
                end[..3].copy_from_slice(&b);
            }
            for (i, lim) in self.cfg.limits.iter().enumerate() {
                if let Some((lo, hi)) = lim {
                    if end[i] < lo - 1e-9 || end[i] > hi + 1e-9 {
                        hit[i] = true;
                    }
                }
            }
        }
        let span = self.block_span(fi, bi);
        let file = self.files.get(fi).map(|f| f.id).unwrap_or_default();
        for (i, h) in hit.iter().enumerate() {
            if !h || self.limit_reports >= 100 {
                continue;
            }
            self.limit_reports += 1;
            let (lo, hi) = self.cfg.limits[i].unwrap_or((0.0, 0.0));
            let letter = ['X', 'Y', 'Z', 'A', 'B', 'C'][i];
            let d = Diagnostic::warning(codes::TRAVEL_LIMIT, span, format!("this block moves {letter} outside its travel ({lo} to {hi} in machine coordinates): the control stops with a soft-limit alarm")).in_file(file);
            self.out.diagnostics.push(d);
        }
    }

    fn end_of_file(&mut self) {
        if self.saw_end {
            return;
        }
        let p = self.files[0].prog.clone();
        let end = p.text.len() as u32;
        let span = Span::new(end, end);
        match self.dialect {
            Dialect::Rs274ngc => {
                let msg = if self.percent_open {
                    "file ended with no percent sign"
                } else {
                    "file ended with no percent sign or program end (M2/M30)"
                };
                if self.canon.is_some() && self.out.canon_error.is_none() {
                    // rs274 shows the last line it read.
                    let last = p
                        .blocks
                        .iter()
                        .rev()
                        .map(|b| p.str_of(b.span).trim().to_string())
                        .find(|t| !t.is_empty())
                        .unwrap_or_default();
                    let text = if self.percent_open {
                        "File ended with no percent sign"
                    } else {
                        "File ended with no percent sign or program end"
                    };
                    self.out.canon_error = Some(format!("{text}\n{last}"));
                }
                self.out
                    .diagnostics
                    .push(Diagnostic::error(codes::MISSING_END, span, msg));
            }
            _ => {
                self.out.diagnostics.push(Diagnostic::warning(codes::MISSING_END, span, "program has no end code (M02/M30): the control stops at the end of the file without the end-of-program resets"));
            }
        }
    }

    fn finish(mut self) -> RunOutput {
        if let Some(r) = &self.resume {
            self.out
                .checkpoints
                .set_executed(self.steps.saturating_sub(r.start_steps));
        }
        if let Some(c) = self.canon.take() {
            self.out.canon = c.lines;
        }
        self.out
    }

    fn snapshot(&mut self) -> BlockSnapshot {
        // Modal state rarely changes between blocks: reuse the formatted codes.
        let modal = match &self.modal_cache {
            Some((m, codes)) if *m == self.st.modal => codes.clone(),
            _ => {
                let codes = self.st.modal.codes(self.ngc());
                self.modal_cache = Some((self.st.modal.clone(), codes.clone()));
                codes
            }
        };
        BlockSnapshot {
            modal,
            position: {
                let lu = self.lu();
                let p = self.st.pos;
                [p[0] * lu, p[1] * lu, p[2] * lu, p[3], p[4], p[5]]
            },
            feed: if self.st.modal.feed_mode == 930 {
                self.st.feed
            } else {
                self.st.feed * self.lu()
            },
            spindle: self.st.spindle,
            tool: self.st.tool,
        }
    }

    /// The source text of a block, trimmed, as rs274 echoes it after an error.
    fn line_text(&self, fi: usize, bi: u32) -> String {
        self.files
            .get(fi)
            .and_then(|f| {
                f.prog
                    .blocks
                    .get(bi as usize)
                    .map(|b| f.prog.str_of(b.span))
            })
            // rs274 shows the line as written, with its indentation.
            .map(|t| t.trim_end().to_string())
            .unwrap_or_default()
    }

    fn block_span(&self, fi: usize, bi: u32) -> Span {
        self.files
            .get(fi)
            .and_then(|f| f.prog.blocks.get(bi as usize))
            .map(|b| b.span)
            .unwrap_or_default()
    }

    fn err(&self, code: &'static str, span: Span, msg: impl Into<String>) -> Diagnostic {
        Diagnostic::error(code, span, msg).in_file(self.file_id())
    }

    fn eval_err(&self, e: EvalError) -> Diagnostic {
        self.err(codes::EXPRESSION, e.span, e.message)
    }

    fn eval(&self, p: &Program, id: ExprId) -> Result<Val, Diagnostic> {
        let locals = self
            .frames
            .last()
            .map(|f| &f.named_locals)
            .or(Some(&self.main_locals));
        let vars = self.vars(locals);
        expr::eval(p, id, self.dialect, &vars, 0).map_err(|e| self.eval_err(e))
    }

    /// What expressions read: the state, the named locals in scope and the
    /// current tool's offsets in parameter units.
    fn vars<'s>(&'s self, locals: Option<&'s HashMap<String, f64>>) -> Vars<'s> {
        let t = self
            .cfg
            .tools
            .get(&self.st.tool)
            .copied()
            .unwrap_or_default();
        // LinuxCNC reads #5401-#5410 straight from its tool table, in the machine's
        // units whatever G20/G21 says.
        Vars {
            st: &self.st,
            locals,
            dialect: self.dialect,
            tool: [t.x_offset, t.y_offset, t.length, t.diameter],
        }
    }

    /// A numbered parameter as an expression would read it (system values included).
    fn read_param(&self, n: i64) -> f64 {
        self.vars(None)
            .get_num(n, Span::default())
            .ok()
            .flatten()
            .unwrap_or(0.0)
    }

    fn eval_num(&self, p: &Program, id: ExprId) -> Result<f64, Diagnostic> {
        Ok(self.eval(p, id)?.unwrap_or(0.0))
    }

    // ----------------------------------------------------------------- blocks

    fn exec_block(&mut self, fi: usize, bi: u32) -> Result<Flow, Diagnostic> {
        let prog = self.files[fi].prog.clone();
        let Some(block) = prog.blocks.get(bi as usize).copied() else {
            return Ok(Flow::Next);
        };
        self.cur_line = block.line;
        self.st.line = block.line + 1;
        if let Some(c) = self.canon.as_mut() {
            c.line_number = None;
        }
        match block.kind {
            BlockKind::Normal => {}
            BlockKind::Percent => {
                if self.ngc() && fi == 0 && self.percent_open && self.seen_content_before(&prog, bi)
                {
                    self.saw_end = true;
                    self.canon("FINISH()");
                    return Ok(Flow::Stop);
                }
                if self.ngc()
                    && fi == 0
                    && !self.percent_open
                    && self.seen_content_before(&prog, bi)
                {
                    // Only a file that opens with `%` may close with one; elsewhere
                    // rs274 reads `%` as a bad character.
                    return Err(self.err(codes::INTERP, block.span, "Bad character '%' used"));
                }
                if self.dialect == Dialect::Fanuc && fi == 0 && self.seen_content_before(&prog, bi)
                {
                    self.saw_end = true;
                    return Ok(Flow::Stop);
                }
                return Ok(Flow::Next);
            }
            BlockKind::Deleted | BlockKind::Ignored => return Ok(Flow::Next),
        }
        if block.skip().is_some() && self.cfg.block_skip {
            return Ok(Flow::Next);
        }
        // RS274/NGC and FANUC stop at a block they cannot read; the parser
        // already reported why (ServoWorks skips unknown data).
        if self.dialect != Dialect::Servoworks
            && !self.files[fi].error_blocks.is_empty()
            && self.files[fi].error_blocks.contains(&bi)
        {
            if self.ngc() && self.canon.is_some() && self.out.canon_error.is_none() {
                let line = self.line_text(fi, bi);
                if let Some(msg) = rs274_parameter_message(&line) {
                    self.out.canon_error = Some(format!("{msg}\n{line}"));
                }
            }
            return Ok(Flow::Stop);
        }
        let items = prog.items_of(&block);
        if items.is_empty() {
            return Ok(Flow::Next);
        }
        // A plain motion line needs nothing of `spec_items` but the clearing of its
        // per-block lists, which the fast path does (no `$`, no expressions). A G7x
        // profile being read collects its moves instead of running them.
        if self.g7x.is_none() {
            if let Some(r) = self.fast_motion_block(items, block.span) {
                return r;
            }
        }
        self.spec_items(&prog, items);
        // A bare O-word line (program title, M98 target) does nothing, not even its comments.
        if self.ngc()
            && items
                .iter()
                .any(|it| matches!(&it.kind, ItemKind::OWord(ow) if ow.keyword.is_none()))
        {
            return Ok(Flow::Next);
        }
        // O-word statements (RS274/NGC) own their block.
        if let Some((ow, span)) = items.iter().find_map(|it| match &it.kind {
            ItemKind::OWord(ow) if ow.keyword.is_some() => Some((*ow, it.span)),
            _ => None,
        }) {
            return self.exec_oword(fi, bi, &prog, ow, span);
        }
        // Macro statements and assignments in FANUC/ServoWorks run in order.
        if !self.ngc() {
            let mut skip_next = false;
            let mut has_words = false;
            for (k, it) in items.iter().enumerate() {
                if skip_next {
                    skip_next = false;
                    continue;
                }
                match &it.kind {
                    ItemKind::Assign { target, value } => {
                        let v = self.eval(&prog, *value)?;
                        self.assign(&prog, *target, v, it.span)?;
                    }
                    ItemKind::Macro(m) => match *m {
                        MacroStmt::IfThen { cond } => {
                            let c = self.eval(&prog, cond)?;
                            if c.unwrap_or(0.0) == 0.0 {
                                skip_next = true;
                            }
                            let _ = k;
                        }
                        MacroStmt::Goto { target } => {
                            let n = self.eval_num(&prog, target)?;
                            return self.goto_seq(fi, bi, n, it.span);
                        }
                        MacroStmt::IfGoto { cond, target } => {
                            if self.eval(&prog, cond)?.unwrap_or(0.0) != 0.0 {
                                let n = self.eval_num(&prog, target)?;
                                return self.goto_seq(fi, bi, n, it.span);
                            }
                        }
                        MacroStmt::While { cond, .. } => {
                            if self.eval(&prog, cond)?.unwrap_or(0.0) == 0.0 {
                                let Some(end) = self.files[fi].loops.get(&bi).copied() else {
                                    return Err(self.err(
                                        codes::FLOW,
                                        it.span,
                                        "WHILE … DO has no matching END (PS0124)",
                                    ));
                                };
                                return Ok(Flow::Goto(fi, end + 1));
                            }
                        }
                        MacroStmt::Do { .. } => {}
                        MacroStmt::End { .. } => {
                            let Some(head) = self.files[fi].loops.get(&bi).copied() else {
                                return Err(self.err(
                                    codes::FLOW,
                                    it.span,
                                    "END has no matching DO (PS0126)",
                                ));
                            };
                            return Ok(Flow::Goto(fi, head));
                        }
                        MacroStmt::Output => {}
                    },
                    ItemKind::Word(_) => has_words = true,
                    _ => {}
                }
            }
            if !has_words {
                return Ok(Flow::Next);
            }
        }
        let mut w = Words::default();
        let mut comments: Vec<(CommentKind, Span)> = Vec::new();
        let mut assigns: Vec<(ExprId, Val, Span)> = Vec::new();
        for it in items {
            match &it.kind {
                ItemKind::Word(word) => {
                    let val = match word.value {
                        WordValue::Num(n) => Some(n.value),
                        WordValue::Expr(e) => self.eval(&prog, e)?,
                        WordValue::Name(s) => {
                            w.pname = Some(prog.str_of(s).into_owned());
                            None
                        }
                        WordValue::Missing => None,
                    };
                    let point = word.num().is_none_or(|n| n.has_point);
                    let Some(val) = val else {
                        // FANUC/ServoWorks: a vacant value drops the word (FAN141).
                        if !self.ngc() && matches!(word.value, WordValue::Expr(_)) {
                            let letter = word.letter as char;
                            self.diag(codes::VACANT_WORD, Severity::Warning, it.span, format!("the value of {letter} is vacant (an unset variable): the control omits the whole {letter} word; set the variable or leave the word out"));
                        }
                        continue;
                    };
                    match word.letter {
                        b'G' => match analyzer::dialect::CodeNum::from_value(val) {
                            Some(c) => w.g.push((c.0, it.span)),
                            None => {
                                return Err(self.err(
                                    codes::UNKNOWN_CODE,
                                    it.span,
                                    format!("G{val} is not a G code"),
                                ))
                            }
                        },
                        b'M' => {
                            // LinuxCNC reads M as an integer within 0.0001 of a whole
                            // number (read_integer_value), so `M3.00005` is M3.
                            let val = if self.ngc() && (val - val.round()).abs() < 1e-4 {
                                val.round()
                            } else {
                                val
                            };
                            if val < 0.0 || val.fract().abs() > 1e-6 {
                                return Err(self.err(
                                    codes::UNKNOWN_CODE,
                                    it.span,
                                    format!("M{val} is not an M code"),
                                ));
                            }
                            w.m.push(((val * 10.0).round() as u32, it.span));
                        }
                        b'N' => {
                            w.n = Some(val as i64);
                            w.n_text = Some(match word.num() {
                                Some(n) => prog
                                    .str_of(n.span)
                                    .chars()
                                    .filter(|c| !c.is_whitespace())
                                    .take_while(|c| *c != '.')
                                    .collect(),
                                None => format!("{}", val as i64),
                            });
                        }
                        b'O' => {}
                        // A G7x profile may use U and W (relative X and Z).
                        c @ (b'U' | b'V' | b'W')
                            if self.ngc()
                                && !self.input.settings.axes.contains(&(c as char))
                                && !(self.g7x_capturing() && c != b'V') =>
                        {
                            return Err(self.err(
                                codes::INTERP,
                                it.span,
                                format!(
                                    "bad character '{}' used: this machine has no {} axis",
                                    (c as char).to_ascii_lowercase(),
                                    c as char
                                ),
                            ));
                        }
                        b'@' => w.polar_r = Some(val),
                        b'^' => w.polar_a = Some(val),
                        c @ b'A'..=b'Z' if !word.comma => {
                            let i = (c - b'A') as usize;
                            // ServoWorks uses the first of duplicated words (§1.4).
                            if self.dialect == Dialect::Servoworks && w.v[i].is_some() {
                                continue;
                            }
                            w.v[i] = Some(val);
                            w.span[i] = it.span;
                            w.point[i] = point;
                            if matches!(
                                c,
                                b'I' | b'J'
                                    | b'K'
                                    | b'A'
                                    | b'B'
                                    | b'C'
                                    | b'D'
                                    | b'E'
                                    | b'F'
                                    | b'H'
                                    | b'M'
                                    | b'Q'
                                    | b'R'
                                    | b'S'
                                    | b'T'
                                    | b'U'
                                    | b'V'
                                    | b'W'
                                    | b'X'
                                    | b'Y'
                                    | b'Z'
                            ) {
                                w.ijk_order.push((c, val));
                            }
                        }
                        _ => {}
                    }
                }
                ItemKind::Comment(k) => comments.push((*k, it.span)),
                ItemKind::Assign { target, value } if self.ngc() => {
                    let v = self.eval(&prog, *value)?;
                    assigns.push((*target, v, it.span));
                }
                _ => {}
            }
        }
        // Canonical output reproduces rs274, which refuses the whole line before
        // running any of it (the static rules report these in every other mode).
        if self.ngc() && self.canon.is_some() {
            self.check_ngc_codes(&w)?;
        }
        // RS274/NGC: parameters are set after the whole line was read.
        for (t, v, s) in assigns {
            self.assign(&prog, t, v, s)?;
        }
        if let (Some(c), Some(n)) = (self.canon.as_mut(), w.n_text.clone()) {
            c.line_number = Some(n);
        }
        if self.st.ended {
            if !self.after_end_reported {
                self.after_end_reported = true;
                self.diag(
                    codes::AFTER_END,
                    Severity::Warning,
                    block.span,
                    "code after the program end is never executed",
                );
            }
            return Ok(Flow::Stop);
        }
        w.raw_k = w.get(b'K');
        self.scale_words(&mut w);
        // A G7x profile block only adds to the profile; LinuxCNC reads it
        // without executing any of its other words.
        if self.g7x_capturing() {
            self.g7x_profile_block(&w, block.span)?;
            return Ok(Flow::Next);
        }
        self.inv_rate_set = false;
        let before = (self.out.motions.len(), self.st.tlo);
        let flow = self.exec_words(fi, bi, &prog, &w, &comments, block.span)?;
        self.refresh_after_tool_change(&w, before);
        Ok(flow)
    }

    /// rs274 re-reads the current point after a block with a tool change (M6, M61)
    /// from its canon, which never saw the tool length offsets given since the last
    /// move (`T4 M6 G43 H4` then a canned cycle starts from the old height).  Only
    /// the canon output follows this: a real LinuxCNC re-reads the machine position
    /// with the new offset, which is what the simulation keeps.
    fn refresh_after_tool_change(&mut self, w: &Words, before: (usize, [f64; 6])) {
        if !self.ngc() || self.canon.is_none() {
            return;
        }
        if self.out.motions.len() != before.0 {
            // Offsets apply before the block's move, which ends at the point the
            // interpreter holds.
            self.tlo_drift = [0.0; 6];
        } else {
            for i in 0..6 {
                self.tlo_drift[i] += before.1[i] - self.st.tlo[i];
            }
        }
        if w.has_m(60) || w.has_m(610) {
            // After G40 the programmed point is where the last compensated move was
            // aimed, but the canon last commanded the tool's offset point, which
            // the tool change re-reads.
            if self.st.modal.comp == 400 {
                let (a, b) = self.plane_axes();
                let here = self.to_program(self.st.mpos);
                self.st.pos[a] = here[a];
                self.st.pos[b] = here[b];
            }
            for i in 0..6 {
                self.st.pos[i] -= self.tlo_drift[i];
            }
            // The machine point follows, so that a later G43/G49 (which re-reads the
            // programmed point from it) starts where rs274 believes the tool is.
            if self.tlo_drift.iter().any(|d| *d != 0.0) {
                self.st.mpos = self.to_machine(self.st.pos);
            }
            self.tlo_drift = [0.0; 6];
        }
    }

    /// rs274's checks of a line's G and M codes: unknown codes, two codes of one
    /// modal group, user M codes (M100-M199) without a program to run.
    fn check_ngc_codes(&self, w: &Words) -> Result<(), Diagnostic> {
        use analyzer::dialect::{lookup, CodeNum};
        let custom = |letter: char, n: u32| {
            self.input.settings.custom_codes.iter().any(|c| {
                let c = c.trim();
                c.len() > 1
                    && c[..1].eq_ignore_ascii_case(&letter.to_string())
                    && c[1..]
                        .parse::<f64>()
                        .is_ok_and(|v| (v * 10.0).round() as u32 == n)
            })
        };
        let mut seen: Vec<(char, u8, u32)> = Vec::new();
        for (letter, list) in [('G', &w.g), ('M', &w.m)] {
            for (n, span) in list.iter().copied() {
                if custom(letter, n) {
                    continue;
                }
                let info = lookup(Dialect::Rs274ngc, letter, CodeNum(n));
                let user_m = letter == 'M' && (1000..=1990).contains(&n);
                let Some(info) = info.filter(|_| !user_m) else {
                    let msg = if letter == 'G' {
                        "Unknown g code used".to_string()
                    } else {
                        format!("Unknown m code used: M{}", n / 10)
                    };
                    return Err(self.err(codes::UNKNOWN_CODE, span, msg));
                };
                let Some(group) = info.group else { continue };
                if let Some(&(_, _, other)) =
                    seen.iter().find(|(l, g, _)| *l == letter && *g == group)
                {
                    // rs274 lets G80 share a line with another motion code.
                    if letter == 'G' && group == 1 && (other == 800 || n == 800) {
                        continue;
                    }
                    let msg = if letter == 'G' {
                        "Two g codes used from same modal group"
                    } else {
                        "Two m codes used from same modal group"
                    };
                    return Err(self.err(codes::UNKNOWN_CODE, span, msg));
                }
                seen.push((letter, group, n));
            }
        }
        Ok(())
    }

    fn seen_content_before(&self, p: &Program, bi: u32) -> bool {
        p.blocks
            .iter()
            .take(bi as usize)
            .any(|b| b.kind == BlockKind::Normal && !p.items_of(b).is_empty())
    }

    /// FANUC decimal-point rules and ServoWorks integer machine units.
    fn scale_words(&self, w: &mut Words) {
        let dist = b"XYZABCUVWIJKRQ";
        match self.dialect {
            Dialect::Fanuc if !self.cfg.decimal_point_input => {
                let inc = if self.st.modal.inch { 0.0001 } else { 0.001 };
                for c in dist {
                    let i = (c - b'A') as usize;
                    if w.v[i].is_some() && !w.point[i] {
                        if *c == b'Q' && w.has_g(760) {
                            continue;
                        }
                        w.v[i] = w.v[i].map(|v| v * inc);
                    }
                }
            }
            Dialect::Servoworks if self.cfg.integer_machine_unit => {
                let mu = self.cfg.machine_unit / if self.st.modal.inch { 25.4 } else { 1.0 };
                for c in dist {
                    let i = (c - b'A') as usize;
                    if w.v[i].is_some() && !w.point[i] {
                        w.v[i] = w.v[i].map(|v| v * mu);
                    }
                }
            }
            Dialect::Rs274ngc => {
                // G7: rs274 halves X words as it reads them (G7/G8 in the block
                // itself take effect for its own X word).
                let diameter = if w.has_g(70) {
                    true
                } else if w.has_g(80) {
                    false
                } else {
                    self.st.modal.diameter
                };
                let i = (b'X' - b'A') as usize;
                if diameter {
                    w.v[i] = w.v[i].map(|v| v / 2.0);
                }
            }
            _ => {}
        }
    }

    fn assign(
        &mut self,
        p: &Program,
        target: ExprId,
        v: Val,
        span: Span,
    ) -> Result<(), Diagnostic> {
        match p.expr(target).expr {
            Expr::Var { index } => {
                let n = self.eval_num(p, index)?.round();
                if n < 0.0 || n as usize >= NUM_PARAMS {
                    return Err(self.err(
                        codes::EXPRESSION,
                        span,
                        format!("parameter number #{n} out of range"),
                    ));
                }
                if n == 0.0 && !self.ngc() {
                    return Err(self.err(codes::EXPRESSION, span, "#0 is read-only (PS0116)"));
                }
                let v = if self.ngc() {
                    Some(v.unwrap_or(0.0))
                } else {
                    v
                };
                if self.dialect == Dialect::Fanuc && (n as usize == 3000 || n as usize == 3006) {
                    let stop = n as usize == 3000;
                    self.event(EventKind::Message(format!("#{} = {}", n, v.unwrap_or(0.0))));
                    if stop {
                        return Err(self.err(
                            codes::MACRO_ALARM,
                            span,
                            format!("macro alarm #3000 = {}", v.unwrap_or(0.0)),
                        ));
                    }
                }
                self.set_param(n as usize, v);
                Ok(())
            }
            Expr::Named { name } => {
                let key = expr::named_key(&p.str_of(name));
                let v = v.unwrap_or(0.0);
                if key.starts_with('_') {
                    Arc::make_mut(&mut self.st.named).insert(key, v);
                } else if let Some(f) = self.frames.last_mut() {
                    f.named_locals.insert(key, v);
                } else {
                    self.main_locals.insert(key, v);
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }

    fn goto_seq(&mut self, fi: usize, bi: u32, n: f64, span: Span) -> Result<Flow, Diagnostic> {
        let blocks = self.files[fi]
            .seq
            .get(&(n.max(0.0) as u64))
            .cloned()
            .unwrap_or_default();
        // Search forward first, then from the top of the program.
        if let Some(b) = blocks.iter().find(|b| **b > bi).or(blocks.first()) {
            return Ok(Flow::Goto(fi, *b));
        }
        Err(self.err(
            codes::FLOW,
            span,
            format!("sequence number N{n} not found (PS0128)"),
        ))
    }

    // ----------------------------------------------------------------- O-words

    fn exec_oword(
        &mut self,
        fi: usize,
        bi: u32,
        p: &Program,
        ow: analyzer::syntax::OWord,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        let Some(kw) = ow.keyword else {
            return Ok(Flow::Next);
        };
        let ctrl = self.files[fi].ctrl.get(&bi).cloned().unwrap_or_default();
        let args: Vec<ExprId> = p.expr_list(ow.args()).to_vec();
        let cond = |s: &Self| -> Result<bool, Diagnostic> {
            match args.first() {
                Some(e) => Ok(s.eval_num(p, *e)? != 0.0),
                None => Ok(false),
            }
        };
        let after = |b: Option<u32>| -> Result<u32, Diagnostic> {
            b.map(|b| b + 1).ok_or_else(|| {
                self.err(
                    codes::FLOW,
                    span,
                    format!("O-word `{}` has no matching end", kw.as_str()),
                )
            })
        };
        if self.ngc()
            && ctrl.partner.is_none()
            && matches!(
                kw,
                OKeyword::Endwhile
                    | OKeyword::Endrepeat
                    | OKeyword::Endif
                    | OKeyword::Else
                    | OKeyword::Elseif
            )
        {
            // rs274 finds no open block of that label when it reaches the closer.
            return Err(self.err(
                codes::FLOW,
                span,
                format!(
                    "{}: undefined O-word label: '{}'",
                    self.cur_line + 1,
                    self.line_text(fi, bi)
                ),
            ));
        }
        match kw {
            OKeyword::Sub => {
                // rs274 refuses a definition inside a definition while it skips over
                // the outer one, and names the inner `sub` line.
                let stop = ctrl.partner.unwrap_or(p.blocks.len() as u32);
                let nested = (bi + 1..stop).find(|b| {
                    p.blocks.get(*b as usize).is_some_and(|blk| {
                        p.items_of(blk).iter().any(|it| {
                            matches!(it.kind, ItemKind::OWord(o) if o.keyword == Some(OKeyword::Sub))
                        })
                    })
                });
                if let (true, Some(b)) = (self.ngc(), nested) {
                    self.cur = (fi, b);
                    let at = p.blocks.get(b as usize).map(|x| x.span).unwrap_or(span);
                    return Err(self.err(codes::FLOW, at, "Nested subroutine definition"));
                }
                if self.ngc() && fi == 0 && ctrl.partner.is_none() {
                    // rs274 skips the definition looking for its endsub and runs off
                    // the end of the file.
                    return Ok(Flow::Goto(fi, p.blocks.len() as u32));
                }
                // A definition met in flow is skipped.
                Ok(Flow::Goto(fi, after(ctrl.partner)?))
            }
            OKeyword::Endsub | OKeyword::Return => {
                let v = match args.first() {
                    Some(e) => Some(self.eval_num(p, *e)?),
                    None => None,
                };
                if self.frames.is_empty() {
                    if kw == OKeyword::Return {
                        return Err(self.err(codes::FLOW, span, "`return` outside a subroutine"));
                    }
                    return Ok(Flow::Next);
                }
                let named = Arc::make_mut(&mut self.st.named);
                named.insert("_value".into(), v.unwrap_or(0.0));
                named.insert(
                    "_value_returned".into(),
                    if v.is_some() { 1.0 } else { 0.0 },
                );
                let saved = self.frames.last_mut().and_then(|f| f.context.take());
                self.ret_from_sub(None);
                self.auto_restore(saved)?;
                Ok(Flow::Goto(self.cur.0, self.cur.1))
            }
            OKeyword::Call => {
                let mut vals = Vec::new();
                for a in &args {
                    vals.push(self.eval_num(p, *a)?);
                }
                let key = match ow.label {
                    OLabel::Expr(e) => Some(format!("{}", self.eval_num(p, e)?.round() as i64)),
                    _ => label_key(p, &ow),
                };
                let Some(key) = key else {
                    return Err(self.err(codes::FLOW, span, "call without a subroutine name"));
                };
                self.call_ngc(fi, bi, &key, vals, span)
            }
            OKeyword::While => {
                if ctrl.closes_do {
                    let head = ctrl.partner.unwrap_or(bi);
                    if std::mem::take(&mut self.pending_break) {
                        return Ok(Flow::Next);
                    }
                    return Ok(if cond(self)? {
                        Flow::Goto(fi, head + 1)
                    } else {
                        Flow::Next
                    });
                }
                if cond(self)? {
                    Ok(Flow::Next)
                } else {
                    Ok(Flow::Goto(fi, after(ctrl.partner)?))
                }
            }
            OKeyword::Endwhile => Ok(Flow::Goto(fi, ctrl.partner.unwrap_or(bi + 1))),
            OKeyword::Do => Ok(Flow::Next),
            OKeyword::Repeat => {
                let n = match args.first() {
                    Some(e) => self.eval_num(p, *e)?.round() as i64,
                    None => 0,
                };
                if n <= 0 {
                    return Ok(Flow::Goto(fi, after(ctrl.partner)?));
                }
                self.repeats.push((fi, bi, n));
                Ok(Flow::Next)
            }
            OKeyword::Endrepeat => {
                let head = ctrl.partner.unwrap_or(bi);
                if let Some(top) = self
                    .repeats
                    .iter_mut()
                    .rev()
                    .find(|r| r.0 == fi && r.1 == head)
                {
                    top.2 -= 1;
                    if top.2 > 0 {
                        return Ok(Flow::Goto(fi, head + 1));
                    }
                }
                self.repeats.retain(|r| !(r.0 == fi && r.1 == head));
                Ok(Flow::Next)
            }
            OKeyword::If => {
                if cond(self)? {
                    return Ok(Flow::Next);
                }
                for b in &ctrl.branches {
                    let blk = p.blocks.get(*b as usize).copied();
                    let Some(blk) = blk else { continue };
                    let item = p.items_of(&blk).iter().find_map(|it| match it.kind {
                        ItemKind::OWord(o) => Some(o),
                        _ => None,
                    });
                    let Some(o) = item else { continue };
                    if o.keyword == Some(OKeyword::Else) {
                        return Ok(Flow::Goto(fi, b + 1));
                    }
                    let a = p.expr_list(o.args()).first().copied();
                    if let Some(a) = a {
                        if self.eval_num(p, a)? != 0.0 {
                            return Ok(Flow::Goto(fi, b + 1));
                        }
                    }
                }
                Ok(Flow::Goto(fi, after(ctrl.partner)?))
            }
            OKeyword::Elseif | OKeyword::Else => Ok(Flow::Goto(fi, after(ctrl.partner)?)),
            OKeyword::Endif => Ok(Flow::Next),
            OKeyword::Break | OKeyword::Continue => {
                let Some(head) = ctrl.partner else {
                    return Err(self.err(
                        codes::FLOW,
                        span,
                        format!("`{}` outside a loop", kw.as_str()),
                    ));
                };
                let hc = self.files[fi].ctrl.get(&head).cloned().unwrap_or_default();
                let end = hc.partner.unwrap_or(head);
                let head_kw = |k: OKeyword| {
                    p.blocks.get(head as usize).is_some_and(|b| {
                        p.items_of(b)
                            .iter()
                            .any(|it| matches!(it.kind, ItemKind::OWord(o) if o.keyword == Some(k)))
                    })
                };
                let is_do = head_kw(OKeyword::Do);
                // LinuxCNC leaves a loop by skipping forward to its end, and a `break`
                // of the same loop met while skipping still runs (even inside a false
                // `if`).  Its flag is cleared only where a `do` loop closes, so a
                // break out of a while or repeat loop also ends the next do-while
                // after one pass.
                let breaks_ahead = (bi + 1..end).any(|b| {
                    self.files[fi].ctrl.get(&b).is_some_and(|c| c.partner == Some(head))
                        && p.blocks.get(b as usize).is_some_and(|blk| {
                            p.items_of(blk).iter().any(|it| matches!(it.kind, ItemKind::OWord(o) if o.keyword == Some(OKeyword::Break)))
                        })
                });
                if kw == OKeyword::Break || (is_do && breaks_ahead) {
                    self.repeats.retain(|r| !(r.0 == fi && r.1 == head));
                    if !is_do {
                        self.pending_break = true;
                    }
                    Ok(Flow::Goto(fi, end + 1))
                } else {
                    if breaks_ahead {
                        self.pending_break = true;
                    }
                    let is_repeat_or_do = is_do || head_kw(OKeyword::Repeat);
                    Ok(Flow::Goto(fi, if is_repeat_or_do { end } else { head }))
                }
            }
        }
    }

    fn load_file(&mut self, name: &str, span: Span) -> Option<usize> {
        let key = name.to_ascii_lowercase();
        if let Some(i) = self.file_names.get(&key) {
            return Some(*i);
        }
        let from = self.file_id();
        let rf = self.input.resolver.resolve(name, from)?;
        let _ = span;
        let opts = analyzer::syntax::ParseOptions {
            dialect: self.dialect,
            variant: self.variant,
        };
        // The interpreter never reads tokens.
        let prog = analyzer::syntax::parse_lean(opts, rf.text.clone());
        let idx = self.files.len();
        for d in &prog.diagnostics {
            self.out
                .diagnostics
                .push(d.clone().in_file(FileId(idx as u32)));
        }
        self.files.push(FileEntry::new(
            ProgRef::Shared(Arc::new(prog)),
            FileId(idx as u32),
        ));
        self.file_names.insert(key, idx);
        // Keep the resolved path for the output list.
        self.file_names.insert(rf.path.clone(), idx);
        self.file_names.remove(&rf.path);
        self.out.files.push(rf.path);
        self.spec_file_loaded(idx, name);
        Some(idx)
    }

    fn depth_check(&self, span: Span) -> Result<(), Diagnostic> {
        if self.frames.len() >= self.cfg.max_depth {
            return Err(self.err(
                codes::CALL_DEPTH,
                span,
                format!("subprogram nesting deeper than {} levels (recursion?): the control alarms here", self.cfg.max_depth),
            ));
        }
        Ok(())
    }

    fn call_ngc(
        &mut self,
        fi: usize,
        bi: u32,
        key: &str,
        vals: Vec<f64>,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        self.depth_check(span)?;
        let (tf, tb) = if let Some(b) = self.files[fi].subs.get(key).copied() {
            (fi, b)
        } else if let Some(b) = self.files[0].subs.get(key).copied() {
            (0, b)
        } else if let Some(f) = self.load_file(key, span) {
            match self.files[f].subs.get(key).copied() {
                Some(b) => (f, b),
                None => (f, u32::MAX),
            }
        } else {
            if self.ngc() && self.canon.is_some() && self.out.canon_error.is_none() {
                // rs274 reads on to the end of the file looking for the definition
                // and shows the last line it read.
                let last = self.files[0]
                    .prog
                    .blocks
                    .iter()
                    .rev()
                    .map(|b| self.files[0].prog.str_of(b.span).trim().to_string())
                    .find(|t| !t.is_empty())
                    .unwrap_or_default();
                self.out.canon_error = Some(format!(
                    "EOF in file:{CANON_FILE_NAME} seeking o-word: o<{key}> from line: {}\n{last}",
                    self.cur_line + 1
                ));
            }
            return Err(self.err(codes::SUB_NOT_FOUND, span, format!("subroutine o<{key}> is not defined in this file and no file `{key}.ngc` was found")));
        };
        // Save the caller's #1-#30 and pass the arguments.
        let saved: Vec<Option<f64>> = (1..=30)
            .map(|n| self.st.params.get(n).copied().flatten())
            .collect();
        for n in 1..=30usize {
            self.set_param(n, Some(vals.get(n - 1).copied().unwrap_or(0.0)));
        }
        Arc::make_mut(&mut self.st.named).remove("_value_returned");
        self.frames.push(Frame {
            kind: FrameKind::NgcSub,
            ret_file: fi,
            ret_block: bi + 1,
            saved: Some(saved),
            named_locals: HashMap::new(),
            call_span: span,
            modal_call: false,
            context: None,
        });
        let start = if tb == u32::MAX { 0 } else { tb + 1 };
        Ok(Flow::Goto(tf, start))
    }

    /// Returns from the innermost frame; sets `self.cur`. `seq` is M99 P.
    fn ret_from_sub(&mut self, seq: Option<f64>) -> bool {
        let Some(mut f) = self.frames.pop() else {
            return false;
        };
        if let FrameKind::Sub { start, repeat } = f.kind {
            if repeat > 1 {
                f.kind = FrameKind::Sub {
                    start,
                    repeat: repeat - 1,
                };
                let file = self.cur.0;
                self.frames.push(f);
                self.cur = (file, start);
                return true;
            }
        }
        if let Some(saved) = f.saved {
            let n0 = 1;
            for (k, v) in saved.into_iter().enumerate() {
                self.set_param(n0 + k, v);
            }
        }
        self.cur = (f.ret_file, f.ret_block);
        if let Some(n) = seq {
            if let Some(b) = self.files[f.ret_file]
                .seq
                .get(&(n as u64))
                .and_then(|v| v.first())
            {
                self.cur = (f.ret_file, *b);
            }
        }
        let _ = f.call_span;
        true
    }

    /// M98 / G65: `name` is the program name or number as written.
    fn call_program(
        &mut self,
        fi: usize,
        bi: u32,
        name: &str,
        repeat: u32,
        args: Option<Vec<Option<f64>>>,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        self.depth_check(span)?;
        let number = name.parse::<u32>().ok();
        let (tf, tb) = if let Some(b) = number.and_then(|n| self.files[fi].heads.get(&n).copied()) {
            (fi, b + 1)
        } else if let Some(b) = number.and_then(|n| self.files[0].heads.get(&n).copied()) {
            (0, b + 1)
        } else {
            let f = self
                .load_file(name, span)
                .or_else(|| number.and_then(|n| self.load_file(&format!("{n:04}"), span)));
            match f {
                Some(f) => {
                    let p = self.files[f].prog.clone();
                    // Start after the program head, if the file has one.
                    let head = p.blocks.iter().position(|b| {
                        p.items_of(b)
                            .iter()
                            .any(|it| matches!(it.kind, ItemKind::ProgramHead { .. }))
                    });
                    (f, head.map(|h| h as u32 + 1).unwrap_or(0))
                }
                None => {
                    let what = if self.dialect == Dialect::Servoworks {
                        format!("subprogram O{name} (file O{name}.dat) not found")
                    } else {
                        format!("program O{name} not found (PS0076)")
                    };
                    return Err(self.err(codes::SUB_NOT_FOUND, span, what));
                }
            }
        };
        let saved = if let Some(a) = &args {
            let saved: Vec<Option<f64>> = (1..=33)
                .map(|n| self.st.params.get(n).copied().flatten())
                .collect();
            for n in 1..=33usize {
                self.set_param(n, a.get(n).copied().flatten());
            }
            Some(saved)
        } else {
            None
        };
        self.frames.push(Frame {
            kind: FrameKind::Sub {
                start: tb,
                repeat: repeat.max(1),
            },
            ret_file: fi,
            ret_block: bi + 1,
            saved,
            named_locals: HashMap::new(),
            call_span: span,
            modal_call: false,
            context: None,
        });
        Ok(Flow::Goto(tf, tb))
    }

    // ----------------------------------------------------------------- words

    fn lin(&self, v: f64) -> f64 {
        v * self.unit()
    }

    fn exec_words(
        &mut self,
        fi: usize,
        bi: u32,
        p: &Program,
        w: &Words,
        comments: &[(CommentKind, Span)],
        bspan: Span,
    ) -> Result<Flow, Diagnostic> {
        let ngc = self.ngc();
        self.block_exact = !ngc && w.has_g(90);
        // Comments and messages.  rs274 keeps only the last parenthesised comment
        // of a line.
        let skip = if ngc {
            let paren = |(_, s): &&(CommentKind, Span)| !p.str_of(*s).starts_with(';');
            comments.iter().filter(paren).count().saturating_sub(1)
        } else {
            0
        };
        let mut seen = 0;
        for (k, s) in comments {
            if ngc && !p.str_of(*s).starts_with(';') {
                seen += 1;
                if seen <= skip {
                    continue;
                }
            }
            self.exec_comment(p, *k, *s)?;
        }
        self.state_checks(w, bspan)?;
        // Units first so that every word of the block is read in them.
        if w.has_g(200) || w.has_g(210) {
            self.switch_units(w.has_g(200));
        }
        // G96/G97.
        if w.has_g(960) {
            self.st.modal.css = true;
            let d = w.get(b'D').map(|v| self.lin(v)).unwrap_or(0.0);
            self.canon(format!("SET_SPINDLE_MODE(0 {})", f4(d / self.unit())));
        }
        if w.has_g(970) {
            self.st.modal.css = false;
            self.canon("SET_SPINDLE_MODE(0 0.0000)");
        }
        // Feed mode.
        for (code, text, mode) in [
            (930u32, "inverse time", 0),
            (940, "units per minute", 0),
            (950, "units per revolution", 1),
        ] {
            if w.has_g(code) {
                self.canon_comment(&format!("interpreter: feed mode set to {text}"));
                self.canon(format!("SET_FEED_MODE(0, {mode})"));
                self.st.modal.feed_mode = code;
                if code != 930 {
                    self.st.feed = 0.0;
                    self.canon("SET_FEED_RATE(0.0000)");
                }
            }
        }
        if let Some(f) = w.get(b'F') {
            let u = if ngc {
                self.unit()
            } else if self.st.modal.inch {
                25.4
            } else {
                1.0
            };
            self.st.feed = if self.st.modal.feed_mode == 930 {
                f
            } else {
                f * u
            };
            if self.st.modal.feed_mode != 930 {
                self.canon(format!("SET_FEED_RATE({})", f4(f)));
            }
        }
        if let Some(s) = w.get(b'S') {
            self.st.spindle = s;
            self.canon(format!("SET_SPINDLE_SPEED(0, {})", f4(s)));
            if self.st.spindle_dir != 0 {
                let (rpm, dir) = (s, self.st.spindle_dir);
                self.event(EventKind::Spindle { rpm, dir });
            }
        }
        if let Some(t) = w.get(b'T') {
            let t = t.round().max(0.0) as u32;
            self.st.next_tool = t;
            self.check_tool(t, w.sp(b'T'))?;
            self.canon(format!("SELECT_TOOL({t})"));
            if self.dialect == Dialect::Servoworks {
                // ServoWorks changes the tool with the T word itself.
                self.st.tool = t;
                self.event(EventKind::ToolChange { tool: t });
            }
        }
        // Subprogram calls (FANUC/ServoWorks) are handled at the end of the block.
        let sw_m_after = self.dialect == Dialect::Servoworks;
        if !sw_m_after {
            self.exec_m_before(w)?;
        }
        // Modal G codes.
        if w.has_g(40) {
            self.exec_dwell(w)?;
        }
        if self.st.modal.rotation && [170u32, 180, 190].iter().any(|g| w.has_g(*g)) {
            let span =
                w.g.iter()
                    .find(|g| matches!(g.0, 170 | 180 | 190))
                    .map(|g| g.1)
                    .unwrap_or_default();
            self.diag(codes::COORD_DURING_ROTATION, Severity::Error, span, "the plane cannot be changed while coordinate rotation (G68) is on: cancel it with G69 first");
        }
        for (code, name, plane) in [
            (170u32, "CANON_PLANE_XY", 170u32),
            (180, "CANON_PLANE_XZ", 180),
            (190, "CANON_PLANE_YZ", 190),
        ] {
            if w.has_g(code) {
                self.st.modal.plane = plane;
                self.canon(format!("SELECT_PLANE({name})"));
            }
        }
        if w.has_g(200) || w.has_g(210) {
            let inch = w.has_g(200);
            self.st.modal.inch = inch;
            self.canon(if inch {
                "USE_LENGTH_UNITS(CANON_UNITS_INCHES)"
            } else {
                "USE_LENGTH_UNITS(CANON_UNITS_MM)"
            });
        }
        if ngc {
            for (code, on) in [(70u32, true), (80, false)] {
                if w.has_g(code) && self.st.modal.diameter != on {
                    self.st.modal.diameter = on;
                    self.canon_comment(if on {
                        "interpreter: Lathe diameter mode changed to diameter"
                    } else {
                        "interpreter: Lathe diameter mode changed to radius"
                    });
                }
            }
        }
        self.exec_comp(w)?;
        self.exec_tlo(w)?;
        self.exec_coord_select(w)?;
        if self.input.program.dialect == analyzer::Dialect::Servoworks {
            if w.has_g(401) {
                self.st.modal.ndc = None;
            } else if w.has_g(411) {
                self.st.modal.ndc = Some(true);
            } else if w.has_g(421) {
                self.st.modal.ndc = Some(false);
            }
            if w.has_g(3110) {
                self.st.modal.feed_linear_only = true;
            } else if w.has_g(3100) {
                self.st.modal.feed_linear_only = false;
            }
        }
        for (code, mode) in [(610u32, "CANON_EXACT_PATH"), (611, "CANON_EXACT_STOP")] {
            if w.has_g(code) {
                self.st.modal.path = code;
                self.canon(format!("SET_MOTION_CONTROL_MODE({mode})"));
            }
        }
        if w.has_g(640) {
            self.st.modal.path = 640;
            let pt = if ngc {
                w.get(b'P').map(|v| self.lin(v))
            } else {
                None
            };
            self.st.modal.path_tol = pt;
            let tol = pt.unwrap_or(0.0) / self.unit();
            let q = w.get(b'Q').unwrap_or(tol);
            self.naive_tol = q;
            self.canon(format!(
                "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, {tol:.6})"
            ));
            self.canon(format!("SET_NAIVECAM_TOLERANCE({})", f4(q)));
        }
        for (code, abs) in [(901u32, true), (911, false)] {
            if w.has_g(code) {
                if self.st.modal.ijk_abs != abs {
                    self.canon_comment(if abs {
                        "interpreter: IJK distance mode changed to absolute"
                    } else {
                        "interpreter: IJK distance mode changed to incremental"
                    });
                }
                self.st.modal.ijk_abs = abs;
            }
        }
        if w.has_g(900) {
            if self.st.modal.incremental {
                self.canon_comment("interpreter: distance mode changed to absolute");
            }
            self.st.modal.incremental = false;
        }
        if w.has_g(910) {
            if !self.st.modal.incremental {
                self.canon_comment("interpreter: distance mode changed to incremental");
            }
            self.st.modal.incremental = true;
        }
        if w.has_g(980) {
            self.st.modal.retract_old_z = true;
            self.canon_comment("interpreter: retract mode set to old_z");
        }
        if w.has_g(990) {
            self.st.modal.retract_old_z = false;
            self.canon_comment("interpreter: retract mode set to r_plane");
        }
        self.exec_fanuc_modes(w)?;
        // Subprogram call blocks (FANUC / ServoWorks): the motion in the block is ignored.
        if w.has_m(980) || (!ngc && w.has_g(650)) {
            return self.exec_call_words(fi, bi, w);
        }
        // G66 registers a modal macro call (arguments only in this block); G67 cancels it.
        if !ngc && w.has_g(670) {
            self.st.g66 = None;
        }
        if !ngc && w.has_g(660) {
            let Some(p) = w.get(b'P') else {
                return Err(self.err(
                    codes::SUB_NOT_FOUND,
                    w.g_span(660),
                    "G66 without P (macro number)",
                ));
            };
            self.st.g66 = Some((format!("{}", p.round() as i64), Arc::new(macro_args(w))));
            return self.exec_stops(w, fi);
        }
        // One-shot codes that consume axis words.
        let consumed = self.exec_modal0(w)?;
        // Motion.
        if !consumed {
            let before = self.out.motions.len();
            self.exec_motion(w, bspan)?;
            if let Some(left) = self.st.modal.ndc {
                self.ndc_after_motion(before, left);
            }
            // A G66 modal call runs the macro after each block that moves an axis.
            if let Some((name, args)) = self.st.g66.clone() {
                if w.any_axis() && !self.frames.iter().any(|f| f.modal_call) {
                    let span = w.g.first().map(|g| g.1).unwrap_or(bspan);
                    let flow = self.call_program(fi, bi, &name, 1, Some(args.to_vec()), span)?;
                    if let Some(f) = self.frames.last_mut() {
                        f.modal_call = true;
                    }
                    return Ok(flow);
                }
            }
        }
        if sw_m_after {
            self.exec_m_before(w)?;
        }
        // Stops and ends.
        self.exec_stops(w, fi)
    }

    fn exec_comment(&mut self, p: &Program, k: CommentKind, s: Span) -> Result<(), Diagnostic> {
        let text = p.str_of(s).into_owned();
        if text.starts_with(';') {
            return Ok(());
        }
        let inner = text
            .trim_start_matches('(')
            .trim_end_matches(')')
            .to_string();
        let after_comma = |t: &str| {
            t.split_once(',')
                .map(|(_, r)| r.to_string())
                .unwrap_or_default()
        };
        match k {
            CommentKind::Plain | CommentKind::Partscope if self.ngc() => {
                self.canon_comment(inner.trim_start())
            }
            CommentKind::Msg => {
                let m = after_comma(&inner);
                self.canon(format!("MESSAGE(\"{m}\")"));
                self.event(EventKind::Message(m));
            }
            CommentKind::Debug | CommentKind::Print => {
                let m = self.substitute(&after_comma(&inner));
                if k == CommentKind::Print {
                    if let Some(c) = self.canon.as_mut() {
                        c.raw(m);
                    }
                } else if !self.ngc() || self.read_param(5599) > 0.0 {
                    // #5599 = 0 silences (DEBUG,) in LinuxCNC.
                    self.canon(format!("MESSAGE(\"{m}\")"));
                }
            }
            CommentKind::Abort => {
                let m = self.substitute(&after_comma(&inner));
                return Err(self.err(codes::MACRO_ALARM, s, format!("abort: {m}")));
            }
            _ => {}
        }
        Ok(())
    }

    /// Replaces `#n` and `#<name>` in a message with `%f`-formatted values.
    fn substitute(&self, text: &str) -> String {
        let b = text.as_bytes();
        let mut out = String::new();
        let mut i = 0;
        // LinuxCNC's `%d`, `%f` (4 decimals) and `%.Nf` set the format of the
        // parameters that follow (a bare `%lf` stays as text); the default is 6 decimals.
        let mut decimals = 6usize;
        while i < b.len() {
            if b[i] == b'%' {
                let rest = &text[i + 1..];
                let (spec_len, d) = if rest.starts_with('d') {
                    (1, Some(0))
                } else if rest.starts_with('f') {
                    (1, Some(4))
                } else if let Some(r) = rest.strip_prefix('.') {
                    let digits = r.bytes().take_while(u8::is_ascii_digit).count();
                    let after = &r[digits..];
                    let tail = if after.starts_with("lf") {
                        2
                    } else if after.starts_with('f') {
                        1
                    } else {
                        0
                    };
                    if digits > 0 && tail > 0 {
                        (
                            1 + digits + tail,
                            r[..digits].parse::<usize>().ok().map(|n| n.min(20)),
                        )
                    } else {
                        (0, None)
                    }
                } else {
                    (0, None)
                };
                if let Some(d) = d {
                    decimals = d;
                    i += 1 + spec_len;
                    continue;
                }
            }
            if b[i] == b'#' {
                if b.get(i + 1) == Some(&b'<') {
                    if let Some(end) = text[i..].find('>') {
                        let name = expr::named_key(&text[i + 2..i + end]);
                        let locals = self
                            .frames
                            .last()
                            .map(|f| &f.named_locals)
                            .unwrap_or(&self.main_locals);
                        let v = locals
                            .get(&name)
                            .copied()
                            .or_else(|| self.st.named.get(&name).copied())
                            .or_else(|| predefined(&self.st, &name));
                        match v {
                            Some(v) => out.push_str(&format!("{v:.decimals$}")),
                            None => out.push_str("######"),
                        }
                        i += end + 1;
                        continue;
                    }
                } else {
                    let mut j = i + 1;
                    while j < b.len() && b[j].is_ascii_digit() {
                        j += 1;
                    }
                    if j > i + 1 {
                        // LinuxCNC has 5602 numbered parameters and prints those
                        // beyond as hashes.
                        match text[i + 1..j].parse::<usize>() {
                            Ok(n) if !self.ngc() || n < 5602 => {
                                let v = self.read_param(n as i64);
                                out.push_str(&format!("{v:.decimals$}"));
                            }
                            _ => out.push_str("######"),
                        }
                        i = j;
                        continue;
                    }
                }
            }
            let ch = text[i..].chars().next().unwrap_or(' ');
            out.push(ch);
            i += ch.len_utf8();
        }
        out
    }

    /// LinuxCNC stops at a T or H number its tool table lacks (spec NGC413/NGC503:
    /// error, in rs274's words); the other controls run on with a zero offset.
    fn check_tool(&mut self, t: u32, span: Span) -> Result<(), Diagnostic> {
        let have_table = self.input.tool_table.is_some() || !self.cfg.tools.is_empty();
        if have_table && t != 0 && !self.cfg.tools.contains_key(&t) {
            if self.ngc() {
                return Err(self.err(
                    codes::UNKNOWN_TOOL,
                    span,
                    format!("Requested tool {t} not found in the tool table"),
                ));
            }
            self.diag(
                codes::UNKNOWN_TOOL,
                Severity::Warning,
                span,
                format!("tool T{t} is not in the tool table"),
            );
        }
        Ok(())
    }

    fn exec_m_before(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let ngc = self.ngc();
        if w.has_m(60) && !(self.dialect == Dialect::Servoworks) {
            let t = self.st.next_tool;
            self.canon("START_CHANGE()");
            self.canon("STOP_SPINDLE_TURNING(0)");
            // rs274 prints the tool's slot in the tool table, not its number.
            let slot = if self.cfg.tool_order.is_empty() {
                t as usize
            } else {
                self.cfg
                    .tool_order
                    .iter()
                    .position(|x| *x == t)
                    .map(|i| i + 1)
                    .unwrap_or(0)
            };
            self.canon(format!("CHANGE_TOOL({slot})"));
            self.st.tool = t;
            self.event(EventKind::ToolChange { tool: t });
        }
        if w.has_m(610) {
            let t = w.get(b'Q').unwrap_or(0.0) as u32;
            // Like M6, M61 stops at a tool number the table lacks.
            if ngc {
                self.check_tool(t, w.sp(b'Q'))?;
            }
            // The standalone rs274 announces the new number but keeps reading the old
            // tool's data (#5400-#5410, G43 without H); `--emit canon` copies it, the
            // dry run loads the tool as a real LinuxCNC does.
            if self.canon.is_none() || !ngc {
                self.st.tool = t;
            }
            self.canon(format!("CHANGE_TOOL_NUMBER({t})"));
        }
        for (m, dir) in [(30u32, 1i8), (40, -1), (50, 0)] {
            if w.has_m(m) {
                self.st.spindle_dir = dir;
                self.canon(match dir {
                    1 => "START_SPINDLE_CLOCKWISE(0)",
                    -1 => "START_SPINDLE_COUNTERCLOCKWISE(0)",
                    _ => "STOP_SPINDLE_TURNING(0)",
                });
                let rpm = if dir == 0 { 0.0 } else { self.st.spindle };
                self.event(EventKind::Spindle { rpm, dir });
            }
        }
        if w.has_m(190) && ngc {
            let r = w.get(b'R').unwrap_or(0.0);
            let q = w.get(b'P').unwrap_or(0.0) as i32;
            self.canon(format!("ORIENT_SPINDLE(0, {}, {q})", f4(r)));
        }
        if ngc {
            self.exec_context_codes(w)?;
        }
        let mut coolant = false;
        if w.has_m(70) {
            self.st.mist = true;
            self.canon("MIST_ON()");
            coolant = true;
        }
        if w.has_m(80) {
            self.st.flood = true;
            self.canon("FLOOD_ON()");
            coolant = true;
        }
        if w.has_m(90) {
            self.st.mist = false;
            self.st.flood = false;
            self.canon("MIST_OFF()");
            self.canon("FLOOD_OFF()");
            coolant = true;
        }
        if coolant {
            let (mist, flood) = (self.st.mist, self.st.flood);
            self.event(EventKind::Coolant { mist, flood });
        }
        if ngc {
            // Override switches: M48/M49 both overrides, M50-M53 one each, on
            // unless P is 0.
            if w.has_m(480) {
                self.feed_override_off = false;
                self.canon("ENABLE_FEED_OVERRIDE()");
                self.canon("ENABLE_SPEED_OVERRIDE(0)");
            }
            if w.has_m(490) {
                self.feed_override_off = true;
                self.canon("DISABLE_FEED_OVERRIDE()");
                self.canon("DISABLE_SPEED_OVERRIDE(0)");
            }
            let on = w.get(b'P').is_none_or(|p| p != 0.0);
            if w.has_m(500) {
                self.feed_override_off = !on;
            }
            for (m, what) in [
                (500u32, "FEED_OVERRIDE()"),
                (510, "SPEED_OVERRIDE(0)"),
                (520, "ADAPTIVE_FEED()"),
                (530, "FEED_HOLD()"),
            ] {
                if w.has_m(m) {
                    let verb = if on { "ENABLE" } else { "DISABLE" };
                    self.canon(format!("{verb}_{what}"));
                }
            }
        }
        if ngc {
            for (m, text) in [
                (620u32, "SET_MOTION_OUTPUT_BIT"),
                (630, "CLEAR_MOTION_OUTPUT_BIT"),
                (640, "SET_AUX_OUTPUT_BIT"),
                (650, "CLEAR_AUX_OUTPUT_BIT"),
            ] {
                if w.has_m(m) {
                    let p = w.get(b'P').unwrap_or(0.0) as i32;
                    self.canon(format!("{text}({p})"));
                }
            }
        }
        Ok(())
    }

    fn exec_dwell(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let secs = match self.dialect {
            Dialect::Rs274ngc => match w.get(b'P') {
                Some(p) => p,
                None => {
                    return Err(self.err(
                        codes::INTERP,
                        w.g_span(40),
                        "dwell time P word missing with G4",
                    ))
                }
            },
            _ => {
                if let Some(x) = w.get(b'X') {
                    x
                } else if let Some(p) = w.get(b'P') {
                    p / 1000.0
                } else {
                    w.get(b'U').unwrap_or(0.0)
                }
            }
        };
        self.canon(format!("DWELL({})", f4(secs)));
        self.event(EventKind::Dwell(secs.max(0.0)));
        Ok(())
    }

    fn tool_diameter(&self, d: Option<f64>) -> f64 {
        let idx = d.map(|v| v.round() as u32).unwrap_or(self.st.tool);
        let Some(t) = self.cfg.tools.get(&idx) else {
            return 0.0;
        };
        if self.ngc() && self.cfg.param_unit == 25.4 {
            // rs274 divides by its external length unit, the rounded constant
            // 0.03937007874016 (a hair above 1/25.4), then by 25.4 in an inch program:
            // compensated points at an exact half of the last printed digit round as
            // they do there.
            let prog = if self.st.modal.inch { 25.4 } else { 1.0 };
            return t.diameter / 0.039_370_078_740_16 / prog;
        }
        t.diameter * self.pfac()
    }

    fn exec_comp(&mut self, w: &Words) -> Result<(), Diagnostic> {
        if w.has_g(400) {
            self.st.modal.comp = 400;
            self.st.comp_radius = 0.0;
            self.comp_flush();
            self.canon_comment("interpreter: cutter radius compensation off");
        }
        for given in [410u32, 420, 411, 421] {
            // LinuxCNC G41.1/G42.1: dynamic compensation with the diameter in D.
            let dynamic = given % 10 == 1;
            if !w.has_g(given) || (dynamic && !self.ngc()) {
                continue;
            }
            let code = given - given % 10;
            {
                self.st.modal.comp = code;
                let dia = match w.get(b'D') {
                    Some(d) if dynamic => self.lin(d),
                    Some(d)
                        if self.dialect == Dialect::Servoworks
                            && w.point[(b'D' - b'A') as usize] =>
                    {
                        self.lin(d)
                    }
                    d => self.tool_diameter(d),
                };
                // A negative diameter puts the tool on the other side.
                if dia < 0.0 {
                    self.st.modal.comp = if code == 410 { 420 } else { 410 };
                }
                self.st.comp_radius = dia.abs() / 2.0;
                // G41.1/G42.1 take the orientation from L (G18 only); G41/G42 from the table.
                self.st.comp_orientation = if dynamic {
                    w.get(b'L').map(|l| l.clamp(0.0, 9.0) as u8).unwrap_or(0)
                } else {
                    let idx = w
                        .get(b'D')
                        .map(|v| v.round() as u32)
                        .unwrap_or(self.st.tool);
                    self.cfg.tools.get(&idx).map(|t| t.orientation).unwrap_or(0)
                };
                let side = if self.comp_left() { "left" } else { "right" };
                self.st.comp_first = true;
                self.comp_flush();
                self.canon_comment(&format!(
                    "interpreter: cutter radius compensation on {side}"
                ));
            }
        }
        Ok(())
    }

    fn exec_tlo(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let set = |s: &mut Self, z: f64, x: f64, y: f64| {
            // The programmed point stays; the machine position follows at the next move.
            s.st.tlo = [x, y, z, 0.0, 0.0, 0.0];
            s.st.pos = s.to_program(s.st.mpos);
            let u = s.unit();
            s.canon(format!(
                "USE_TOOL_LENGTH_OFFSET({} {} {}, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)",
                f4(x / u),
                f4(y / u),
                f4(z / u)
            ));
        };
        if w.has_g(490) {
            self.st.modal.tlo_mode = 490;
            set(self, 0.0, 0.0, 0.0);
        }
        for code in [430u32, 440] {
            if w.has_g(code) {
                self.st.modal.tlo_mode = code;
                let h = w
                    .get(b'H')
                    .map(|v| v.round() as u32)
                    .unwrap_or(self.st.tool);
                if w.has(b'H') {
                    self.check_tool(h, w.sp(b'H'))?;
                }
                let t = self.cfg.tools.get(&h).copied().unwrap_or_default();
                let sign = if code == 440 { -1.0 } else { 1.0 };
                let f = self.pfac();
                set(
                    self,
                    sign * t.length * f,
                    sign * t.x_offset * f,
                    sign * t.y_offset * f,
                );
            }
        }
        if w.has_g(432) {
            self.st.modal.tlo_mode = 432;
            if self.dialect == Dialect::Servoworks {
                let h = w.get(b'H').map(|v| v.round().max(0.0) as u32).unwrap_or(0);
                let tool = self.cfg.tools.get(&h).copied().unwrap_or_default();
                self.st.tcp_length = self.cfg.tcp_arm_length + tool.length * self.pfac();
            }
            if self.ngc() {
                // LinuxCNC G43.2 adds a tool's offset (H) to the one in force.
                let add;
                if let Some(h) = w.get(b'H').map(|v| v.round().max(0.0) as u32) {
                    self.check_tool(h, w.sp(b'H'))?;
                    let t = self.cfg.tools.get(&h).copied().unwrap_or_default();
                    let f = self.pfac();
                    add = [t.x_offset * f, t.y_offset * f, t.length * f];
                } else {
                    // LinuxCNC 2.9 looks up tool -1 for G43.2 without H and stops.
                    return Err(self.err(
                        codes::UNKNOWN_TOOL,
                        w.g_span(432),
                        "Requested tool -1 not found in the tool table",
                    ));
                }
                let cur = self.st.tlo;
                set(self, cur[2] + add[2], cur[0] + add[0], cur[1] + add[1]);
            }
        }
        if w.has_g(431) && self.ngc() {
            // Dynamic tool length offset from the block's axis words.
            self.st.modal.tlo_mode = 431;
            let x = w.get(b'X').map(|v| self.lin(v)).unwrap_or(0.0);
            let z = w.get(b'Z').map(|v| self.lin(v)).unwrap_or(0.0);
            set(self, z, x, 0.0);
        }
        Ok(())
    }

    fn exec_coord_select(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let mut origin = None;
        for (code, o) in [
            (540u32, 1usize),
            (550, 2),
            (560, 3),
            (570, 4),
            (580, 5),
            (590, 6),
            (591, 7),
            (592, 8),
            (593, 9),
        ] {
            if w.has_g(code) {
                origin = Some(o);
            }
        }
        if w.has_g(541) {
            // FANUC has at most 300 extended work offsets; clamping keeps the
            // parameter arithmetic (`100 + p`, `20 * (origin - 101)`) from
            // overflowing on `P1e30` (fuzz: interpret, add overflow).
            // A NaN P (from a macro expression) would cast to 0 and select
            // the nonexistent origin 100 (fuzz: interpret, subtract overflow).
            let p = w
                .get(b'P')
                .filter(|v| v.is_finite())
                .unwrap_or(1.0)
                .round()
                .clamp(1.0, 300.0) as usize;
            origin = Some(100 + p);
        }
        let Some(o) = origin else { return Ok(()) };
        if self.st.modal.rotation {
            let span =
                w.g.iter()
                    .find(|(g, _)| (540..=593).contains(g))
                    .map(|x| x.1)
                    .unwrap_or_default();
            self.diag(codes::COORD_DURING_ROTATION, Severity::Error, span, "work coordinate systems cannot be changed while coordinate rotation (G68) is on: cancel it with G69 first");
        }
        if o == self.st.modal.origin {
            self.canon_comment("interpreter: continuing to use same coordinate system");
            return Ok(());
        }
        self.st.modal.origin = o;
        self.st.pos = self.to_program(self.st.mpos);
        let u = self.unit();
        let g = self.g5x_prog();
        let g92 = self.st.g92;
        if o < 100 {
            self.canon(format!(
                "SET_G5X_OFFSET({o}, {})",
                Canon::six(&scale6(g, u))
            ));
            self.canon(format!("SET_G92_OFFSET({})", Canon::six(&scale6(g92, u))));
            let r = self.rotation_canon(o);
            self.canon(r);
        }
        Ok(())
    }

    fn exec_fanuc_modes(&mut self, w: &Words) -> Result<(), Diagnostic> {
        // (ServoWorks look-ahead and FANUC/ServoWorks coordinate transforms.)
        if self.ngc() {
            return Ok(());
        }
        // Between M29 and the G84/G74 block the spindle is already switched to position control:
        // the seed (§5.2.1) says an S command or axis movement there stops with PS0203.
        let starts_tap = w.has_g(840) || w.has_g(740);
        if self.dialect == Dialect::Fanuc
            && self.st.modal.rigid_tap
            && !matches!(self.st.modal.motion, 740 | 840)
            && !starts_tap
            && !w.has_m(290)
            && (w.has(b'S') || w.any_axis())
        {
            let span = if w.has(b'S') {
                w.sp(b'S')
            } else {
                b"XYZABCUVW"
                    .iter()
                    .find(|c| w.has(**c))
                    .map(|c| w.sp(*c))
                    .unwrap_or_default()
            };
            self.diag(codes::RIGID_TAP, Severity::Error, span, "S command or axis movement between M29 and G84/G74: the control alarms (PS0203); position the tool before M29 and give the tap right after it");
        }
        if w.has_m(290) {
            let span =
                w.m.iter()
                    .find(|m| m.0 == 290)
                    .map(|m| m.1)
                    .unwrap_or_default();
            if matches!(self.st.modal.motion, 740 | 840) {
                self.diag(codes::RIGID_TAP, Severity::Error, span, "M29 given while a tapping cycle is already modal: give M29 before G84/G74 (PS0204)");
            }
            self.st.modal.rigid_tap = true;
        }
        if w.has_g(800) || w.g.iter().any(|(g, _)| matches!(g, 0 | 10 | 20 | 30)) {
            self.st.modal.rigid_tap = false;
        }
        if w.has_g(150) {
            self.st.modal.polar = false;
        }
        if w.has_g(160) {
            self.st.modal.polar = true;
        }
        if w.has_g(500) {
            self.st.modal.scaling = false;
        }
        if w.has_g(510) {
            let c = [
                w.get(b'X').map(|v| self.lin(v)).unwrap_or(self.st.pos[0]),
                w.get(b'Y').map(|v| self.lin(v)).unwrap_or(self.st.pos[1]),
                w.get(b'Z').map(|v| self.lin(v)).unwrap_or(self.st.pos[2]),
            ];
            let p = w.get(b'P');
            let f = match p {
                Some(p) => {
                    let p = if w.point[(b'P' - b'A') as usize] {
                        p
                    } else {
                        p * 0.001
                    };
                    [p; 3]
                }
                None => {
                    // ServoWorks (§6.3.19, SW106): a factor left out keeps its value from
                    // the previous G51; elsewhere it is 1.
                    let kept = if self.dialect == Dialect::Servoworks {
                        self.st.scale.1
                    } else {
                        [1.0; 3]
                    };
                    [
                        w.get(b'I').unwrap_or(kept[0]),
                        w.get(b'J').unwrap_or(kept[1]),
                        w.get(b'K').unwrap_or(kept[2]),
                    ]
                }
            };
            self.st.scale = (c, f);
            self.st.modal.scaling = true;
        }
        if w.has_g(501) {
            // G50.1 cancels the mirror of the axes it names (all when it names none).
            let named: Vec<usize> = [b'X', b'Y', b'Z']
                .iter()
                .enumerate()
                .filter(|(_, c)| w.has(**c))
                .map(|(i, _)| i)
                .collect();
            if named.is_empty() {
                self.st.mirror = ([false; 3], [0.0; 3]);
            }
            for i in named {
                self.st.mirror.0[i] = false;
            }
            self.st.modal.mirror = self.st.mirror.0.iter().any(|b| *b);
        }
        if w.has_g(511) {
            for (i, c) in [b'X', b'Y', b'Z'].iter().enumerate() {
                if let Some(v) = w.get(*c) {
                    self.st.mirror.0[i] = true;
                    self.st.mirror.1[i] = self.lin(v);
                }
            }
            self.st.modal.mirror = self.st.mirror.0.iter().any(|b| *b);
        }
        if w.has_g(690) {
            self.st.modal.rotation = false;
        }
        if w.has_g(680) {
            let (a, b) = self.plane_axes();
            let letters = [b'X', b'Y', b'Z'];
            let ca = w
                .get(letters[a])
                .map(|v| self.lin(v))
                .unwrap_or(self.st.pos[a]);
            let cb = w
                .get(letters[b])
                .map(|v| self.lin(v))
                .unwrap_or(self.st.pos[b]);
            let r = w.get(b'R').unwrap_or(0.0);
            self.st.rotation = ([ca, cb], r);
            self.st.modal.rotation = true;
        }
        if self.dialect == Dialect::Servoworks && (w.has_g(50) || w.has_g(80)) {
            // Exactly four forms switch 3D-DLACC (§6.3.7); anything else is ignored.
            let p = w.get(b'P').map(|p| p.round() as i64);
            let on = match (w.has_g(50), p) {
                (true, Some(10000)) | (false, Some(1)) => Some(true),
                (_, Some(0)) => Some(false),
                _ => None,
            };
            if on == Some(true) && self.st.modal.tlo_mode == 432 {
                let span =
                    w.g.iter()
                        .find(|g| g.0 == 50 || g.0 == 80)
                        .map(|g| g.1)
                        .unwrap_or_default();
                return Err(self.err(codes::DLACC_TCP, span, "3D-DLACC cannot be combined with tool centre point control (G43.2): the control stops"));
            }
            if let Some(on) = on {
                self.st.modal.dlacc = on;
            }
        }
        if self.st.modal.dlacc {
            self.check_dlacc(w)?;
        }
        Ok(())
    }

    /// While 3D-DLACC is on only the manual's whitelist of G codes may run;
    /// the control stops at the first other one (SW056).
    fn check_dlacc(&mut self, w: &Words) -> Result<(), Diagnostic> {
        const ALLOWED: &[u32] = &[
            0, 10, 20, 30, 40, 50, 80, 170, 180, 190, 200, 210, 280, 290, 300, 500, 510, 501, 511,
            520, 530, 540, 550, 560, 570, 580, 590, 541, 610, 640, 641, 650, 900, 910, 920, 3100,
            3110,
        ];
        for (g, s) in &w.g {
            if !ALLOWED.contains(g) {
                let name = analyzer::dialect::CodeNum(*g).display();
                let code = if *g == 432 {
                    codes::DLACC_TCP
                } else {
                    codes::DLACC_INCOMPATIBLE
                };
                return Err(self.err(code, *s, format!("G{name} cannot be used while 3D dynamic look-ahead is on: turn it off with G08 P0 (or G05 P0) first")));
            }
        }
        Ok(())
    }

    fn exec_call_words(&mut self, fi: usize, bi: u32, w: &Words) -> Result<Flow, Diagnostic> {
        let span =
            w.m.iter()
                .find(|(m, _)| *m == 980)
                .map(|x| x.1)
                .unwrap_or(w.g_span(650));
        if w.has_g(650) {
            let Some(p) = w.get(b'P') else {
                return Err(self.err(codes::SUB_NOT_FOUND, span, "G65 without P (macro number)"));
            };
            let l = w.get(b'L').unwrap_or(1.0).max(1.0) as u32;
            let args = macro_args(w);
            let name = format!("{}", p.round() as i64);
            return self.call_program(fi, bi, &name, l, Some(args), span);
        }
        // M98.
        let (name, repeat) = match (&w.pname, w.get(b'P')) {
            (Some(n), _) => (n.clone(), w.get(b'R').or(w.get(b'L')).unwrap_or(1.0)),
            (None, Some(p)) => {
                let p = p.round() as i64;
                if self.dialect == Dialect::Fanuc && !w.has(b'L') && p > 9999 {
                    (format!("{}", p % 10000), (p / 10000) as f64)
                } else {
                    let r = if self.dialect == Dialect::Servoworks {
                        w.get(b'R')
                    } else {
                        w.get(b'L')
                    };
                    (format!("{p}"), r.unwrap_or(1.0))
                }
            }
            (None, None) => {
                return Err(self.err(
                    codes::SUB_NOT_FOUND,
                    span,
                    "M98 without P (subprogram name)",
                ))
            }
        };
        if w.any_axis() {
            self.diag(
                codes::INTERP,
                Severity::Warning,
                span,
                "M98 shares its block with axis words: the motion in this block is ignored",
            );
        }
        // LinuxCNC runs `M98 P.. L0` zero times.
        if self.ngc() && repeat < 1.0 {
            return Ok(Flow::Next);
        }
        self.call_program(fi, bi, &name, repeat.max(1.0) as u32, None, span)
    }

    /// Non-modal codes that consume axis words. Returns whether they did.
    fn exec_modal0(&mut self, w: &Words) -> Result<bool, Diagnostic> {
        if self.dialect == Dialect::Servoworks && w.has_g(370) {
            self.exec_g37(w)?;
            return Ok(true);
        }
        // Scaling, mirror and rotation codes take their centre from the axis words.
        if !self.ngc() && [510u32, 511, 501, 680].iter().any(|g| w.has_g(*g)) {
            return Ok(true);
        }
        if self.ngc() && w.has_g(431) {
            return Ok(true);
        }
        // FANUC/ServoWorks `G04 X…` gives the dwell time in X, not a move.
        if !self.ngc() && w.has_g(40) {
            return Ok(true);
        }
        let u = self.unit();
        let letters = [b'X', b'Y', b'Z', b'A', b'B', b'C'];
        let axis = |s: &Self, i: usize| -> Option<f64> {
            w.get(letters[i]).map(|v| if i < 3 { s.lin(v) } else { v })
        };
        if w.has_g(100) {
            let l = w.get(b'L').unwrap_or(0.0).round() as i64;
            let p = w.get(b'P').unwrap_or(0.0).round() as i64;
            match l {
                // FANUC/ServoWorks tool offset memory: L10/L11 length (H), L12/L13
                // radius (D); R is the value, added under G91.
                10..=13 if !self.ngc() => {
                    let t = p.max(0) as u32;
                    let mut tool = self.cfg.tools.get(&t).copied().unwrap_or_default();
                    let f = self.pfac();
                    if let Some(r) = w.get(b'R') {
                        let r = self.lin(r) / f;
                        let inc = self.st.modal.incremental;
                        if l <= 11 {
                            tool.length = if inc { tool.length + r } else { r };
                        } else {
                            let rad = if inc { tool.diameter / 2.0 + r } else { r };
                            tool.diameter = 2.0 * rad;
                        }
                    }
                    self.cfg.tools.insert(t, tool);
                }
                20 if self.input.program.dialect == Dialect::Servoworks => {
                    self.servoworks_axis_types(w, p);
                }
                2 | 20 => {
                    let origin = if p == 0 {
                        self.st.modal.origin
                    } else {
                        p.clamp(1, 9) as usize
                    };
                    let base = 5201 + 20 * origin;
                    if let Some(r) = w.get(b'R').filter(|_| self.ngc()) {
                        if l == 20 {
                            return Err(self.err(
                                codes::INTERP,
                                w.sp(b'R'),
                                "R not allowed in G10 L20",
                            ));
                        }
                        self.set_param(5210 + 20 * origin, Some(r));
                    }
                    let cur_machine = self.st.mpos;
                    let rot = self.read_param((5210 + 20 * origin) as i64);
                    let rotated_l20 = l == 20
                        && rot != 0.0
                        && (axis(self, 0).is_some() || axis(self, 1).is_some());
                    if rotated_l20 {
                        // The point is given in the rotated system: both X and Y of the
                        // origin move (LinuxCNC's convert_setup).
                        let f = self.pfac();
                        let abs: Vec<f64> = (0..2)
                            .map(|i| {
                                cur_machine[i] - self.st.g92[i] - self.st.g52[i] - self.st.tlo[i]
                            })
                            .collect();
                        let off = [
                            self.read_param(base as i64) * f,
                            self.read_param(base as i64 + 1) * f,
                        ];
                        let (sn, cs) = rot.to_radians().sin_cos();
                        let (dx, dy) = (abs[0] - off[0], abs[1] - off[1]);
                        let cur = [dx * cs + dy * sn, -dx * sn + dy * cs];
                        let want = [
                            axis(self, 0).unwrap_or(cur[0]),
                            axis(self, 1).unwrap_or(cur[1]),
                        ];
                        let rw = [want[0] * cs - want[1] * sn, want[0] * sn + want[1] * cs];
                        // Round-off from the rotation would print as -0.0000.
                        let snap = |v: f64| if v.abs() < 1e-12 { 0.0 } else { v };
                        self.set_param(base, Some(snap((abs[0] - rw[0]) / f)));
                        self.set_param(base + 1, Some(snap((abs[1] - rw[1]) / f)));
                    }
                    for i in 0..6 {
                        if rotated_l20 && i < 2 {
                            continue;
                        }
                        let Some(v) = axis(self, i) else { continue };
                        let scale = if i < 3 { self.pfac() } else { 1.0 };
                        let new = if l == 2 {
                            v
                        } else {
                            cur_machine[i] - self.st.g92[i] - self.st.g52[i] - self.st.tlo[i] - v
                        };
                        self.set_param(base + i, Some(new / scale));
                    }
                    if origin == self.st.modal.origin {
                        self.st.pos = self.to_program(self.st.mpos);
                        let g = self.g5x_of(origin);
                        self.canon(format!(
                            "SET_G5X_OFFSET({origin}, {})",
                            Canon::six(&scale6(g, u))
                        ));
                        let r = self.rotation_canon(origin);
                        self.canon(r);
                    } else {
                        self.canon_comment("interpreter: setting coordinate system origin");
                    }
                }
                1 | 10 | 11 => {
                    let t = p.max(0) as u32;
                    if self.ngc() {
                        self.check_tool(t, w.sp(b'P'))?;
                    }
                    let mut tool = self.cfg.tools.get(&t).copied().unwrap_or_default();
                    let f = self.pfac();
                    if l == 1 {
                        for (i, slot) in [&mut tool.x_offset, &mut tool.y_offset, &mut tool.length]
                            .into_iter()
                            .enumerate()
                        {
                            if let Some(v) = axis(self, i) {
                                *slot = v / f;
                            }
                        }
                    } else {
                        // L10/L11 make the current point read the given value in the
                        // current system (L10) or in G59.3, the touch-off fixture (L11),
                        // as LinuxCNC's convert_setup_tool: the spindle point in that
                        // system without tool offset, unrotated; G92/G52 count for L10
                        // only, so that they do not move the fixture.
                        let dest = if l == 11 { 9 } else { self.st.modal.origin };
                        let g5 = self.g5x_of(dest);
                        let rot = if dest < 100 {
                            self.read_param((5210 + 20 * dest) as i64)
                        } else {
                            0.0
                        };
                        let mut t = [0.0; 3];
                        for (i, v) in t.iter_mut().enumerate() {
                            *v = self.st.mpos[i] - g5[i];
                        }
                        let rotate = |x: f64, y: f64, deg: f64| {
                            let (sn, cs) = deg.to_radians().sin_cos();
                            (x * cs - y * sn, x * sn + y * cs)
                        };
                        (t[0], t[1]) = rotate(t[0], t[1], -rot);
                        if l == 10 {
                            for (i, v) in t.iter_mut().enumerate() {
                                *v -= self.st.g92[i] + self.st.g52[i];
                            }
                        }
                        let (x, y) = (axis(self, 0), axis(self, 1));
                        if x.is_some() || y.is_some() {
                            // The component of the old offset along the axis not given
                            // is kept (in the possibly rotated system).
                            let (mut ox, mut oy) =
                                rotate(tool.x_offset * f, tool.y_offset * f, -rot);
                            let (mut tx, mut ty) = (t[0], t[1]);
                            match (x, y) {
                                (Some(xv), Some(yv)) => {
                                    (ox, oy) = (0.0, 0.0);
                                    tx -= xv;
                                    ty -= yv;
                                }
                                (Some(xv), None) => {
                                    ox = 0.0;
                                    tx -= xv;
                                    ty = 0.0;
                                }
                                (None, Some(yv)) => {
                                    oy = 0.0;
                                    ty -= yv;
                                    tx = 0.0;
                                }
                                (None, None) => {}
                            }
                            let (ox, oy) = rotate(ox, oy, rot);
                            let (tx, ty) = rotate(tx, ty, rot);
                            tool.x_offset = (tx + ox) / f;
                            tool.y_offset = (ty + oy) / f;
                        }
                        if let Some(z) = axis(self, 2) {
                            tool.length = (t[2] - z) / f;
                        }
                    }
                    if let Some(r) = w.get(b'R') {
                        tool.diameter = 2.0 * self.lin(r) / f;
                    }
                    self.cfg.tools.insert(t, tool);
                    if !self.cfg.tool_order.contains(&t) {
                        self.cfg.tool_order.push(t);
                    }
                    if self.canon.is_some() {
                        let slot = self
                            .cfg
                            .tool_order
                            .iter()
                            .position(|x| *x == t)
                            .map(|i| i + 1)
                            .unwrap_or(0);
                        // rs274 reports the entry in the tool table's units, not the program's.
                        let entry = format!(
                            "{} {} {} 0.0000 0.0000 0.0000 0.0000 0.0000 0.0000, 0.0000, 0.0000, 0",
                            f4(tool.x_offset),
                            f4(tool.y_offset),
                            f4(tool.length)
                        );
                        self.canon(format!("SET_TOOL_TABLE_ENTRY({slot}, {t}, {entry})"));
                        if t == self.st.tool || self.st.tool == 0 {
                            self.canon(format!("SET_TOOL_TABLE_ENTRY(0, {t}, {entry})"));
                        }
                    }
                }
                _ => {}
            }
            return Ok(true);
        }
        for (code, base) in [(281u32, 5161usize), (301, 5181)] {
            if w.has_g(code) && self.ngc() {
                // Store the current absolute position as the G28/G30 home.
                for i in 0..6 {
                    let scale = if i < 3 { self.pfac() } else { 1.0 };
                    self.set_param(base + i, Some(self.st.mpos[i] / scale));
                }
                return Ok(true);
            }
        }
        if w.has_g(280) || w.has_g(300) {
            let g30 = w.has_g(300);
            let span = w.g_span(if g30 { 300 } else { 280 });
            if self.st.modal.rotation {
                self.diag(codes::COORD_DURING_ROTATION, Severity::Error, span, "reference-position return (G28/G30) is not allowed while coordinate rotation (G68) is on");
            }
            // G80 in the same block cancels the cycle first (`G80 G28 G91 X0 Y0 Z0`
            // ends the FANUC manual's cycle examples).
            if !self.ngc() && self.st.modal.modal_cycle() && !w.has_g(800) {
                self.diag(codes::CYCLE_STATE, Severity::Error, span, "reference-position return while a canned cycle is modal: cancel it with G80 first (PS0044)");
                self.st.modal.motion = 800;
                self.st.cycle = CycleMem::default();
            }
            let mut mid = self.st.pos;
            for (i, m) in mid.iter_mut().enumerate() {
                if let Some(v) = axis(self, i) {
                    *m = if self.st.modal.incremental { *m + v } else { v };
                }
            }
            self.rapid_to(mid);
            self.st.g28_mid = Some(mid);
            let home_base = if g30 { 5181 } else { 5161 };
            // FANUC/ServoWorks: reference position 1 for G28, P2 (default), P3 or P4 for
            // G30, from the machine profile (a P outside 2-4 is W007; the second is used).
            let reference = if g30 {
                w.get(b'P')
                    .map(f64::round)
                    .filter(|p| (2.0..=4.0).contains(p))
                    .map_or(1, |p| p as usize - 1)
            } else {
                0
            };
            let mut home_m = self.st.mpos;
            let all = !w.any_axis() || self.ngc() && !w.any_axis();
            for (i, h) in home_m.iter_mut().enumerate() {
                if all || w.has(letters[i]) {
                    let raw = if self.ngc() {
                        self.param(home_base + i)
                    } else {
                        self.cfg.reference_positions[reference][i] / self.cfg.param_unit
                    };
                    *h = if i < 3 { raw * self.pfac() } else { raw };
                }
            }
            let target = self.to_program(home_m);
            self.rapid_to(target);
            return Ok(true);
        }
        if w.has_g(290) && !self.ngc() {
            // G29: back through the G28/G30 intermediate point to the commanded point.
            let target = self.target(w);
            if let Some(mid) = self.st.g28_mid {
                let mut via = self.st.pos;
                for (i, v) in via.iter_mut().enumerate() {
                    if w.has(letters[i]) {
                        *v = mid[i];
                    }
                }
                self.rapid_to(via);
            }
            self.rapid_to(target);
            return Ok(true);
        }
        if w.has_g(520) && !self.ngc() {
            // ServoWorks ignores a G52 given in incremental mode (SW107; K003 says so).
            if self.dialect == Dialect::Servoworks && self.st.modal.incremental {
                return Ok(true);
            }
            if self.st.modal.rotation {
                self.diag(
                    codes::COORD_DURING_ROTATION,
                    Severity::Error,
                    w.g_span(520),
                    "G52 is not allowed while coordinate rotation (G68) is on",
                );
            }
            let mut g52 = self.st.g52;
            for (i, g) in g52.iter_mut().enumerate() {
                if let Some(v) = axis(self, i) {
                    *g = v;
                }
            }
            self.st.g52 = g52;
            self.st.pos = self.to_program(self.st.mpos);
            return Ok(true);
        }
        if w.has_g(920) || (w.has_g(520) && self.ngc()) {
            if self.dialect != Dialect::Rs274ngc && !w.any_axis() {
                return Ok(true);
            }
            // Make the current point read as the given values.
            let cur = self.st.pos;
            let mut g92 = self.st.g92;
            let g52_ngc = w.has_g(520);
            for (i, g) in g92.iter_mut().enumerate() {
                if let Some(v) = axis(self, i) {
                    // LinuxCNC's G52 sets the offset itself; G92 makes the current point read `v`.
                    *g = if g52_ngc { v } else { cur[i] + *g - v };
                }
            }
            self.st.g92 = g92;
            for i in 0..6 {
                self.set_param(
                    5211 + i,
                    Some(g92[i] / if i < 3 { self.pfac() } else { 1.0 }),
                );
            }
            self.set_param(5210, Some(1.0));
            self.st.pos = self.to_program(self.st.mpos);
            self.canon(format!("SET_G92_OFFSET({})", Canon::six(&scale6(g92, u))));
            return Ok(true);
        }
        for code in [921u32, 922] {
            if w.has_g(code) {
                self.st.g92 = [0.0; 6];
                if code == 921 {
                    for i in 0..7 {
                        self.set_param(5210 + i, Some(0.0));
                    }
                } else {
                    self.set_param(5210, Some(0.0));
                }
                self.st.pos = self.to_program(self.st.mpos);
                self.canon(format!("SET_G92_OFFSET({})", Canon::six(&[0.0; 6])));
            }
        }
        if w.has_g(923) {
            let mut g92 = [0.0; 6];
            for (i, g) in g92.iter_mut().enumerate() {
                *g = self.param(5211 + i) * if i < 3 { self.pfac() } else { 1.0 };
            }
            self.st.g92 = g92;
            self.set_param(5210, Some(1.0));
            self.st.pos = self.to_program(self.st.mpos);
            self.canon(format!("SET_G92_OFFSET({})", Canon::six(&scale6(g92, u))));
        }
        Ok(false)
    }

    /// The end point of a straight move from the block's axis words.
    fn target(&self, w: &Words) -> [f64; 6] {
        let letters = [b'X', b'Y', b'Z', b'A', b'B', b'C'];
        let mut t = self.st.pos;
        let inc = self.st.modal.incremental;
        if self.ngc() && (w.polar_r.is_some() || w.polar_a.is_some()) {
            // LinuxCNC polar words: radius/angle about the origin of the plane.
            let (a, b) = self.plane_axes();
            let (x, y) = (t[a], t[b]);
            let (r0, th0) = (x.hypot(y), y.atan2(x));
            let (r, th) = if inc {
                (
                    r0 + w.polar_r.map(|v| self.lin(v)).unwrap_or(0.0),
                    th0 + w.polar_a.unwrap_or(0.0).to_radians(),
                )
            } else {
                (
                    w.polar_r.map(|v| self.lin(v)).unwrap_or(r0),
                    w.polar_a.map(f64::to_radians).unwrap_or(th0),
                )
            };
            t[a] = r * th.cos();
            t[b] = r * th.sin();
            let n = self.normal_axis();
            for i in [n, 3, 4, 5] {
                if let Some(v) = w.get(letters[i]) {
                    let v = if i < 3 { self.lin(v) } else { v };
                    t[i] = if inc { t[i] + v } else { v };
                }
            }
            return t;
        }
        if self.st.modal.polar && !self.ngc() {
            let (a, b) = self.plane_axes();
            let pl = [b'X', b'Y', b'Z'];
            if w.has(pl[a]) || w.has(pl[b]) {
                let (r0, t0) = (
                    self.st.pos[a].hypot(self.st.pos[b]),
                    self.st.pos[b].atan2(self.st.pos[a]).to_degrees(),
                );
                let r = w
                    .get(pl[a])
                    .map(|v| self.lin(v))
                    .map(|v| if inc { r0 + v } else { v })
                    .unwrap_or(r0);
                let th = w
                    .get(pl[b])
                    .map(|v| if inc { t0 + v } else { v })
                    .unwrap_or(t0);
                t[a] = r * th.to_radians().cos();
                t[b] = r * th.to_radians().sin();
            }
            let n = self.normal_axis();
            if let Some(v) = w.get(pl[n]) {
                let v = self.lin(v);
                t[n] = if inc { t[n] + v } else { v };
            }
            return t;
        }
        for i in 0..6 {
            if self.st.torque_axes & (1 << i) != 0 {
                continue;
            }
            if let Some(v) = w.get(letters[i]) {
                let v = if i < 3 { self.lin(v) } else { v };
                t[i] = if inc { t[i] + v } else { v };
            }
        }
        // FANUC/ServoWorks incremental addresses U V W on lathes are not modelled.
        t
    }

    /// Normal direction control after the block's motion (at index `i`): the
    /// in-place turn of the tool axis goes in before it and arcs turn the axis
    /// by their sweep. Blocks that made other than one G01/G02/G03 motion, and
    /// moves held back by radius compensation, are left alone.
    fn ndc_after_motion(&mut self, i: usize, left: bool) {
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
        let Some(step) = super::ndc::step(m, m.start[a], left, &cfg) else {
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
    fn servoworks_axis_types(&mut self, w: &Words, p: i64) {
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
    fn motion_base(&self, kind: MotionKind, start: [f64; 6], end: [f64; 6], feed: f64) -> Motion {
        let exact = matches!(self.st.modal.path, 610 | 611) || self.block_exact;
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
            blend_tolerance: if self.st.modal.path == 640 {
                self.st.modal.path_tol.map(|t| t * lu)
            } else {
                None
            },
            file: self.file_id(),
            block: self.cur.1,
            line: self.cur_line,
            tool: self.st.tool,
            spindle_rpm: self.st.spindle,
        }
    }

    fn rapid_to(&mut self, t: [f64; 6]) {
        if self.canon.is_some() {
            let s = self.canon_pos(&t);
            self.canon(format!("STRAIGHT_TRAVERSE({s})"));
        }
        let end = self.to_machine(t);
        let m = self.motion_base(MotionKind::Rapid, self.st.mpos, end, 0.0);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
    }

    fn feed_to(&mut self, t: [f64; 6], span: Span) -> Result<(), Diagnostic> {
        self.check_feed(span)?;
        if self.st.modal.feed_mode == 930 && !std::mem::take(&mut self.inv_rate_set) {
            let len = dist(&self.st.pos, &t);
            // LinuxCNC gives a zero-length move a nominal rate of 0.1 (its issue 2410).
            let rate = if len == 0.0 {
                0.1
            } else {
                len * self.st.feed / self.unit()
            };
            self.canon(format!("SET_FEED_RATE({})", f4(rate)));
        }
        if self.canon.is_some() {
            let s = self.canon_pos(&t);
            self.canon(format!("STRAIGHT_FEED({s})"));
        }
        let end = self.to_machine(t);
        let feed = self.effective_feed(dist(&self.st.mpos, &end));
        let m = self.motion_base(MotionKind::Feed, self.st.mpos, end, feed);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
        Ok(())
    }

    fn effective_feed(&self, len: f64) -> f64 {
        match self.st.modal.feed_mode {
            930 => len * self.st.feed,
            _ => self.st.feed,
        }
    }

    fn check_feed(&mut self, span: Span) -> Result<(), Diagnostic> {
        if self.st.feed <= 0.0 {
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
            let e = self.err(codes::ZERO_FEED, span, msg);
            if self.ngc() {
                return Err(e);
            }
            self.out.diagnostics.push(e);
        }
        Ok(())
    }

    /// Leaving cycle mode: FANUC/ServoWorks forget the drilling data;
    /// LinuxCNC keeps P/Q/R for the next cycle and only forgets the initial level.
    fn clear_cycle(&mut self) {
        if self.ngc() {
            self.st.cycle.initial = None;
        } else {
            self.st.cycle = CycleMem::default();
        }
    }

    fn exec_motion(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let mut motion = None;
        for (g, _) in &w.g {
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
                    self.exec_arc(w, mode == 20, bspan)?;
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
                self.canon(format!("START_SPEED_FEED_SYNC({:.6},0)", k / self.unit()));
                let s = self.canon_pos(&t);
                self.canon(format!("STRAIGHT_FEED({s})"));
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
                    return Err(self.err(codes::INTERP, bspan, "Spindle not turning in G33.1"));
                }
                let t = self.target(w);
                let k = w.get(b'K').map(|v| self.lin(v)).unwrap_or(0.0);
                let u = self.unit();
                self.canon(format!("START_SPEED_FEED_SYNC({:.6},0)", k / u));
                self.canon(format!(
                    "RIGID_TAP({}, {}, {})",
                    f4(t[0] / u),
                    f4(t[1] / u),
                    f4(t[2] / u)
                ));
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
                    return Err(self.err(
                        codes::PROBE_STATE,
                        bspan,
                        "All axes missing with motion code",
                    ));
                }
                let t = self.target(w);
                // G38.3 and G38.5 report a failed probe in #5070 instead of
                // stopping, so LinuxCNC lets them start at their target.
                if self.ngc() && matches!(mode, 382 | 384) && dist(&self.st.pos, &t) == 0.0 {
                    return Err(self.err(codes::PROBE_STATE, bspan, "Start point too close to probe point: a G38.2/G38.4 move needs a target away from the current position"));
                }
                self.check_feed(bspan)?;
                self.canon("TURN_PROBE_ON()");
                let s = self.canon_pos(&t);
                self.canon(format!("STRAIGHT_PROBE({s})"));
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
            m if is_cycle(m) && (motion.is_some() || has_axes) => self.exec_cycle(m, w, bspan)?,
            _ => {}
        }
        Ok(())
    }

    /// The motion kind of a G02.2/G03.2 block ending at machine point `end`: the
    /// involute of the base circle (radius R, centre start + I/J/K in the plane)
    /// through the start. Undefined curves (the checks report them) leave a
    /// straight move.
    fn involute_kind(&self, w: &Words, end: &[f64; 6], ccw: bool) -> MotionKind {
        let (a, b) = self.plane_axes();
        let (la, lb) = (b"IJK"[a.min(2)], b"IJK"[b.min(2)]);
        let (Some(i), Some(j), Some(r)) = (w.get(la), w.get(lb), w.get(b'R')) else {
            return MotionKind::Feed;
        };
        let lu = self.lu();
        let (i, j, r) = (self.lin(i) * lu, self.lin(j) * lu, self.lin(r).abs() * lu);
        let s = [self.st.mpos[a] * lu, self.st.mpos[b] * lu];
        let e = [end[a] * lu, end[b] * lu];
        match super::involute::InvoluteCurve::new(s, e, [s[0] + i, s[1] + j], r, ccw) {
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
    fn exponential_kind(&mut self, w: &Words, t: &mut [f64; 6]) -> MotionKind {
        let lu = self.lu();
        let (i, j, r) = (w.get(b'I'), w.get(b'J'), w.get(b'R'));
        let curve = match (i, j, r) {
            (Some(i), Some(j), Some(r)) => super::exponential::ExpCurve::new(
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
    fn exec_spline(&mut self, w: &Words, quadratic: bool, span: Span) -> Result<(), Diagnostic> {
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
        self.canon(format!(
            "NURBS_FEED({}, ...)",
            if quadratic { 3 } else { 4 }
        ));
        self.sampled_curve(&ctrl, t);
        Ok(())
    }

    fn finish_nurbs(&mut self, span: Span) -> Result<(), Diagnostic> {
        let pts = std::mem::take(&mut self.nurbs);
        self.st.modal.motion = 800;
        if pts.is_empty() {
            return Ok(());
        }
        self.check_feed(span)?;
        self.canon(format!("NURBS_FEED({}, ...)", pts.len() + 1));
        // Follow the control polygon: a close enough length for cycle time.
        let mut ctrl = vec![[self.st.pos[0], self.st.pos[1]]];
        ctrl.extend(pts.iter().map(|(p, _)| [p[0], p[1]]));
        let end = pts.last().map(|p| p.0).unwrap_or(self.st.pos);
        self.sampled_curve(&ctrl, end);
        Ok(())
    }

    /// Feed motions along a Bézier curve with these control points (de Casteljau).
    fn sampled_curve(&mut self, ctrl: &[[f64; 2]], end: [f64; 6]) {
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
    fn exec_threading(&mut self, w: &Words, span: Span) -> Result<(), Diagnostic> {
        use std::f64::consts::PI;
        if self.st.modal.comp != 400 {
            return Err(self.err(
                codes::CYCLE_STATE,
                span,
                "cannot use G76 threading cycle with cutter radius compensation on",
            ));
        }
        // The 2007 EMC2 limited G76 to G18 without X or Y and E up to half the
        // thread; LinuxCNC 2.9 runs all of these (checked against its rs274).
        let emc2 = self.variant == Variant::Emc2;
        if emc2 && self.st.modal.plane != 180 {
            return Err(self.err(
                codes::CYCLE_STATE,
                span,
                "G76 threading works only in the XZ plane: select G18 first",
            ));
        }
        let refused: &[u8] = if emc2 { b"XYABC" } else { b"ABC" };
        if let Some(c) = refused.iter().copied().find(|c| w.has(*c)) {
            return Err(self.err(
                codes::CYCLE_STATE,
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
                    return Err(self.err(codes::CYCLE_STATE, w.sp(b'E'), msg));
                }
                self.diag(codes::CYCLE_STATE, Severity::Warning, w.sp(b'E'), msg);
            }
        }
        if i == 0.0 {
            return Err(self.err(codes::CYCLE_STATE, span, "in G76, I must not be 0"));
        }
        if j <= 0.0 {
            return Err(self.err(codes::CYCLE_STATE, span, "in G76, J must be greater than 0"));
        }
        if k <= j {
            return Err(self.err(codes::CYCLE_STATE, span, "in G76, K must be greater than J"));
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
        let sync = |s: &mut Self, p: f64| s.canon(format!("START_SPEED_FEED_SYNC({:.6},0)", p / u));
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
    fn thread_to(&mut self, t: [f64; 6], pitch: f64) {
        if self.canon.is_some() {
            let s = self.canon_pos(&t);
            self.canon(format!("STRAIGHT_FEED({s})"));
        }
        let end = self.to_machine(t);
        let m = self.motion_base(MotionKind::Thread, self.st.mpos, end, pitch);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
    }

    /// A straight move, offset for cutter radius compensation when it is on
    /// (LinuxCNC's algorithm: entry move perpendicular to the path, arcs around
    /// convex corners, held-back moves whose end points concave corners pull back).
    fn comp_move(&mut self, t: [f64; 6], rapid: bool, span: Span) -> Result<(), Diagnostic> {
        if self.st.modal.comp == 400 || self.st.comp_radius <= 0.0 {
            if rapid {
                self.rapid_to(t);
            } else {
                self.feed_to(t, span)?;
            }
            return Ok(());
        }
        if self.st.modal.feed_mode == 930 && !rapid {
            self.check_feed(span)?;
            let len = dist(&self.st.pos, &t);
            let rate = if len == 0.0 {
                0.1
            } else {
                len * self.st.feed / self.unit()
            };
            self.canon(format!("SET_FEED_RATE({})", f4(rate)));
            self.inv_rate_set = true;
        }
        use std::f64::consts::{FRAC_PI_2, PI};
        let (a, b) = self.plane_axes();
        let r = self.st.comp_radius;
        let left = self.comp_left();
        let op = self.st.pos;
        // rs274 stores its ±π/2 in a double and takes the cosine of a double sum: along the
        // axes the sign of the tiny remainder decides whether `-0.0000` or `0.0000` is
        // printed, so no rounding to zero here.
        let dir = |ang: f64, gamma: f64| {
            let (s, c) = (ang + gamma).sin_cos();
            (c, s)
        };
        if self.st.comp_first {
            let dist = (t[a] - op[a]).hypot(t[b] - op[b]);
            if dist <= r && self.ngc() {
                return Err(self.err(
                    codes::INTERP,
                    span,
                    "length of cutter compensation entry move is not greater than the tool radius",
                ));
            }
            let alpha =
                (t[b] - op[b]).atan2(t[a] - op[a]) + if left { FRAC_PI_2 } else { -FRAC_PI_2 };
            let mut end = t;
            end[a] += r * alpha.cos();
            end[b] += r * alpha.sin();
            self.comp_flush();
            self.st.comp_endpoint = Some([op[a], op[b]]);
            // LinuxCNC records the offset direction, not the travel direction, for this move.
            self.comp_emit(end, rapid, [alpha.cos(), alpha.sin()], span)?;
            self.st.comp_first = false;
            self.st.pos = t;
            self.st.comp_tip = end;
            return Ok(());
        }
        let c = self.st.comp_tip;
        if t[a] == op[a] && t[b] == op[b] {
            let mut end = t;
            end[a] = c[a];
            end[b] = c[b];
            self.comp_emit(end, rapid, [0.0, 0.0], span)?;
            self.st.pos = t;
            self.st.comp_tip = end;
            return Ok(());
        }
        let mut theta = (c[b] - op[b]).atan2(c[a] - op[a]);
        let mut alpha = (t[b] - op[b]).atan2(t[a] - op[a]);
        let (beta, gamma) = if left {
            if theta < alpha {
                let (hi, lo) = add_ld(theta, 2.0 * PI);
                theta = hi + lo;
            }
            (theta - alpha - FRAC_PI_2, FRAC_PI_2)
        } else {
            if alpha < theta {
                let (hi, lo) = add_ld(alpha, 2.0 * PI);
                alpha = hi + lo;
            }
            (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
        };
        let (ex, ey) = dir(alpha, gamma);
        let mut end = t;
        end[a] += r * ex;
        end[b] += r * ey;
        let mut mid = c;
        mid[a] = op[a] + r * ex;
        mid[b] = op[b] + r * ey;
        let small = 0.05;
        let front = self.st.comp_queue.first().copied();
        let front_arc = front.filter(|q| q.kind == 2);
        // An "h" shape (tangent arc into a line with the tool outside the arc) is
        // treated as concave, as LinuxCNC does.
        let concave = beta < -small
            || beta > PI + small
            || (beta > PI - small
                && front_arc.is_some_and(|q| (q.turn > 0) != left && q.turn != 0));
        if !concave && beta > small {
            self.comp_move_endpoint([c[a], c[b]], span)?;
            if rapid {
                self.rapid_to(mid);
            } else {
                self.comp_corner_arc(c, mid, op, left, span)?;
            }
            self.st.comp_endpoint = Some([mid[a], mid[b]]);
        } else if concave {
            if self.variant == Variant::Emc2 {
                return Err(self.err(codes::INTERP, span, EMC2_CONCAVE));
            }
            match front_arc {
                None => {
                    let half = (beta + PI) / 2.0;
                    if half == 0.0 {
                        return Err(self.err(
                            codes::INTERP,
                            span,
                            "zero degree inside corner is invalid for cutter compensation",
                        ));
                    }
                    let retreat = r / half.tan();
                    let (rx, ry) = dir(theta, gamma);
                    let back = [c[a] + retreat * rx, c[b] + retreat * ry];
                    self.comp_move_endpoint(back, span)?;
                }
                Some(prev) => {
                    // Arc into line: the held-back arc (already compensated) ends where
                    // it meets the line's offset.
                    let oldrad = (prev.center[1] - c[b]).hypot(prev.center[0] - c[a]);
                    let base = (t[b] - op[b]).atan2(t[a] - op[a]);
                    let th = if prev.turn > 0 {
                        base + FRAC_PI_2
                    } else {
                        base - FRAC_PI_2
                    };
                    let phi = (prev.center[1] - op[b]).atan2(prev.center[0] - op[a]);
                    let inside = tool_inside_arc(left, prev.turn);
                    let oldrad_uncomp = if inside { oldrad + r } else { oldrad - r };
                    let d = oldrad_uncomp * (th - phi).cos();
                    let d2 = if inside { d - r } else { d + r };
                    let l = d2 / oldrad;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(self.err(
                            codes::INTERP,
                            span,
                            "Arc to straight motion makes a corner the compensated tool can't fit in without gouging",
                        ));
                    }
                    let ang = if inside == (prev.turn > 0) {
                        -l.acos() + th + PI
                    } else {
                        l.acos() + th + PI
                    };
                    let back = [
                        prev.center[0] + oldrad * ang.cos(),
                        prev.center[1] + oldrad * ang.sin(),
                    ];
                    self.comp_move_endpoint(back, span)?;
                }
            }
        } else {
            // Collinear lines or a tangent arc into a line: nothing to adjust.
            self.comp_flush();
            self.st.comp_endpoint = Some([c[a], c[b]]);
        }
        self.comp_emit(end, rapid, [t[a] - op[a], t[b] - op[b]], span)?;
        self.st.pos = t;
        self.st.comp_tip = end;
        Ok(())
    }

    /// Emits a compensated straight move and holds it back (LinuxCNC's enqueue).
    /// Where a compensated point `p` puts the tool's origin. LinuxCNC compensates the centre
    /// of a lathe tool's nose radius, and moves its origin (the imaginary tip the tool table
    /// measures) by the radius along X and Z as the orientation says; mill cutters
    /// (orientation 0 or 9) and other planes than G18 are not moved.
    fn lathe_origin(&self, mut p: [f64; 6]) -> [f64; 6] {
        if !self.ngc()
            || self.st.modal.plane != 180
            || self.st.modal.comp == 400
            || matches!(self.st.comp_orientation, 0 | 9)
        {
            return p;
        }
        let r = self.st.comp_radius;
        match self.st.comp_orientation {
            1 | 2 | 6 => p[0] -= r,
            3 | 4 | 8 => p[0] += r,
            _ => {}
        }
        match self.st.comp_orientation {
            2 | 3 | 7 => p[2] -= r,
            1 | 4 | 5 => p[2] += r,
            _ => {}
        }
        p
    }

    fn comp_emit(
        &mut self,
        end: [f64; 6],
        rapid: bool,
        dir: [f64; 2],
        span: Span,
    ) -> Result<(), Diagnostic> {
        let end = self.lathe_origin(end);
        if rapid {
            self.rapid_to(end);
        } else {
            self.feed_to(end, span)?;
        }
        self.comp_hold(u8::from(rapid), dir, [0.0; 2], 0, 0.0);
        Ok(())
    }

    /// Holds back the move just emitted (its canonical line and motion are the last ones).
    fn comp_hold(&mut self, kind: u8, dir: [f64; 2], center: [f64; 2], turn: i32, sweep: f64) {
        let canon = self
            .canon
            .as_ref()
            .map(|c| c.lines.len().saturating_sub(1))
            .unwrap_or(0);
        self.st.comp_queue.push(CompQueued {
            canon,
            motion: self.out.motions.len().saturating_sub(1),
            kind,
            dir,
            center,
            turn,
            sweep,
        });
    }

    /// Releases the held-back moves. LinuxCNC queues them (and every canonical
    /// call after them) until now, so they carry this block's N number.
    pub(super) fn comp_flush(&mut self) {
        self.st.comp_endpoint = None;
        let Some(first) = self.st.comp_queue.first().map(|q| q.canon) else {
            return;
        };
        self.st.comp_queue.clear();
        if let Some(c) = self.canon.as_mut() {
            let prefix = c.current_prefix();
            for line in c.lines.iter_mut().skip(first) {
                if line.starts_with(" N") && line.len() >= 8 && line.is_char_boundary(8) {
                    line.replace_range(..8, &prefix);
                }
            }
        }
    }

    /// Moves the plane end point of every held-back move to `p`, refusing moves
    /// that would reverse (the tool would gouge), then releases them.
    fn comp_move_endpoint(&mut self, p: [f64; 2], span: Span) -> Result<(), Diagnostic> {
        let queue = std::mem::take(&mut self.st.comp_queue);
        let endpoint = self.st.comp_endpoint;
        let (a, b) = self.plane_axes();
        let shift = self.lathe_origin([0.0; 6]);
        let u = self.unit();
        for q in queue.iter().copied() {
            if q.kind == 2 {
                if let Some(e) = endpoint {
                    let new_sweep = find_turn(e, q.center, q.turn, p);
                    let tol = if self.st.modal.inch { 0.001 } else { 0.0254 };
                    if q.sweep != 0.0 && new_sweep.abs() > q.sweep.abs() + tol {
                        self.st.comp_queue.clone_from(&queue);
                        return Err(self.err(
                            codes::INTERP,
                            span,
                            "Arc move in concave corner cannot be reached by the tool without gouging",
                        ));
                    }
                }
            } else if let Some(e) = endpoint {
                let dot = q.dir[0] * (p[0] - e[0]) + q.dir[1] * (p[1] - e[1]);
                if dot < 0.0 {
                    self.st.comp_queue.clone_from(&queue);
                    let what = if q.kind == 1 {
                        "Straight traverse"
                    } else {
                        "Straight feed"
                    };
                    return Err(self.err(
                        codes::INTERP,
                        span,
                        format!("{what} in concave corner cannot be reached by the tool without gouging"),
                    ));
                }
            }
            if let Some(line) = self.canon.as_mut().and_then(|c| c.lines.get_mut(q.canon)) {
                let name = match q.kind {
                    2 => "ARC_FEED(",
                    1 => "STRAIGHT_TRAVERSE(",
                    _ => "STRAIGHT_FEED(",
                };
                if let Some(at) = line.find(name) {
                    let head = line[..at + name.len()].to_string();
                    let mut args: Vec<String> = line[at + name.len()..]
                        .trim_end_matches(')')
                        .split(", ")
                        .map(str::to_string)
                        .collect();
                    let (ia, ib) = if q.kind == 2 { (0, 1) } else { (a, b) };
                    if args.len() > ia.max(ib) {
                        args[ia] = f4((p[0] + shift[a]) / u);
                        args[ib] = f4((p[1] + shift[b]) / u);
                        *line = format!("{head}{})", args.join(", "));
                    }
                }
            }
            let mut tip = self.st.comp_tip;
            tip[a] = p[0];
            tip[b] = p[1];
            let m_end = self.to_machine(self.lathe_origin(tip));
            // Motions are stored in mm, the machine position in program units.
            let lu = self.lu();
            if let Some(m) = self.out.motions.get_mut(q.motion) {
                m.end[a] = m_end[a] * lu;
                m.end[b] = m_end[b] * lu;
            }
        }
        self.st.comp_queue = queue;
        if !self.st.comp_queue.is_empty() {
            let mut tip = self.st.comp_tip;
            tip[a] = p[0];
            tip[b] = p[1];
            let m_end = self.to_machine(self.lathe_origin(tip));
            self.st.mpos[a] = m_end[a];
            self.st.mpos[b] = m_end[b];
            self.st.comp_tip = tip;
        }
        self.comp_flush();
        self.st.comp_endpoint = Some(p);
        Ok(())
    }

    /// The arc LinuxCNC inserts around a convex corner (radius = tool radius).
    fn comp_corner_arc(
        &mut self,
        from: [f64; 6],
        to: [f64; 6],
        center: [f64; 6],
        left: bool,
        span: Span,
    ) -> Result<(), Diagnostic> {
        self.check_feed(span)?;
        let (to, center) = (self.lathe_origin(to), self.lathe_origin(center));
        let (a, b) = self.plane_axes();
        let n = self.normal_axis();
        let u = self.unit();
        let rot = if left { -1 } else { 1 };
        self.canon(format!(
            "ARC_FEED({}, {}, {}, {}, {}, {}, {}, {}, {})",
            f4(to[a] / u),
            f4(to[b] / u),
            f4(center[a] / u),
            f4(center[b] / u),
            rot,
            f4(from[n] / u),
            f4(to[3]),
            f4(to[4]),
            f4(to[5])
        ));
        let mut c3 = from;
        c3[a] = center[a];
        c3[b] = center[b];
        let cm = self.to_machine(c3);
        let mut normal = [0.0; 3];
        normal[n] = if left { -1.0 } else { 1.0 };
        let mut end_p = to;
        end_p[n] = from[n];
        let end = self.to_machine(end_p);
        let radius = (from[a] - center[a]).hypot(from[b] - center[b]);
        let m = self.motion_base(
            MotionKind::Arc {
                center: [cm[0], cm[1], cm[2]],
                normal,
                turns: 0,
                radius,
            },
            self.st.mpos,
            end,
            self.st.feed,
        );
        self.out.motions.push(m);
        self.st.mpos = end;
        Ok(())
    }

    fn exec_arc(&mut self, w: &Words, cw: bool, bspan: Span) -> Result<(), Diagnostic> {
        let (a, b) = self.plane_axes();
        let n = self.normal_axis();
        let t = self.target(w);
        let ijk = [b'I', b'J', b'K'];
        let (ca, cb) = (ijk[a], ijk[b]);
        let s2 = [self.st.pos[a], self.st.pos[b]];
        let e2 = [t[a], t[b]];
        let has_r = w.has(b'R');
        let has_c = w.has(ca) || w.has(cb);
        let span =
            w.g.iter()
                .find(|(g, _)| *g == 20 || *g == 30)
                .map(|x| x.1)
                .unwrap_or(bspan);
        if self.st.modal.polar && !self.ngc() && has_c {
            self.diag(
                codes::ARC_POLAR_IJK,
                Severity::Error,
                span,
                "I/J/K centre words cannot be used in polar coordinate mode (G16): use R",
            );
        }
        if !has_r && !has_c {
            if self.ngc() {
                return Err(self.err(
                    codes::ARC_NO_CENTER,
                    span,
                    "R, I, J and K words all missing for arc",
                ));
            }
            self.diag(
                codes::ARC_NO_CENTER,
                Severity::Error,
                span,
                "arc without R or centre words (I/J/K)",
            );
            self.feed_to(t, bspan)?;
            return Ok(());
        }
        if has_r && has_c && self.ngc() && self.canon.is_some() {
            return Err(self.err(
                codes::ARC_NO_CENTER,
                w.sp(b'R'),
                "Mixed radius ijk format for arc",
            ));
        }
        if has_r && has_c && self.dialect == Dialect::Servoworks {
            return Err(self.err(
                codes::ARC_NO_CENTER,
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
            let code = if has_r {
                codes::ARC_CORRECTED_R
            } else {
                codes::ARC_CORRECTED_IJK
            };
            self.diag(
                code,
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
            self.canon(format!("SET_FEED_RATE({})", f4(len * self.st.feed / u)));
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
            self.canon(format!(
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
            ));
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

    /// Cutter compensation of an arc, following LinuxCNC (entry arcs get a new
    /// centre; concave corners pull the held-back move back to the offset arc;
    /// convex corners get an arc around the programmed corner).
    fn comp_arc(
        &mut self,
        t: [f64; 6],
        e2: [f64; 2],
        c: [f64; 2],
        r: f64,
        turn: i32,
        span: Span,
    ) -> Result<CompArc, Diagnostic> {
        let plain = CompArc {
            end: e2,
            target: t,
            radius: r,
            center: c,
            sweep: 0.0,
        };
        if self.st.modal.comp == 400 || self.st.comp_radius <= 0.0 {
            return Ok(plain);
        }
        use std::f64::consts::{FRAC_PI_2, PI};
        let (a, b) = self.plane_axes();
        let rt = self.st.comp_radius;
        let left = self.comp_left();
        let cw = turn < 0;
        let inside = left != cw;
        let op = self.st.pos;
        let o2 = [op[a], op[b]];
        let too_big = || {
            self.err(
                codes::INTERP,
                span,
                "Tool radius not less than arc radius with comp",
            )
        };
        if self.st.comp_first {
            // Entry arc: the end point moves off the contour and the arc gets a
            // new centre so that it still starts at the current point.
            if (e2[0] - o2[0]).hypot(e2[1] - o2[1]) <= rt {
                return Err(self.err(
                    codes::INTERP,
                    span,
                    "Radius of cutter compensation entry arc is not greater than the tool radius",
                ));
            }
            let gamma = if inside {
                (c[1] - e2[1]).atan2(c[0] - e2[0])
            } else {
                (e2[1] - c[1]).atan2(e2[0] - c[0])
            };
            let end = [e2[0] + rt * gamma.cos(), e2[1] + rt * gamma.sin()];
            let b_len = (o2[1] - end[1]).hypot(o2[0] - end[0]) / 2.0;
            let ab_ang = (c[1] - end[1]).atan2(c[0] - end[0]);
            let a_ang = (o2[1] - end[1]).atan2(o2[0] - end[0]) - ab_ang;
            if a_ang.cos().abs() < 0.0001 {
                return Err(too_big());
            }
            let c_len = b_len / a_ang.cos();
            let center = [end[0] + c_len * ab_ang.cos(), end[1] + c_len * ab_ang.sin()];
            // A lathe tool first moves its origin to where the compensated arc starts, or
            // the arc would not be one (LinuxCNC queues this feed before the arc).
            if self.lathe_origin([0.0; 6]) != [0.0; 6] {
                let here = self.st.pos;
                self.comp_emit(here, false, [0.0; 2], span)?;
                self.st.pos = here;
            }
            self.st.comp_first = false;
            let mut target = t;
            target[a] = end[0];
            target[b] = end[1];
            return Ok(CompArc {
                end,
                target,
                radius: c_len.abs(),
                center,
                sweep: find_turn(o2, center, turn, end),
            });
        }
        let small = 0.05;
        let cx = [self.st.comp_tip[a], self.st.comp_tip[b]];
        let arc_radius = (c[0] - e2[0]).hypot(c[1] - e2[1]);
        let mut theta = (cx[1] - o2[1]).atan2(cx[0] - o2[0]);
        theta = if left {
            theta - FRAC_PI_2
        } else {
            theta + FRAC_PI_2
        };
        let mut delta = (c[1] - o2[1]).atan2(c[0] - o2[0]);
        let alpha = if cw {
            delta + FRAC_PI_2
        } else {
            delta - FRAC_PI_2
        };
        let mut beta = if left { theta - alpha } else { alpha - theta };
        if beta > 1.5 * PI {
            beta -= 2.0 * PI;
        } else if beta < -FRAC_PI_2 {
            beta += 2.0 * PI;
        }
        let gamma = if inside {
            if arc_radius <= rt {
                return Err(too_big());
            }
            (c[1] - e2[1]).atan2(c[0] - e2[0])
        } else {
            delta += PI;
            (e2[1] - c[1]).atan2(e2[0] - c[0])
        };
        let end = [e2[0] + rt * gamma.cos(), e2[1] + rt * gamma.sin()];
        let newrad = if inside {
            arc_radius - rt
        } else {
            arc_radius + rt
        };
        let gouge = |s: &Self, what: &str| -> Diagnostic {
            s.err(
                codes::INTERP,
                span,
                format!("{what} makes a corner the compensated tool can't fit in without gouging"),
            )
        };
        if beta < -small || beta > PI + small || ((beta - PI).abs() < small && !inside) {
            if self.variant == Variant::Emc2 {
                return Err(self.err(codes::INTERP, span, EMC2_CONCAVE));
            }
            let front_arc = self.st.comp_queue.first().copied().filter(|q| q.kind == 2);
            let mid = match front_arc {
                None => {
                    // Line into arc.
                    let cyy = arc_radius * (beta - FRAC_PI_2).sin();
                    let (dist, toward) = if inside {
                        (arc_radius - rt, cyy + rt)
                    } else {
                        (arc_radius + rt, cyy - rt)
                    };
                    let l = toward / dist;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(self.err(
                            codes::INTERP,
                            span,
                            "Arc move in concave corner cannot be reached by the tool without gouging",
                        ));
                    }
                    let ang = match (inside, turn > 0) {
                        (true, true) => theta + l.asin(),
                        (true, false) => theta - l.asin(),
                        (false, true) => theta + PI - l.asin(),
                        (false, false) => theta + PI + l.asin(),
                    };
                    [c[0] + dist * ang.cos(), c[1] + dist * ang.sin()]
                }
                Some(prev) => {
                    // Arc into arc: where the two offset circles meet.
                    let oldrad = (prev.center[1] - cx[1]).hypot(prev.center[0] - cx[0]);
                    let arc_cc = (prev.center[1] - c[1]).hypot(prev.center[0] - c[0]);
                    if oldrad == 0.0 || arc_cc == 0.0 {
                        return Err(self.err(
                            codes::INTERP,
                            span,
                            "Arc to arc motion is invalid because the arcs have the same center",
                        ));
                    }
                    let ca = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad)
                        / (2.0 * oldrad * arc_cc);
                    if !(-1.0..=1.0).contains(&ca) {
                        return Err(gouge(self, "Arc to arc motion"));
                    }
                    let pullback = ca.acos();
                    let cc_dir = (c[1] - prev.center[1]).atan2(c[0] - prev.center[0]);
                    let dir = if tool_inside_arc(left, prev.turn) == (turn > 0) {
                        cc_dir + pullback
                    } else {
                        cc_dir - pullback
                    };
                    [
                        prev.center[0] + oldrad * dir.cos(),
                        prev.center[1] + oldrad * dir.sin(),
                    ]
                }
            };
            self.comp_move_endpoint(mid, span)?;
        } else if beta > small {
            // Convex: an arc around the programmed corner first.
            self.comp_flush();
            let tip = self.st.comp_tip;
            let mut mid = tip;
            mid[a] = o2[0] + rt * delta.cos();
            mid[b] = o2[1] + rt * delta.sin();
            self.comp_corner_arc(tip, mid, op, left, span)?;
            self.st.comp_tip[a] = mid[a];
            self.st.comp_tip[b] = mid[b];
            self.st.comp_endpoint = Some([mid[a], mid[b]]);
        } else {
            self.comp_flush();
            self.st.comp_endpoint = Some(cx);
        }
        let mut target = t;
        target[a] = end[0];
        target[b] = end[1];
        Ok(CompArc {
            end,
            target,
            radius: newrad,
            center: c,
            sweep: find_turn(o2, c, turn, e2),
        })
    }

    fn arc_error(
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
                self.err(codes::ARC_SAME_END_R, span, msg)
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
                self.err(codes::ARC_RADIUS_TOO_SMALL, span, msg)
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
                self.err(codes::ARC_RADIUS_MISMATCH, span, msg)
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
                    self.err(codes::ARC_RADIUS_MISMATCH, span, msg)
                }
                _ => self.err(codes::ARC_RADIUS_MISMATCH, span, "zero-radius arc"),
            },
        }
    }

    fn exec_stops(&mut self, w: &Words, fi: usize) -> Result<Flow, Diagnostic> {
        if w.has_m(600) && self.ngc() {
            self.canon("PALLET_SHUTTLE()");
        }
        if w.has_m(0) || w.has_m(600) {
            self.canon("PROGRAM_STOP()");
            self.event(EventKind::Stop { optional: false });
        }
        if w.has_m(10) {
            self.canon("OPTIONAL_PROGRAM_STOP()");
            // With the optional-stop switch off the control runs through M1.
            if self.cfg.optional_stop {
                self.event(EventKind::Stop { optional: true });
            }
        }
        if w.has_m(990) && (!self.ngc() || !self.frames.is_empty()) {
            if self.frames.is_empty() {
                // `M99 P<n>` in a main program jumps to block N<n> of the main
                // program (a common way to skip to the end or a restart point);
                // a missing N is alarm PS0078.
                if let Some(n) = w.get(b'P') {
                    let span =
                        w.m.iter()
                            .find(|m| m.0 == 990)
                            .map(|m| m.1)
                            .unwrap_or_default();
                    return self.goto_seq(fi, self.cur.1, n, span);
                }
                // M99 in a main program: the control loops back to the start.
                self.diag(
                    codes::INTERP,
                    Severity::Warning,
                    w.m.iter()
                        .find(|m| m.0 == 990)
                        .map(|m| m.1)
                        .unwrap_or_default(),
                    "M99 in the main program restarts it from the top: an endless loop (the dry run stops here)",
                );
                self.saw_end = true;
                self.st.ended = true;
                self.event(EventKind::ProgramEnd);
                return Ok(Flow::Stop);
            }
            let seq = w.get(b'P');
            self.ret_from_sub(seq);
            return Ok(Flow::Goto(self.cur.0, self.cur.1));
        }
        if self.ngc() && w.has_m(990) && self.frames.is_empty() {
            // LinuxCNC ends the program at M99 in the main file, like M2.
            self.program_end(false);
            self.saw_end = true;
            self.st.ended = true;
            self.event(EventKind::ProgramEnd);
            return Ok(Flow::Stop);
        }
        if w.has_m(20) || w.has_m(300) {
            let span = Self::m_span(w, if w.has_m(20) { 20 } else { 300 });
            self.end_checks(span);
            self.program_end(w.has_m(300));
            self.saw_end = true;
            self.st.ended = true;
            self.event(EventKind::ProgramEnd);
            // Later blocks are never run; flag the first one that has content.
            self.flag_after_end(fi);
            return Ok(Flow::Stop);
        }
        Ok(Flow::Next)
    }

    fn flag_after_end(&mut self, fi: usize) {
        if fi != 0 || !self.frames.is_empty() {
            return;
        }
        let p = self.files[0].prog.clone();
        let start = self.cur.1 as usize + 1;
        for b in p.blocks.iter().skip(start) {
            if b.kind != BlockKind::Normal {
                continue;
            }
            let items = p.items_of(b);
            let only_heads = items
                .iter()
                .all(|it| matches!(it.kind, ItemKind::Comment(_)));
            if items.is_empty() || only_heads {
                continue;
            }
            // FANUC/ServoWorks files may hold subprograms after M30; they start with O.
            if self.dialect != Dialect::Rs274ngc
                && items
                    .iter()
                    .any(|it| matches!(it.kind, ItemKind::ProgramHead { .. }))
            {
                return;
            }
            if self.dialect == Dialect::Rs274ngc {
                return;
            }
            self.diag(
                codes::AFTER_END,
                Severity::Warning,
                b.span,
                "code after the program end (M02/M30) is never executed",
            );
            return;
        }
    }

    fn program_end(&mut self, m30: bool) {
        self.comp_flush();
        if self.ngc() {
            // LinuxCNC resets: origin G54, plane XY, absolute, feed mode, spindle, coolant.
            self.st.modal.origin = 1;
            self.st.pos = self.to_program(self.st.mpos);
            let u = self.unit();
            let g = self.g5x_prog();
            self.canon(format!("SET_G5X_OFFSET(1, {})", Canon::six(&scale6(g, u))));
            let r = self.rotation_canon(1);
            self.canon(r);
            if self.st.modal.plane != 170 {
                self.canon("SELECT_PLANE(CANON_PLANE_XY)");
            }
            self.st.modal.plane = 170;
            self.st.modal.incremental = false;
            self.st.modal.feed_mode = 940;
            self.canon("SET_FEED_MODE(0, 0)");
            self.canon("SET_FEED_RATE(0.0000)");
            if self.feed_override_off && self.ngc() {
                self.feed_override_off = false;
                self.canon("ENABLE_FEED_OVERRIDE()");
            }
            self.st.modal.comp = 400;
            self.canon("STOP_SPINDLE_TURNING(0)");
            self.canon("SET_SPINDLE_MODE(0 0.0000)");
            self.st.spindle_dir = 0;
            self.st.modal.motion = 10;
            if self.st.mist {
                self.canon("MIST_OFF()");
            }
            if self.st.flood {
                self.canon("FLOOD_OFF()");
            }
            self.st.mist = false;
            self.st.flood = false;
            if m30 {
                self.canon("PALLET_SHUTTLE()");
            }
            self.canon("PROGRAM_END()");
            if self.percent_open && self.cur.0 == 0 {
                let p = self.files[0].prog.clone();
                let closed = p
                    .blocks
                    .iter()
                    .skip(self.cur.1 as usize + 1)
                    .any(|b| b.kind == BlockKind::Percent);
                if !closed {
                    self.canon_comment("interpreter: percent sign missing from end of file");
                }
            }
        }
    }

    // ----------------------------------------------------------------- canned cycles

    fn exec_cycle(&mut self, mode: u32, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let ngc = self.ngc();
        let span =
            w.g.iter()
                .find(|(g, _)| is_cycle(*g))
                .map(|x| x.1)
                .unwrap_or(bspan);
        // LinuxCNC's canned cycles move only X, Y and Z.
        if ngc && mode != 800 {
            for c in [b'A', b'B', b'C'] {
                if w.has(c) {
                    return Err(self.err(
                        codes::INTERP,
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
                codes::CYCLE_STATE,
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
        }
        if let Some(z) = w.get(zl) {
            cyc.z = Some(self.lin(z));
        }
        if cyc.r.is_none() || (ngc && !same && !w.has(b'R')) {
            return Err(self.err(
                codes::CYCLE_MISSING,
                span,
                if ngc {
                    "R clearance plane unspecified in cycle"
                } else {
                    "canned cycle without R (point R level)"
                },
            ));
        }
        if cyc.z.is_none() || (ngc && !same && !w.has(zl)) {
            return Err(self.err(
                codes::CYCLE_MISSING,
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
                    return Err(self.err(codes::CYCLE_Q, w.sp(b'Q'), msg));
                }
                self.diag(codes::CYCLE_Q, Severity::Warning, w.sp(b'Q'), msg);
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
            return Err(self.err(codes::CYCLE_Q, span, "Q word missing with G73/G83"));
        }
        // Rigid tapping (FANUC M29) checks.
        if self.dialect == Dialect::Fanuc
            && matches!(mode, 740 | 840)
            && self.st.modal.rigid_tap
            && self.st.spindle <= 0.0
        {
            self.diag(
                codes::RIGID_TAP,
                Severity::Error,
                span,
                "rigid tapping (M29) needs a spindle speed S (PS0203)",
            );
        }
        if ngc && mode == 840 && self.st.spindle_dir != 1 {
            return Err(self.err(
                codes::CYCLE_STATE,
                span,
                "spindle not turning clockwise in G84",
            ));
        }
        if ngc && mode == 740 && self.st.spindle_dir != -1 {
            return Err(self.err(
                codes::CYCLE_STATE,
                span,
                "spindle not turning counterclockwise in G74",
            ));
        }
        if ngc && matches!(mode, 860 | 870 | 880) && self.st.spindle_dir == 0 {
            return Err(self.err(
                codes::CYCLE_STATE,
                span,
                format!("spindle not turning in G{}", mode / 10),
            ));
        }
        let repeats = if ngc {
            let l = w.get(b'L').unwrap_or(1.0).round() as i64;
            if l == 0 {
                return Err(self.err(codes::CYCLE_STATE, span, "cannot do zero repeats of cycle"));
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
                codes::CYCLE_STATE,
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
                codes::CYCLE_Q,
                span,
                format!("Q word missing with g{}", mode / 10),
            ));
        }
        if missing_p {
            return Err(self.err(
                codes::CYCLE_MISSING,
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
            self.diag(codes::STEP_BUDGET, Severity::Warning, span, format!("{repeats} cycle repetitions exceed the remaining step budget; only {left} are simulated (raise it with --step-budget)"));
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
                    self.canon(format!(
                        "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, {tol:.6})"
                    ));
                    self.canon(format!("SET_NAIVECAM_TOLERANCE({})", f4(tol)));
                }
            }
        }
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    fn cycle_body(
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
                s.canon(format!("DWELL({})", f4(dwell)));
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

fn scale6(v: [f64; 6], u: f64) -> [f64; 6] {
    v6([v[0] / u, v[1] / u, v[2] / u, v[3], v[4], v[5]])
}

fn dist(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    let l = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
    if l > 0.0 {
        l
    } else {
        ((a[3] - b[3]).powi(2) + (a[4] - b[4]).powi(2) + (a[5] - b[5]).powi(2)).sqrt()
    }
}

/// The result of compensating an arc: plane end point, full target, radius,
/// centre (plane) and the programmed sweep LinuxCNC keeps for its gouge check.
struct CompArc {
    end: [f64; 2],
    target: [f64; 6],
    radius: f64,
    center: [f64; 2],
    sweep: f64,
}

/// rs274's wording of an interpreter error, from our message: known messages map
/// to its text; otherwise the part before the first explanation, capitalised.
/// rs274's words for a `#` it cannot read in `line`, the first one from the left: a name
/// that is no function (`#foo`), a `<name` without `>`, or nothing it can read as a number
/// (`#]`). `None` when every `#` reads (the block failed for another reason).
fn rs274_parameter_message(line: &str) -> Option<String> {
    // rs274 reads a letter after `#` as a unary function; the first letter picks the
    // candidates, and a letter no function starts with has its own message.
    const FUNCTIONS: [&str; 14] = [
        "abs", "acos", "asin", "atan", "cos", "exists", "exp", "fix", "fup", "ln", "round", "sin",
        "sqrt", "tan",
    ];
    const FIRST: &[u8] = b"aceflrst";
    let text = line.to_ascii_lowercase();
    let b = text.as_bytes();
    let mut i = 0;
    let mut comment = false;
    while i < b.len() {
        let c = b[i];
        i += 1;
        match c {
            b'(' => comment = true,
            b')' => comment = false,
            b';' if !comment => return None,
            b'#' if !comment => {
                let mut j = i;
                while j < b.len() && (b[j] == b' ' || b[j] == b'\t') {
                    j += 1;
                }
                match b.get(j) {
                    Some(b'<') => {
                        if !b[j..].contains(&b'>') {
                            return Some("Named parameter not terminated".to_string());
                        }
                    }
                    Some(c) if c.is_ascii_alphabetic() => {
                        let word: String = b[j..]
                            .iter()
                            .take_while(|c| c.is_ascii_alphabetic())
                            .map(|&c| c as char)
                            .collect();
                        if !FUNCTIONS.iter().any(|f| word.starts_with(f)) {
                            return Some(if FIRST.contains(c) {
                                format!("Unknown word starting with {}", *c as char)
                            } else {
                                "Unknown word where unary operation could be".to_string()
                            });
                        }
                    }
                    Some(c)
                        if c.is_ascii_digit() || matches!(c, b'[' | b'+' | b'-' | b'.' | b'#') => {}
                    _ => {
                        return Some("bad number format (conversion failed) parsing ''".to_string())
                    }
                }
            }
            _ => {}
        }
    }
    None
}

fn rs274_message(msg: &str) -> String {
    const KNOWN: &[(&str, &str)] = &[
        (
            "cannot feed with zero feed rate",
            "Cannot do g1 with zero feed rate",
        ),
        (
            "R, I, J and K words all missing",
            "R i j k words all missing for arc",
        ),
        ("SQRT of a negative", "Negative argument to sqrt"),
        (
            "Start point too close to probe point",
            "Start point too close to probe point",
        ),
        ("argument to sqrt out of range", "Negative argument to sqrt"),
        (
            "argument to ln out of range",
            "Zero or negative argument to ln",
        ),
        (
            "Arc with both a radius R",
            "Mixed radius ijk format for arc",
        ),
        ("bad character '", ""),
        (
            "length of cutter compensation entry move",
            "Length of cutter compensation entry move is not greater than the tool radius",
        ),
        (
            "zero degree inside corner",
            "Zero degree inside corner is invalid for cutter compensation",
        ),
    ];
    if msg.starts_with("parameter number #") && msg.contains("out of range") {
        return "Parameter number out of range".to_string();
    }
    if msg.starts_with("M72 restores a modal state that no M70") {
        return "Cannot restore context from invalid stack frame - missing M70/M73?".to_string();
    }
    if msg.contains("is the first move after G40") {
        return "The move just after exiting cutter compensation mode must be straight, not an arc"
            .to_string();
    }
    for (ours, theirs) in KNOWN {
        if msg.starts_with(ours) {
            if theirs.is_empty() {
                break;
            }
            return (*theirs).to_string();
        }
    }
    // Our own wording starts in lower case and explains after a colon; messages
    // already in rs274's words start with a capital and are kept whole.
    let head = if msg.starts_with(|c: char| c.is_ascii_lowercase()) {
        msg.split(": ").next().unwrap_or(msg)
    } else {
        msg
    };
    let mut c = head.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// LinuxCNC's `TOOL_INSIDE_ARC`: the tool is on the centre's side of the arc.
fn tool_inside_arc(left: bool, turn: i32) -> bool {
    (left && turn > 0) || (!left && turn < 0)
}

/// Signed sweep (radians) of an arc from `s` to `e` about `c` with `turn` turns
/// (positive counter-clockwise), as LinuxCNC's `find_turn` computes it.
fn find_turn(s: [f64; 2], c: [f64; 2], turn: i32, e: [f64; 2]) -> f64 {
    use std::f64::consts::TAU;
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = (s[1] - c[1]).atan2(s[0] - c[0]);
    let mut beta = (e[1] - c[1]).atan2(e[0] - c[0]);
    if turn > 0 {
        if beta <= alpha {
            beta += TAU;
        }
        beta - alpha + f64::from(turn - 1) * TAU
    } else {
        if alpha <= beta {
            alpha += TAU;
        }
        beta - alpha + f64::from(turn + 1) * TAU
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

/// G65/G66 arguments: specification I, with the I/J/K sets of specification II.
fn macro_args(w: &Words) -> Vec<Option<f64>> {
    let mut args = vec![None; 34];
    let map1 = |c: u8| -> Option<usize> {
        Some(match c {
            b'A' => 1,
            b'B' => 2,
            b'C' => 3,
            b'D' => 7,
            b'E' => 8,
            b'F' => 9,
            b'H' => 11,
            b'M' => 13,
            b'Q' => 17,
            b'R' => 18,
            b'S' => 19,
            b'T' => 20,
            b'U' => 21,
            b'V' => 22,
            b'W' => 23,
            b'X' => 24,
            b'Y' => 25,
            b'Z' => 26,
            _ => return None,
        })
    };
    let mut ijk_set = 0usize;
    let mut last_ijk = 0u8;
    for (c, v) in &w.ijk_order {
        if matches!(c, b'I' | b'J' | b'K') {
            let ord = match c {
                b'I' => 0,
                b'J' => 1,
                _ => 2,
            };
            if ijk_set == 0 || ord <= last_ijk {
                ijk_set += 1;
            }
            last_ijk = ord;
            let n = 3 * ijk_set + 1 + ord as usize;
            if n <= 33 {
                args[n] = Some(*v);
            }
        } else if let Some(n) = map1(*c) {
            args[n] = Some(*v);
        }
    }
    args
}

/// `a + b` where `b` is the double constant 2π standing for LinuxCNC's long-double
/// `2 * M_PIl`: the sum as a double and the remainder, including what the double constant
/// lacks of the true value; their sum rounds as rs274's long-double sum stored in a double.
fn add_ld(a: f64, b: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    // 2π − 2.0 * PI (the double constant is short of the true value by this much).
    const TWO_PI_LO: f64 = 2.449_293_598_294_706_4e-16;
    let b_lo = if b == 2.0 * PI { TWO_PI_LO } else { 0.0 };
    let s = a + b;
    let bb = s - a;
    let err = (a - (s - bb)) + (b - bb);
    (s, err + b_lo)
}
