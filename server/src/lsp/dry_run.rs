//! The dry run (interpreter + planner) as the language server sees it.
//!
//! The runtime is built on other branches; everything the server needs from
//! it goes through [`DryRunner`], so wiring it is one new implementation of
//! that trait. The result shape ([`DryRunResult`]) is what the VS Code
//! preview consumes, produced by [`summarize`] from runtime-neutral
//! [`Segment`]s and [`Timing`].

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use analyzer::{Diagnostic, Settings};
use serde::Serialize;

pub use super::decimate::{Decimation, Path, Request};

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

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bounds {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Toolpath {
    pub segments: Vec<Segment>,
    pub bounds: Bounds,
}

/// The result of `partscope/dryRun` and of the `partscope.dryRun` command.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DryRunResult {
    // Times are `null` when no planner ran (the preview shows "–").
    pub version: i32,
    pub cycle_time_s: Option<f64>,
    pub motion_s: Option<f64>,
    pub rapid_s: Option<f64>,
    pub cutting_s: Option<f64>,
    pub dwell_s: Option<f64>,
    pub tool_change_s: Option<f64>,
    pub distance_mm: f64,
    pub toolpath: Toolpath,
    /// LSP diagnostics (converted by the caller).
    pub diagnostics: Vec<serde_json::Value>,
    /// False when the run stopped before the program's end: the times are partial.
    pub complete: bool,
    /// Where and why it stopped (`null` when complete).
    pub stopped_at: Option<StoppedAt>,
    /// The cycle time by cause and the top causes in words (`null` when no
    /// planner ran).
    pub breakdown: Option<Breakdown>,
    /// How the toolpath was decimated and capped for this answer.
    pub decimation: Decimation,
}

/// The result of the `partscope.showBreakdown` command (the cycle-time
/// lens): the figures of the dry run without its toolpath, and `text`, the
/// breakdown as the server shows it in `window/showMessage`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BreakdownResult {
    pub uri: String,
    pub version: i32,
    pub cycle_time_s: Option<f64>,
    pub motion_s: Option<f64>,
    pub rapid_s: Option<f64>,
    pub cutting_s: Option<f64>,
    pub dwell_s: Option<f64>,
    pub tool_change_s: Option<f64>,
    pub other_s: Option<f64>,
    pub distance_mm: f64,
    pub complete: bool,
    pub stopped_at: Option<StoppedAt>,
    pub breakdown: Option<Breakdown>,
    pub text: String,
}

/// The breakdown of `report` for the document `name` (its file name).
pub fn breakdown_of(uri: String, name: &str, version: i32, report: &RunReport) -> BreakdownResult {
    let distance = report.path.distance;
    let t = report.timing;
    BreakdownResult {
        uri,
        version,
        cycle_time_s: t.map(|t| t.cycle_time_s),
        motion_s: t.map(|t| t.motion_s),
        rapid_s: t.map(|t| t.rapid_s),
        cutting_s: t.map(|t| t.cutting_s),
        dwell_s: t.map(|t| t.dwell_s),
        tool_change_s: t.map(|t| t.tool_change_s),
        other_s: t.map(|t| t.other_s),
        distance_mm: distance,
        complete: report.stopped.is_none(),
        stopped_at: report.stopped.clone(),
        breakdown: report.breakdown.clone(),
        text: breakdown_text(name, report, distance),
    }
}

/// Plain text, one figure a line: the cycle time (clock and seconds, as
/// `partscope run` gives them), its split, where the time goes and the top
/// causes. Plain text because `window/showMessage` is shown as it is.
pub fn breakdown_text(name: &str, report: &RunReport, distance_mm: f64) -> String {
    use super::server::format_duration as clock;
    let Some(t) = report.timing else {
        return format!("{name}: no cycle time (no planner ran)");
    };
    let mut out = format!(
        "{name}: cycle time {} ({:.3} s{})",
        clock(t.cycle_time_s),
        t.cycle_time_s,
        if report.stopped.is_some() {
            ", partial"
        } else {
            ""
        }
    );
    if let Some(s) = &report.stopped {
        out.push_str(&format!("\n  {}", s.describe()));
    }
    let rows = [
        ("cutting", t.cutting_s, true),
        ("rapid", t.rapid_s, true),
        ("dwell", t.dwell_s, true),
        ("tool change", t.tool_change_s, true),
        ("other", t.other_s, t.other_s > 0.0),
    ];
    for (label, s, shown) in rows {
        if shown {
            out.push_str(&format!("\n  {label:<12} {:>9}", clock(s)));
        }
    }
    out.push_str(&format!("\n  {:<12} {distance_mm:>9.1} mm", "distance"));
    if let Some(b) = &report.breakdown {
        if t.cycle_time_s > 0.0 && t.cycle_time_s.is_finite() {
            out.push_str("\nwhere the time goes");
            for (key, label) in &b.labels {
                let s = b.parts.get(key).copied().unwrap_or(0.0);
                if s > 0.0 {
                    out.push_str(&format!(
                        "\n  {label:<34} {s:>9.3} s {:>5.1} %",
                        100.0 * s / t.cycle_time_s
                    ));
                }
            }
        }
        for c in &b.top_causes {
            out.push_str(&format!("\n  - {c}"));
        }
    }
    out
}

