//! `check` of a file too large to hold: read in windows of whole lines
//! (`analyzer::stream` says what each part of the analysis sees).
//!
//! Three passes over the file, each holding a few windows at a time:
//! 1. every window feeds the skeleton the whole-file rules run over, and the
//!    facts the interpreter needs before it starts (single pass or not);
//! 2. every window is linted by the block rules on this thread while the
//!    interpreter, on another, runs the windows in order (a channel of one
//!    window between them bounds the memory);
//! 3. the lines the report shows are read back ([`Sparse`]).

use std::fs::File;
use std::io::Read;
use std::path::Path;
use std::sync::Arc;

use analyzer::syntax::{self, ParserState, Program};
use analyzer::{Diagnostic, Settings};

use super::output::{FileReport, Sparse};

/// Files above this size are checked in windows.
pub const STREAM_ABOVE: u64 = 32 << 20;
/// Bytes per window (the last line of a window is completed past it).
pub const WINDOW_BYTES: usize = 4 << 20;

/// Reads a file as windows of whole lines, in order.
pub struct Windows {
    file: File,
    /// Bytes read past the last complete line.
    carry: Vec<u8>,
    size: usize,
    base: u64,
    line: u32,
    done: bool,
}

/// One window: its bytes, file offset and first line.
pub struct Window {
    pub bytes: Arc<[u8]>,
    pub base: u32,
    pub line: u32,
}

impl Windows {
    pub fn open(path: &Path, size: usize) -> std::io::Result<Windows> {
        Ok(Windows {
            file: File::open(path)?,
            carry: Vec::new(),
            size: size.max(1),
            base: 0,
            line: 0,
            done: false,
        })
    }

    /// The next window, `None` at the end of the file.
    pub fn next_window(&mut self) -> std::io::Result<Option<Window>> {
        if self.done && self.carry.is_empty() {
            return Ok(None);
        }
        let mut buf = std::mem::take(&mut self.carry);
        // Read until the window holds `size` bytes and a line break, or the file ends.
        loop {
            // A CR last may be half of a CR LF: it is a break only once a byte follows.
            let before_last = &buf[..buf.len().saturating_sub(1)];
            let have_break = buf.contains(&b'\n') || before_last.contains(&b'\r');
            if self.done || (buf.len() >= self.size && have_break) {
                break;
            }
            let want = self.size.max(buf.len() / 2 + 1);
            let old = buf.len();
            buf.resize(old + want, 0);
            let n = loop {
                match self.file.read(&mut buf[old..]) {
                    Ok(n) => break n,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e),
                }
            };
            buf.truncate(old + n);
            if n == 0 {
                self.done = true;
            }
        }
        // Cut after the last `\n`; without one, after the last `\r` that a
        // later byte shows is no CR LF.
        let cut = if self.done {
            buf.len()
        } else if let Some(i) = buf.iter().rposition(|&c| c == b'\n') {
            i + 1
        } else {
            match buf[..buf.len().saturating_sub(1)]
                .iter()
                .rposition(|&c| c == b'\r')
            {
                Some(i) => i + 1,
                None => buf.len(),
            }
        };
        self.carry = buf.split_off(cut);
        if buf.is_empty() {
            return Ok(None);
        }
        let base = u32::try_from(self.base).map_err(|_| {
            std::io::Error::other("the file is larger than 4 GiB, which Partscope cannot check")
        })?;
        let w = Window {
            base,
            line: self.line,
            bytes: Arc::from(buf),
        };
        self.base += w.bytes.len() as u64;
        self.line = self
            .line
            .saturating_add(analyzer::span::line_breaks(&w.bytes));
        Ok(Some(w))
    }
}

/// Parses the windows of a file in order.
pub struct Parsed {
    windows: Windows,
    opts: syntax::ParseOptions,
    state: ParserState,
}

impl Parsed {
    pub fn new(windows: Windows, settings: &Settings) -> Parsed {
        Parsed {
            windows,
            opts: settings.parse_options(),
            state: ParserState::default(),
        }
    }

    pub fn next_program(&mut self) -> std::io::Result<Option<Program>> {
        let Some(w) = self.windows.next_window()? else {
            return Ok(None);
        };
        let (p, state) = syntax::parse_window(self.opts, w.bytes, w.base, w.line, self.state);
        self.state = state;
        Ok(Some(p))
    }
}

