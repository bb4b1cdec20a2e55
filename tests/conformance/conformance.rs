//! RS274/NGC conformance: `partscope run --dialect rs274ngc --emit canon` against LinuxCNC's
//! own interpreter.
//!
//! Two sources of reference output are compared with what our binary prints:
//!
//! * `tests/conformance/programs/*.ngc` with goldens in `tests/conformance/goldens/`, produced
//!   by `tests/conformance/regenerate.sh` from the real `rs274` (see that script's header);
//! * the LinuxCNC test corpus in `../shared/corpus/linuxcnc` (GPL data, read at test time and
//!   never copied), for the tests whose recorded command is a plain `rs274` run.
//!
//! Conformance is incomplete while the emitter is being written, so this test does not demand
//! that everything matches.  It prints a table and enforces a ratchet instead: every program
//! named in `tests/conformance/baseline.toml` must keep matching at the level it is listed
//! under, and programs that newly match are reported so the baseline can be raised.  Run with
//! `UPDATE_BASELINE=1` to rewrite the baseline from the current results.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Mutex};
use std::thread;
use std::time::{Duration, Instant};

/// A run that takes longer than this is killed and counted as a failure, so a looping
/// interpreter shows up as a failing row instead of a hung test.
const RUN_TIMEOUT: Duration = Duration::from_secs(10);

/// Numeric tolerance of the motion comparison; rs274 prints every real with `%.4f`, so a
/// difference of one unit in the last printed digit is still accepted at this level.
const MOTION_TOLERANCE: f64 = 1e-4;

/// The canonical calls that describe where the tool goes and for how long it waits.
const MOTION_CALLS: [&str; 4] = ["STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "DWELL"];

/// The binary under test: normally the one cargo built for this package; `PARTSCOPE_BIN`
/// substitutes another program with the same command line (`oracle-shim.sh` runs the real
/// rs274 that way, which checks this harness's own normalisations end to end).
fn partscope() -> PathBuf {
    std::env::var_os("PARTSCOPE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_partscope")))
}

fn repo_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

fn conformance_dir() -> PathBuf {
    repo_root().join("tests").join("conformance")
}

/// The corpus lives beside the checkout (`../shared`) for the main tree; worktrees sit one
/// level deeper, and `PARTSCOPE_CORPUS` overrides both.
fn corpus_dir() -> Option<PathBuf> {
    if let Ok(dir) = std::env::var("PARTSCOPE_CORPUS") {
        let dir = PathBuf::from(dir);
        return dir.join("TEST_COMMANDS.tsv").is_file().then_some(dir);
    }
    let root = repo_root();
    let candidates = [
        root.join("../shared/corpus/linuxcnc"),
        root.join("../../shared/corpus/linuxcnc"),
    ];
    candidates
        .into_iter()
        .find(|dir| dir.join("TEST_COMMANDS.tsv").is_file())
}

// ---------------------------------------------------------------------------------------
// Running the binary
// ---------------------------------------------------------------------------------------

/// What one run of our binary produced.
#[derive(Debug, Default)]
struct RunOutput {
    stdout: String,
    stderr: String,
    /// The exit code; `None` when the process was killed (timeout or signal) or never started.
    code: Option<i32>,
    timed_out: bool,
    /// Why the process could not be started, if it could not.
    spawn_error: Option<String>,
}

/// Runs `partscope run --dialect rs274ngc --emit canon` on `program` from the program's own
/// directory (relative subroutine paths then resolve the way they do for rs274).
fn run_partscope(program: &Path, tool_table: Option<&Path>, var_file: Option<&Path>) -> RunOutput {
    // The real interpreter rewrites its parameter file on exit; a scratch copy keeps the
    // committed inputs untouched whatever our implementation does with the file.
    let scratch_var = var_file.and_then(|var| {
        static SEQ: AtomicUsize = AtomicUsize::new(0);
        let name = format!(
            "partscope-conformance-{}-{}.var",
            std::process::id(),
            SEQ.fetch_add(1, Ordering::Relaxed)
        );
        let copy = std::env::temp_dir().join(name);
        fs::copy(var, &copy).ok().map(|_| copy)
    });
    let mut cmd = Command::new(partscope());
    cmd.args(["run", "--dialect", "rs274ngc", "--emit", "canon"]);
    if let Some(tbl) = tool_table {
        cmd.arg("--tool-table").arg(tbl);
    }
    // Should the copy fail, the original is still the right input to pass.
    if let Some(var) = scratch_var.as_deref().or(var_file) {
        cmd.arg("--var-file").arg(var);
    }
    cmd.arg(program);
    if let Some(dir) = program.parent() {
        cmd.current_dir(dir);
    }
    let out = run_with_timeout(cmd, RUN_TIMEOUT);
    if let Some(copy) = scratch_var {
        let _ = fs::remove_file(&copy);
        let _ = fs::remove_file(copy.with_extension("var.bak"));
    }
    out
}

