//! Mutated programs through the real `partscope` binary.
//!
//! The example programs and the robustness fixtures are mutated a few hundred
//! times per run, deterministically (fixed-seed generator): byte flips,
//! truncations, duplicated lines, inserted brackets and `#`, huge numbers,
//! endless macro loops, runaway recursion, binary junk and very long lines.
//! Each mutant goes through `partscope check --format json` (and
//! `partscope run`, both with `--dialect` set: mostly the file's own dialect, a
//! quarter of the time another one of the three). The contract: the
//! process exits with 0, 1 or 2 (never a signal or a panic's 101), stdout of
//! `check` is a JSON array of located diagnostics, and no run takes more than
//! ten seconds (a guard against hangs, not a benchmark).

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_partscope");
/// The hang guard is on CPU time (user + system, from `/proc`), because on a
/// shared, overloaded machine the wall clock of a healthy run can exceed ten
/// seconds; the wall clock has its own, looser backstop.
const LIMIT: Duration = Duration::from_secs(10);
const WALL_BACKSTOP: Duration = Duration::from_secs(120);
/// Step budget passed to `check` and `run`. The tests run a debug build, some
/// 20-50 times slower than release, so the default budgets (tens of millions
/// of blocks, a few seconds in release) would turn every endless-loop mutant
/// into a timeout; a smaller budget still makes each loop hit the limit.
const STEP_BUDGET: &str = "200000";
/// Mutants per seed file; with the seeds in the repository this gives a few
/// hundred mutants per run.
const MUTANTS_PER_SEED: usize = 16;

#[path = "../../tests/common/rng.rs"]
mod rng;
use rng::Rng;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Dialect {
    Servoworks,
    Rs274ngc,
    Fanuc,
}

impl Dialect {
    fn arg(self) -> &'static str {
        match self {
            Dialect::Servoworks => "servoworks",
            Dialect::Rs274ngc => "rs274ngc",
            Dialect::Fanuc => "fanuc",
        }
    }
    fn ext(self) -> &'static str {
        match self {
            Dialect::Servoworks => "nc",
            Dialect::Rs274ngc => "ngc",
            Dialect::Fanuc => "fnc",
        }
    }
    fn of_path(p: &Path, text: &[u8]) -> Dialect {
        let head = String::from_utf8_lossy(&text[..text.len().min(200)]).to_lowercase();
        if head.contains("dialect=servoworks") {
            return Dialect::Servoworks;
        }
        if head.contains("dialect=fanuc") {
            return Dialect::Fanuc;
        }
        if head.contains("dialect=rs274ngc") {
            return Dialect::Rs274ngc;
        }
        match p.extension().and_then(|e| e.to_str()) {
            Some("ngc") => Dialect::Rs274ngc,
            Some("fnc") => Dialect::Fanuc,
            _ => Dialect::Servoworks,
        }
    }

    /// A loop that never ends unless the interpreter's step budget stops it.
    fn endless_loop(self) -> &'static str {
        match self {
            Dialect::Servoworks => "#101 = 0\nO9100\nG65 P9100 L999999\n#101 = #101 + 1\nM99\n",
            Dialect::Rs274ngc => "o100 while [1]\nG1 X[#1] F100\n#1 = [#1 + 1]\no100 endwhile\n",
            Dialect::Fanuc => "#1=0\nWHILE [1 EQ 1] DO1\nG1 X#1 F100.\n#1=#1+1\nEND1\n",
        }
    }

    /// A subprogram that calls itself without end.
    fn recursion(self) -> &'static str {
        match self {
            Dialect::Servoworks => "G65 P9200\nM30\nO9200\nG65 P9200\nM99\n%\n",
            Dialect::Rs274ngc => "o<deep> sub\no<deep> call\no<deep> endsub\no<deep> call\nM2\n",
            Dialect::Fanuc => "G65 P9200\nM30\nO9200\nG65 P9200\nM99\n",
        }
    }

    /// Arithmetic and geometry at the edges of f64.
    fn numeric_edges(self) -> &'static str {
        match self {
            Dialect::Servoworks => "#101 = 1 / 0\nG01 X#101 F100\nG01 X1e308 Y-1e308\nG02 X0 Y0 R1e300\nG02 X0 Y0 I0 J0\nG04 P99999999999999999999\n",
            Dialect::Rs274ngc => "#1 = [1 / 0]\n#2 = [sqrt[-1]]\n#3 = [10 ** 400]\nG1 X#1 Y#2 Z#3 F100\nG1 X1e308 Y-1e308\nG2 X0 Y0 I0 J0\nG2 X1 Y0 R1e300\nG4 P1e300\n",
            Dialect::Fanuc => "#1=1/0\n#2=SQRT[-1]\n#3=10**400\nG1 X#1 Y#2 Z#3 F100.\nG1 X1E308 Y-1E308\nG2 X0 Y0 I0 J0\nG2 X1. Y0 R1E300\nG4 P1E300\n",
        }
    }
}

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from(".."))
}

