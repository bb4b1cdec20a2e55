//! The [`DryRunner`] backed by `runtime::run` (the interpreter), with a
//! resolver that finds subprogram files inside the workspace only.
//!
//! The interpreter gives motions, events, per-block state and flow-sensitive
//! diagnostics; the velocity planner plans the motions on a second thread
//! while the interpreter makes them, and the toolpath is sampled when the
//! run is done.

use std::path::PathBuf;
use std::sync::Arc;

use analyzer::FileId;
use runtime::dryrun::{self, DryRun};
use runtime::machine::MachineProfile;
use runtime::{EventKind, RunInput};

use analyzer::names::{self as nav, Sym};

use super::decimate::{self, Path};
use super::run::{DryRunInput, DryRunner, RunReport, SegmentKind, StoppedAt, Timing};
use super::workspace;
use crate::resolve::{FsResolver, SizeLimit};

/// Upper bound on executed blocks per run (loops and calls included).
#[cfg(not(fuzzing))]
pub const STEP_BUDGET: u64 = 5_000_000;
/// The fuzz target compiles this module with coverage instrumentation, where
/// a runaway loop at the real budget costs over ten seconds per input; a small
/// budget reaches the same code (the budget diagnostic included) cheaply.
#[cfg(fuzzing)]
pub const STEP_BUDGET: u64 = 20_000;
/// Chord tolerance for sampling arcs in the preview, mm: the finest used.
pub(crate) const CHORD_TOLERANCE: f64 = 0.01;
/// Chunks of motions waiting for the planner: enough to ride out its
/// uneven pace, few enough that memory stays flat.
const PLAN_QUEUE: usize = 4;

/// Motions per chunk [`send_run`] sends.
const PLAN_CHUNK: usize = 4096;
/// A chunk of the run's motions and events on its way to the planner.
type Chunk = (Vec<runtime::Motion>, Vec<runtime::Event>);

pub use crate::resolve::Loaded;

/// Moves a diagnostic located in a subprogram file onto the document's call
/// of that file (the document is what the editor shows), naming the file
/// and line in the message.
fn onto_call_site(
    program: &analyzer::syntax::Program,
    d: &analyzer::Diagnostic,
    files: &[String],
    loaded: &[Loaded],
) -> Option<analyzer::Diagnostic> {
    let path = files.get((d.file.0 as usize).checked_sub(1)?)?;
    let (name, _, text) = loaded.iter().find(|(_, p, _)| p == path)?;
    let calls: Vec<nav::Occ> = nav::occurrences(program)
        .into_iter()
        .filter(|o| o.call)
        .collect();
    let wanted = [
        Sym::OLabel(name.to_ascii_lowercase()),
        Sym::Program(name.to_ascii_uppercase()),
    ];
    let numeric = name
        .parse::<u32>()
        .ok()
        .map(|n| Sym::Program(n.to_string()));
    let site = calls
        .iter()
        .filter(|o| wanted.contains(&o.sym) || numeric.as_ref() == Some(&o.sym))
        .min_by_key(|o| o.span.start)
        // A file called from another subprogram file: blame the first external call.
        .or_else(|| calls.iter().min_by_key(|o| o.span.start))?;
    let line = analyzer::LineIndex::new(text).line_col(d.span.start).0 + 1;
    let file_name = std::path::Path::new(path)
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut out = analyzer::Diagnostic::new(
        d.code,
        d.severity,
        site.span,
        format!("{} (in {file_name}, line {line})", d.message),
    );
    out.related = d
        .related
        .iter()
        .filter(|r| r.file == FileId(0))
        .cloned()
        .collect();
    Some(out)
}

pub struct RuntimeRunner;

