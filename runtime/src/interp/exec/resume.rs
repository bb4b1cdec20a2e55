//! Re-running an edited program from a checkpoint (the language server's
//! incremental dry run).
//!
//! A run made with [`run_checkpointed`] records the complete interpreter
//! state every [`EVERY`] blocks of the main file. [`rerun`] takes that output
//! and the edited program: it restores the last checkpoint before the edit,
//! runs from there, and at each checkpoint position after the edit compares
//! its state with the previous run's state at the same (shifted) block. When
//! they are equal the rest of the run would repeat the previous one, so it
//! stops and takes the previous run's later motions, events, snapshots,
//! diagnostics and checkpoints, shifted by the edit.
//!
//! That argument holds only when the blocks after the checkpoint never run
//! code before it again, so checkpoints are recorded only for *single-pass*
//! programs: no subprogram calls or definitions, no O-word or macro flow
//! control, no M98/M99/G65/G66 (the bulk of CAM output). Anything else, and
//! any change of the inputs besides the program text, falls back to a full run.

use std::cell::RefCell;
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use super::*;
use crate::interp::values::{ValueLimits, ValueRecord};

/// Main-file blocks between checkpoints: a rerun re-executes about this many
/// blocks before and after an edit.
pub(super) const EVERY: u32 = 2048;

/// What a checkpointed run keeps for [`rerun`]. Opaque; empty for runs made
/// without checkpoints.
#[derive(Debug, Clone, Default)]
pub struct Checkpoints {
    /// Hash of every input except the program text.
    key: u64,
    /// The text the run was made on.
    text: Option<Arc<[u8]>>,
    nblocks: usize,
    points: Vec<Checkpoint>,
    /// Blocks this run executed (a rerun executes only those around the edit).
    executed: u64,
}

impl Checkpoints {
    /// How many checkpoints the run recorded.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    pub(super) fn set_executed(&mut self, n: u64) {
        self.executed = n;
    }

    /// Blocks the run executed: all of them for a full run, those between the
    /// restart checkpoint and the meeting point for a rerun.
    pub fn executed(&self) -> u64 {
        self.executed
    }
}

/// The interpreter's state before executing main-file block `block`.
#[derive(Debug, Clone)]
pub(super) struct Checkpoint {
    block: u32,
    /// Byte offset and line of that block.
    start: u32,
    line: u32,
    motions: usize,
    events: usize,
    diags: usize,
    steps: u64,
    seen_content: bool,
    st: State,
    cur_line: u32,
    percent_open: bool,
    saw_end: bool,
    after_end_reported: bool,
    main_locals: HashMap<String, f64>,
    limit_reports: u32,
    block_exact: bool,
    rules: crate::rules::check::Memory,
    items: crate::rules::check::BlockItems,
    spline_pq: (f64, f64),
    tlo_drift: [f64; 6],
    feed_override_off: bool,
    inv_rate_set: bool,
    top_context: Option<context::SavedContext>,
    naive_tol: f64,
    machine_vars: machine_vars::MachineVars,
    pending_break: bool,
    cfg: MachineCfg,
}

/// How positions move from the previous run to this one after the edit.
#[derive(Debug, Clone, Copy)]
struct Shift {
    blocks: i64,
    bytes: i64,
    lines: i64,
    /// Motions, counted from the start of the run.
    motions: i64,
}

fn add(v: u32, d: i64) -> u32 {
    (i64::from(v) + d).clamp(0, i64::from(u32::MAX)) as u32
}

fn shift_span(s: Span, d: i64) -> Span {
    Span::new(add(s.start, d), add(s.end, d))
}

