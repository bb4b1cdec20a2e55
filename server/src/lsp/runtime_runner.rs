//! The [`DryRunner`] backed by `runtime::run` (the interpreter), with a
//! resolver that finds subprogram files inside the workspace only.
//!
//! The interpreter gives motions, events, per-block state and flow-sensitive
//! diagnostics. The velocity planner is not wired yet, so the run carries no
//! timing (the preview shows "–" for times).

use std::cell::RefCell;
use std::path::PathBuf;
use std::sync::Arc;

use analyzer::{Dialect, FileId};
use runtime::{EventKind, MotionKind, ResolvedFile, Resolver, RunInput};

use super::dry_run::{BlockState, DryRunInput, DryRunner, RunReport, Segment, SegmentKind};
use super::nav::{self, Sym};
use super::workspace;

/// Upper bound on executed blocks per run (loops and calls included).
pub const STEP_BUDGET: u64 = 5_000_000;
/// Chord tolerance for sampling arcs in the preview, mm.
const CHORD_TOLERANCE: f64 = 0.01;

/// A file the resolver loaded: (name as called, path, text).
type Loaded = (String, String, Arc<[u8]>);

/// Resolves subprogram names to files next to the document, in
/// `subroutine_path`, or at the top of a workspace folder.
struct WorkspaceResolver<'a> {
    dialect: Dialect,
    doc: Option<PathBuf>,
    subroutine_path: Vec<PathBuf>,
    roots: &'a [PathBuf],
    /// Every file handed to the interpreter.
    loaded: RefCell<Vec<Loaded>>,
}

impl Resolver for WorkspaceResolver<'_> {
    fn resolve(&self, name: &str, _from: FileId) -> Option<ResolvedFile> {
        let doc = self.doc.as_deref()?;
        let path = workspace::find_program_file(
            self.dialect,
            name,
            doc,
            &self.subroutine_path,
            self.roots,
        )?;
        let (canon, text) = workspace::read_confined(&path, self.roots)?;
        let path = canon.display().to_string();
        let text: Arc<[u8]> = Arc::from(text.into_bytes());
        self.loaded
            .borrow_mut()
            .push((name.to_string(), path.clone(), text.clone()));
        Some(ResolvedFile { path, text })
    }
}

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