/// What the first pass learnt of the file.
pub struct FirstPass {
    pub skeleton: analyzer::stream::Skeleton,
    pub main: runtime::interp::MainFileFacts,
    pub signature: Option<analyzer::Signature>,
    pub blocks: usize,
}

pub fn first_pass(path: &Path, settings: &Settings, window: usize) -> std::io::Result<FirstPass> {
    let first = first_pass_with(path, settings, window, true)?;
    if first.skeleton.is_numbered() && first.skeleton.branches() {
        // A branch searches for sequence numbers: the rules need every one.
        return first_pass_with(path, settings, window, false);
    }
    Ok(first)
}

fn first_pass_with(
    path: &Path,
    settings: &Settings,
    window: usize,
    numbered: bool,
) -> std::io::Result<FirstPass> {
    let mut parsed = Parsed::new(Windows::open(path, window)?, settings);
    let mut skeleton = if numbered {
        analyzer::stream::Skeleton::for_settings(settings)
    } else {
        analyzer::stream::Skeleton::default()
    };
    let numbered = skeleton.is_numbered();
    let mut main = runtime::interp::MainFileFacts::default();
    let mut signs = analyzer::control::SignScan::default();
    let mut blocks = 0;
    while let Some(p) = parsed.next_program()? {
        skeleton.add(&p);
        main.add(&p);
        signs.add(&p);
        blocks += p.blocks.len();
        if numbered && skeleton.branches() {
            break;
        }
    }
    Ok(FirstPass {
        skeleton,
        main,
        signature: signs.finish(),
        blocks,
    })
}

/// Pass 3: the lines around every position the report names, as a
/// [`Sparse`] text.
pub fn report_lines(
    path: &Path,
    diagnostics: &[Diagnostic],
    window: usize,
) -> std::io::Result<Sparse> {
    // The ranges an excerpt shows: each diagnostic with its nearby related spans.
    let mut want: Vec<(u32, u32)> = Vec::new();
    for d in diagnostics.iter().filter(|d| d.file == analyzer::FileId(0)) {
        let (mut lo, mut hi) = (d.span.start, d.span.end.max(d.span.start));
        for r in d.related.iter().filter(|r| r.file == d.file) {
            let near = (r.span.start as usize).abs_diff(d.span.start as usize)
                <= super::excerpt::MAX_RELATED_DISTANCE;
            if near {
                lo = lo.min(r.span.start);
                hi = hi.max(r.span.end);
            } else {
                want.push((r.span.start, r.span.end.max(r.span.start)));
            }
        }
        want.push((lo, hi));
    }
    want.sort_unstable();
    let mut sparse = Sparse::default();
    let mut windows = Windows::open(path, window)?;
    let mut next = 0;
    while let Some(w) = windows.next_window()? {
        let end = w.base + w.bytes.len() as u32;
        let index = analyzer::LineIndex::new(&w.bytes);
        // Ranges that end before this window were taken by earlier ones.
        while want.get(next).is_some_and(|r| r.1 < w.base) {
            next += 1;
        }
        let mut pieces: Vec<(u32, u32)> = Vec::new();
        let mut k = next;
        while let Some(&(lo, hi)) = want.get(k) {
            if lo > end {
                break;
            }
            k += 1;
            if hi < w.base {
                continue;
            }
            let (lo, hi) = (lo.max(w.base) - w.base, hi.min(end) - w.base);
            // One line of context either side, within the window.
            let (l0, _) = index.line_col(lo);
            let (l1, _) = index.line_col(hi);
            let from = index.line_start(l0.saturating_sub(1)).unwrap_or(0);
            let to = index
                .line_start(l1 + 2)
                .unwrap_or(w.bytes.len() as u32)
                .min(w.bytes.len() as u32);
            match pieces.last_mut() {
                Some(p) if p.1 >= from => p.1 = p.1.max(to),
                _ => pieces.push((from, to)),
            }
        }
        for (from, to) in pieces {
            let (line, _) = index.line_col(from);
            sparse.push(
                w.base + from,
                w.line + line,
                &w.bytes[from as usize..to as usize],
            );
        }
    }
    Ok(sparse)
}