/// Example programs and robustness fixtures (crashes found by fuzzing and
/// hand-written hostile programs).
fn seeds() -> Vec<(PathBuf, Vec<u8>)> {
    let root = repo_root();
    let mut out = Vec::new();
    for dir in [
        "examples",
        "tests/robustness/seeds",
        "tests/robustness/crashes",
    ] {
        let Ok(rd) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        for p in paths {
            if p.is_file() && p.extension().and_then(|e| e.to_str()) != Some("md") {
                if let Ok(bytes) = std::fs::read(&p) {
                    out.push((p, bytes));
                }
            }
        }
    }
    out
}

fn line_starts(text: &[u8]) -> Vec<usize> {
    let mut v = vec![0];
    v.extend(
        text.iter()
            .enumerate()
            .filter(|(_, b)| **b == b'\n')
            .map(|(i, _)| i + 1)
            .filter(|i| *i < text.len()),
    );
    v
}

/// Applies one mutation; returns its name (for failure messages) and the text.
fn mutate(rng: &mut Rng, dialect: Dialect, text: &[u8]) -> (&'static str, Vec<u8>) {
    let mut t = text.to_vec();
    let pos = rng.below(t.len() + 1);
    let kind = rng.below(14);
    let name = match kind {
        0 => {
            for _ in 0..1 + rng.below(8) {
                if !t.is_empty() {
                    let i = rng.below(t.len());
                    t[i] ^= 1 << rng.below(8);
                }
            }
            "byte flips"
        }
        1 => {
            t.truncate(pos);
            "truncation"
        }
        2 => {
            let starts = line_starts(&t);
            let s = rng.pick(&starts);
            let e = t[s..]
                .iter()
                .position(|b| *b == b'\n')
                .map_or(t.len(), |i| s + i + 1);
            let line = t[s..e].to_vec();
            let times = 1 + rng.below(200);
            for _ in 0..times {
                t.splice(e..e, line.iter().copied());
            }
            "duplicated line"
        }
        3 => {
            let junk: &[u8] = rng.pick(&[
                &b"["[..],
                b"(",
                b"#",
                b"]",
                b")",
                b"[[[",
                b"((",
                b"#[",
                b"<",
                b"o",
            ]);
            for _ in 0..1 + rng.below(5) {
                let p = rng.below(t.len() + 1);
                t.splice(p..p, junk.iter().copied());
            }
            "inserted bracket"
        }
        4 => {
            let huge: &[u8] = rng.pick(&[
                &b"1e308"[..],
                b"1E308",
                b"-1e308",
                b"99999999999999999999999999999999999999",
                b"0.000000000000000000000000000000001",
                b"1e-320",
                b"-0",
                b"0",
                b"1.7976931348623157e308",
            ]);
            // Replace the digits of some number in the text.
            if let Some(start) = t
                .iter()
                .skip(pos)
                .position(|b| b.is_ascii_digit())
                .map(|i| i + pos)
            {
                let end = t[start..]
                    .iter()
                    .position(|b| !(b.is_ascii_digit() || *b == b'.'))
                    .map_or(t.len(), |i| start + i);
                t.splice(start..end, huge.iter().copied());
            } else {
                t.extend_from_slice(b"\nG1 X");
                t.extend_from_slice(huge);
                t.push(b'\n');
            }
            "huge number"
        }
        5 => {
            let at = line_starts(&t);
            let p = rng.pick(&at);
            t.splice(p..p, dialect.endless_loop().bytes());
            "endless loop"
        }
        6 => {
            let at = line_starts(&t);
            let p = rng.pick(&at);
            t.splice(p..p, dialect.recursion().bytes());
            "runaway recursion"
        }
        7 => {
            let n = 1 + rng.below(64);
            let junk: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
            t.splice(pos..pos, junk);
            "binary junk"
        }
        8 => {
            let unit: &[u8] = rng.pick(&[&b"X1.0 "[..], b"9", b"(", b"[", b"G1 ", b"#1=", b" "]);
            let n = 60_000 + rng.below(140_000);
            let mut long = Vec::with_capacity(unit.len() * n + 1);
            for _ in 0..n / unit.len().max(1) {
                long.extend_from_slice(unit);
            }
            long.push(b'\n');
            let at = line_starts(&t);
            let p = rng.pick(&at);
            t.splice(p..p, long);
            "very long line"
        }
        9 => {
            let depth = 100 + rng.below(5_000);
            let mut e = b"G1 X".to_vec();
            e.extend(std::iter::repeat_n(b'[', depth));
            e.push(b'1');
            e.extend(std::iter::repeat_n(b']', depth));
            e.push(b'\n');
            let at = line_starts(&t);
            let p = rng.pick(&at);
            t.splice(p..p, e);
            "deep nesting"
        }
        10 => {
            let at = line_starts(&t);
            let p = rng.pick(&at);
            t.splice(p..p, dialect.numeric_edges().bytes());
            "numeric edges"
        }
        11 => {
            // Cut a slice out of the middle, as a half-typed edit would.
            let end = (pos + 1 + rng.below(40)).min(t.len());
            if pos < end {
                t.drain(pos..end);
            }
            "deleted range"
        }
        12 => {
            // Invalid UTF-8 and CR-only line ends.
            t.splice(pos..pos, [0xff, 0xfe, b'\r', 0xc3, b'\r']);
            "bad encoding"
        }
        _ => {
            // Swap two lines' worth of content.
            let starts = line_starts(&t);
            if starts.len() > 2 {
                let a = rng.below(starts.len() - 1);
                let (s, e) = (starts[a], starts[a + 1]);
                let chunk: Vec<u8> = t.drain(s..e).collect();
                let p = rng.below(t.len() + 1);
                t.splice(p..p, chunk);
            }
            "moved line"
        }
    };
    (name, t)
}

