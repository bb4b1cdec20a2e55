//! The dry run as the language server answers with it: the result shapes
//! ([`DryRunResult`], what the VS Code preview consumes, produced by
//! [`summarize`] from the run's [`Segment`]s and [`Timing`], and
//! [`BreakdownResult`]). The run itself is made and kept by
//! [`crate::document`].

use serde::Serialize;
use tower_lsp_server::ls_types::Uri;

pub use crate::document::decimate::{Decimation, Request};
pub use crate::document::run::*;
use crate::document::runner::{path_of, report_of, Loaded, CHORD_TOLERANCE};
use runtime::dryrun::DryRun;
use runtime::machine::MachineProfile;

use super::snapshot::lsp_diagnostic;

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
    /// False when the times are partial: the run stopped before the program's
    /// end, or skipped a call it could not follow.
    pub complete: bool,
    /// Where and why it stopped (`null` when it did not stop).
    pub stopped_at: Option<StoppedAt>,
    /// A called program was not run (F002): the figures leave out what it does.
    pub skipped_calls: bool,
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
    pub skipped_calls: bool,
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
        complete: report.stopped.is_none() && !report.skipped_calls,
        stopped_at: report.stopped.clone(),
        skipped_calls: report.skipped_calls,
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
        if report.stopped.is_some() || report.skipped_calls {
            ", partial"
        } else {
            ""
        }
    );
    if let Some(s) = &report.stopped {
        out.push_str(&format!("\n  {}", s.describe()));
    }
    if report.skipped_calls {
        out.push_str("\n  a called program was not run (F002): its time is left out");
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
        complete: report.stopped.is_none() && !report.skipped_calls,
        stopped_at: report.stopped.clone(),
        skipped_calls: report.skipped_calls,
        breakdown: report.breakdown.clone(),
        decimation,
    }
}

/// The `partscope/dryRun` result of a run the command line made
/// (`partscope run --html`): the request's own conversion, from the
/// program's run, plan and loaded files instead of an open document.
pub fn dry_run_result(
    program: &analyzer::syntax::Program,
    path: &std::path::Path,
    out: &runtime::RunOutput,
    profile: &MachineProfile,
    plan: &DryRun,
    loaded: &[Loaded],
) -> DryRunResult {
    let toolpath = path_of(out, Some(profile), CHORD_TOLERANCE, &|| false).unwrap_or_default();
    let report = report_of(program, out, toolpath, Some(plan), loaded);
    // Ranges are counted in a rope of the text; an invalid byte becomes one `?`
    // (not U+FFFD, three bytes) so byte offsets stay those of the file.
    let mut text = String::with_capacity(program.text.len());
    for chunk in program.text.utf8_chunks() {
        text.push_str(chunk.valid());
        text.extend(std::iter::repeat_n('?', chunk.invalid().len()));
    }
    let rope = ropey::Rope::from_str(&text);
    let uri = std::path::absolute(path)
        .ok()
        .and_then(Uri::from_file_path)
        .or_else(|| "file:///".parse().ok());
    let diagnostics = match &uri {
        Some(uri) => report
            .diagnostics
            .iter()
            .filter_map(|d| serde_json::to_value(lsp_diagnostic(uri, &rope, d)).ok())
            .collect(),
        None => Vec::new(),
    };
    summarize(0, &report, diagnostics, Request::EXACT)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::decimate::Path;

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
            skipped_calls: false,
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
    fn a_skipped_call_makes_the_answers_partial() {
        let report = RunReport {
            timing: Some(Timing {
                cycle_time_s: 2.0,
                ..Timing::default()
            }),
            skipped_calls: true,
            ..RunReport::default()
        };
        let r = summarize(1, &report, vec![], Request::EXACT);
        assert!(!r.complete && r.skipped_calls && r.stopped_at.is_none());
        let b = breakdown_of("u".into(), "p.ngc", 1, &report);
        assert!(!b.complete && b.skipped_calls);
        assert!(
            b.text.starts_with("p.ngc: cycle time 0:02.0 (2.000 s, partial)\n  a called program was not run (F002): its time is left out"),
            "{}",
            b.text
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
}