/// What passes 1 gives: the skeleton, the whole-file findings (moved to the
/// file and finished) and the facts every window's findings need.
struct WholeFile {
    first: FirstPass,
    skeleton: analyzer::stream::Sealed,
    findings: Vec<Diagnostic>,
    facts: analyzer::stream::FileFacts,
    /// The file's size in bytes.
    size: u64,
}

impl WholeFile {
    fn read(path: &Path, settings: &Settings, window: usize) -> std::io::Result<WholeFile> {
        let first = first_pass(path, settings, window)?;
        let skeleton = first.skeleton.seal(settings);
        let (mut findings, facts) = skeleton.check(settings);
        // The skeleton holds only some of the blocks: the signature of the
        // whole file decides P010.
        findings.retain(|d| !analyzer::stream::is_mismatch(d));
        if let Some(d) = first
            .signature
            .as_ref()
            .and_then(analyzer::stream::mismatch_finding)
        {
            let end = empty_window(settings, skeleton.end(), 0);
            let kept = analyzer::finish_window(&end, &facts, settings, vec![d]);
            if !kept.is_empty() {
                findings = kept;
            }
        }
        Ok(WholeFile {
            first,
            skeleton,
            findings,
            facts,
            size: std::fs::metadata(path)?.len(),
        })
    }

    /// The file is for another control (P010): it gets that finding alone.
    fn mismatch(&self) -> bool {
        self.findings.iter().any(analyzer::stream::is_mismatch)
    }
}

/// The report of a file read in windows: its findings, with the lines they
/// need read back (pass 3).
fn report(
    path: &Path,
    window: usize,
    dialect: &(analyzer::Dialect, String),
    diagnostics: Vec<Diagnostic>,
    files: &[String],
) -> std::io::Result<FileReport> {
    let sparse = report_lines(path, &diagnostics, window)?;
    Ok(FileReport {
        path: path.to_path_buf(),
        text: Arc::from(sparse.text.as_slice()),
        diagnostics,
        io_error: false,
        extra_files: super::output::read_extra_files(files),
        dialect: Some(dialect.clone()),
        sparse: Some(sparse),
    })
}

/// One file's check in windows.
pub struct Job<'a> {
    pub path: &'a Path,
    pub args: &'a super::CheckArgs,
    pub loaded: &'a super::workspace::LoadedConfig,
    pub settings: &'a Settings,
    pub window: usize,
    /// The limit on files the interpreter loads whole (called programs).
    pub called: crate::resolve::SizeLimit,
    /// The file is a subprogram by its name (a ServoWorks `O….dat`).
    pub subprogram_by_name: bool,
}

/// `check` of `job.path` in windows; `head` is its first bytes. `None`: the
/// file is better read whole (flow control the windows cannot run, in a file
/// small enough to hold).
pub fn check_file(
    job: &Job<'_>,
    head: Arc<[u8]>,
    dialect: (analyzer::Dialect, String),
) -> Option<FileReport> {
    let parsed = analyzer::parse_text_lean(head.clone(), job.settings);
    if parsed.binary {
        return Some(FileReport {
            path: job.path.to_path_buf(),
            text: head,
            diagnostics: analyzer::lint(&parsed, job.settings),
            io_error: false,
            extra_files: Vec::new(),
            dialect: Some(dialect),
            sparse: None,
        });
    }
    check_windows(job, &dialect)
        .unwrap_or_else(|e| Some(FileReport::io_error(job.path.to_path_buf(), e.to_string())))
}

fn check_windows(
    job: &Job<'_>,
    dialect: &(analyzer::Dialect, String),
) -> std::io::Result<Option<FileReport>> {
    let (path, settings, window) = (job.path, job.settings, job.window);
    let whole = WholeFile::read(path, settings, window)?;
    if whole.mismatch() {
        return report(path, window, dialect, whole.findings, &[]).map(Some);
    }
    let subprogram = job.subprogram_by_name
        || runtime::interp::files::is_subprogram_file(
            whole.skeleton.program(),
            settings.file_stem.as_deref(),
        );
    let single_pass = whole.first.main.single_pass();
    let run = !job.args.no_run && !subprogram;
    if run && !single_pass && holdable(whole.size) && job.args.window_bytes.is_none() {
        return Ok(None);
    }
    let interpret = run && single_pass;
    let (tx, rx) = std::sync::mpsc::sync_channel::<Arc<Program>>(1);
    let ((mut diagnostics, tail), run_out) = std::thread::scope(|s| -> std::io::Result<_> {
        let interp = interpret.then(|| s.spawn(|| run_windows(job, &whole.first, rx)));
        let linted = lint_windows(path, settings, window, &whole, Some(tx))?;
        Ok((linted, interp.and_then(|h| h.join().ok()).flatten()))
    })?;
    if run && !single_pass {
        diagnostics.push(not_run(whole.size));
    }
    let mut files = Vec::new();
    if let Some((out_diagnostics, called)) = run_out {
        let finished = analyzer::finish_window(&tail, &whole.facts, settings, out_diagnostics);
        diagnostics = analyzer::merge(diagnostics, finished, settings);
        files = called;
    }
    report(path, window, dialect, diagnostics, &files).map(Some)
}