fn run_with_timeout(mut cmd: Command, timeout: Duration) -> RunOutput {
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    // A process group of its own lets a timeout kill everything the run started (a wrapper
    // script's children too), so no orphan keeps our pipes open.
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        cmd.process_group(0);
    }
    let mut child = match cmd.spawn() {
        Ok(child) => child,
        Err(err) => {
            return RunOutput {
                spawn_error: Some(err.to_string()),
                ..RunOutput::default()
            }
        }
    };
    // Both pipes are drained on their own threads so a chatty child cannot block on a full
    // pipe while we wait for it to exit.
    let stdout_reader = child.stdout.take().map(drain);
    let stderr_reader = child.stderr.take().map(drain);
    let deadline = Instant::now() + timeout;
    let mut timed_out = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if Instant::now() >= deadline => {
                timed_out = true;
                kill_group(&mut child);
                break child.wait().ok();
            }
            Ok(None) => thread::sleep(Duration::from_millis(5)),
            Err(_) => break None,
        }
    };
    // Output still arriving a second after the process ended comes from a straggler we could
    // not kill; it is dropped rather than waited for.
    let collect = |reader: Option<mpsc::Receiver<Vec<u8>>>| {
        reader
            .and_then(|rx| rx.recv_timeout(Duration::from_secs(1)).ok())
            .map(|bytes| String::from_utf8_lossy(&bytes).into_owned())
            .unwrap_or_default()
    };
    RunOutput {
        stdout: collect(stdout_reader),
        stderr: collect(stderr_reader),
        code: if timed_out {
            None
        } else {
            status.and_then(|s| s.code())
        },
        timed_out,
        spawn_error: None,
    }
}

/// Reads a pipe to its end on a helper thread and hands the bytes over through a channel.
fn drain(mut pipe: impl Read + Send + 'static) -> mpsc::Receiver<Vec<u8>> {
    let (tx, rx) = mpsc::channel();
    thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = pipe.read_to_end(&mut buf);
        let _ = tx.send(buf);
    });
    rx
}

/// Kills the child's whole process group (it was started as the group leader), falling back
/// to the child alone.
fn kill_group(child: &mut std::process::Child) {
    #[cfg(unix)]
    {
        let group = format!("-{}", child.id());
        let killed = Command::new("kill")
            .args(["-KILL", "--", &group])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|status| status.success());
        if killed {
            return;
        }
    }
    let _ = child.kill();
}

/// Runs `jobs` on a few worker threads and returns the results in input order.
fn parallel_map<T: Sync, R: Send>(jobs: &[T], work: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let workers = thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(2)
        .clamp(1, 4)
        .min(jobs.len().max(1));
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<R>>> = Mutex::new((0..jobs.len()).map(|_| None).collect());
    thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| loop {
                let index = next.fetch_add(1, Ordering::Relaxed);
                let Some(job) = jobs.get(index) else { break };
                let result = work(job);
                if let Ok(mut slots) = results.lock() {
                    slots[index] = Some(result);
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap_or_default()
        .into_iter()
        .map(|slot| slot.expect("every job index was processed by a worker"))
        .collect()
}

// ---------------------------------------------------------------------------------------
// Comparing canonical output
// ---------------------------------------------------------------------------------------

/// How closely the motion calls of two outputs agree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum MotionMatch {
    No,
    /// Same calls, every number within [`MOTION_TOLERANCE`].
    Tolerance,
    /// Same calls, every number identical once printed with `%.4f` (and `-0.0000` read as
    /// `0.0000`).
    Exact,
}

impl MotionMatch {
    fn label(self) -> &'static str {
        match self {
            MotionMatch::No => "no",
            MotionMatch::Tolerance => "tol",
            MotionMatch::Exact => "yes",
        }
    }
}

/// One motion call reduced to its name and arguments; the `N.....` prefix is dropped because
/// it is not motion.
#[derive(Debug, PartialEq)]
struct Call {
    name: String,
    args: Vec<String>,
}

fn motion_calls(canon: &str) -> Vec<Call> {
    canon.lines().filter_map(parse_motion_call).collect()
}