fn xyz(p: &[f64; 6]) -> [f64; 3] {
    [p[0], p[1], p[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(b, a);
    dot(d, d).sqrt()
}

/// Samples an arc (possibly helical) turning counter-clockwise about `normal`
/// from `start` to `end`, with `turns` extra full turns. Returns the points and
/// the exact length of the helix.
pub fn sample_arc(
    start: [f64; 3],
    end: [f64; 3],
    center: [f64; 3],
    normal: [f64; 3],
    turns: i32,
) -> (Vec<[f64; 3]>, f64) {
    let nl = dot(normal, normal).sqrt();
    // Also catches NaN: a normal that is not a positive length.
    if nl.is_nan() || nl <= 0.0 {
        return (vec![start, end], dist(start, end));
    }
    let n = scale(normal, 1.0 / nl);
    let u = sub(start, center);
    let v = sub(end, center);
    let (h0, h1) = (dot(u, n), dot(v, n));
    let up = sub(u, scale(n, h0));
    let vp = sub(v, scale(n, h1));
    let r = dot(up, up).sqrt();
    if r.is_nan() || r <= 1e-9 {
        return (vec![start, end], dist(start, end));
    }
    let mut theta = dot(cross(up, vp), n).atan2(dot(up, vp));
    if theta <= 1e-9 {
        theta += std::f64::consts::TAU;
    }
    theta += std::f64::consts::TAU * f64::from(turns.max(0));
    // Steps so that the chord error stays below the tolerance, within sane bounds.
    let max_step = 2.0 * (1.0 - (CHORD_TOLERANCE / r).min(1.0)).acos();
    let steps = ((theta / max_step.max(1e-3)).ceil() as usize).clamp(2, 4096);
    let w = cross(n, up);
    let length = ((r * theta).powi(2) + (h1 - h0).powi(2)).sqrt();
    let points = (0..=steps)
        .map(|i| {
            let t = i as f64 / steps as f64;
            let a = theta * t;
            let radial = add(scale(up, a.cos()), scale(w, a.sin()));
            add(center, add(radial, scale(n, h0 + (h1 - h0) * t)))
        })
        .collect();
    (points, length)
}

impl DryRunner for RuntimeRunner {
    fn run(&self, input: &DryRunInput<'_>) -> Option<RunReport> {
        let subs = workspace::subroutine_path(input.machine, input.config_path.as_deref());
        let subs: Vec<PathBuf> = subs
            .iter()
            .filter_map(|p| workspace::confine(p, input.roots))
            .collect();
        let resolver = WorkspaceResolver {
            dialect: input.settings.dialect,
            doc: input.doc_path.clone(),
            subroutine_path: subs,
            roots: input.roots,
            loaded: RefCell::new(Vec::new()),
        };
        let out = runtime::run(&RunInput {
            program: input.program,
            settings: input.settings,
            machine: input.machine,
            resolver: &resolver,
            step_budget: STEP_BUDGET,
            emit_canon: false,
            tool_table: None,
            var_file: None,
        });
        if input.cancel.is_cancelled() {
            return None;
        }
        let segments = out
            .motions
            .iter()
            .map(|m| {
                let (s, e) = (xyz(&m.start), xyz(&m.end));
                let (kind, (points, length)) = match m.kind {
                    MotionKind::Rapid => (SegmentKind::Rapid, (vec![s, e], dist(s, e))),
                    MotionKind::Arc {
                        center,
                        normal,
                        turns,
                        ..
                    } => (SegmentKind::Arc, sample_arc(s, e, center, normal, turns)),
                    // FIXME: exponential and involute moves are drawn as chords until
                    // the interpolator exposes sampled points.
                    _ => (SegmentKind::Feed, (vec![s, e], dist(s, e))),
                };
                Segment {
                    kind,
                    line: m.line,
                    feed: m.feed,
                    tool: m.tool,
                    points,
                    length,
                }
            })
            .collect();
        let tool_changes = out
            .events
            .iter()
            .filter(|e| e.file == FileId(0) && matches!(e.kind, EventKind::ToolChange { .. }))
            .map(|e| e.line)
            .collect();
        let snapshots = out
            .snapshots
            .into_iter()
            .map(|s| {
                s.map(|s| BlockState {
                    modal: s.modal,
                    position: s.position,
                    feed: s.feed,
                    spindle: s.spindle,
                    tool: s.tool,
                })
            })
            .collect();
        let loaded = resolver.loaded.borrow();
        let diagnostics = out
            .diagnostics
            .iter()
            .filter_map(|d| {
                if d.file == FileId(0) {
                    Some(d.clone())
                } else {
                    onto_call_site(input.program, d, &out.files, &loaded)
                }
            })
            .collect();
        Some(RunReport {
            segments,
            timing: None,
            tool_changes,
            diagnostics,
            snapshots,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    }

    #[test]
    fn quarter_circle_ccw_in_xy() {
        let (pts, len) = sample_arc(
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0; 3],
            [0.0, 0.0, 1.0],
            0,
        );
        assert!((len - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(close(pts[0], [1.0, 0.0, 0.0]));
        assert!(close(*pts.last().unwrap(), [0.0, 1.0, 0.0]));
        // Every sample is on the unit circle, in the first quadrant.
        for p in &pts {
            assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs() < 1e-9);
            assert!(p[0] >= -1e-9 && p[1] >= -1e-9);
        }
        // Chord error within 0.01 mm on r = 1: 2·acos(0.99) = 0.2838 rad per
        // step at most, so 90° takes 6 steps (7 points).
        assert_eq!(pts.len(), 7);
        for w in pts.windows(2) {
            let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
            let sagitta = 1.0 - (mid[0] * mid[0] + mid[1] * mid[1]).sqrt();
            assert!(sagitta <= CHORD_TOLERANCE, "{sagitta}");
        }
    }

    #[test]
    fn clockwise_is_ccw_about_the_negative_normal_and_helix_rises() {
        let (pts, len) = sample_arc(
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 2.0],
            [0.0; 3],
            [0.0, 0.0, -1.0],
            0,
        );
        // A quarter turn rising 2: sqrt((π/2)² + 2²).
        assert!((len - (std::f64::consts::FRAC_PI_2.powi(2) + 4.0).sqrt()).abs() < 1e-12);
        let mid = pts[pts.len() / 2];
        assert!(mid[0] > 0.0 && mid[1] < 0.0, "{mid:?}");
        assert!((mid[2] - 1.0).abs() < 0.05, "{mid:?}");
        assert!(close(*pts.last().unwrap(), [0.0, -1.0, 2.0]));
        // A full circle (start = end) sweeps 2π.
        let (full, len) = sample_arc(
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0; 3],
            [0.0, 0.0, 1.0],
            0,
        );
        assert!((len - std::f64::consts::TAU).abs() < 1e-12);
        assert!(full.iter().any(|p| p[0] < -0.99));
    }
}

#[cfg(test)]
mod run_tests {
    use super::*;
    use crate::lsp::dry_run::CancelFlag;
    use analyzer::Settings;

    fn run(text: &str) -> RunReport {
        let settings = Settings::new(Dialect::Rs274ngc);
        let program = analyzer::analyze(text.as_bytes().to_vec(), &settings).program;
        let machine = toml::Table::new();
        let cancel = CancelFlag::default();
        let input = DryRunInput {
            program: &program,
            settings: &settings,
            machine: &machine,
            doc_path: None,
            config_path: None,
            roots: &[],
            cancel: &cancel,
        };
        RuntimeRunner.run(&input).unwrap()
    }

    #[test]
    fn motions_become_segments() {
        let r = run("G21 G90\nG0 X1 Y2 Z3\nG1 X4 F100\nG2 X6 Y4 I0 J2\nM2\n");
        let kinds: Vec<(SegmentKind, u32)> = r.segments.iter().map(|s| (s.kind, s.line)).collect();
        assert_eq!(
            kinds,
            vec![
                (SegmentKind::Rapid, 1),
                (SegmentKind::Feed, 2),
                (SegmentKind::Arc, 3)
            ]
        );
        assert_eq!(r.segments[1].points, vec![[1.0, 2.0, 3.0], [4.0, 2.0, 3.0]]);
        assert_eq!(r.segments[1].feed, 100.0);
        let last = *r.segments[2].points.last().unwrap();
        assert!(
            (last[0] - 6.0).abs() < 1e-9 && (last[1] - 4.0).abs() < 1e-9,
            "{last:?}"
        );
        let s = r.snapshots[2].as_ref().unwrap();
        assert_eq!(s.position[0], 4.0);
        assert!(s.modal.iter().any(|m| m == "G1"), "{:?}", s.modal);
    }
}