/// An empty window at file offset `at` on line `line`: the window of an
/// empty file, or the end of one.
fn empty_window(settings: &Settings, at: u32, line: u32) -> Program {
    let opts = settings.parse_options();
    syntax::parse_window(opts, Arc::from(&b""[..]), at, line, ParserState::default()).0
}

/// Whether a file is small enough to read whole (a program with flow control
/// runs only so).
fn holdable(size: u64) -> bool {
    size <= super::workspace::DEFAULT_MAX_FILE_MB << 20
}

fn not_run(size: u64) -> Diagnostic {
    runtime::interp::not_run_in_windows(
        size.div_ceil(1 << 20),
        super::workspace::DEFAULT_MAX_FILE_MB,
    )
}

/// Pass 2's static checks: every window through the block rules (and, with
/// `feed`, to the interpreter as well), joined with the whole-file findings
/// and finished. Also returns an empty window at the end of the file, which
/// the findings made once for the file are finished with.
fn lint_windows(
    path: &Path,
    settings: &Settings,
    window: usize,
    whole: &WholeFile,
    mut feed: Option<std::sync::mpsc::SyncSender<Arc<Program>>>,
) -> std::io::Result<(Vec<Diagnostic>, Program)> {
    let facts = &whole.facts;
    let mut checks = analyzer::stream::WindowChecks::new(settings, &whole.first.skeleton);
    // The windows' findings come in file order: bounded as they come.
    let mut statics = analyzer::Limiter::new(settings);
    let mut end = None;
    let mut parsed = Parsed::new(Windows::open(path, window)?, settings);
    let mut utf8 = true;
    // The interpreter may stop before the end (and drop its end).
    while let Some(p) = parsed.next_program()? {
        let p = Arc::new(p);
        if feed.as_ref().is_some_and(|tx| tx.send(p.clone()).is_err()) {
            feed = None;
        }
        let found = checks.check(&p, settings, facts, utf8);
        utf8 &= !found
            .iter()
            .any(|d| d.code == analyzer::rules::NOT_TEXT.code);
        for d in found {
            statics.push(d);
        }
        end = Some((p.end_offset(), p.blocks.last().map_or(0, |b| b.line)));
    }
    drop(feed);
    let mut statics = statics.finish();
    statics.extend(whole.findings.iter().cloned());
    let (at, line) = end.unwrap_or((0, 0));
    let tail = empty_window(settings, at, line);
    statics.extend(checks.finish(&tail, facts, settings));
    Ok((analyzer::join_finished(statics, settings), tail))
}

/// What `run` needs besides the program (`runtime::RunInput` without it).
pub struct RunParts<'a> {
    pub settings: &'a Settings,
    pub machine: &'a analyzer::config::MachineConfig,
    pub resolver: &'a dyn runtime::Resolver,
    pub tool_table: Option<&'a str>,
    pub var_file: Option<&'a str>,
    pub step_budget: Option<u64>,
    pub motion_budget: Option<u64>,
}

impl RunParts<'_> {
    /// The run's input with `program` (the file, or its first window); the
    /// budgets default to those of a file of `blocks` blocks.
    pub fn input<'p>(&'p self, program: &'p Program, blocks: usize) -> runtime::RunInput<'p> {
        runtime::RunInput {
            program,
            settings: self.settings,
            machine: self.machine,
            resolver: self.resolver,
            step_budget: self
                .step_budget
                .unwrap_or_else(|| runtime::default_step_budget(blocks)),
            motion_budget: self
                .motion_budget
                .unwrap_or_else(|| runtime::default_motion_budget(blocks)),
            emit_canon: false,
            tool_table: self.tool_table,
            var_file: self.var_file,
        }
    }
}