fn parse_motion_call(line: &str) -> Option<Call> {
    let body = line.trim_start();
    // Skip the "N....." / "N10" block-number field that precedes every call.
    let body = match body.split_once(' ') {
        Some((first, rest)) if first.starts_with('N') => rest.trim_start(),
        _ => body,
    };
    let (name, rest) = body.split_once('(')?;
    if !MOTION_CALLS.contains(&name) {
        return None;
    }
    let inner = rest.strip_suffix(')').unwrap_or(rest);
    let args = inner.split(',').map(|arg| arg.trim().to_string()).collect();
    Some(Call {
        name: name.to_string(),
        args,
    })
}

fn format4(value: f64) -> String {
    let text = format!("{value:.4}");
    if text == "-0.0000" {
        "0.0000".to_string()
    } else {
        text
    }
}

fn compare_motion(ours: &str, reference: &str) -> MotionMatch {
    let ours = motion_calls(ours);
    let reference = motion_calls(reference);
    if ours.len() != reference.len() {
        return MotionMatch::No;
    }
    let mut level = MotionMatch::Exact;
    for (a, b) in ours.iter().zip(&reference) {
        if a.name != b.name || a.args.len() != b.args.len() {
            return MotionMatch::No;
        }
        for (x, y) in a.args.iter().zip(&b.args) {
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) => {
                    if format4(x) == format4(y) {
                        continue;
                    }
                    // A small slack above the tolerance absorbs the binary representation of
                    // values such as 0.0001 themselves.
                    if (x - y).abs() <= MOTION_TOLERANCE + 1e-9 {
                        level = MotionMatch::Tolerance;
                    } else {
                        return MotionMatch::No;
                    }
                }
                _ if x == y => {}
                _ => return MotionMatch::No,
            }
        }
    }
    level
}

/// rs274 itself prints a five-wide counter before every canonical call; our binary (like
/// `run_rs274.sh`) leaves it out.  Corpus expectations were recorded from raw rs274 output, so
/// the counter is put back on every line that carries a block-number field.  `(print,…)`
/// lines never had one.
fn add_counter(stdout: &str) -> String {
    let mut counter = 0usize;
    let mut out = String::with_capacity(stdout.len() + stdout.len() / 8);
    for line in stdout.split_inclusive('\n') {
        let is_call = line
            .strip_prefix(" N")
            .and_then(|rest| rest.chars().next())
            .is_some_and(|c| c == '.' || c.is_ascii_digit());
        if is_call {
            counter += 1;
            let _ = write!(out, "{counter:5}");
        }
        out.push_str(line);
    }
    out
}

/// `awk '{$1=""; print}'`: drop the first field and rejoin the others with single spaces; the
/// emptied first field leaves a leading space.
fn awk_drop_first_field(line: &str) -> String {
    let fields: Vec<&str> = line.split_whitespace().collect();
    if fields.len() <= 1 {
        String::new()
    } else {
        format!(" {}", fields[1..].join(" "))
    }
}

/// The post-processing steps LinuxCNC's test scripts apply to rs274's stdout.
#[derive(Debug, Clone, PartialEq)]
enum Filter {
    /// `awk '{$1=""; print}'`
    DropFirstField,
    /// `awk '/MESSAGE/ {$1=""; print}'`
    MessagesDropFirstField,
    /// `sed 's/-0\.0000/0.0000/g'`
    NegativeZero,
}

fn apply_filters(raw: &str, filters: &[Filter]) -> String {
    let mut text = raw.to_string();
    for filter in filters {
        text = match filter {
            Filter::DropFirstField => text
                .lines()
                .map(|line| awk_drop_first_field(line) + "\n")
                .collect(),
            Filter::MessagesDropFirstField => text
                .lines()
                .filter(|line| line.contains("MESSAGE"))
                .map(|line| awk_drop_first_field(line) + "\n")
                .collect(),
            Filter::NegativeZero => text.replace("-0.0000", "0.0000"),
        };
    }
    text
}

// ---------------------------------------------------------------------------------------
// Our programs with committed goldens
// ---------------------------------------------------------------------------------------

struct Program {
    name: String,
    ngc: PathBuf,
    tbl: Option<PathBuf>,
    var: Option<PathBuf>,
    canon: String,
    stderr: String,
    status: i32,
}

fn load_programs() -> Vec<Program> {
    let dir = conformance_dir();
    let programs = dir.join("programs");
    let goldens = dir.join("goldens");
    let mut names: Vec<String> = fs::read_dir(&programs)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .filter_map(|e| {
                    let path = e.path();
                    (path.extension()? == "ngc")
                        .then(|| path.file_stem()?.to_str().map(str::to_string))?
                })
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    // CONFORMANCE_FILTER=substring narrows the run while working on one feature.
    if let Ok(filter) = std::env::var("CONFORMANCE_FILTER") {
        names.retain(|name| name.contains(&filter));
    }
    names
        .into_iter()
        .filter_map(|name| {
            let read = |ext: &str| fs::read_to_string(goldens.join(format!("{name}.{ext}"))).ok();
            let status = read("status")?.trim().parse().ok()?;
            let existing = |ext: &str| {
                let path = programs.join(format!("{name}.{ext}"));
                path.is_file().then_some(path)
            };
            Some(Program {
                ngc: programs.join(format!("{name}.ngc")),
                tbl: existing("tbl"),
                var: existing("var"),
                canon: read("canon")?,
                stderr: read("stderr").unwrap_or_default(),
                status,
                name,
            })
        })
        .collect()
}

