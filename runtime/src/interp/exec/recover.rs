//! Recovery after runtime errors: which errors the dry run goes on after, and how
//! (`Interp::after_error`); the unknown ("tainted") values a failed expression leaves
//! behind (`Taint`); the cap on runtime errors per file; and where a run that does
//! stop stopped (`RunOutput::stopped`).
//!
//! A recovered error is reported once and the run goes on with the next block, so a
//! program with five faults shows five diagnostics. Errors after which the state is
//! not defined (broken flow, alarms, compensation, anything not listed in
//! [`recoverable`]) stop the run, and their message says so. Canonical output
//! (`--emit canon`) imitates rs274 and always stops at the first error.

use std::cell::{Cell, RefCell};

use super::*;
use crate::rules::{
    arc_no_center::ARC_NO_CENTER, arc_radius_mismatch::ARC_RADIUS_MISMATCH,
    arc_radius_too_small::ARC_RADIUS_TOO_SMALL, arc_same_end_r::ARC_SAME_END_R,
    arc_words::ARC_WORDS, cycle_missing::CYCLE_MISSING, cycle_q::CYCLE_Q, expression::EXPRESSION,
    interp::INTERP, step_budget::STEP_BUDGET, sub_not_found::SUB_NOT_FOUND,
    unknown_code::UNKNOWN_CODE, zero_feed::ZERO_FEED,
};

/// What a recoverable error leaves the position at.
#[derive(Debug, Clone, Copy)]
pub(super) enum Recover {
    /// A straight feed move to the programmed end point (an arc whose end is off
    /// its circle: the control would have gone there).
    Feed([f64; 6]),
    /// The position is set to the programmed end point without a motion (an arc
    /// without a centre, a canned cycle without its levels, a feed move without F).
    SetPos([f64; 6]),
}

/// The errors the dry run recovers from: the rest of the block is skipped, and the
/// position goes where `Interp::recover_to` says (set by the failing step) or stays.
/// Each rule's doc says how ("After this error the dry run continues as if …");
/// every other error stops the run.
fn recoverable(code: &str) -> bool {
    [
        &ARC_RADIUS_MISMATCH,
        &ARC_RADIUS_TOO_SMALL,
        &ARC_NO_CENTER,
        &ARC_SAME_END_R,
        &ARC_WORDS,
        &CYCLE_MISSING,
        &CYCLE_Q,
        &ZERO_FEED,
        &SUB_NOT_FOUND,
        &EXPRESSION,
        &UNKNOWN_CODE,
    ]
    .iter()
    .any(|r| r.code == code)
}

/// Said at the end of the message of an error that stops the run.
pub const STOP_SUFFIX: &str = analyzer::twins::STOP_SUFFIX;

/// Per-block memory of failed expressions and of reads of tainted parameters.
#[derive(Default)]
pub(super) struct Taint {
    /// The last evaluation read a tainted parameter or failed.
    pub(super) last: Cell<bool>,
    /// Some evaluation of this block did.
    pub(super) block: Cell<bool>,
    /// The errors and notes of this block, reported after its other diagnostics
    /// are dropped (they would be consequences of the unknown value).
    pub(super) pending: RefCell<Vec<Diagnostic>>,
}

impl Interp<'_, '_> {
    /// Whether failed expressions yield an unknown value instead of stopping: always,
    /// except for canonical output, which stops where rs274 stops.
    pub(super) fn recovering(&self) -> bool {
        self.canon.is_none()
    }

    /// An expression error in recovering mode: reported (once, with the block's
    /// other errors dropped; not at all when it follows from an unknown value),
    /// and the value is unknown, read as 0.
    pub(super) fn taint_failed(&self, d: Option<Diagnostic>) -> Val {
        self.taint.pending.borrow_mut().extend(d);
        self.taint.last.set(true);
        self.taint.block.set(true);
        Some(0.0)
    }

    /// Records whether the parameter `key` now holds an unknown value.
    pub(super) fn mark_taint(&mut self, key: impl FnOnce() -> String, tainted: bool) {
        if tainted {
            let key = key();
            if !self.st.tainted.contains(&key) {
                self.st.tainted.push(key);
            }
        } else if !self.st.tainted.is_empty() {
            let key = key();
            self.st.tainted.retain(|k| *k != key);
        }
    }

