//! Public input and output types of the interpreter.

use std::sync::Arc;

use analyzer::syntax::Program;
use analyzer::{Diagnostic, FileId, Settings, Span};

/// A file the host found for a subprogram name.
#[derive(Debug, Clone)]
pub struct ResolvedFile {
    pub path: String,
    pub text: Arc<[u8]>,
}

/// Finds subprogram files. `name` is as written: `"MoveXY"` (ServoWorks
/// `M98 PMoveXY` → `OMoveXY.dat`), `"1234"` (FANUC `O1234`), `"drill"`
/// (RS274/NGC `o<drill> call` → `drill.ngc`).
pub trait Resolver {
    fn resolve(&self, name: &str, from: FileId) -> Option<ResolvedFile>;

    /// Whether the host wants the run to stop now (its client cancelled the
    /// request or went away). Polled every [`CANCEL_POLL_STEPS`] blocks; a
    /// stopped run's output ends where it stopped. The default never stops.
    fn cancelled(&self) -> bool {
        false
    }

    /// Whether the host searched every folder the control would (for LinuxCNC,
    /// its SUBROUTINE_PATH), so that a name it cannot resolve is really missing.
    /// A host without that configuration answers `false`, and an unresolved
    /// RS274/NGC subroutine is then information, not an error.
    fn searches_like_the_control(&self) -> bool {
        true
    }

    /// Why the host found the file `name` names but would not read it (above its
    /// size limit, not a regular file), when that is why `resolve` said `None`.
    fn refused(&self, _name: &str) -> Option<String> {
        None
    }
}

/// How many executed blocks pass between two [`Resolver::cancelled`] polls.
pub const CANCEL_POLL_STEPS: u64 = 1024;

/// Whether a run at `steps` executed blocks should stop for its host.
pub(crate) fn stop_requested(steps: u64, resolver: &dyn Resolver) -> bool {
    steps.is_multiple_of(CANCEL_POLL_STEPS) && resolver.cancelled()
}

/// A resolver that never finds anything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoResolver;

impl Resolver for NoResolver {
    fn resolve(&self, _name: &str, _from: FileId) -> Option<ResolvedFile> {
        None
    }
}

/// The default step budget for a program of `blocks` blocks: a floor of a million
/// (macro loops in short programs) plus a hundred executions of every block, so
/// that loops which terminate run to their end.
pub fn default_step_budget(blocks: usize) -> u64 {
    (blocks as u64)
        .saturating_mul(100)
        .saturating_add(1_000_000)
}

/// The default motion budget: a floor of a million motions plus eight per block
/// (a canned-cycle block makes three or four), some 400 MB at most for a short
/// program's dry run.
pub fn default_motion_budget(blocks: usize) -> u64 {
    (blocks as u64).saturating_mul(8).saturating_add(1_000_000)
}

/// Everything one run needs.
pub struct RunInput<'a> {
    pub program: &'a Program,
    pub settings: &'a Settings,
    /// The `[machine]` table of the configuration.
    pub machine: &'a analyzer::config::MachineConfig,
    pub resolver: &'a dyn Resolver,
    /// Upper bound on executed blocks (loops and calls included).
    pub step_budget: u64,
    /// Upper bound on motions produced (canned-cycle repeats and pecks included):
    /// memory grows with motions, which one block can multiply.
    pub motion_budget: u64,
    /// Produce LinuxCNC canonical lines (rs274ngc only).
    pub emit_canon: bool,
    /// LinuxCNC `.tbl` text.
    pub tool_table: Option<&'a str>,
    /// LinuxCNC `.var` text.
    pub var_file: Option<&'a str>,
}

/// Kind of a motion segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MotionKind {
    Rapid,
    Feed,
    /// Circular or helical arc. `normal` is a unit vector; the arc turns
    /// counter-clockwise about it. `turns` counts the extra full turns.
    Arc {
        center: [f64; 3],
        normal: [f64; 3],
        turns: i32,
        radius: f64,
    },
    /// ServoWorks exponential interpolation (G02.3/G03.3): A turns with X
    /// along `curve`; the feed runs from the motion's `feed` (F) to `end_feed`
    /// (Q, mm/min) along X. Without a defined curve the block is a `Feed`.
    Exponential {
        curve: super::exponential::ExpCurve,
        end_feed: f64,
    },
    /// Involute interpolation (G02.2/G03.2) along `curve`, whose coordinates are
    /// the machine axes `axes` (mm). Without a defined curve the block is a `Feed`.
    Involute {
        curve: super::involute::InvoluteCurve,
        axes: [u8; 2],
    },
    /// Spindle-synchronised move (G33, G76 passes); `feed` is the pitch in mm/rev.
    Thread,
    Probe,
}