struct Outcome {
    code: Option<i32>,
    stdout: Vec<u8>,
    stderr: Vec<u8>,
    elapsed: Duration,
    timed_out: bool,
}

/// Runs the binary with a wall-clock limit; a child over the limit is killed.
fn run(args: &[&str], cwd: &Path) -> Outcome {
    let start = Instant::now();
    let mut child = Command::new(BIN)
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn partscope");
    // Drain pipes on threads so a chatty child never blocks on a full pipe.
    let mut out = child.stdout.take().expect("stdout");
    let mut err = child.stderr.take().expect("stderr");
    let t_out = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = out.read_to_end(&mut v);
        v
    });
    let t_err = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = err.read_to_end(&mut v);
        v
    });
    let mut timed_out = false;
    let mut cpu = Duration::ZERO;
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None)
                if {
                    cpu = cpu_time(child.id()).unwrap_or(cpu);
                    cpu > LIMIT || start.elapsed() > WALL_BACKSTOP
                } =>
            {
                timed_out = true;
                let _ = child.kill();
                break child.wait().ok();
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(_) => break None,
        }
    };
    // Report CPU time where /proc has it (Linux), else the wall clock.
    let elapsed = if cpu > Duration::ZERO {
        cpu
    } else {
        start.elapsed()
    };
    Outcome {
        code: status.and_then(|s| s.code()),
        stdout: t_out.join().unwrap_or_default(),
        stderr: t_err.join().unwrap_or_default(),
        elapsed,
        timed_out,
    }
}

/// User + system CPU time of a running process, from `/proc/<pid>/stat`
/// (fields 14 and 15, in clock ticks of 1/100 s on Linux).
fn cpu_time(pid: u32) -> Option<Duration> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) may hold spaces; fields restart after ')'.
    let rest = &stat[stat.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?;
    Some(Duration::from_millis(ticks * 10))
}