struct ProgramResult {
    name: String,
    canon: bool,
    stderr: bool,
    status: bool,
    motion: MotionMatch,
    note: String,
}

impl ProgramResult {
    fn exact(&self) -> bool {
        self.canon && self.stderr && self.status
    }
}

fn check_program(program: &Program) -> ProgramResult {
    let out = run_partscope(&program.ngc, program.tbl.as_deref(), program.var.as_deref());
    // Messages that name the file carry its directory; the goldens were stored without it.
    let dir_prefix = program
        .ngc
        .parent()
        .map(|dir| format!("{}/", dir.display()))
        .unwrap_or_default();
    let stderr = out.stderr.replace(&dir_prefix, "");
    let note = if let Some(err) = &out.spawn_error {
        format!("cannot start: {err}")
    } else if out.timed_out {
        format!("killed after {}s", RUN_TIMEOUT.as_secs())
    } else if out.code.is_none() {
        "killed by a signal".to_string()
    } else if out.code != Some(program.status) {
        let first = stderr.lines().next().unwrap_or("").trim();
        format!("exit {:?}: {}", out.code.unwrap_or(-1), truncate(first, 60))
    } else {
        String::new()
    };
    ProgramResult {
        name: program.name.clone(),
        canon: out.stdout == program.canon,
        stderr: stderr == program.stderr,
        status: out.code == Some(program.status),
        motion: compare_motion(&out.stdout, &program.canon),
        note,
    }
}

fn truncate(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        text.to_string()
    } else {
        let cut: String = text.chars().take(max).collect();
        format!("{cut}…")
    }
}

// ---------------------------------------------------------------------------------------
// The LinuxCNC corpus
// ---------------------------------------------------------------------------------------

/// A recorded `rs274 [-t T] [-v V] -g FILE [| filters]` command, paths resolved against the
/// test directory.
#[derive(Debug, PartialEq)]
struct PlainRun {
    program: PathBuf,
    tbl: Option<PathBuf>,
    var: Option<PathBuf>,
    filters: Vec<Filter>,
}

/// How one corpus test decides pass or fail.
enum CorpusCheck {
    /// A plain run whose filtered output is compared with the `expected` file.
    Expected { run: PlainRun, expected: PathBuf },
    /// `tests/interp/bad`: the program must fail, and the second-to-last stderr line must be
    /// the message written in the program's first line (`;msg` or `(msg)`).
    BadProgram { program: PathBuf, message: String },
    /// `tests/interp/good`: raw stdout (with counter) must equal `<file>.expected`.
    GoodProgram { program: PathBuf, expected: PathBuf },
}

struct CorpusTest {
    id: String,
    check: CorpusCheck,
}

/// Parses a recorded test command; `None` unless it is a single plain rs274 invocation whose
/// options our CLI can reproduce (tool table, parameter file, stop-at-first-error).
fn parse_plain_command(dir: &Path, command: &str) -> Option<PlainRun> {
    let mut stages = command.split(" | ").map(str::trim);
    let invocation = stages.next()?;
    // Several commands, redirections, background jobs and shell variables all mean the
    // test needs more than one plain run.
    if invocation.contains([';', '>', '&', '$', '!']) {
        return None;
    }
    let mut words = invocation.split_whitespace();
    if words.next()? != "rs274" {
        return None;
    }
    let (mut program, mut tbl, mut var) = (None, None, None);
    while let Some(word) = words.next() {
        match word {
            "-g" => {}
            "-t" => tbl = Some(dir.join(words.next()?)),
            "-v" => var = Some(dir.join(words.next()?)),
            "-n" if words.next()? == "2" => {}
            flag if flag.starts_with('-') => return None,
            file if program.is_none() => program = Some(dir.join(file)),
            _ => return None,
        }
    }
    let mut filters = Vec::new();
    for stage in stages {
        filters.push(match stage {
            r#"awk '{$1=""; print}'"# => Filter::DropFirstField,
            r#"awk '/MESSAGE/ {$1=""; print}'"# => Filter::MessagesDropFirstField,
            r"sed 's/-0\.0000/0.0000/g'" => Filter::NegativeZero,
            _ => return None,
        });
    }
    Some(PlainRun {
        program: program?,
        tbl,
        var,
        filters,
    })
}