/// One motion segment in the machine frame (mm and degrees).
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    pub kind: MotionKind,
    pub start: [f64; 6],
    pub end: [f64; 6],
    /// mm/min (G95 feeds converted with the programmed spindle speed; threads:
    /// the pitch in mm/rev); 0 for rapids.
    pub feed: f64,
    /// G93 inverse-time value (1/min) when in inverse-time mode.
    pub inverse_time: Option<f64>,
    pub exact_stop: bool,
    /// LinuxCNC G61 "exact path": the planner stops only at corners, not at tangent
    /// joints (G61.1 and G09 are true exact stops).
    pub exact_path: bool,
    /// G64 P, mm; 0 when not blending or P is not given (the planner's default
    /// applies). Resolved here, not kept optional: no reader tells the two apart,
    /// and a million motions are kept.
    pub blend_tolerance: f64,
    /// LinuxCNC G64 Q, mm: the naive-CAM tolerance; `blend_tolerance` when Q is
    /// not given or the dialect has none.
    pub naive_tolerance: f64,
    pub file: FileId,
    pub block: u32,
    pub line: u32,
    pub tool: u32,
    pub spindle_rpm: f64,
}

/// A non-motion happening that takes time or changes the machine.
#[derive(Debug, Clone, PartialEq)]
pub enum EventKind {
    /// Dwell in seconds.
    Dwell(f64),
    ToolChange {
        tool: u32,
    },
    /// Spindle speed (rpm) and direction: 1 CW, -1 CCW, 0 stopped.
    Spindle {
        rpm: f64,
        dir: i8,
    },
    Coolant {
        mist: bool,
        flood: bool,
    },
    /// A T word that selects the next tool without changing it (FANUC, RS274/NGC).
    ToolSelect {
        tool: u32,
    },
    /// An M code with no event of its own (M19, a pallet change, machine-builder
    /// codes): its number × 10 (190 for M19), for the profile's time table.
    MCode {
        code: u32,
    },
    /// Program stop (M0) or optional stop (M1).
    Stop {
        optional: bool,
    },
    ProgramEnd,
    Message(String),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    pub kind: EventKind,
    /// Index of the next motion in [`RunOutput::motions`]: the event happens before it.
    pub motion_index: usize,
    pub file: FileId,
    pub block: u32,
    pub line: u32,
}

/// The state after a block of the main file.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockSnapshot {
    /// Modal codes in force, e.g. `["G1","G17","G21","G90","G94","G54","G40","G49","G64"]`,
    /// shared by the blocks with the same modal state (one allocation, not
    /// ten, per block of a million-line program).
    pub modal: std::sync::Arc<[String]>,
    /// Position after the block in program coordinates (mm/deg): X Y Z A B C.
    pub position: [f64; 6],
    /// Programmed feed in mm/min (or mm/rev under G95).
    pub feed: f64,
    pub spindle: f64,
    pub tool: u32,
}

#[derive(Debug, Clone, Default)]
pub struct RunOutput {
    pub diagnostics: Vec<Diagnostic>,
    /// Paths of resolved files: `FileId(i)` is `files[i - 1]`.
    pub files: Vec<String>,
    pub motions: Vec<Motion>,
    pub events: Vec<Event>,
    /// One entry per block of the main file (None when never executed, and
    /// for blocks past `SNAPSHOT_LIMIT` (2 000 000) so that huge files fit in memory).
    pub snapshots: Vec<Option<BlockSnapshot>>,
    pub canon: Vec<String>,
    /// Canonical output only: the error that stopped the run, as rs274 prints it
    /// on stderr (its message, a newline, the offending source line).  rs274 names
    /// the program file in some messages; the interpreter does not know its path and
    /// writes [`CANON_FILE_NAME`] there for the caller to replace.
    pub canon_error: Option<String>,
    /// Checkpoints of a [`super::run_checkpointed`] run, for [`super::rerun`].
    pub checkpoints: super::Checkpoints,
    /// Where and why the run ended before the program's end (an error that leaves
    /// the state undefined, a budget, the runtime-error cap, a block the control
    /// cannot read): the motions and totals then cover only what ran. `None` when
    /// the run reached the end of the program (recovered errors included).
    pub stopped: Option<Stopped>,
    /// A call the run could not follow (its file not found, not read, or written for
    /// another control) was skipped: the motions and totals leave out what it runs.
    pub skipped_calls: bool,
    /// The values the main file's expressions took, when the run was asked to
    /// record them ([`super::run_checkpointed_recording`]).
    pub values: Option<super::values::ValueRecord>,
}

/// Where a run stopped early ([`RunOutput::stopped`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Stopped {
    pub file: FileId,
    /// Span of the diagnostic that says why, in `file`.
    pub span: Span,
    /// Zero-based line of the block that stopped the run, in `file`.
    pub line: u32,
    /// Code of that diagnostic (`F004` for the budgets and the error cap).
    pub code: &'static str,
    /// Its message, without the "the dry run stops here" suffix.
    pub reason: String,
}

/// Stands for the program's path in [`RunOutput::canon_error`].
pub const CANON_FILE_NAME: &str = "\u{1}file\u{1}";

/// FANUC G65/G66 Argument Specification I: the local variable a letter sets
/// (`X` → #24); see [`analyzer::dialect::fanuc::macro_argument_variable`].
pub fn macro_argument_variable(letter: u8) -> Option<usize> {
    analyzer::dialect::fanuc::macro_argument_variable(letter).map(|n| n as usize)
}