fn has_run_subcommand() -> bool {
    let o = run(&["--help"], &repo_root());
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .any(|l| l.trim_start().starts_with("run "))
}

/// Checks one `check --format json` result; returns a failure description.
fn judge_check(o: &Outcome) -> Option<String> {
    if o.timed_out {
        return Some(format!("check took over {LIMIT:?} of CPU time"));
    }
    if !matches!(o.code, Some(0..=2)) {
        return Some(format!(
            "check exit status {:?}; stderr: {}",
            o.code,
            String::from_utf8_lossy(&o.stderr)
        ));
    }
    let v: serde_json::Value = match serde_json::from_slice(&o.stdout) {
        Ok(v) => v,
        Err(e) => return Some(format!("check printed invalid JSON: {e}")),
    };
    let Some(arr) = v.as_array() else {
        return Some("check JSON is not an array".into());
    };
    for d in arr {
        let line = d.get("line").and_then(|l| l.as_u64()).unwrap_or(0);
        let code = d.get("code").and_then(|c| c.as_str()).unwrap_or("");
        if line == 0 || code.is_empty() {
            return Some(format!("diagnostic without line or code: {d}"));
        }
    }
    None
}

fn judge_run(o: &Outcome) -> Option<String> {
    if o.timed_out {
        return Some(format!("run took over {LIMIT:?} of CPU time"));
    }
    if !matches!(o.code, Some(0..=2)) {
        return Some(format!(
            "run exit status {:?}; stderr: {}",
            o.code,
            String::from_utf8_lossy(&o.stderr)
        ));
    }
    None
}