impl DryRunner for RuntimeRunner {
    fn run(&self, input: &DryRunInput<'_>) -> Option<RunReport> {
        // The same resolver as `partscope run`, confined to the workspace folders;
        // called files obey the document's dry-run size limit.
        let resolver = FsResolver::for_workspace(
            input.doc_path.as_deref(),
            input.roots,
            input.settings.dialect,
            input.machine,
            input.config_path.as_deref(),
            SizeLimit::bytes(input.max_file_size as u64, "the `maxRunFileSize` setting"),
        )
        .with_cancel(input.cancel.clone());
        // Missing or outside-the-workspace files leave the run without them, as
        // `partscope run` does for files a config names.
        let read = |p: &Option<PathBuf>| {
            p.as_deref()
                .and_then(|p| workspace::read_confined(p, input.roots))
                .map(|(_, t)| t)
        };
        let (tool_table, var_file) = (read(&input.tool_table), read(&input.var_file));
        let run_input = RunInput {
            program: input.program,
            settings: input.settings,
            machine: input.machine,
            resolver: &resolver,
            step_budget: STEP_BUDGET,
            motion_budget: runtime::default_motion_budget(input.program.blocks.len()),
            emit_canon: false,
            tool_table: tool_table.as_deref(),
            var_file: var_file.as_deref(),
        };
        // An earlier version's run continues from its last checkpoint before
        // the edit (`runtime::rerun`); without one, a checkpointed full run.
        let previous = input
            .previous
            .and_then(|p| p.lock().unwrap_or_else(|e| e.into_inner()).take());
        let profile = input.profile;
        let timing = std::env::var_os("PARTSCOPE_LSP_TIMING").is_some();
        let t0 = std::time::Instant::now();
        let rerun = previous.is_some();
        // A full run is planned on a second thread while it runs (the same glue
        // as `partscope run`: planner segments and the plan come from
        // `runtime::dryrun`); the toolpath, whose sampling depends on the whole
        // run's extent, is built here once the interpreter is done, beside the
        // planner's tail.
        let (mut out, path, streamed, t_path) = std::thread::scope(|s| {
            let (tx, rx) = std::sync::mpsc::sync_channel::<Chunk>(PLAN_QUEUE);
            // Planned chunks come back to be filled again: fresh memory for
            // every chunk would cost a page fault per 4 KB.
            let (back_tx, back_rx) = std::sync::mpsc::channel::<Chunk>();
            let planner = s.spawn(move || {
                let mut plan = dryrun::RunPlan::new(profile);
                plan.reserve(input.program.blocks.len());
                for (mut m, mut e) in rx {
                    plan.push(&m, &e, &|| input.cancel.is_cancelled());
                    m.clear();
                    e.clear();
                    let _ = back_tx.send((m, e));
                }
                plan
            });
            let send = |m: &[runtime::Motion], e: &[runtime::Event]| {
                let (mut mb, mut eb) = back_rx.try_recv().unwrap_or_default();
                mb.extend_from_slice(m);
                eb.extend_from_slice(e);
                // A planner that panicked drops its end; the join passes the panic on.
                let _ = tx.send((mb, eb));
            };
            let out = match previous {
                Some(prev) => {
                    let out = runtime::rerun(&run_input, true, prev);
                    // The rerun took most of its motions from the previous
                    // run: the planner gets the whole run afterwards.
                    send_run(&out, &send);
                    out
                }
                None => runtime::run_checkpointed_observed(
                    &run_input,
                    true,
                    Some(runtime::ValueLimits::default()),
                    &mut |m, e| send(m, e),
                ),
            };
            drop(tx);
            if timing {
                eprintln!(
                    "partscope lsp: interpreter {:?}, {} of {} blocks executed{}; {}",
                    t0.elapsed(),
                    out.checkpoints.executed(),
                    input.program.blocks.len(),
                    if rerun { " (rerun)" } else { "" },
                    memory()
                );
            }
            // A cancelled run stopped part way: no toolpath.
            let path = (!input.cancel.is_cancelled())
                .then(|| {
                    // Arcs are sampled at half the default view tolerance (a finer one
                    // costs points no view of the whole part can show).
                    let chord = CHORD_TOLERANCE
                        .max(motion_extent(&out) / decimate::DEFAULT_VIEW_SIZE / 2.0);
                    path_of(&out, Some(profile), chord, &|| input.cancel.is_cancelled())
                })
                .flatten();
            let t_path = t0.elapsed();
            let streamed = planner
                .join()
                .unwrap_or_else(|e| std::panic::resume_unwind(e));
            (out, path, streamed, t_path)
        });
        // A cancelled run stopped part way: no answer, and nothing to rerun from.
        let path = path?;
        if input.cancel.is_cancelled() {
            return None;
        }
        let stop = || input.cancel.is_cancelled();
        // A run past the servo-simulation limit is planned again in closed form.
        let mut plan = if streamed.over_limit() {
            dryrun::plan_run_until(&out, profile, &stop)?
        } else {
            streamed.finish(&out.events)?
        };
        if input.cancel.is_cancelled() {
            return None;
        }
        if timing {
            eprintln!(
                "partscope lsp: interpreter and toolpath {t_path:?} ({} motions), with the planner {:?}; {}",
                out.motions.len(),
                t0.elapsed(),
                memory()
            );
        }
        let loaded = resolver.loaded();
        let report = report_of(input.program, &out, path, Some(&plan), &loaded);
        // The canonical lines are not needed again; the rest is what a rerun
        // continues from.
        out.canon = Vec::new();
        // The document's blocks, moved out of the plan (a million of them
        // would be a large copy).
        let mut blocks = std::mem::take(&mut plan.blocks);
        blocks.retain(|b| b.file == 0);
        let breakdown = Some(super::run::Breakdown::of(
            &plan.totals,
            profile.traj_max_velocity,
        ));
        Some(RunReport {
            blocks,
            breakdown,
            run: Arc::new(std::sync::Mutex::new(Some(out))),
            ..report
        })
    }
}