/// Reads the message a `tests/interp/bad` program declares on its first line.
fn declared_error(first_line: &str) -> String {
    let line = first_line.trim_end_matches(['\r', '\n']);
    if let Some(rest) = line.strip_prefix(';') {
        rest.to_string()
    } else if let Some(rest) = line.strip_prefix('(') {
        let mut chars = rest.chars();
        chars.next_back();
        chars.as_str().to_string()
    } else {
        String::new()
    }
}

fn load_corpus(corpus: &Path) -> (Vec<CorpusTest>, usize) {
    let Ok(table) = fs::read_to_string(corpus.join("TEST_COMMANDS.tsv")) else {
        return (Vec::new(), 0);
    };
    let mut tests = Vec::new();
    let mut skipped = 0;
    for row in table.lines().skip(1) {
        let mut cols = row.splitn(3, '\t');
        let (Some(test_dir), Some(check), Some(command)) = (cols.next(), cols.next(), cols.next())
        else {
            continue;
        };
        let dir = corpus.join(test_dir);
        match (test_dir, check) {
            ("tests/interp/bad", "checkresult") => {
                for program in sorted_files(&dir, ".ngc") {
                    let first = fs::read_to_string(&program)
                        .ok()
                        .and_then(|text| text.lines().next().map(str::to_string))
                        .unwrap_or_default();
                    tests.push(CorpusTest {
                        id: format!("{test_dir}/{}", file_name(&program)),
                        check: CorpusCheck::BadProgram {
                            message: declared_error(&first),
                            program,
                        },
                    });
                }
            }
            ("tests/interp/good", "checkresult") => {
                for program in sorted_files(&dir, ".ngc") {
                    let expected = PathBuf::from(format!("{}.expected", program.display()));
                    if expected.is_file() {
                        tests.push(CorpusTest {
                            id: format!("{test_dir}/{}", file_name(&program)),
                            check: CorpusCheck::GoodProgram { program, expected },
                        });
                    }
                }
            }
            (_, "expected") => {
                let expected = dir.join("expected");
                match parse_plain_command(&dir, command) {
                    Some(run) if expected.is_file() && run.program.is_file() => {
                        tests.push(CorpusTest {
                            id: test_dir.to_string(),
                            check: CorpusCheck::Expected { run, expected },
                        })
                    }
                    _ => skipped += 1,
                }
            }
            _ => skipped += 1,
        }
    }
    (tests, skipped)
}

fn sorted_files(dir: &Path, suffix: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.to_str().is_some_and(|s| s.ends_with(suffix)))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Returns whether the test passed and, when it did not, a short reason.
fn check_corpus(test: &CorpusTest) -> (bool, String) {
    match &test.check {
        CorpusCheck::Expected { run, expected } => {
            let out = run_partscope(&run.program, run.tbl.as_deref(), run.var.as_deref());
            let Ok(expected) = fs::read_to_string(expected) else {
                return (false, "unreadable expected".into());
            };
            if out.timed_out {
                return (false, "timeout".into());
            }
            let ours = apply_filters(&add_counter(&out.stdout), &run.filters);
            if ours == expected {
                (true, String::new())
            } else {
                (false, first_difference(&ours, &expected))
            }
        }
        CorpusCheck::BadProgram { program, message } => {
            let out = run_partscope(program, None, None);
            if out.code == Some(0) {
                return (false, "accepted bad gcode".into());
            }
            if out.code.is_none() {
                return (false, "killed".into());
            }
            let lines: Vec<&str> = out.stderr.lines().collect();
            let got = lines
                .len()
                .checked_sub(2)
                .and_then(|i| lines.get(i))
                .map(|l| l.trim())
                .unwrap_or("");
            if got == message.trim() {
                (true, String::new())
            } else {
                (false, format!("got error {:?}", truncate(got, 50)))
            }
        }
        CorpusCheck::GoodProgram { program, expected } => {
            let out = run_partscope(program, None, None);
            let Ok(expected) = fs::read_to_string(expected) else {
                return (false, "unreadable expected".into());
            };
            let ours = add_counter(&out.stdout);
            if ours == expected {
                (true, String::new())
            } else {
                (false, first_difference(&ours, &expected))
            }
        }
    }
}

fn first_difference(ours: &str, expected: &str) -> String {
    let mut ours_lines = ours.lines();
    for (n, want) in expected.lines().enumerate() {
        match ours_lines.next() {
            Some(got) if got == want => {}
            Some(got) => return format!("line {}: got {:?}", n + 1, truncate(got.trim(), 50)),
            None => return format!("output ends before line {}", n + 1),
        }
    }
    "extra output lines".to_string()
}