/// Builds the preview result from a run report, its toolpath decimated as
/// `request` asks (bounds and distance are those of the whole toolpath).
pub fn summarize(
    version: i32,
    report: &RunReport,
    diagnostics: Vec<serde_json::Value>,
    request: Request,
) -> DryRunResult {
    let (min, max) = report.path.bounds.unwrap_or(([0.0; 3], [0.0; 3]));
    let distance = report.path.distance;
    let (segments, decimation) = report.path.select(request);
    let t = report.timing;
    DryRunResult {
        version,
        cycle_time_s: t.map(|t| t.cycle_time_s),
        motion_s: t.map(|t| t.motion_s),
        rapid_s: t.map(|t| t.rapid_s),
        cutting_s: t.map(|t| t.cutting_s),
        dwell_s: t.map(|t| t.dwell_s),
        tool_change_s: t.map(|t| t.tool_change_s),
        distance_mm: distance,
        toolpath: Toolpath {
            segments,
            bounds: Bounds { min, max },
        },
        diagnostics,
        complete: report.stopped.is_none(),
        stopped_at: report.stopped.clone(),
        breakdown: report.breakdown.clone(),
        decimation,
    }
}

/// Runs a program. `None` means no runtime is available.
pub trait DryRunner: Send + Sync {
    fn run(&self, input: &DryRunInput<'_>) -> Option<RunReport>;
}

/// The runner the server uses.
pub fn default_runner() -> Arc<dyn DryRunner> {
    Arc::new(super::runtime_runner::RuntimeRunner)
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
    fn summary_sums_lengths_and_bounds_and_passes_times() {
        let mut path = Path::default();
        path.push(
            SegmentKind::Rapid,
            0,
            0.0,
            1,
            &[[0.0, 0.0, 5.0], [3.0, 4.0, 5.0]],
            5.0,
        );
        path.push(
            SegmentKind::Feed,
            1,
            600.0,
            1,
            &[[3.0, 4.0, 5.0], [3.0, 4.0, -1.0]],
            6.0,
        );
        path.finish();
        let report = RunReport {
            path,
            timing: Some(Timing {
                rapid_s: 0.5,
                cutting_s: 0.6,
                dwell_s: 2.0,
                tool_change_s: 4.0,
                other_s: 0.25,
                motion_s: 1.1,
                cycle_time_s: 7.35,
            }),
            tool_changes: vec![],
            diagnostics: vec![],
            run: Default::default(),
            stopped: None,
            values: None,
            blocks: vec![],
            breakdown: None,
        };
        let r = summarize(7, &report, vec![], Request::EXACT);
        assert_eq!(r.version, 7);
        assert_eq!(r.distance_mm, 11.0);
        assert_eq!(
            r.toolpath.bounds,
            Bounds {
                min: [0.0, 0.0, -1.0],
                max: [3.0, 4.0, 5.0]
            }
        );
        assert_eq!(r.motion_s, Some(1.1));
        assert_eq!(r.cycle_time_s, Some(7.35));
        assert_eq!(r.tool_change_s, Some(4.0));
        let json = serde_json::to_value(&r).unwrap();
        assert_eq!(json["toolpath"]["segments"][0]["kind"], "rapid");
        assert_eq!(
            json["toolpath"]["segments"][1]["points"][1],
            serde_json::json!([3.0, 4.0, -1.0])
        );
    }

    #[test]
    fn empty_toolpath_has_zero_bounds() {
        let r = summarize(1, &RunReport::default(), vec![], Request::EXACT);
        assert_eq!(
            r.toolpath.bounds,
            Bounds {
                min: [0.0; 3],
                max: [0.0; 3]
            }
        );
        assert_eq!(r.cycle_time_s, None);
        assert_eq!(
            serde_json::to_value(&r).unwrap()["cutting_s"],
            serde_json::Value::Null
        );
    }

    #[test]
    fn a_partial_breakdown_says_where_the_run_stopped() {
        let report = RunReport {
            timing: Some(Timing {
                rapid_s: 0.25,
                cutting_s: 1.5,
                dwell_s: 0.0,
                tool_change_s: 0.0,
                other_s: 3.0,
                motion_s: 1.75,
                cycle_time_s: 4.75,
            }),
            stopped: Some(StoppedAt {
                line: 6,
                reason: "unknown code M123".into(),
            }),
            ..RunReport::default()
        };
        let r = breakdown_of("file:///w/p.nc".into(), "p.nc", 2, &report);
        assert_eq!(
            r.text,
            "p.nc: cycle time 0:04.8 (4.750 s, partial)
  stopped at line 7: unknown code M123
  cutting         0:01.5
  rapid           0:00.3
  dwell           0:00.0
  tool change     0:00.0
  other           0:03.0
  distance           0.0 mm"
        );
        assert!(!r.complete);
        assert_eq!(r.other_s, Some(3.0));
        let none = breakdown_of("u".into(), "p.nc", 1, &RunReport::default());
        assert_eq!(none.text, "p.nc: no cycle time (no planner ran)");
        assert_eq!(none.cycle_time_s, None);
    }

    #[test]
    fn cancel_guard_sets_flag_on_drop() {
        let f = CancelFlag::default();
        let g = f.guard();
        assert!(!f.is_cancelled());
        drop(g);
        assert!(f.is_cancelled());
    }
}
