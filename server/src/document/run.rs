//! The dry run (interpreter + planner) of one document, as the editor
//! features read it: what a run needs ([`DryRunInput`]), what it gives
//! ([`RunReport`]) and the [`DryRunner`] that makes it. Protocol-free: the
//! language server converts a report into its results (`lsp::dry_run`).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use analyzer::{Diagnostic, Settings};
use serde::Serialize;

use super::decimate::Path;

/// What one dry run needs.
pub struct DryRunInput<'a> {
    pub program: &'a analyzer::syntax::Program,
    pub settings: &'a Settings,
    pub machine: &'a analyzer::config::MachineConfig,
    /// The planner's machine.
    pub profile: &'a runtime::machine::MachineProfile,
    pub doc_path: Option<PathBuf>,
    /// The `partscope.toml` in force (relative paths in it start at its folder).
    pub config_path: Option<PathBuf>,
    pub tool_table: Option<PathBuf>,
    pub var_file: Option<PathBuf>,
    pub roots: &'a [PathBuf],
    /// Set when the client cancelled the request; a runner checks it between steps.
    pub cancel: &'a CancelFlag,
    /// The run of an earlier version of the document, which an incremental
    /// runner may continue from (it takes the run out).
    pub previous: Option<&'a PreviousRun>,
    /// The dry-run size limit (bytes) of the document, which called files obey too.
    pub max_file_size: usize,
}

/// A runner's own record of a run, kept for the next version's rerun.
pub type PreviousRun = std::sync::Mutex<Option<runtime::RunOutput>>;

/// The kind of a toolpath segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SegmentKind {
    Rapid,
    Feed,
    Arc,
}

/// One motion, already sampled into points (arcs at a chord tolerance).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Segment {
    pub kind: SegmentKind,
    /// 0-based line of the block in the document.
    pub line: u32,
    pub feed: f64,
    pub tool: u32,
    pub points: Vec<[f64; 3]>,
    /// A segment that holds several motions (decimated, [`super::decimate`]):
    /// the 0-based line of the motion each point ends; `line` is the first's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lines: Option<Vec<u32>>,
    /// Exact path length in XYZ (arcs are longer than their sampled polyline).
    #[serde(skip)]
    pub length: f64,
}

/// Times from the planner, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Timing {
    pub rapid_s: f64,
    pub cutting_s: f64,
    pub dwell_s: f64,
    pub tool_change_s: f64,
    /// Other non-motion time (spindle ramps, M-code times, program stops).
    pub other_s: f64,
    /// The planner's totals: motion time counts overlaps once, and the cycle
    /// time is the end of the last event.
    pub motion_s: f64,
    pub cycle_time_s: f64,
}

/// The machine state after one block of the document: modal codes in force,
/// program coordinates (mm, degrees), feed, spindle and tool.
pub type BlockState = runtime::BlockSnapshot;

/// What a runner returns: segments, timing (when a planner is available),
/// tool changes, per-block state and flow-sensitive diagnostics.
#[derive(Debug, Clone, Default)]
pub struct RunReport {
    /// The toolpath, which each request decimates to its own tolerance.
    pub path: Path,
    pub timing: Option<Timing>,
    /// The document's tool changes: 0-based line and program time (when planned).
    pub tool_changes: Vec<(u32, Option<f64>)>,
    /// Runtime diagnostics in the document (FileId 0).
    pub diagnostics: Vec<Diagnostic>,
    /// The interpreter's output (with one state per block of the document),
    /// until the next version's run takes it to continue from.
    pub run: Arc<PreviousRun>,
    /// Where the run stopped before the program's end, when it did: the times
    /// and toolpath then cover only what ran.
    pub stopped: Option<StoppedAt>,
    /// A call the run could not follow was skipped (F002): the times leave out
    /// what it runs.
    pub skipped_calls: bool,
    /// The values the document's expressions took (hover), kept apart from
    /// `run` because the next version's run takes that.
    pub values: Option<Arc<runtime::ValueRecord>>,
    /// The document's blocks that take time (inlay hints, hover), by line.
    pub blocks: Vec<runtime::dryrun::BlockTime>,
    /// Where the time goes: the cycle time by cause and the top causes in words
    /// (when planned).
    pub breakdown: Option<Breakdown>,
}