/// Sends a finished run to the planner in chunks of [`PLAN_CHUNK`] motions
/// (an event goes with the motion it comes before).
fn send_run(out: &runtime::RunOutput, send: &dyn Fn(&[runtime::Motion], &[runtime::Event])) {
    let mut first_event = 0;
    let mut end = 0;
    for motions in out.motions.chunks(PLAN_CHUNK) {
        end += motions.len();
        let rest = out.events.get(first_event..).unwrap_or_default();
        let n = rest.partition_point(|e| e.motion_index < end);
        send(motions, rest.get(..n).unwrap_or_default());
        first_event += n;
    }
    send(&[], out.events.get(first_event..).unwrap_or_default());
}

/// The process's resident and peak memory, for `PARTSCOPE_LSP_TIMING`.
fn memory() -> String {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .filter(|l| l.starts_with("VmRSS") || l.starts_with("VmHWM"))
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The longest side of the box around the motions' end points.
fn motion_extent(out: &runtime::RunOutput) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for m in &out.motions {
        for p in [&m.start, &m.end] {
            for k in 0..3 {
                if p[k].is_finite() {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
    }
    (0..3)
        .map(|k| hi[k] - lo[k])
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max)
}

/// The toolpath of a run as the preview's path: arcs sampled at `chord`,
/// rapids as `profile` moves them (straight without one), with each point's
/// significance for decimation.
pub fn path_of(
    out: &runtime::RunOutput,
    profile: Option<&MachineProfile>,
    chord: f64,
    stop: &dyn Fn() -> bool,
) -> Option<Path> {
    let mut path = Path::with_capacity(out.motions.len());
    let mut index = 0u32;
    let mut stopped = false;
    dryrun::for_each_toolpath_segment(out, chord, profile, |m, kind, points| {
        // A million motions take a good part of a second: a cancel is looked
        // at every few thousand.
        if index.is_multiple_of(4096) && stop() {
            stopped = true;
            return std::ops::ControlFlow::Break(());
        }
        let kind = match kind {
            "rapid" => SegmentKind::Rapid,
            "arc" => SegmentKind::Arc,
            _ => SegmentKind::Feed,
        };
        index += 1;
        path.push(kind, m.line, m.feed, m.tool, points, dryrun::length_of(m));
        std::ops::ControlFlow::Continue(())
    });
    if stopped || !path.finish_until(stop) {
        return None;
    }
    Some(path)
}

/// The report of a finished run of `program`, as the language server keeps it
/// (without the run itself, which the caller keeps or not): times from `plan`,
/// tool changes, the run's diagnostics and stop in the document (those in a
/// called file moved onto its call, found in `loaded`). Shared with
/// `partscope run --html`, whose page holds what the preview gets.
pub fn report_of(
    program: &analyzer::syntax::Program,
    out: &runtime::RunOutput,
    path: Path,
    plan: Option<&DryRun>,
    loaded: &[Loaded],
) -> RunReport {
    let timing = plan.map(|p| Timing {
        rapid_s: p.totals.rapid_s,
        cutting_s: p.totals.cutting_s,
        dwell_s: p.totals.dwell_s,
        tool_change_s: p.totals.tool_change_s,
        other_s: p.totals.other_s,
        cycle_time_s: p.totals.cycle_time_s,
        motion_s: p.totals.motion_s,
    });
    let tool_changes = out
        .events
        .iter()
        .enumerate()
        .filter(|(_, e)| e.file == FileId(0) && matches!(e.kind, EventKind::ToolChange { .. }))
        .map(|(i, e)| (e.line, plan.and_then(|p| p.event_times.get(i).copied())))
        .collect();
    let diagnostics = out
        .diagnostics
        .iter()
        .filter_map(|d| {
            if d.file == FileId(0) {
                Some(d.clone())
            } else {
                onto_call_site(program, d, &out.files, loaded)
            }
        })
        .collect();
    let stopped = out.stopped.as_ref().and_then(|s| {
        if s.file == FileId(0) {
            return Some(StoppedAt {
                line: s.line,
                reason: s.reason.clone(),
            });
        }
        // A stop inside a called file is shown on the document's call.
        let d = analyzer::Diagnostic::new(s.code, analyzer::Severity::Info, s.span, &s.reason)
            .in_file(s.file);
        let moved = onto_call_site(program, &d, &out.files, loaded)?;
        Some(StoppedAt {
            line: analyzer::LineIndex::new(&program.text)
                .line_col(moved.span.start)
                .0,
            reason: moved.message,
        })
    });
    RunReport {
        values: out.values.clone().map(Arc::new),
        path,
        timing,
        tool_changes,
        diagnostics,
        run: Arc::default(),
        stopped,
        skipped_calls: out.skipped_calls,
        blocks: Vec::new(),
        breakdown: None,
    }
}

#[cfg(test)]
mod run_tests {
    use super::*;
    use crate::document::decimate::Request;
    use crate::document::run::CancelFlag;
    use analyzer::{Dialect, Settings};

    fn run(text: &str) -> RunReport {
        let settings = Settings::new(Dialect::Rs274ngc);
        let program = analyzer::analyze(text.as_bytes().to_vec(), &settings).program;
        let machine = analyzer::config::MachineConfig::default();
        let profile = runtime::machine::MachineProfile::default_for(Dialect::Rs274ngc);
        let cancel = CancelFlag::default();
        let input = DryRunInput {
            program: &program,
            settings: &settings,
            machine: &machine,
            profile: &profile,
            doc_path: None,
            config_path: None,
            tool_table: None,
            var_file: None,
            roots: &[],
            cancel: &cancel,
            previous: None,
            max_file_size: usize::MAX,
        };
        RuntimeRunner.run(&input).unwrap()
    }

    fn segments(r: &RunReport) -> Vec<crate::document::run::Segment> {
        r.path.select(Request::EXACT).0
    }

    #[test]
    fn motions_become_segments() {
        let r = run("G21 G90\nG0 X1 Y2 Z3\nG1 X4 F100\nG2 X6 Y4 I0 J2\nM2\n");
        let segs = segments(&r);
        let kinds: Vec<(SegmentKind, u32)> = segs.iter().map(|s| (s.kind, s.line)).collect();
        assert_eq!(
            kinds,
            vec![
                (SegmentKind::Rapid, 1),
                (SegmentKind::Feed, 2),
                (SegmentKind::Arc, 3)
            ]
        );
        assert_eq!(segs[1].points, vec![[1.0, 2.0, 3.0], [4.0, 2.0, 3.0]]);
        assert_eq!(segs[1].feed, 100.0);
        let last = *segs[2].points.last().unwrap();
        assert!(
            (last[0] - 6.0).abs() < 1e-9 && (last[1] - 4.0).abs() < 1e-9,
            "{last:?}"
        );
        let s = r.block_state(2).unwrap();
        assert_eq!(s.position[0], 4.0);
        assert!(s.modal.iter().any(|m| m == "G1"), "{:?}", s.modal);
    }
}