impl Checkpoint {
    /// The same state with its positions moved by `d` (motion and diagnostic
    /// counts move separately).
    fn shifted(&self, d: Shift) -> Checkpoint {
        let mut c = self.clone();
        c.block = add(c.block, d.blocks);
        c.start = add(c.start, d.bytes);
        c.line = add(c.line, d.lines);
        c.steps = (c.steps as i64 + d.blocks).max(0) as u64;
        c.st.line = add(c.st.line, d.lines);
        c.cur_line = add(c.cur_line, d.lines);
        c.rules.shift_spans(|s| shift_span(s, d.bytes));
        c.items.shift_spans(|s| shift_span(s, d.bytes));
        c.motions = (c.motions as i64 + d.motions).max(0) as usize;
        c.rules.shift_motion_count(d.motions);
        c
    }

    /// Whether two checkpoints hold the same interpreter state (positions
    /// already shifted onto the same text).
    fn same_state(&self, o: &Checkpoint) -> bool {
        let params_same =
            Arc::ptr_eq(&self.st.params, &o.st.params) || self.st.params == o.st.params;
        let named_same = Arc::ptr_eq(&self.st.named, &o.st.named) || self.st.named == o.st.named;
        params_same
            && named_same
            && State {
                params: o.st.params.clone(),
                named: o.st.named.clone(),
                ..self.st.clone()
            } == o.st
            && self.seen_content == o.seen_content
            && self.cur_line == o.cur_line
            && self.percent_open == o.percent_open
            && self.saw_end == o.saw_end
            && self.after_end_reported == o.after_end_reported
            && self.main_locals == o.main_locals
            && self.limit_reports == o.limit_reports
            && self.block_exact == o.block_exact
            && self.rules == o.rules
            && self.items == o.items
            && self.spline_pq == o.spline_pq
            && self.tlo_drift == o.tlo_drift
            && self.feed_override_off == o.feed_override_off
            && self.inv_rate_set == o.inv_rate_set
            && self.top_context == o.top_context
            && self.naive_tol == o.naive_tol
            && self.machine_vars == o.machine_vars
            && self.pending_break == o.pending_break
            && self.cfg == o.cfg
    }
}

/// Hash of the inputs a run depends on besides the program text.
fn input_key(input: &RunInput<'_>, snapshots: bool) -> u64 {
    let mut h = DefaultHasher::new();
    format!("{:?}", input.settings).hash(&mut h);
    format!("{:?}", input.machine).hash(&mut h);
    input.tool_table.hash(&mut h);
    input.var_file.hash(&mut h);
    input.step_budget.hash(&mut h);
    input.emit_canon.hash(&mut h);
    snapshots.hash(&mut h);
    h.finish()
}

/// Whether every block of `p` runs at most once, in order: no flow control,
/// no calls, at most one program head.
fn single_pass(p: &Program) -> bool {
    let (flow, heads) = flow_and_heads(p);
    !flow && heads <= 1
}

/// Whether `p` holds flow control or a call (a computed G or M code could be
/// one), and how many program heads.
pub(super) fn flow_and_heads(p: &Program) -> (bool, u32) {
    let mut heads = 0;
    for it in &p.items {
        match &it.kind {
            ItemKind::OWord(_) | ItemKind::Macro(_) => return (true, heads),
            ItemKind::ProgramHead { .. } => heads += 1,
            ItemKind::Word(w) => {
                let v = w.num().map(|n| n.value);
                let calls = match w.letter {
                    b'M' => matches!(v, Some(x) if x == 98.0 || x == 99.0 || x == 198.0),
                    b'G' => matches!(v, Some(x) if x == 65.0 || x == 66.0 || x == 66.1),
                    _ => false,
                };
                let computed = matches!(w.value, analyzer::syntax::WordValue::Expr(_));
                if calls || (matches!(w.letter, b'M' | b'G') && computed) {
                    return (true, heads);
                }
            }
            _ => {}
        }
    }
    (false, heads)
}

/// Whether a run of `input` can record checkpoints.
fn eligible(input: &RunInput<'_>) -> bool {
    let p = input.program;
    !input.emit_canon
        && (p.blocks.len() as u64).saturating_mul(2) < input.step_budget
        && single_pass(p)
}