// ---------------------------------------------------------------------------------------
// Baseline ratchet
// ---------------------------------------------------------------------------------------

#[derive(Debug, Default, PartialEq)]
struct Baseline {
    exact: BTreeSet<String>,
    motion: BTreeSet<String>,
    status: BTreeSet<String>,
    corpus: BTreeSet<String>,
}

const BASELINE_KEYS: [&str; 4] = ["exact", "motion", "status", "corpus"];

fn baseline_path() -> PathBuf {
    conformance_dir().join("baseline.toml")
}

fn read_baseline(path: &Path) -> Result<Baseline, String> {
    let text = match fs::read_to_string(path) {
        Ok(text) => text,
        Err(err) if err.kind() == std::io::ErrorKind::NotFound => return Ok(Baseline::default()),
        Err(err) => return Err(format!("{}: {err}", path.display())),
    };
    let table: toml::Table = text
        .parse()
        .map_err(|err| format!("{}: {err}", path.display()))?;
    let mut baseline = Baseline::default();
    for (key, value) in &table {
        let set = match key.as_str() {
            "exact" => &mut baseline.exact,
            "motion" => &mut baseline.motion,
            "status" => &mut baseline.status,
            "corpus" => &mut baseline.corpus,
            other => return Err(format!("{}: unknown key `{other}`", path.display())),
        };
        let items = value
            .as_array()
            .ok_or_else(|| format!("{}: `{key}` must be an array", path.display()))?;
        for item in items {
            let name = item
                .as_str()
                .ok_or_else(|| format!("{}: `{key}` holds a non-string", path.display()))?;
            set.insert(name.to_string());
        }
    }
    Ok(baseline)
}

fn render_baseline(baseline: &Baseline) -> String {
    let mut text = String::from(
        "# Conformance ratchet for tests/conformance/conformance.rs.\n\
         # Every name listed here must keep matching rs274 at that level; the test fails on a\n\
         # regression and prints newly matching names.  Regenerate with\n\
         #   UPDATE_BASELINE=1 cargo test -p partscope --test conformance\n\
         # exact:  stdout, stderr and exit status identical to the golden\n\
         # motion: STRAIGHT_TRAVERSE/STRAIGHT_FEED/ARC_FEED/DWELL agree within 1e-4\n\
         # status: both succeed or both fail (same exit status)\n\
         # corpus: LinuxCNC corpus tests (../shared/corpus/linuxcnc) that pass\n",
    );
    for key in BASELINE_KEYS {
        let set = match key {
            "exact" => &baseline.exact,
            "motion" => &baseline.motion,
            "status" => &baseline.status,
            _ => &baseline.corpus,
        };
        if set.is_empty() {
            let _ = writeln!(text, "{key} = []");
        } else {
            let _ = writeln!(text, "{key} = [");
            for name in set {
                let _ = writeln!(text, "    {name:?},");
            }
            text.push_str("]\n");
        }
    }
    text
}

/// Names in `listed` that are missing from `now` (regressions), and names in `now` that are
/// not yet listed (improvements).
fn ratchet(listed: &BTreeSet<String>, now: &BTreeSet<String>) -> (Vec<String>, Vec<String>) {
    (
        listed.difference(now).cloned().collect(),
        now.difference(listed).cloned().collect(),
    )
}

// ---------------------------------------------------------------------------------------
// The test
// ---------------------------------------------------------------------------------------