#[test]
fn mutated_programs_never_crash_or_hang() {
    let seeds = seeds();
    assert!(seeds.len() >= 3, "examples/ must hold the seed programs");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("robustness");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    // Every mutant goes through `run` too; a build without the subcommand
    // must fail here rather than silently test only `check`.
    let with_run = has_run_subcommand();
    assert!(
        with_run,
        "`partscope run` is missing from `partscope --help`"
    );

    // Build the whole job list first so the order and content are fixed.
    let mut jobs: Vec<(String, Dialect, &'static str, Vec<u8>)> = Vec::new();
    let mut rng = Rng(0x0BAD_5EED);
    for (path, text) in &seeds {
        let natural = Dialect::of_path(path, text);
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("seed");
        for i in 0..MUTANTS_PER_SEED {
            // Mostly the file's own dialect; sometimes another one, as when a
            // user picks the wrong dialect for a file.
            let dialect = if rng.below(4) == 0 {
                rng.pick(&[Dialect::Servoworks, Dialect::Rs274ngc, Dialect::Fanuc])
            } else {
                natural
            };
            let (what, mut t) = mutate(&mut rng, dialect, text);
            // A second mutation on a third of the mutants compounds damage.
            if rng.below(3) == 0 {
                t = mutate(&mut rng, dialect, &t).1;
            }
            jobs.push((format!("{stem}_{i:03}.{}", dialect.ext()), dialect, what, t));
        }
    }
    assert!(jobs.len() >= 100, "only {} mutants", jobs.len());

    let next = AtomicUsize::new(0);
    let failures = Mutex::new(Vec::<String>::new());
    let slowest = Mutex::new(Duration::ZERO);
    let workers = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .clamp(2, 4);
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some((name, dialect, what, text)) = jobs.get(i) else {
                    break;
                };
                let file = dir.join(name);
                std::fs::write(&file, text).expect("write mutant");
                let f = file.to_string_lossy().into_owned();
                let o = run(
                    &[
                        "check",
                        &f,
                        "--format",
                        "json",
                        "--dialect",
                        dialect.arg(),
                        "--step-budget",
                        STEP_BUDGET,
                    ],
                    &dir,
                );
                let mut worst = o.elapsed;
                let mut problem = judge_check(&o);
                if problem.is_none() && with_run {
                    let o = run(
                        &[
                            "run",
                            &f,
                            "--dialect",
                            dialect.arg(),
                            "--step-budget",
                            STEP_BUDGET,
                        ],
                        &dir,
                    );
                    worst = worst.max(o.elapsed);
                    problem = judge_run(&o);
                }
                {
                    let mut w = slowest.lock().unwrap_or_else(|e| e.into_inner());
                    *w = (*w).max(worst);
                }
                match problem {
                    Some(p) => failures
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .push(format!("{name} ({what}): {p}")),
                    // Keep failing mutants on disk for reproduction only.
                    None => {
                        let _ = std::fs::remove_file(&file);
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap_or_default();
    eprintln!(
        "robustness: {} mutants, run subcommand: {with_run}, slowest (CPU) {:?}, failures {}",
        jobs.len(),
        slowest.into_inner().unwrap_or_default(),
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {} mutants failed (kept in {}):\n{}",
        failures.len(),
        jobs.len(),
        dir.display(),
        failures.join("\n")
    );
}

/// Every input that ever crashed a fuzz target (and the hostile seeds),
/// through the properties the fuzz targets check, in every dialect and variant.
#[test]
fn crash_fixtures_stay_fixed() {
    use analyzer::dialect::{variants_of, Dialect as D};
    use analyzer::syntax::{parse, ParseOptions};
    let mut files: Vec<PathBuf> = ["tests/robustness/crashes", "tests/robustness/seeds"]
        .iter()
        .filter_map(|d| std::fs::read_dir(repo_root().join(d)).ok())
        .flat_map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())))
        .collect();
    files.retain(|p| p.is_file() && p.extension().and_then(|e| e.to_str()) != Some("md"));
    files.sort();
    assert!(files.len() >= 10, "fixtures missing: {files:?}");
    for path in &files {
        let bytes = std::fs::read(path).expect("read fixture");
        // The `config` fuzz target's property: any text reads as a configuration.
        let text = String::from_utf8_lossy(&bytes);
        let (_, issues) = analyzer::Config::load(&text);
        assert!(
            issues
                .iter()
                .filter_map(|i| i.span.as_ref())
                .all(|s| s.start <= s.end && s.end <= text.len()),
            "{}: config issue spans",
            path.display()
        );
        for dialect in D::ALL {
            for &variant in variants_of(dialect) {
                let program = parse(ParseOptions { dialect, variant }, bytes.clone());
                assert_eq!(program.print(), bytes, "{}: round trip", path.display());
                for d in &program.diagnostics {
                    assert!(d.span.start <= d.span.end && d.span.end as usize <= bytes.len());
                }
                let mut settings = analyzer::Settings::new(dialect);
                settings.variant = variant;
                let analysis = analyzer::analyze(bytes.clone(), &settings);
                for d in &analysis.diagnostics {
                    assert!(
                        d.span.end as usize <= bytes.len(),
                        "{}: {d:?}",
                        path.display()
                    );
                }
                // The interpreter and planner as the `interpret` fuzz target
                // drives them: this test runs in a debug build, so an integer
                // overflow panics here as it did under the fuzzer.
                let machine = analyzer::config::MachineConfig::default();
                let out = runtime::run(&runtime::RunInput {
                    program: &program,
                    settings: &settings,
                    machine: &machine,
                    resolver: &runtime::NoResolver,
                    step_budget: 20_000,
                    motion_budget: u64::MAX,
                    emit_canon: dialect == D::Rs274ngc,
                    tool_table: None,
                    var_file: None,
                });
                let mut profile = runtime::machine::MachineProfile::default_for(dialect);
                profile.servo_simulation = false;
                let t = runtime::dryrun::plan_run(&out, &profile)
                    .totals
                    .cycle_time_s;
                assert!(
                    t.is_finite() && t >= 0.0,
                    "{}: cycle time {t}",
                    path.display()
                );
            }
        }
    }
}