/// The cycle time by cause ([`runtime::plan::explain`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Breakdown {
    /// `feed_s`, `accel_s`, … → seconds; they sum to the cycle time.
    pub parts: std::collections::BTreeMap<&'static str, f64>,
    /// Plain-words labels of `parts`, in the order `partscope run` prints them.
    #[serde(skip)]
    pub labels: Vec<(&'static str, &'static str)>,
    /// The causes that cost the most cutting time, in words.
    pub top_causes: Vec<String>,
}

impl Breakdown {
    pub fn of(totals: &runtime::plan::Totals, traj_max_velocity: f64) -> Breakdown {
        let parts = runtime::plan::explain::parts(totals);
        Breakdown {
            parts: parts.iter().map(|p| (p.key, p.seconds)).collect(),
            labels: parts.iter().map(|p| (p.key, p.label)).collect(),
            top_causes: runtime::plan::explain::top_causes(totals, traj_max_velocity),
        }
    }

    /// Markdown: one line per part that takes time, then the top causes.
    pub fn markdown(&self) -> String {
        let mut md = String::from("**Where the time goes**\n\n");
        for (key, label) in &self.labels {
            let s = self.parts.get(key).copied().unwrap_or(0.0);
            if s > 0.0 {
                md.push_str(&format!("- {label}: {s:.3} s\n"));
            }
        }
        for c in &self.top_causes {
            md.push_str(&format!("\n{c}  "));
        }
        md
    }

    /// The block's time by cause in words (`1.000 s at feed, 0.050 s acceleration`).
    pub fn of_block(b: &runtime::dryrun::BlockTime) -> String {
        let c = &b.causes;
        let parts = [
            (c.feed_s, "at feed"),
            (c.accel_s, "acceleration"),
            (c.corner_s, "corners"),
            (c.axis_cap_s, "axis velocity"),
            (c.traj_cap_s, "TRAJ velocity cap"),
            (c.curve_cap_s, "arc acceleration"),
            (c.servo_cap_s, "servo period"),
            (c.rapid_s, "rapid"),
            (b.dwell_s, "dwell"),
            (b.aux_s, "auxiliary"),
        ];
        parts
            .iter()
            .filter(|(s, _)| *s > 0.0)
            .map(|(s, w)| format!("{s:.3} s {w}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Where a run stopped early, in the document.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StoppedAt {
    /// 0-based line in the document (a stop inside a called file is put on the call).
    pub line: u32,
    pub reason: String,
}

impl StoppedAt {
    /// "stopped at line N: reason", with a 1-based line and the reason cut short.
    pub fn describe(&self) -> String {
        let mut reason: String = self.reason.chars().take(100).collect();
        if reason.len() < self.reason.len() {
            reason.push('…');
        }
        format!("stopped at line {}: {reason}", self.line + 1)
    }
}

impl RunReport {
    /// The machine state after block `bi` (`None`: never executed, or the
    /// run has been handed to a newer version).
    pub fn block_state(&self, bi: usize) -> Option<BlockState> {
        let run = self.run.lock().unwrap_or_else(|p| p.into_inner());
        run.as_ref()?.snapshots.get(bi)?.clone()
    }
}

/// Runs a program. `None` means no runtime is available.
pub trait DryRunner: Send + Sync {
    fn run(&self, input: &DryRunInput<'_>) -> Option<RunReport>;
}

/// The runner the server uses.
pub fn default_runner() -> Arc<dyn DryRunner> {
    Arc::new(super::runner::RuntimeRunner)
}

/// A flag set when a request is cancelled (its future dropped).
#[derive(Debug, Clone, Default)]
pub struct CancelFlag(Arc<AtomicBool>);

impl CancelFlag {
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// A guard that sets the flag when dropped: the request future owns it,
    /// so dropping the future (what `$/cancelRequest` does) cancels the work.
    pub fn guard(&self) -> CancelOnDrop {
        CancelOnDrop(self.clone())
    }
}

pub struct CancelOnDrop(CancelFlag);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cancel_guard_sets_flag_on_drop() {
        let f = CancelFlag::default();
        let g = f.guard();
        assert!(!f.is_cancelled());
        drop(g);
        assert!(f.is_cancelled());
    }
}