/// Like [`run_with_snapshots`], and records checkpoints for [`rerun`] when
/// the program is single-pass.
pub fn run_checkpointed(input: &RunInput<'_>, snapshots: bool) -> RunOutput {
    run_checkpointed_recording(input, snapshots, None)
}

/// Like [`run_checkpointed`]; with `values` it also records the values of the
/// main file's expressions within those limits ([`RunOutput::values`]), and a
/// [`rerun`] of its output records them again.
pub fn run_checkpointed_recording(
    input: &RunInput<'_>,
    snapshots: bool,
    values: Option<ValueLimits>,
) -> RunOutput {
    checkpointed(input, snapshots, values, None)
}

/// [`run_checkpointed_recording`] that shows `observe` the motions and events
/// as the run makes them ([`MotionObserver`]); they stay in the output.
pub fn run_checkpointed_observed(
    input: &RunInput<'_>,
    snapshots: bool,
    values: Option<ValueLimits>,
    observe: &mut MotionObserver<'_>,
) -> RunOutput {
    checkpointed(input, snapshots, values, Some(observe))
}

fn checkpointed(
    input: &RunInput<'_>,
    snapshots: bool,
    values: Option<ValueLimits>,
    mut observe: Option<&mut MotionObserver<'_>>,
) -> RunOutput {
    let mut it = Interp::new(input, snapshots);
    // The motions stay in the output: room for one per block up front. Grown
    // by doubling instead, the copies pass through sizes the allocator keeps
    // in its heap and leave holes there (tens of MB on a million blocks).
    it.out.motions.reserve(
        input
            .program
            .blocks
            .len()
            .min(crate::dryrun::RESERVED_MOTIONS),
    );
    it.values = values.map(|l| RefCell::new(ValueRecord::new(l)));
    if eligible(input) {
        it.rules.rapid_no_motion.single_pass = true;
        it.out.checkpoints = Checkpoints {
            key: input_key(input, snapshots),
            text: Some(input.program.text.clone()),
            nblocks: input.program.blocks.len(),
            points: Vec::new(),
            executed: 0,
        };
        it.resume = Some(Resume::default());
    }
    it.run_main_with(None, observe.as_deref_mut(), None);
    let (m, e) = it.observed;
    let out = it.finish();
    // The run is over: what a pending compensated move held back is final.
    if let Some(observe) = observe {
        observe(
            out.motions.get(m..).unwrap_or_default(),
            out.events.get(e..).unwrap_or_default(),
        );
    }
    out
}

/// Runs `input` (an edited program) reusing `prev`, the output of a
/// checkpointed run of its previous version with the same other inputs. The
/// result equals `run_checkpointed(input, snapshots)` (recording values within
/// the same limits when `prev` recorded them).
pub fn rerun(input: &RunInput<'_>, snapshots: bool, prev: RunOutput) -> RunOutput {
    let values = prev.values.as_ref().map(ValueRecord::limits);
    match plan_rerun(input, snapshots, &prev) {
        Some(plan) => resume_from(input, snapshots, prev, plan),
        None => run_checkpointed_recording(input, snapshots, values),
    }
}

/// Where a rerun restarts and what the edit moved.
struct Plan {
    /// Index of the checkpoint to restart from.
    checkpoint: usize,
    /// Block and byte shift for blocks after the edit (lines are measured at
    /// the checkpoint where the runs meet).
    shift: Shift,
    /// First block of the new text that is the old text's block, shifted
    /// (with one block of margin).
    after_edit: u32,
}

