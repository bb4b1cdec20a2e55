//! Running a main file read in windows (a host's check of a file too large
//! to hold): when the interpreter runs out of one window's blocks it asks
//! for the next and goes on with the same state, as if the blocks had been
//! one program. Only a *single-pass* file can run so: one whose blocks run
//! once each, in order ([`FileFacts::single_pass`]), since nothing else looks
//! back at blocks already dropped.

use super::*;

/// What the interpreter needs to know about the whole main file before it
/// runs the first window; [`FileFacts::add`] reads each window in order.
#[derive(Debug, Clone, Copy, Default)]
pub struct FileFacts {
    flow: bool,
    heads: u32,
    /// A tapping cycle anywhere makes M29 the rigid-tapping code ([`FileEntry::taps`]).
    taps: bool,
}

impl FileFacts {
    /// Reads one window of the file.
    pub fn add(&mut self, window: &Program) {
        let (flow, heads) = resume::flow_and_heads(window);
        self.flow |= flow;
        self.heads += heads;
        self.taps |= window.items.iter().any(|it| {
            matches!(&it.kind, analyzer::syntax::ItemKind::Word(w) if super::super::files::is_tapping_cycle(w))
        });
    }

    /// Whether every block runs at most once, in order: no flow control, no
    /// calls, at most one program head. Only such a file can run in windows.
    pub fn single_pass(&self) -> bool {
        !self.flow && self.heads <= 1
    }
}

/// The next window of the main file, or `None` after the last.
pub type NextWindow<'s> = dyn FnMut() -> Option<Arc<Program>> + 's;

/// [`run_streaming`] of a single-pass main file read in windows:
/// `input.program` is the first window, `next` gives the others in order and
/// `facts` holds what [`FileFacts::add`] read from all of them. The step and
/// motion budgets of `input` are the whole file's.
pub fn run_windowed(
    input: &RunInput<'_>,
    facts: &FileFacts,
    next: &mut NextWindow<'_>,
    sink: &mut MotionSink<'_>,
) -> RunOutput {
    run_windowed_owned(input, facts, next, &mut |m, e| sink(m, e))
}

/// [`run_windowed`] handing over the buffers themselves ([`OwnedMotionSink`]).
pub fn run_windowed_owned(
    input: &RunInput<'_>,
    facts: &FileFacts,
    next: &mut NextWindow<'_>,
    sink: &mut OwnedMotionSink<'_>,
) -> RunOutput {
    let mut it = Interp::new(input, false);
    // A single-pass file has no M99, so it never `returns`.
    it.files[0].taps = facts.taps;
    it.windows = Some(*facts);
    // Block indices restart in every window: only a single-pass file runs in
    // windows, and for it the rule keeps no per-block memory.
    it.rules.rapid_no_motion.single_pass = true;
    it.run_main_with(Some(sink), None, Some(next));
    it.finish_streamed(sink)
}

impl Interp<'_, '_> {
    /// Moves on to the next window of the main file, if there is one.
    pub(super) fn next_window(&mut self, next: &mut NextWindow<'_>) -> bool {
        let Some(facts) = self.windows else {
            return false;
        };
        let Some(window) = next() else {
            return false;
        };
        let mut entry = FileEntry::new(ProgRef::Shared(window), FileId(0));
        entry.taps = facts.taps;
        self.files[0] = entry;
        self.cur = (0, 0);
        true
    }
}

/// The finding for a main file read in windows that is not single-pass: its
/// dry run is not made (F004, the run's memory budget). `size_mb` is the
/// file's size, `limit_mb` the largest file a host reads whole.
pub fn not_run_in_windows(size_mb: u64, limit_mb: u64) -> Diagnostic {
    STEP_BUDGET.warning(
        Span::new(0, 0),
        format!(
            "the dry run was not made: this program of {size_mb} MB calls subprograms or has flow control, for which the run needs the whole program in memory, and it is above the {limit_mb} MB Partscope reads whole (--max-file-size); the static checks cover all of it"
        ),
    )
}
