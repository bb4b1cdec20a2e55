//! Block execution: the interpreter type `Interp`, its state between blocks, the
//! block loop (`run_main_with`) and the end of a run.
//!
//! The executor is one type whose methods live in several modules, by topic:
//! `decode` (a block → its steps in the dialect's order), `flow` (O-words, calls,
//! GOTO/WHILE, stops), `modal` (units, M codes, FANUC/ServoWorks modes), `offsets`
//! (work offsets, frame transforms, tool length, G10/G28/G92), `motion` (moves, arcs,
//! curves, threading), `comp` (cutter radius compensation), `cycles` (canned cycles),
//! `params` (parameters and expression evaluation) and `messages` (comments, rs274
//! error wording); `context`, `g37`, `g7x` and `resume` hold single features.

// Axis arrays are indexed in parallel (program, machine, offsets), which reads
// more clearly with indices than with zipped iterators.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;
use std::sync::Arc;

use analyzer::rules::RuleMeta;
use analyzer::syntax::{
    BlockKind, CommentKind, Expr, ExprId, ItemKind, MacroStmt, OKeyword, OLabel, Program, WordValue,
};
use analyzer::{Diagnostic, Dialect, FileId, Severity, Span, Variant};

use super::arc::{self, ArcError, ArcSpec};
use super::expr::{self, EvalError, Val, VarSource};
use super::files::{label_key, FileEntry, ProgRef};
use super::machine_cfg::{parse_tool_table, parse_var_file, MachineCfg};
use super::rotary_feed;
use super::state::{is_cycle, is_group_1, moves_to_axis_words, CompQueued, CycleMem, Modal, State};
use super::types::*;

/// Writes a canonical line, formatting it only when canonical output is on:
/// formatting every F and S word of a run that prints nothing cost 7 % of the
/// instructions of a macro loop.
macro_rules! canon {
    ($it:expr, $($fmt:tt)*) => {
        if $it.canon.is_some() {
            let line = format!($($fmt)*);
            $it.canon(line);
        }
    };
}

mod budget;
mod comp;
mod context;
mod cycles;
mod decode;
mod flow;
mod g37;
mod g7x;
mod g7x_geom;
mod machine_vars;
mod messages;
mod modal;
mod motion;
mod offsets;
mod params;
mod record;
mod recover;
pub(super) use g37::G37Cfg;
pub(crate) use motion::target_of;
pub(crate) use offsets::tool_diameter_of;
pub use recover::STOP_SUFFIX;
mod resume;
mod windows;
use crate::canon::{f4, Canon};
use crate::rules::{
    interp::INTERP, missing_end::MISSING_END, step_budget::STEP_BUDGET, travel_limit::TRAVEL_LIMIT,
};
use messages::{rs274_message, rs274_parameter_message};
pub use resume::{
    rerun, run_checkpointed, run_checkpointed_observed, run_checkpointed_recording, Checkpoints,
};
pub use windows::{
    not_run_in_windows, run_windowed, run_windowed_owned, FileFacts as MainFileFacts, NextWindow,
};

#[path = "checks.rs"]
mod checks;

const NUM_PARAMS: usize = 20_000;

/// Blocks of the main file that get a [`BlockSnapshot`]; beyond this the
/// snapshots stay `None` so that multi-million-line programs fit in memory.
pub const SNAPSHOT_LIMIT: usize = 2_000_000;

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

/// A watcher of a run's motions and events while they stay in the output: it
/// sees each motion and event once, in order, in chunks it may copy (a host
/// plans them on another thread while the program runs). An event's
/// `motion_index` counts from the run's first motion, as in [`RunOutput`].
pub type MotionObserver<'s> = dyn FnMut(&[Motion], &[Event]) + 's;

/// [`run_streaming`] handing over the buffers themselves ([`OwnedMotionSink`]).
pub fn run_streaming_owned(input: &RunInput<'_>, sink: &mut OwnedMotionSink<'_>) -> RunOutput {
    let mut it = Interp::new(input, false);
    it.run_main_with(Some(sink), None, None);
    it.finish_streamed(sink)
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
    /// Motions made before the call: the call's first motion is the one that
    /// positions the tool for it, whatever the caller did before.
    motions_at_call: usize,
}