/// The plan of a rerun; `None` when only a full run will do.
fn plan_rerun(input: &RunInput<'_>, snapshots: bool, prev: &RunOutput) -> Option<Plan> {
    let cps = &prev.checkpoints;
    let old_text = cps.text.as_ref()?;
    if cps.points.is_empty() || cps.key != input_key(input, snapshots) || !eligible(input) {
        return None;
    }
    // A value record that reached its limits may have left out blocks the
    // edited program would record: only a full run knows.
    if prev.values.as_ref().is_some_and(|v| v.truncated) {
        return None;
    }
    let p = input.program;
    let edit = analyzer::incremental::diff(old_text, &p.text)?;
    // The block before the edited one may change too (its terminator looks
    // ahead), so restart no later than that block.
    let first_changed = p.block_at(edit.start as u32).unwrap_or(0).saturating_sub(1) as u32;
    let checkpoint = cps.points.iter().rposition(|c| c.block <= first_changed)?;
    // The block holding the edit's end may end after it: one block of margin.
    let after = p
        .blocks
        .partition_point(|b| (b.span.start as usize) < edit.new_end)
        .saturating_add(1)
        .min(p.blocks.len()) as u32;
    Some(Plan {
        checkpoint,
        shift: Shift {
            blocks: p.blocks.len() as i64 - cps.nblocks as i64,
            bytes: edit.new_end as i64 - edit.old_end as i64,
            lines: 0,
            motions: 0,
        },
        after_edit: after.max(first_changed),
    })
}

/// Rerun bookkeeping inside the interpreter.
#[derive(Debug, Default)]
pub(super) struct Resume {
    /// What is left of the previous run, until the runs meet.
    prev: Option<Prev>,
    /// The next block where a checkpoint is due.
    next_at: u32,
    /// In a rerun: the interpreter was restored, not started afresh.
    pub(super) restored: bool,
    /// The step count the run started from.
    pub(super) start_steps: u64,
}

#[derive(Debug)]
struct Prev {
    /// The previous run's checkpoints after the restart point.
    points: Vec<Checkpoint>,
    /// The previous run's output from the restart checkpoint on.
    motions: Vec<Motion>,
    events: Vec<Event>,
    diags: Vec<Diagnostic>,
    snapshots: Vec<Option<BlockSnapshot>>,
    values: Option<ValueRecord>,
    /// Output counts and block of the restart checkpoint (previous run).
    base: (usize, usize, usize, u32),
    shift: Shift,
    after_edit: u32,
}

impl Prev {
    /// Whether block `bi` (new numbering) is where the previous run has its
    /// next checkpoint after the edit; drops the previous checkpoints that
    /// can no longer be met.
    fn compare_at(&mut self, bi: u32) -> bool {
        if bi < self.after_edit {
            return false;
        }
        let moved = |c: &Checkpoint| i64::from(c.block) + self.shift.blocks;
        let passed = self
            .points
            .iter()
            .take_while(|c| moved(c) < i64::from(bi))
            .count();
        if passed > 0 {
            self.points.drain(..passed);
        }
        self.points
            .first()
            .is_some_and(|c| moved(c) == i64::from(bi))
    }
}

fn resume_from(input: &RunInput<'_>, snapshots: bool, prev: RunOutput, plan: Plan) -> RunOutput {
    let RunOutput {
        mut diagnostics,
        mut motions,
        mut events,
        snapshots: mut snaps,
        checkpoints,
        mut values,
        ..
    } = prev;
    let Checkpoints {
        key, mut points, ..
    } = checkpoints;
    let later = points.split_off(plan.checkpoint + 1);
    let Some(start) = points.last().cloned() else {
        let limits = values.as_ref().map(ValueRecord::limits);
        return run_checkpointed_recording(input, snapshots, limits);
    };
    let tail_v = values.as_mut().map(|v| v.split_off(start.block));
    let p = input.program;
    let base = (start.motions, start.events, start.diags, start.block);
    let tail_m = motions.split_off(start.motions.min(motions.len()));
    let tail_e = events.split_off(start.events.min(events.len()));
    let tail_d = diagnostics.split_off(start.diags.min(diagnostics.len()));
    let tail_s = snaps.split_off((start.block as usize).min(snaps.len()));
    let mut it = Interp::new(input, snapshots);
    it.rules.rapid_no_motion.single_pass = true;
    it.restore(&start);
    it.values = values.map(RefCell::new);
    it.out.diagnostics = diagnostics;
    it.out.motions = motions;
    it.out.events = events;
    if snapshots {
        snaps.resize(p.blocks.len(), None);
        it.out.snapshots = snaps;
    }
    it.out.checkpoints = Checkpoints {
        key,
        text: Some(p.text.clone()),
        nblocks: p.blocks.len(),
        points,
        executed: 0,
    };
    it.resume = Some(Resume {
        prev: Some(Prev {
            points: later,
            motions: tail_m,
            events: tail_e,
            diags: tail_d,
            snapshots: tail_s,
            values: tail_v,
            base,
            shift: plan.shift,
            after_edit: plan.after_edit,
        }),
        // The restart block is a checkpoint already.
        next_at: start.block.saturating_add(1),
        restored: true,
        start_steps: start.steps,
    });
    it.cur = (0, start.block);
    it.run_main();
    it.finish()
}