    /// After a condition was evaluated: an Info note when it read an unknown value,
    /// since the branch taken then decides what the rest of the run means.
    pub(super) fn note_tainted_branch(&self, span: Span) {
        if !self.taint.last.get() {
            return;
        }
        let d = EXPRESSION.diagnostic(
            Severity::Info,
            span,
            "this condition reads a value an earlier error left unknown (taken as 0): the branch the dry run takes may not be the one the control takes",
        )
        .in_file(self.file_id());
        self.taint.pending.borrow_mut().push(d);
    }

    /// After a block that evaluated a failed or tainted expression: its other
    /// diagnostics (from `mark` on) are consequences of the unknown value and are
    /// dropped, its own errors and notes are reported, and an error it returned is
    /// one of those consequences too, so the run goes on.
    pub(super) fn settle_taint(
        &mut self,
        mark: usize,
        result: Result<Flow, Diagnostic>,
        fi: usize,
        bi: u32,
    ) -> Result<Flow, Diagnostic> {
        if !self.taint.block.replace(false) {
            return result;
        }
        let pending = std::mem::take(&mut *self.taint.pending.borrow_mut());
        self.out
            .diagnostics
            .truncate(mark.min(self.out.diagnostics.len()));
        for d in pending {
            if d.severity == Severity::Error {
                self.st.runtime_errors = self.st.runtime_errors.saturating_add(1);
            }
            self.out.diagnostics.push(d);
        }
        match result {
            Err(_) if self.can_recover(fi, bi) => Ok(Flow::Next),
            r => r,
        }
    }

    /// Whether the state after an error in block `bi` of file `fi` allows going on.
    fn can_recover(&self, fi: usize, bi: u32) -> bool {
        // Recovery needs a block that ran where the loop put it (a G7x profile runs
        // blocks of its own) and no compensated move held back, whose corner the
        // skipped block would have decided.
        self.recovering()
            && self.cur == (fi, bi)
            && self.g7x.is_none()
            && self.st.modal.comp == 400
            && self.st.comp_queue.is_empty()
    }

    /// An error came out of block `bi` of file `fi`. Reports it, and either recovers
    /// (true: the run goes on with the next block) or stops the run (false).
    pub(super) fn after_error(&mut self, mut d: Diagnostic, fi: usize, bi: u32) -> bool {
        let recover = self.recover_to.take();
        if !(recoverable(d.code) && self.can_recover(fi, bi)) {
            self.stop_with(&mut d, fi);
            self.out.diagnostics.push(d);
            return false;
        }
        // A repeat (same file, code and message) of a recovered error or warning,
        // such as a skipped call, is folded into its first report.
        let key = (d.file, d.code, d.message.clone());
        if let Some(r) = Arc::make_mut(&mut self.st.recovered).get_mut(&key) {
            // The same fault again: folded into the first report (at finish).
            r.count = r.count.saturating_add(1);
            if r.spans.len() < MAX_REPEAT_LOCATIONS {
                r.spans.push((d.file, d.span));
            }
            self.recover_position(recover);
            return true;
        }
        let index = self.out.diagnostics.len();
        Arc::make_mut(&mut self.st.recovered).insert(
            key,
            crate::interp::state::Repeated {
                index,
                count: 0,
                spans: Vec::new(),
            },
        );
        if d.severity == Severity::Error {
            self.st.runtime_errors = self.st.runtime_errors.saturating_add(1);
        }
        self.out.diagnostics.push(d);
        self.recover_position(recover);
        true
    }

    fn recover_position(&mut self, recover: Option<Recover>) {
        match recover {
            Some(Recover::Feed(t)) => self.recover_feed(t),
            Some(Recover::SetPos(t)) => self.set_position(t),
            None => {}
        }
    }