/// The evaluated words of one block (the rule checks in `crate::rules` read them).
///
/// `letters` has bit `c - b'A'` set for every letter that holds a value, and
/// `g_bits` bit `n` for every G code `n` (tenths) below [`G_BITS`], so that asking
/// for a letter or a code costs one mask test whatever the block holds; clearing
/// touches only what the block wrote.
#[derive(Default)]
pub(crate) struct Words {
    v: [Option<f64>; 26],
    letters: u32,
    pub(crate) span: [Span; 26],
    pub(crate) point: [bool; 26],
    /// The G codes in the order written (tenths: G41.1 is 411).
    g: Vec<(u32, Span)>,
    g_bits: [u64; G_BITS / 64],
    /// A G code that is not a motion code (`state::is_group_1`) is in `g`.
    other_g: bool,
    pub(crate) m: Vec<(u32, Span)>,
    pub(crate) pname: Option<String>,
    pub(crate) n: Option<i64>,
    pub(crate) ijk_order: Vec<(u8, f64)>,
    /// The N number's text (whitespace kept); `n_text` reads it as written.
    pub(crate) n_span: Option<Span>,
    /// RS274/NGC polar words `@` (radius) and `^` (angle, degrees).
    pub(crate) polar_r: Option<f64>,
    pub(crate) polar_a: Option<f64>,
    /// K as written (a repeat count in FANUC/ServoWorks cycles).
    pub(crate) raw_k: Option<f64>,
}

/// The mask bit of letter `c` (`A`..=`Z`); 0 for anything else.
const fn letter_bit(c: u8) -> u32 {
    if c.is_ascii_uppercase() {
        1 << (c - b'A')
    } else {
        0
    }
}

/// The mask of every letter in `s`.
pub(crate) const fn letter_mask(s: &[u8]) -> u32 {
    let mut m = 0;
    let mut i = 0;
    while i < s.len() {
        m |= letter_bit(s[i]);
        i += 1;
    }
    m
}

/// G codes (tenths) below this have a bit in [`Words`]; every code of the dialect
/// tables is (G0 to G99.9), others are looked up in the list.
const G_BITS: usize = 1024;

/// The axis letters a block can move.
const AXIS_LETTERS: u32 = letter_mask(b"XYZABCUVW");

impl Words {
    /// Makes the words those of `Words::default()` again, keeping the lists' buffers.
    fn clear(&mut self) {
        let Words {
            v,
            letters,
            span,
            point,
            g,
            g_bits,
            other_g,
            m,
            pname,
            n,
            ijk_order,
            n_span,
            polar_r,
            polar_a,
            raw_k,
        } = self;
        let mut left = *letters;
        while left != 0 {
            let i = left.trailing_zeros() as usize;
            left &= left - 1;
            v[i] = None;
            span[i] = Span::default();
            point[i] = false;
        }
        *letters = 0;
        for (code, _) in g.iter() {
            if let Some(word) = g_bits.get_mut(*code as usize / 64) {
                *word = 0;
            }
        }
        g.clear();
        *other_g = false;
        m.clear();
        *pname = None;
        *n = None;
        ijk_order.clear();
        *n_span = None;
        *polar_r = None;
        *polar_a = None;
        *raw_k = None;
    }

    /// Gives letter `c` the value `val` (the span and decimal point stay as they are).
    pub(crate) fn set(&mut self, c: u8, val: f64) {
        if let Some(slot) = self.v.get_mut(usize::from(c.wrapping_sub(b'A'))) {
            *slot = Some(val);
            self.letters |= letter_bit(c);
        }
    }

    /// Gives letter `c` a word read from the block.
    pub(crate) fn set_word(&mut self, c: u8, val: f64, span: Span, point: bool) {
        let i = usize::from(c.wrapping_sub(b'A'));
        if i < 26 {
            self.v[i] = Some(val);
            self.span[i] = span;
            self.point[i] = point;
            self.letters |= letter_bit(c);
        }
    }

    /// Applies `f` to letter `c`'s value, if it has one.
    pub(crate) fn map(&mut self, c: u8, f: impl FnOnce(f64) -> f64) {
        if let Some(slot) = self.v.get_mut(usize::from(c.wrapping_sub(b'A'))) {
            *slot = slot.map(f);
        }
    }