#[test]
fn rs274ngc_conformance() {
    let baseline_file = baseline_path();
    let baseline = read_baseline(&baseline_file).unwrap_or_else(|err| panic!("{err}"));

    let programs = load_programs();
    let filter = std::env::var("CONFORMANCE_FILTER").ok();
    let selected = |name: &str| filter.as_deref().is_none_or(|f| name.contains(f));
    let update = std::env::var_os("UPDATE_BASELINE").is_some_and(|v| v == "1");
    assert!(
        !(update && filter.is_some()),
        "UPDATE_BASELINE=1 needs the full run; unset CONFORMANCE_FILTER"
    );
    assert!(
        filter.is_some() || programs.len() >= 40,
        "expected the committed conformance programs with goldens, found {}",
        programs.len()
    );
    let started = Instant::now();
    let results = parallel_map(&programs, check_program);

    let mut report = String::new();
    let _ = writeln!(
        report,
        "\n{:<28} {:>5} {:>5} {:>6} {:>6} {:>6}  note",
        "program", "exact", "canon", "stderr", "motion", "status"
    );
    let yes_no = |b: bool| if b { "yes" } else { "no" };
    for r in &results {
        let _ = writeln!(
            report,
            "{:<28} {:>5} {:>5} {:>6} {:>6} {:>6}  {}",
            r.name,
            yes_no(r.exact()),
            yes_no(r.canon),
            yes_no(r.stderr),
            r.motion.label(),
            yes_no(r.status),
            r.note
        );
    }
    let mut now = Baseline::default();
    for r in &results {
        if r.exact() {
            now.exact.insert(r.name.clone());
        }
        if r.motion >= MotionMatch::Tolerance {
            now.motion.insert(r.name.clone());
        }
        if r.status {
            now.status.insert(r.name.clone());
        }
    }
    let motion_exact = results
        .iter()
        .filter(|r| r.motion == MotionMatch::Exact)
        .count();
    let _ = writeln!(
        report,
        "programs: {} | exact {} | motion {} (exact after %.4f: {}) | status agree {} | {:.1}s",
        results.len(),
        now.exact.len(),
        now.motion.len(),
        motion_exact,
        now.status.len(),
        started.elapsed().as_secs_f64()
    );

    // The corpus is optional: it lives outside the repository and is absent on most machines.
    let corpus_present;
    match corpus_dir() {
        Some(corpus) => {
            corpus_present = true;
            let (mut tests, skipped) = load_corpus(&corpus);
            tests.retain(|test| selected(&test.id));
            let started = Instant::now();
            let outcomes = parallel_map(&tests, check_corpus);
            let _ = writeln!(report, "\n{:<56} {:>4}  note", "corpus test", "pass");
            for (test, (pass, note)) in tests.iter().zip(&outcomes) {
                let _ = writeln!(report, "{:<56} {:>4}  {}", test.id, yes_no(*pass), note);
                if *pass {
                    now.corpus.insert(test.id.clone());
                }
            }
            let _ = writeln!(
                report,
                "corpus ({}): {} runnable, {} pass, {} entries skipped (need -i/-p/2>&1/multiple commands or the full stack) | {:.1}s",
                corpus.display(),
                tests.len(),
                now.corpus.len(),
                skipped,
                started.elapsed().as_secs_f64()
            );
        }
        None => {
            corpus_present = false;
            let _ = writeln!(
                report,
                "corpus: ../shared/corpus/linuxcnc not found, 0 corpus tests run (set PARTSCOPE_CORPUS to point at it)"
            );
            now.corpus = baseline
                .corpus
                .iter()
                .filter(|n| selected(n))
                .cloned()
                .collect();
        }
    }

    let mut regressions = Vec::new();
    let mut improvements = Vec::new();
    let pairs = [
        ("exact", &baseline.exact, &now.exact),
        ("motion", &baseline.motion, &now.motion),
        ("status", &baseline.status, &now.status),
        ("corpus", &baseline.corpus, &now.corpus),
    ];
    for (key, listed, current) in pairs {
        let listed: BTreeSet<String> = listed.iter().filter(|n| selected(n)).cloned().collect();
        let (lost, gained) = ratchet(&listed, current);
        regressions.extend(lost.into_iter().map(|n| format!("{key}: {n}")));
        improvements.extend(gained.into_iter().map(|n| format!("{key}: {n}")));
    }
    if !improvements.is_empty() {
        let _ = writeln!(
            report,
            "\nnewly matching (raise the baseline with UPDATE_BASELINE=1):\n  {}",
            improvements.join("\n  ")
        );
    }
    println!("{report}");

    if update {
        if !corpus_present {
            println!("corpus absent: keeping the baseline's corpus list unchanged");
        }
        fs::write(&baseline_file, render_baseline(&now))
            .unwrap_or_else(|err| panic!("writing {}: {err}", baseline_file.display()));
        println!("baseline rewritten: {}", baseline_file.display());
        return;
    }
    assert!(
        regressions.is_empty(),
        "conformance regressed against {} (these were listed as matching):\n  {}",
        baseline_file.display(),
        regressions.join("\n  ")
    );
}

// ---------------------------------------------------------------------------------------
// Checks of the comparison machinery itself, on fixed inputs
// ---------------------------------------------------------------------------------------