/// `run`'s figures of a file read in windows.
pub struct RunWindows {
    /// The findings and the lines they need, as for `check`.
    pub report: FileReport,
    /// The run's output (motions and events went to the planner), `None` when
    /// no run was made: a program for another control (P010), or one with flow
    /// control too large to hold (F004).
    pub out: Option<runtime::RunOutput>,
    pub totals: runtime::plan::Totals,
}

/// `run`'s summary of `path` in windows: the static checks on one thread while
/// the interpreter reads the file again on this one and the planner plans on
/// a third (`run::plan_beside_with`, which passes over the file twice when a
/// long program needs the closed-form planner).
pub fn run_file(
    path: &Path,
    window: usize,
    parts: &RunParts<'_>,
    profile: &runtime::machine::MachineProfile,
    dialect: (analyzer::Dialect, String),
) -> std::io::Result<RunWindows> {
    let settings = parts.settings;
    let whole = WholeFile::read(path, settings, window)?;
    let none = |diagnostics| -> std::io::Result<RunWindows> {
        Ok(RunWindows {
            report: report(path, window, &dialect, diagnostics, &[])?,
            out: None,
            totals: Default::default(),
        })
    };
    if whole.mismatch() {
        return none(whole.findings);
    }
    if !whole.first.main.single_pass() {
        let (mut diagnostics, _) = lint_windows(path, settings, window, &whole, None)?;
        diagnostics.push(not_run(whole.size));
        return none(diagnostics);
    }
    let (linted, run) = std::thread::scope(|s| {
        let lint = s.spawn(|| lint_windows(path, settings, window, &whole, None));
        let (out, totals, _) = super::run::plan_beside_with(profile, false, |sink| {
            run_pass(path, window, &whole.first, parts, sink)
        });
        (lint.join(), (out, totals))
    });
    let (statics, tail) =
        linted.map_err(|_| std::io::Error::other("the static checks failed"))??;
    let (out, totals) = run;
    let mut out = out?;
    let finished = analyzer::finish_window(
        &tail,
        &whole.facts,
        settings,
        std::mem::take(&mut out.diagnostics),
    );
    let diagnostics = analyzer::merge(statics, finished, settings);
    Ok(RunWindows {
        report: report(path, window, &dialect, diagnostics, &out.files)?,
        out: Some(out),
        totals,
    })
}

/// One pass of the interpreter over the file's windows, its motions to `sink`.
fn run_pass(
    path: &Path,
    window: usize,
    first: &FirstPass,
    parts: &RunParts<'_>,
    sink: &mut runtime::interp::OwnedMotionSink<'_>,
) -> std::io::Result<runtime::RunOutput> {
    let mut parsed = Parsed::new(Windows::open(path, window)?, parts.settings);
    let program = match parsed.next_program()? {
        Some(p) => p,
        None => empty_window(parts.settings, 0, 0),
    };
    let input = parts.input(&program, first.blocks);
    let mut failed = None;
    let mut next = || match parsed.next_program() {
        Ok(p) => p.map(Arc::new),
        Err(e) => {
            failed = Some(e);
            None
        }
    };
    let out = runtime::interp::run_windowed_owned(&input, &first.main, &mut next, sink);
    match failed {
        Some(e) => Err(e),
        None => Ok(out),
    }
}

/// The interpreter's thread: runs the windows `rx` brings, in order.
fn run_windows(
    job: &Job<'_>,
    first: &FirstPass,
    rx: std::sync::mpsc::Receiver<Arc<Program>>,
) -> Option<(Vec<Diagnostic>, Vec<String>)> {
    let settings = job.settings;
    // An empty file has no window: it runs as an empty program.
    let program = rx
        .recv()
        .unwrap_or_else(|_| Arc::new(empty_window(settings, 0, 0)));
    super::check::with_run_parts(
        job.path,
        settings,
        job.loaded,
        job.args,
        job.called,
        |parts| {
            let input = parts.input(&program, first.blocks);
            let mut next = || rx.recv().ok();
            let out = runtime::interp::run_windowed(&input, &first.main, &mut next, &mut |_, _| {});
            Some((out.diagnostics, out.files))
        },
    )
}
