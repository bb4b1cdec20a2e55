//! A program read in windows (`check` of a file above 32 MB) is checked as if
//! it were read whole: the hidden `--window-bytes` forces windows of a few
//! lines on the repository's program fixtures, in every dialect, and the JSON
//! must be byte-identical. A program with flow control or calls cannot run in
//! windows: its static findings must still be identical, and its run is
//! reported as not made (F004) instead of being guessed.

use std::path::{Path, PathBuf};
use std::process::Command;

fn check(dir: &Path, file: &str, extra: &[&str]) -> (Option<i32>, String) {
    partscope(dir, file, &["check", "--format", "json"], extra)
}

fn partscope(dir: &Path, file: &str, command: &[&str], extra: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_partscope"))
        .current_dir(dir)
        .args(command)
        .args(extra)
        .arg(file)
        .output()
        .expect("partscope runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

fn programs(root: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(root) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            programs(&p, out);
        } else if p
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| ["ngc", "nc", "dat", "tap"].contains(&e.to_ascii_lowercase().as_str()))
        {
            out.push(p);
        }
    }
}

#[test]
fn windows_of_a_few_lines_check_as_the_whole_file() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in [
        "analyzer/tests/rules",
        "tests/conformance/programs",
        "tests/holdout",
        "tests/recovery",
        "examples",
    ] {
        programs(&root.join(dir), &mut files);
    }
    assert!(files.len() > 300, "fixtures found: {}", files.len());
    let (mut same, mut not_run) = (0, 0);
    let mut failures = Vec::new();
    for f in &files {
        let dir = f.parent().unwrap_or(Path::new("."));
        let name = f.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        // 64 bytes: two or three lines a window, so nearly every block meets a seam.
        let whole = check(dir, name, &["--no-run"]);
        let windows = check(dir, name, &["--no-run", "--window-bytes", "64"]);
        if whole != windows {
            failures.push(format!("{} (static)", f.display()));
            continue;
        }
        let whole = check(dir, name, &[]);
        let windows = check(dir, name, &["--window-bytes", "64"]);
        if whole == windows {
            same += 1;
        } else if windows.1.contains("the dry run was not made") {
            not_run += 1;
        } else {
            failures.push(format!("{} (run)", f.display()));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} programs check differently in windows:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
    // Most fixtures are single-pass and run in windows too.
    assert!(same > not_run, "{same} identical, {not_run} not run");
}

/// `run`'s summary of a program read in windows: the same figures and
/// findings as the whole-file run (per-block figures and what-ifs, which the
/// windows do not gather, are off in both).
#[test]
fn run_in_windows_gives_the_whole_files_figures() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in ["tests/conformance/programs", "tests/holdout", "examples"] {
        programs(&root.join(dir), &mut files);
    }
    let run = [
        "run",
        "--format",
        "json",
        "--what-if",
        "off",
        "--blocks",
        "off",
    ];
    let (mut same, mut failures) = (0, Vec::new());
    for f in &files {
        let dir = f.parent().unwrap_or(Path::new("."));
        let name = f.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        let whole = partscope(dir, name, &run, &[]);
        let windows = partscope(dir, name, &run, &["--window-bytes", "64"]);
        if whole == windows {
            same += 1;
        } else if !windows.1.contains("the dry run was not made") {
            failures.push(f.display().to_string());
        }
    }
    assert!(
        failures.is_empty(),
        "run differs in windows:\n{}",
        failures.join("\n")
    );
    assert!(same > 100, "{same} identical");
}