#[test]
fn motion_comparison_levels() {
    let reference = " N..... SET_FEED_RATE(100.0000)\n N..... STRAIGHT_FEED(1.0000, 0.0000, -0.0000, 0.0000, 0.0000, 0.0000)\n N10    ARC_FEED(20.0000, 10.0000, 10.0000, 10.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)\n";
    // Different non-motion lines and block numbers, -0.0000 vs 0.0000: still exact motion.
    let same = " N..... SET_FEED_RATE(50.0000)\n N..... STRAIGHT_FEED(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n N..... ARC_FEED(20.0000, 10.0000, 10.0000, 10.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)\n";
    assert_eq!(compare_motion(same, reference), MotionMatch::Exact);
    let close = same.replace("20.0000, 10.0000, 10.0000", "20.0001, 10.0000, 10.0000");
    assert_eq!(compare_motion(&close, reference), MotionMatch::Tolerance);
    let far = same.replace("20.0000, 10.0000, 10.0000", "20.0002, 10.0000, 10.0000");
    assert_eq!(compare_motion(&far, reference), MotionMatch::No);
    let turns = same.replace(", -1, ", ", -2, ");
    assert_eq!(compare_motion(&turns, reference), MotionMatch::No);
    let missing = " N..... STRAIGHT_FEED(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n";
    assert_eq!(compare_motion(missing, reference), MotionMatch::No);
}

#[test]
fn corpus_normalisation_matches_linuxcnc_scripts() {
    let ours = " N..... USE_LENGTH_UNITS(CANON_UNITS_MM)\n hello 1.000000\n N10    STRAIGHT_FEED(-0.0000, 1.0000)\n";
    let raw = add_counter(ours);
    assert_eq!(
        raw,
        "    1 N..... USE_LENGTH_UNITS(CANON_UNITS_MM)\n hello 1.000000\n    2 N10    STRAIGHT_FEED(-0.0000, 1.0000)\n"
    );
    let filtered = apply_filters(&raw, &[Filter::DropFirstField, Filter::NegativeZero]);
    assert_eq!(
        filtered,
        " N..... USE_LENGTH_UNITS(CANON_UNITS_MM)\n 1.000000\n N10 STRAIGHT_FEED(0.0000, 1.0000)\n"
    );
    let messages = apply_filters(
        "    1 N..... MESSAGE(\"a  b\")\n    2 N..... ON_RESET()\n",
        &[Filter::MessagesDropFirstField],
    );
    assert_eq!(messages, " N..... MESSAGE(\"a b\")\n");
}

#[test]
fn plain_command_parsing() {
    let dir = Path::new("/c/t");
    let parsed = parse_plain_command(
        dir,
        r#"rs274 -g test.ngc -t test.tbl | awk '{$1=""; print}' | sed 's/-0\.0000/0.0000/g'"#,
    );
    assert_eq!(
        parsed,
        Some(PlainRun {
            program: PathBuf::from("/c/t/test.ngc"),
            tbl: Some(PathBuf::from("/c/t/test.tbl")),
            var: None,
            filters: vec![Filter::DropFirstField, Filter::NegativeZero]
        })
    );
    assert_eq!(
        parse_plain_command(dir, "rs274 -g g52.ngc"),
        Some(PlainRun {
            program: PathBuf::from("/c/t/g52.ngc"),
            tbl: None,
            var: None,
            filters: vec![]
        })
    );
    for rejected in [
        "rs274 -n 2 -i test.ini -g test.ngc 2>&1",
        "rs274 -n 0 -g test.ngc | awk '{$1=\"\"; print}'",
        "! rs274 -g test.ngc",
        "rs274 -p canterp.so -g canon | awk '{$1=\"\"; print}'",
        "rs274 -g a.ngc;rs274 -g b.ngc",
        "rs274 -g test.ngc | grep -i m6",
    ] {
        assert_eq!(parse_plain_command(dir, rejected), None, "{rejected}");
    }
    assert_eq!(
        declared_error(";Cannot do g1 with zero feed rate\n"),
        "Cannot do g1 with zero feed rate"
    );
    assert_eq!(
        declared_error("(Expected # reading parameter)"),
        "Expected # reading parameter"
    );
}

#[test]
fn baseline_round_trip() {
    let mut baseline = Baseline::default();
    baseline.exact.insert("arc_xy_r".into());
    baseline.motion.insert("arc_xy_r".into());
    baseline.corpus.insert("tests/interp/g6164".into());
    let text = render_baseline(&baseline);
    let dir = std::env::temp_dir().join(format!("partscope-baseline-{}", std::process::id()));
    fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("baseline.toml");
    fs::write(&path, &text).expect("write baseline");
    let read = read_baseline(&path);
    let _ = fs::remove_dir_all(&dir);
    assert_eq!(read, Ok(baseline));
    let (lost, gained) = ratchet(
        &["a".to_string(), "b".to_string()].into(),
        &["b".to_string(), "c".to_string()].into(),
    );
    assert_eq!(
        (lost, gained),
        (vec!["a".to_string()], vec!["c".to_string()])
    );
}