impl Interp<'_, '_> {
    fn capture(&self, bi: u32) -> Checkpoint {
        let p = &self.files[0].prog;
        let (start, line) = p
            .blocks
            .get(bi as usize)
            .map_or((p.text.len() as u32, 0), |b| (b.span.start, b.line));
        Checkpoint {
            block: bi,
            start,
            line,
            motions: self.out.motions.len(),
            events: self.out.events.len(),
            diags: self.out.diagnostics.len(),
            steps: self.steps,
            seen_content: self.seen_content_before(p, bi),
            st: self.st.clone(),
            cur_line: self.cur_line,
            percent_open: self.percent_open,
            saw_end: self.saw_end,
            after_end_reported: self.after_end_reported,
            main_locals: self.main_locals.clone(),
            limit_reports: self.limit_reports,
            block_exact: self.block_exact,
            rules: self.rules.clone(),
            items: self.items.clone(),
            spline_pq: self.spline_pq,
            tlo_drift: self.tlo_drift,
            feed_override_off: self.feed_override_off,
            inv_rate_set: self.inv_rate_set,
            top_context: self.top_context.clone(),
            naive_tol: self.naive_tol,
            machine_vars: self.machine_vars.clone(),
            pending_break: self.pending_break,
            cfg: self.cfg.clone(),
        }
    }

    fn restore(&mut self, c: &Checkpoint) {
        self.steps = c.steps;
        self.st = c.st.clone();
        self.cur_line = c.cur_line;
        self.percent_open = c.percent_open;
        self.saw_end = c.saw_end;
        self.after_end_reported = c.after_end_reported;
        self.main_locals = c.main_locals.clone();
        self.limit_reports = c.limit_reports;
        self.block_exact = c.block_exact;
        self.rules = c.rules.clone();
        self.items = c.items.clone();
        self.spline_pq = c.spline_pq;
        self.tlo_drift = c.tlo_drift;
        self.feed_override_off = c.feed_override_off;
        self.inv_rate_set = c.inv_rate_set;
        self.top_context = c.top_context.clone();
        self.naive_tol = c.naive_tol;
        self.machine_vars = c.machine_vars.clone();
        self.pending_break = c.pending_break;
        self.cfg = c.cfg.clone();
    }

    /// Called at the top of the main loop before block `bi` of file `fi` runs.
    /// Records a checkpoint when one is due; in a rerun, returns true when the
    /// state has met the previous run's again and the output is complete.
    pub(super) fn resume_point(&mut self, fi: usize, bi: u32) -> bool {
        let Some(r) = self.resume.as_mut() else {
            return false;
        };
        if fi != 0 {
            return false;
        }
        let record = bi >= r.next_at;
        let compare = r.prev.as_mut().is_some_and(|p| p.compare_at(bi));
        if !(record || compare)
            || !self.frames.is_empty()
            || !self.repeats.is_empty()
            || !self.st.comp_queue.is_empty()
            || !self.nurbs.is_empty()
            || self.motions_drained != 0
        {
            return false;
        }
        let cp = self.capture(bi);
        if compare && self.try_converge(&cp) {
            return true;
        }
        if let Some(r) = self.resume.as_mut() {
            r.next_at = bi.saturating_add(EVERY);
        }
        self.out.checkpoints.points.push(cp);
        false
    }