/// Files above `--max-file-size` are refused before they are read: `check`
/// reports one located L000 error and exits 2, `run` exits 2 with a message,
/// instead of holding the program, its tree and its run in memory (about 27
/// bytes per byte of program: a multi-GB file would exhaust memory).
#[test]
fn files_above_the_size_limit_are_refused_with_a_located_error() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("size-limit");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("big.ngc");
    // 1.5 MB of valid blocks and a program end: above a 1 MB limit.
    let block = "G1 X1.000 Y2.000 F100\n";
    let text = block.repeat(1536 * 1024 / block.len() + 1) + "M2\n";
    std::fs::write(&file, &text).expect("write program");
    let f = file.to_string_lossy().into_owned();

    let o = run(
        &["check", &f, "--format", "json", "--max-file-size", "1"],
        &dir,
    );
    assert_eq!(o.code, Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let arr = v.as_array().expect("array");
    assert_eq!(arr.len(), 1, "{v}");
    assert_eq!(arr[0]["code"], "L000");
    assert_eq!(arr[0]["line"], 1);
    assert_eq!(arr[0]["column"], 1);
    assert_eq!(
        arr[0]["message"],
        "cannot read file: too large to analyse: 2 MB, above the limit of 1 MB \
         (raise it with --max-file-size, or split the program)"
    );

    let o = run(&["run", &f, "--max-file-size", "1"], &dir);
    assert_eq!(o.code, Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("too large to analyse: 2 MB"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );

    // Under the limit the same file is checked normally (exit 0, no diagnostics).
    let o = run(
        &[
            "check",
            &f,
            "--format",
            "json",
            "--max-file-size",
            "2",
            "--no-run",
        ],
        &dir,
    );
    assert_eq!(o.code, Some(0), "{}", String::from_utf8_lossy(&o.stdout));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Numeric limits through `partscope run`: a 1e300 s dwell and a move to
/// ±1e308 (whose length overflows to infinity) print readable cycle times,
/// and a full circle of radius 0 is the located arc error A001.
#[test]
fn numeric_limits_print_readable_cycle_times() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("numeric-limits");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let cases = [
        (
            "dwell.ngc",
            "G21 G17 G90 G94\nG4 P[10 ** 300]\nM2\n",
            Some(0),
            "  cycle time    2.778e296 h  (1.000e300 s)",
        ),
        (
            "far.ngc",
            "G21 G17 G90 G94\n#4 = [10 ** 308]\nG1 X#4 Y[-#4] F100\nM2\n",
            Some(0),
            "  cycle time            inf  (inf s)",
        ),
    ];
    for (name, text, code, line) in cases {
        let file = dir.join(name);
        std::fs::write(&file, text).expect("write program");
        let o = run(&["run", &file.to_string_lossy()], &dir);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.code, code, "{name}: {out}");
        // Line 2 names the dialect; the cycle time follows it.
        assert_eq!(
            out.lines().nth(1),
            Some("  dialect          rs274ngc  (the `.ngc` extension)"),
            "{name}: {out}"
        );
        assert_eq!(out.lines().nth(2), Some(line), "{name}: {out}");
    }
    let file = dir.join("zero_arc.ngc");
    std::fs::write(
        &file,
        "G21 G17 G90 G94\nG1 X0 Y0 F100\nG2 X0 Y0 I0 J0\nM2\n",
    )
    .expect("write");
    let o = run(
        &["check", &file.to_string_lossy(), "--format", "json"],
        &dir,
    );
    assert_eq!(o.code, Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let codes: Vec<(&str, u64)> = v
        .as_array()
        .expect("array")
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap_or(""),
                d["line"].as_u64().unwrap_or(0),
            )
        })
        .collect();
    assert_eq!(codes, vec![("A001", 3)]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every crash fixture through the real `check` and `run` as it is (the
/// mutation test only mutates them): exit 0, 1 or 2, never a panic's 101.
/// `interp-g54.1-huge-p.fnc` panicked with an add overflow in `run`.
#[test]
fn crash_fixtures_check_and_run_without_panicking() {
    let dir = repo_root().join("tests/robustness/crashes");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).expect("crashes dir").flatten() {
        let f = e.path().to_string_lossy().into_owned();
        for args in [
            vec![
                "check",
                f.as_str(),
                "--format",
                "json",
                "--step-budget",
                STEP_BUDGET,
            ],
            vec!["run", f.as_str(), "--step-budget", STEP_BUDGET],
        ] {
            let o = run(&args, &dir);
            assert!(
                matches!(o.code, Some(0..=2)),
                "{args:?}: exit {:?}: {}",
                o.code,
                String::from_utf8_lossy(&o.stderr)
            );
        }
        n += 1;
    }
    assert!(n >= 3, "only {n} crash fixtures");
}