    pub(crate) fn get(&self, c: u8) -> Option<f64> {
        self.v
            .get(usize::from(c.wrapping_sub(b'A')))
            .copied()
            .flatten()
    }
    pub(crate) fn has(&self, c: u8) -> bool {
        self.letters & letter_bit(c) != 0
    }
    /// Whether any letter of `mask` (from [`letter_mask`]) holds a value.
    pub(crate) fn has_any(&self, mask: u32) -> bool {
        self.letters & mask != 0
    }
    /// Whether the block has no letter word, no G and no M code.
    pub(crate) fn is_empty(&self) -> bool {
        self.letters == 0 && self.g.is_empty() && self.m.is_empty()
    }
    pub(crate) fn sp(&self, c: u8) -> Span {
        self.span
            .get(usize::from(c.wrapping_sub(b'A')))
            .copied()
            .unwrap_or_default()
    }
    /// The block's G codes in the order written.
    pub(crate) fn g(&self) -> &[(u32, Span)] {
        &self.g
    }
    /// Adds G code `code` (tenths).
    pub(crate) fn push_g(&mut self, code: u32, span: Span) {
        self.g.push((code, span));
        self.other_g |= !is_group_1(code);
        if let Some(word) = self.g_bits.get_mut(code as usize / 64) {
            *word |= 1 << (code % 64);
        }
    }
    /// Whether the block has a G code other than a motion code: only such codes
    /// change modes, offsets or the coordinate system.
    pub(crate) fn has_other_g(&self) -> bool {
        self.other_g
    }
    pub(crate) fn has_g(&self, t: u32) -> bool {
        match self.g_bits.get(t as usize / 64) {
            Some(word) => word & (1 << (t % 64)) != 0,
            None => self.g.iter().any(|(g, _)| *g == t),
        }
    }
    pub(crate) fn g_span(&self, t: u32) -> Span {
        self.g
            .iter()
            .find(|(g, _)| *g == t)
            .map(|(_, s)| *s)
            .unwrap_or_default()
    }
    pub(crate) fn has_m(&self, t: u32) -> bool {
        self.m.iter().any(|(m, _)| *m == t)
    }
    /// The span of M code `t` (tenths), or an empty one.
    pub(crate) fn m_span(&self, t: u32) -> Span {
        self.m
            .iter()
            .find(|(m, _)| *m == t)
            .map(|(_, s)| *s)
            .unwrap_or_default()
    }
    pub(crate) fn any_axis(&self) -> bool {
        self.has_any(AXIS_LETTERS) || self.polar_r.is_some() || self.polar_a.is_some()
    }
    /// The first axis letter (in `XYZABCUVW` order) the block has.
    pub(crate) fn first_axis(&self) -> Option<u8> {
        if !self.has_any(AXIS_LETTERS) {
            return None;
        }
        b"XYZABCUVW".iter().copied().find(|c| self.has(*c))
    }
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
    /// What the rule checks remember between blocks (`crate::rules::check`).
    rules: crate::rules::check::Memory,
    /// The block's `$` words and bare axis letters, for the checks.
    items: crate::rules::check::BlockItems,
    modal_cache: Option<(Modal, std::sync::Arc<[String]>)>,
    /// Motions already handed to a streaming sink.
    motions_drained: usize,
    /// Motions and events a [`MotionObserver`] has seen.
    observed: (usize, usize),
    /// P/Q of the last G5 (the next G5 without I/J mirrors them).
    spline_pq: (f64, f64),
    /// Control points of an open G5.2 NURBS block.
    nurbs: Vec<([f64; 6], f64)>,
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
    /// The last block's words, kept between blocks (`Words::clear`).
    block_words: Option<Box<Words>>,
    /// RS274/NGC: the state saved by M70 outside any subroutine.
    top_context: Option<context::SavedContext>,
    /// G64 Q (naive CAM tolerance) as written; M70 saves it.
    naive_tol: f64,
    /// FANUC #500–#999: which the machine alone knows, and the branches they decided.
    machine_vars: machine_vars::MachineVars,
    /// LinuxCNC's `doing_break`: set by a break out of a while or repeat loop and
    /// consumed by the next `do` loop's closing `while`.
    pending_break: bool,
    /// Checkpoints and rerun state (`resume.rs`); `None` for plain runs.
    resume: Option<resume::Resume>,
    /// The main file runs in windows (`windows.rs`): what is known of all of it.
    windows: Option<windows::FileFacts>,
    /// RS274/NGC: the profile of a G70-G72 cycle being read from its subroutine.
    g7x: Option<g7x::Capture>,
    /// Where a recoverable error of this block leaves the position (`recover.rs`).
    recover_to: Option<recover::Recover>,
    /// Failed and tainted expressions of this block (`recover.rs`).
    taint: recover::Taint,
    /// The values of the main file's expressions, when the host asked for them
    /// (`values.rs`); evaluation reads the interpreter immutably, hence the cell.
    values: Option<std::cell::RefCell<super::values::ValueRecord>>,
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
            tainted: Vec::new(),
            runtime_errors: 0,
            recovered: Default::default(),
            skipped_call: false,
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
            rules: Default::default(),
            items: Default::default(),
            modal_cache: None,
            spline_pq: (0.0, 0.0),
            nurbs: Vec::new(),
            motions_drained: 0,
            observed: (0, 0),
            tlo_drift: [0.0; 6],
            feed_override_off: false,
            inv_rate_set: false,
            block_words: Some(Box::default()),
            top_context: None,
            naive_tol: 0.0,
            machine_vars: machine_vars::MachineVars::default(),
            pending_break: false,
            g7x: None,
            resume: None,
            windows: None,
            recover_to: None,
            taint: Default::default(),
            values: None,
        };
        if let Some(n) = bad_origin {
            if it.variant == Variant::Emc2 {
                it.diag(
                    &INTERP,
                    Severity::Error,
                    Span::default(),
                    format!("parameter #5220 is {n}: the start-up coordinate system must be a whole number 1 to 9 (G54 to G59.3); the control faults"),
                );
            }
        }
        if dialect == Dialect::Fanuc {
            it.machine_vars = machine_vars::MachineVars::new(&it.st.params);
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
        unit_of(self.ngc(), self.st.modal.inch)
    }

    /// Millimetres per internal length unit.
    fn lu(&self) -> f64 {
        lu_of(self.ngc(), self.st.modal.inch)
    }

    /// Internal units per parameter/tool-table unit.
    fn pfac(&self) -> f64 {
        pfac_of(&self.cfg, self.ngc(), self.st.modal.inch)
    }

    fn ngc(&self) -> bool {
        self.dialect == Dialect::Rs274ngc
    }

    fn plane_axes(&self) -> (usize, usize) {
        self.st.modal.plane_axes()
    }

    fn normal_axis(&self) -> usize {
        self.st.modal.normal_axis()
    }

    fn file_id(&self) -> FileId {
        self.files.get(self.cur.0).map(|f| f.id).unwrap_or_default()
    }

    fn diag(&mut self, rule: &'static RuleMeta, sev: Severity, span: Span, msg: impl Into<String>) {
        let d = rule.diagnostic(sev, span, msg).in_file(self.file_id());
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

    /// The output of a streamed run, its last motions and events handed to `sink`.
    fn finish_streamed(self, sink: &mut OwnedMotionSink<'_>) -> RunOutput {
        let mut out = self.finish();
        if !out.motions.is_empty() || !out.events.is_empty() {
            sink(&mut out.motions, &mut out.events);
        }
        out.motions = Vec::new();
        out.events = Vec::new();
        out
    }

    fn run_main(&mut self) {
        self.run_main_with(None, None, None);
    }

    /// Shows `observe` the motions and events it has not seen, unless a
    /// compensated move is still pending (it may yet be moved).
    fn observe_new(&mut self, observe: &mut MotionObserver<'_>) {
        if !self.st.comp_queue.is_empty() {
            return;
        }
        let (m, e) = self.observed;
        observe(
            self.out.motions.get(m..).unwrap_or_default(),
            self.out.events.get(e..).unwrap_or_default(),
        );
        self.observed = (self.out.motions.len(), self.out.events.len());
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

    fn run_main_with(
        &mut self,
        mut sink: Option<&mut OwnedMotionSink<'_>>,
        mut observe: Option<&mut MotionObserver<'_>>,
        mut more: Option<&mut windows::NextWindow<'_>>,
    ) {
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
                // A main file read in windows goes on in the next one.
                if fi == 0 && self.frames.is_empty() {
                    if let Some(next) = more.as_deref_mut() {
                        if self.next_window(next) {
                            continue;
                        }
                    }
                }
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
            if super::types::stop_requested(self.steps, self.input.resolver) {
                break;
            }
            if self.steps > budget {
                let span = self.block_span(fi, bi);
                match self.machine_vars.waiting(self.steps) {
                    // A handshake loop (`WHILE [#890 NE 3]`, a dwell, `END`) ends
                    // when the machine or a cell controller sets the variable.
                    Some((var, line)) => self.diag(
                        &STEP_BUDGET,
                        Severity::Info,
                        span,
                        format!("execution stopped after {budget} blocks in a loop that waits for #{var} (tested on line {}), {}: the machine or a cell controller changes it, the dry run cannot; the time from here on is unknown", line + 1, machine_vars::describe(var)),
                    ),
                    None => self.diag(
                        &STEP_BUDGET,
                        Severity::Warning,
                        span,
                        format!("execution stopped after {budget} blocks: the step budget was reached and the rest of the program is not simulated; raise it with --step-budget"),
                    ),
                }
                self.stopped_by_last(fi);
                break;
            }
            let first_motion = self.out.motions.len();
            let mark = self.out.diagnostics.len();
            self.recover_to = None;
            let result = self.exec_block(fi, bi);
            self.check_limits(fi, bi, first_motion);
            let result = self.settle_taint(mark, result, fi, bi);
            let diags_before_budget = self.out.diagnostics.len();
            if self.motion_budget_reached(self.block_span(fi, bi)) {
                if self.out.diagnostics.len() > diags_before_budget {
                    self.stopped_by_last(fi);
                }
                break;
            }
            match result {
                Ok(Flow::Next) => self.cur = (self.cur.0, self.cur.1 + 1),
                Ok(Flow::Goto(f, b)) => self.cur = (f, b),
                Ok(Flow::Stop) => break,
                Err(d) => {
                    if self.canon.is_some() {
                        // rs274 never prints the calls cutter compensation still holds
                        // back when it stops at an error.
                        let held = self.st.comp_queue.first().map(|q| q.canon);
                        if let (Some(first), Some(c)) = (held, self.canon.as_mut()) {
                            c.lines.truncate(first);
                        }
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
                    if !self.after_error(d, fi, bi) {
                        break;
                    }
                    self.cur = (fi, bi + 1);
                }
            }
            if self.st.runtime_errors > 0 && self.error_cap_reached(fi, bi) {
                break;
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
            if self.out.motions.len() >= self.observed.0 + STREAM_CHUNK {
                if let Some(observe) = observe.as_deref_mut() {
                    self.observe_new(observe);
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
            let d = TRAVEL_LIMIT.warning(span, format!("this block moves {letter} outside its travel ({lo} to {hi} in machine coordinates): the control stops with a soft-limit alarm")).in_file(file);
            self.out.diagnostics.push(d);
        }
    }

    fn end_of_file(&mut self) {
        if self.saw_end {
            return;
        }
        let p = self.files[0].prog.clone();
        let end = p.end_offset();
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
                self.out.diagnostics.push(MISSING_END.error(span, msg));
            }
            _ => {
                self.out.diagnostics.push(MISSING_END.warning(span, "program has no end code (M02/M30): the control stops at the end of the file without the end-of-program resets"));
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
        self.fold_repeats();
        self.out.skipped_calls = self.st.skipped_call;
        self.out.values = self.values.take().map(std::cell::RefCell::into_inner);
        self.out
    }

    fn snapshot(&mut self) -> BlockSnapshot {
        // Modal state rarely changes between blocks: reuse the formatted codes.
        let modal = match &self.modal_cache {
            Some((m, codes)) if *m == self.st.modal => codes.clone(),
            _ => {
                let codes: std::sync::Arc<[String]> = self.st.modal.codes(self.ngc()).into();
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

    fn err(&self, rule: &'static RuleMeta, span: Span, msg: impl Into<String>) -> Diagnostic {
        rule.error(span, msg).in_file(self.file_id())
    }
}

/// Internal length units per program unit (see `Interp::unit`); the rule checks
/// share it through `rules::check::Cx`.
pub(crate) fn unit_of(ngc: bool, inch: bool) -> f64 {
    if ngc || !inch {
        1.0
    } else {
        25.4
    }
}

/// Millimetres per internal length unit.
fn lu_of(ngc: bool, inch: bool) -> f64 {
    if ngc && inch {
        25.4
    } else {
        1.0
    }
}

/// Internal units per parameter/tool-table unit.
fn pfac_of(cfg: &MachineCfg, ngc: bool, inch: bool) -> f64 {
    let lu = lu_of(ngc, inch);
    if cfg.param_unit == lu {
        1.0
    } else if lu == 1.0 {
        cfg.param_unit
    } else {
        cfg.param_unit / lu
    }
}

fn scale6(v: [f64; 6], u: f64) -> [f64; 6] {
    v6([v[0] / u, v[1] / u, v[2] / u, v[3], v[4], v[5]])
}

pub(crate) fn dist(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    let l = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
    if l > 0.0 {
        l
    } else {
        ((a[3] - b[3]).powi(2) + (a[4] - b[4]).powi(2) + (a[5] - b[5]).powi(2)).sqrt()
    }
}