    /// One fault, one diagnostic: writes the repeats of each recovered error
    /// (same code and message on a later block: every feed move of a program
    /// without F) into its first report, as a count and related locations.
    /// Done from the state at the end, so a resumed rerun writes them afresh.
    pub(super) fn fold_repeats(&mut self) {
        for r in self.st.recovered.values().filter(|r| r.count > 0) {
            let Some(d) = self.out.diagnostics.get_mut(r.index) else {
                continue;
            };
            d.related.retain(|x| x.message != REPEAT_NOTE);
            d.related.extend(
                r.spans
                    .iter()
                    .map(|&(file, span)| analyzer::diagnostic::Related {
                        file,
                        span,
                        message: REPEAT_NOTE.into(),
                    }),
            );
            let base = d
                .message
                .split(REPEAT_SUFFIX)
                .next()
                .unwrap_or_default()
                .to_string();
            let n = r.count;
            d.message = format!(
                "{base}{REPEAT_SUFFIX}{n} later block{})",
                if n == 1 { "" } else { "s" }
            );
        }
    }

    /// Marks the run stopped by `d` and says so in its message.
    fn stop_with(&mut self, d: &mut Diagnostic, fi: usize) {
        if self.out.stopped.is_none() {
            self.out.stopped = Some(Stopped {
                file: self.files.get(fi).map(|f| f.id).unwrap_or_default(),
                span: d.span,
                line: self.cur_line,
                code: d.code,
                reason: without_line_prefix(&d.message, self.cur_line).to_string(),
            });
        }
        // The budgets' messages say already that execution stopped.
        if d.code != STEP_BUDGET.code && !d.message.ends_with(STOP_SUFFIX) {
            d.message.push_str(STOP_SUFFIX);
        }
    }

    /// Marks the run stopped by the diagnostic just pushed (a budget).
    pub(super) fn stopped_by_last(&mut self, fi: usize) {
        if self.out.stopped.is_some() {
            return;
        }
        if let Some(mut d) = self.out.diagnostics.pop() {
            self.stop_with(&mut d, fi);
            self.out.diagnostics.push(d);
        }
    }

    /// Marks the run stopped at block `bi` of file `fi` for `reason` (a block the
    /// control cannot read: the parser's diagnostic says why).
    pub(super) fn stopped_at_block(&mut self, fi: usize, bi: u32, reason: &str) {
        if self.out.stopped.is_none() {
            let span = self.block_span(fi, bi);
            self.out.stopped = Some(Stopped {
                file: self.files.get(fi).map(|f| f.id).unwrap_or_default(),
                span,
                line: self.cur_line,
                code: INTERP.code,
                reason: reason.to_string(),
            });
        }
    }

    /// Whether the cap on runtime errors per file is reached; the first time, says
    /// so (F004) and marks the run stopped.
    pub(super) fn error_cap_reached(&mut self, fi: usize, bi: u32) -> bool {
        let cap = self.input.settings.max_runtime_errors.max(1);
        if (self.st.runtime_errors as usize) < cap {
            return false;
        }
        let span = self.block_span(fi, bi);
        self.diag(
            &STEP_BUDGET,
            Severity::Warning,
            span,
            format!("execution stopped after {cap} runtime errors: the rest of the program is not simulated and its faults are not reported; raise the limit with --max-runtime-errors"),
        );
        self.stopped_by_last(fi);
        true
    }

    /// The position after a skipped motion block: its programmed end point.
    fn set_position(&mut self, t: [f64; 6]) {
        self.st.mpos = self.to_machine(t);
        self.st.pos = t;
    }

    /// A straight feed move to `t` in place of an arc that could not be made, or,
    /// without a feed rate, the position set there (a zero feed would be reported
    /// again).
    fn recover_feed(&mut self, t: [f64; 6]) {
        if self.st.feed <= 0.0 {
            self.set_position(t);
            return;
        }
        let end = self.to_machine(t);
        let feed = self.effective_feed(dist(&self.st.mpos, &end));
        let m = self.motion_base(MotionKind::Feed, self.st.mpos, end, feed);
        self.out.motions.push(m);
        self.st.mpos = end;
        self.st.pos = t;
    }
}

/// Repeats of a recovered error kept as related locations of the first report.
const MAX_REPEAT_LOCATIONS: usize = 20;
const REPEAT_NOTE: &str = "the same fault again";
const REPEAT_SUFFIX: &str = " (the same fault on ";

/// `reason` without rs274's leading "N: " when N is the stop's own (0-based
/// `line` + 1) line: the stop names its line already.
fn without_line_prefix(reason: &str, line: u32) -> &str {
    let prefix = format!("{}: ", line + 1);
    reason.strip_prefix(prefix.as_str()).unwrap_or(reason)
}