#[test]
fn a_program_with_flow_control_is_not_run_in_windows_and_says_so() {
    let dir = std::env::temp_dir().join(format!("partscope-windows-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let text = "G21 G90\n#1=0\no100 while [#1 LT 3]\nG1 X#1 F100\n#1=[#1+1]\no100 endwhile\nM2\n";
    std::fs::write(dir.join("loop.ngc"), text).expect("write");
    let (code, out) = check(&dir, "loop.ngc", &["--window-bytes", "32"]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let codes: Vec<&str> = v
        .as_array()
        .expect("array")
        .iter()
        .filter_map(|d| d["code"].as_str())
        .collect();
    assert_eq!(codes, ["F004"], "{out}");
    assert_eq!(code, Some(1));
    // `run` gives no figures for it, and says why.
    let (code, out) = partscope(
        &dir,
        "loop.ngc",
        &["run", "--format", "json"],
        &["--window-bytes", "32"],
    );
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(
        (v["cycle_time_s"].is_null(), &v["partial"]),
        (true, &serde_json::json!(true))
    );
    assert_eq!(v["diagnostics"][0]["code"], "F004");
    assert_eq!(code, Some(1));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Shapes a window reader can trip on, each checked in windows of 16 bytes
/// against the whole file: no line break at all, CR-only and CR LF breaks
/// (a window must never end between CR and LF), invalid UTF-8 past the first
/// window (reported once), a binary file, an empty file, a file of blank lines.
#[test]
fn hostile_shapes_check_in_windows_as_whole() {
    let dir =
        std::env::temp_dir().join(format!("partscope-windows-hostile-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let long_line: Vec<u8> = std::iter::repeat_n(&b"X1. "[..], 3000)
        .flatten()
        .copied()
        .collect();
    let mut crlf = Vec::new();
    let mut cr = Vec::new();
    let mut bad_utf8 = Vec::new();
    for i in 0..200 {
        crlf.extend_from_slice(format!("G1 X{i} Y{i} F100\r\n").as_bytes());
        cr.extend_from_slice(format!("G1 X{i} F100\r").as_bytes());
        bad_utf8.extend_from_slice(format!("G1 X{i} F100 (caf").as_bytes());
        bad_utf8.extend_from_slice(&[0xE9, b')', b'\n']);
    }
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("long.ngc", long_line),
        ("crlf.ngc", crlf),
        ("cr.ngc", cr),
        ("latin1.ngc", bad_utf8),
        (
            "binary.ngc",
            [&b"G1 X1\n"[..], &[0u8, 1, 2, 3][..], &b"\nM2\n"[..]].concat(),
        ),
        ("empty.ngc", Vec::new()),
        ("blank.ngc", b"\n\n\n\n\r\n\n".repeat(50)),
        // More findings of one code than are reported (the cap counts across windows).
        ("many.ngc", b"G1 X1 F-100 (neg)\n".repeat(2500)),
        // Suppressions far from the findings they silence, a block one and a file one.
        (
            "allow.ngc",
            [
                &b"(partscope: allow-file W007)\nG21 G90\n"[..],
                &b"G1 X1 F100\n".repeat(40),
                &b"G1 X2 F-5\nS-100 (partscope: allow W007)\nG0 X1 Y1 Z1 Q-1\n"[..],
                &b"G1 X1 F100\n".repeat(40),
                &b"M2\n"[..],
            ]
            .concat(),
        ),
        // Text LinuxCNC never reads: syntax errors after M2, windows later.
        (
            "dead.ngc",
            [
                &b"G21 G90\nG1 X1 F100\nM2\n"[..],
                &b"G1 X1 Y2\n".repeat(40),
                &b"G1 X$ Y%%\n(unclosed\n"[..],
            ]
            .concat(),
        ),
        // A lathe program: its two signs windows apart give one P010.
        (
            "lathe.nc",
            [
                &b"(partscope: dialect=fanuc)\n%\nO1000\nT0101\n"[..],
                &b"G1 X1. Z-1. F0.2\n".repeat(60),
                &b"G71 P10 Q20 U0.2 W0.1 D1.\nN10 G1 X2.\nN20 Z-2.\nM30\n%\n"[..],
            ]
            .concat(),
        ),
        // FANUC: text after M30 up to the next sequence number is never read.
        (
            "jumped.nc",
            [
                &b"(partscope: dialect=fanuc)\n%\nO1000\nG1 X1. F100.\nM30\n"[..],
                &b"G1 X$1\n".repeat(30),
                &b"N100 G1 X2.\nM30\n%\n"[..],
            ]
            .concat(),
        ),
    ];
    for (name, bytes) in &cases {
        std::fs::write(dir.join(name), bytes).expect("write");
        for extra in [&["--no-run"][..], &[][..]] {
            let whole = check(&dir, name, extra);
            let windows = check(&dir, name, &[extra, &["--window-bytes", "16"]].concat());
            assert_eq!(whole, windows, "{name} {extra:?}");
        }
        let run = [
            "run",
            "--format",
            "json",
            "--what-if",
            "off",
            "--blocks",
            "off",
        ];
        let whole = partscope(&dir, name, &run, &[]);
        let windows = partscope(&dir, name, &run, &["--window-bytes", "16"]);
        assert_eq!(whole, windows, "run {name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