    /// Compares the state at `cp` with the previous run's checkpoint at the
    /// same block; on a match, completes the output from the previous run.
    fn try_converge(&mut self, cp: &Checkpoint) -> bool {
        let Some(prev) = self.resume.as_mut().and_then(|r| r.prev.as_mut()) else {
            return false;
        };
        let Some(old) = prev.points.first() else {
            return false;
        };
        let d = Shift {
            blocks: prev.shift.blocks,
            bytes: i64::from(cp.start) - i64::from(old.start),
            lines: i64::from(cp.line) - i64::from(old.line),
            motions: cp.motions as i64 - old.motions as i64,
        };
        // Past the edit every byte moved by the same amount.
        if d.bytes != prev.shift.bytes || add(old.block, d.blocks) != cp.block {
            return false;
        }
        if !cp.same_state(&old.shifted(d)) {
            return false;
        }
        let Some(prev) = self.resume.as_mut().and_then(|r| r.prev.take()) else {
            return false;
        };
        self.splice_previous(prev, cp, d);
        true
    }

    /// Appends the previous run's output from checkpoint `prev.points[0]` on,
    /// moved by `d`, after this run's output up to `cp`.
    fn splice_previous(&mut self, prev: Prev, cp: &Checkpoint, d: Shift) {
        let Prev {
            points,
            motions,
            events,
            diags,
            snapshots,
            values,
            base,
            ..
        } = prev;
        let Some(old) = points.first() else {
            return;
        };
        if let (Some(rec), Some(tail)) = (self.values.as_mut(), values) {
            rec.get_mut().splice(tail, old.block, d.blocks);
        }
        let (bm, be, bd, bb) = base;
        let motion_delta = d.motions;
        let moved_line = |l: u32| add(l, d.lines);
        self.out.motions.extend(
            motions
                .into_iter()
                .skip(old.motions.saturating_sub(bm))
                .map(|mut m| {
                    if m.file == FileId(0) {
                        m.block = add(m.block, d.blocks);
                        m.line = moved_line(m.line);
                    }
                    m
                }),
        );
        self.out
            .events
            .extend(
                events
                    .into_iter()
                    .skip(old.events.saturating_sub(be))
                    .map(|mut e| {
                        e.motion_index = (e.motion_index as i64 + motion_delta).max(0) as usize;
                        if e.file == FileId(0) {
                            e.block = add(e.block, d.blocks);
                            e.line = moved_line(e.line);
                        }
                        e
                    }),
            );
        self.out
            .diagnostics
            .extend(
                diags
                    .into_iter()
                    .skip(old.diags.saturating_sub(bd))
                    .map(|mut x| {
                        if x.file == FileId(0) {
                            x.span = shift_span(x.span, d.bytes);
                        }
                        for r in &mut x.related {
                            if r.file == FileId(0) {
                                r.span = shift_span(r.span, d.bytes);
                            }
                        }
                        for f in &mut x.fixes {
                            for e in &mut f.edits {
                                e.span = shift_span(e.span, d.bytes);
                            }
                        }
                        x
                    }),
            );
        if !self.out.snapshots.is_empty() {
            self.out.snapshots.truncate(cp.block as usize);
            self.out.snapshots.extend(
                snapshots
                    .into_iter()
                    .skip(old.block.saturating_sub(bb) as usize),
            );
            let n = self.files[0].prog.blocks.len();
            self.out.snapshots.resize(n, None);
        }
        self.out.checkpoints.points.extend(points.iter().map(|c| {
            let mut s = c.shifted(d);
            s.events = (c.events as i64 - old.events as i64 + cp.events as i64).max(0) as usize;
            s.diags = (c.diags as i64 - old.diags as i64 + cp.diags as i64).max(0) as usize;
            s
        }));
    }
}
