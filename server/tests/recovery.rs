//! Recovery after runtime errors seen from both hosts (issue #17): the fixtures with
//! several independent runtime errors (`tests/recovery`) get the same diagnostics
//! from `partscope check --format json` and from the language server's
//! publishDiagnostics over stdio, and a run that stops is partial in `partscope run`
//! (human and JSON) and in the LSP code lens and dry-run result.

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::{Path, PathBuf};
use std::process::Command;

use harness::Client;
use serde_json::{json, Value};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_partscope"))
}

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/recovery")
}

/// A fresh folder holding the fixtures and their `partscope.toml`.
fn workspace(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("partscope-recovery-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for e in std::fs::read_dir(fixtures()).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
    }
    dir.canonicalize().unwrap()
}

fn uri_of(p: &Path) -> String {
    format!("file://{}", p.display())
}

/// (code, 0-based line) of `check --format json`, in its order.
fn check(path: &Path) -> Vec<(String, u64)> {
    let out = bin()
        .args(["check", "--format", "json"])
        .arg(path)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    v.as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap().to_string(),
                d["line"].as_u64().unwrap() - 1,
            )
        })
        .collect()
}

fn lsp_session(root: &Path) -> Client {
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(root),
            "capabilities": {},
            "workspaceFolders": [{"uri": uri_of(root), "name": "ws"}],
        }),
    );
    c.notify("initialized", json!({}));
    c
}

fn open(c: &mut Client, path: &Path, language: &str) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let uri = uri_of(path);
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": language, "version": 1, "text": text}}),
    );
    uri
}

/// The runtime errors each fixture holds, as (code, 0-based line).
fn expected(ext: &str) -> Vec<(&'static str, u64)> {
    match ext {
        "ngc" => vec![
            ("F001", 4),
            ("A001", 6),
            ("A002", 8),
            ("C001", 10),
            ("F002", 12),
            ("X001", 13),
        ],
        "fnc" => vec![
            ("A001", 6),
            ("A002", 8),
            ("C001", 10),
            ("F002", 12),
            ("X001", 13),
            ("X001", 16),
        ],
        _ => vec![
            ("A001", 5),
            ("A002", 7),
            ("C001", 9),
            ("F002", 11),
            ("X001", 13),
        ],
    }
}

#[test]
fn check_json_and_lsp_report_the_same_runtime_errors_on_their_lines() {
    let root = workspace("agree");
    let mut c = lsp_session(&root);
    for (ext, language) in [("ngc", "ngc"), ("fnc", "fanuc"), ("sw", "servoworks")] {
        let path = root.join(format!("runtime_errors.{ext}"));
        let want: Vec<(String, u64)> = expected(ext)
            .into_iter()
            .map(|(c, l)| (c.to_string(), l))
            .collect();
        // Every error, each on its line, and nothing else (no secondary diagnostics).
        assert_eq!(check(&path), want, "check {ext}");
        let uri = open(&mut c, &path, language);
        let wanted: Vec<(&str, u64)> = expected(ext);
        c.diagnostics_become(&uri, 1, &wanted);
        // The run went on to the program's end, but the F002 call (line 11) was
        // skipped, so its time is left out: the lens says partial, not where it stopped.
        let lens = c.request(
            "textDocument/codeLens",
            json!({"textDocument": {"uri": uri}}),
        );
        let title = lens[0]["command"]["title"].as_str().unwrap().to_string();
        assert!(
            title.starts_with("Cycle time ")
                && title.contains(" partial (cutting ")
                && title.ends_with(": a called program was not run"),
            "{title}"
        );
        // And `run --format json` says the figures are partial, with no stop.
        let out = bin()
            .args(["run", "--format", "json"])
            .arg(&path)
            .output()
            .unwrap();
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["complete"], false, "{ext}");
        assert_eq!(v["partial"], true, "{ext}");
        assert_eq!(v["stopped_at"], Value::Null, "{ext}");
        // Exit 1: the program has errors.
        assert_eq!(out.status.code(), Some(1));
    }
    assert!(c.shutdown().success());
}

/// `G4` without P leaves the dwell undefined: the run stops at line 4.
const STOPS: &str = "G21 G90 G17\nG0 X0 Y0 Z5\nG1 X10 F100\nG4\nG1 X20\nM2\n";

#[test]
fn a_stopped_run_is_partial_in_run_output_and_in_the_code_lens() {
    let root = workspace("stopped");
    let path = root.join("stops.ngc");
    std::fs::write(&path, STOPS).unwrap();

    let out = bin().arg("run").arg(&path).output().unwrap();
    let human = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        human.contains("  stopped at line 4: dwell time P word missing with G4\n"),
        "{human}"
    );
    assert!(human.contains(" s, partial)\n"), "{human}");

    let out = bin()
        .args(["run", "--format", "json"])
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["complete"], false);
    assert_eq!(v["partial"], true);
    assert_eq!(
        v["stopped_at"],
        json!({"file": path.display().to_string(), "line": 4, "reason": "dwell time P word missing with G4"})
    );
    // One diagnostic for the fault: the static W003 stands for the interpreter's
    // X003 and carries its stop note.
    let msgs: Vec<(&str, &str)> = v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| (d["code"].as_str().unwrap(), d["message"].as_str().unwrap()))
        .collect();
    assert_eq!(
        msgs,
        vec![("W003", "G4 needs P: the dwell time in seconds (`Dwell time missing with G4`). Write for example `G4 P0.5`. (the dry run stops here)")]
    );

    let mut c = lsp_session(&root);
    let uri = open(&mut c, &path, "ngc");
    c.diagnostics_become(&uri, 1, &[("W003", 3)]);
    let lens = c.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": uri}}),
    );
    let title = lens[0]["command"]["title"].as_str().unwrap();
    assert!(title.starts_with("Cycle time 0:06."), "{title}");
    assert!(
        title.contains(" partial ")
            && title.ends_with(": stopped at line 4: dwell time P word missing with G4"),
        "{title}"
    );
    let r = c.request("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    assert_eq!(r["complete"], false);
    assert_eq!(
        r["stopped_at"],
        json!({"line": 3, "reason": "dwell time P word missing with G4"})
    );
    assert!(c.shutdown().success());
}

/// rs274 puts the line number in front of some messages ("7: undefined O-word
/// label: …"); the stop names its line already, so the reason does not repeat it.
#[test]
fn a_stop_reason_does_not_repeat_its_line_number() {
    let root = workspace("stray_endwhile");
    let path = root.join("stray.ngc");
    std::fs::write(
        &path,
        "G21 G90\nG0 X0 Y0 Z5\nG1 X40 F300\no100 endwhile\nG1 Y30\nM2\n",
    )
    .unwrap();
    let out = bin().arg("run").arg(&path).output().unwrap();
    let human = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        human.contains("  stopped at line 4: undefined O-word label: 'o100 endwhile'\n"),
        "{human}"
    );
}

#[test]
fn a_step_budget_makes_run_exit_1_with_a_partial_time() {
    let root = workspace("budget");
    let path = root.join("loop.fnc");
    std::fs::write(&path, "WHILE [1 EQ 1] DO1;\nG91 G00 X1.;\nEND1;\nM30;\n").unwrap();
    let out = bin()
        .args(["run", "--format", "json", "--step-budget", "50"])
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["complete"], false);
    assert_eq!(v["stopped_at"]["line"], 2);
    assert!(v["stopped_at"]["reason"]
        .as_str()
        .unwrap()
        .starts_with("execution stopped after 50 blocks"));
}

#[test]
fn max_runtime_errors_caps_the_reported_errors() {
    let root = workspace("cap");
    let path = root.join("runtime_errors.ngc");
    let out = bin()
        .args(["run", "--format", "json", "--max-runtime-errors", "2"])
        .arg(&path)
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let codes: Vec<&str> = v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["code"].as_str().unwrap())
        .collect();
    assert_eq!(codes, vec!["F001", "A001", "F004"]);
    assert_eq!(v["complete"], false);
    assert_eq!(v["stopped_at"]["line"], 7);
}

#[test]
fn the_lsp_says_when_a_file_is_too_large_for_the_dry_run() {
    let root = workspace("large");
    let path = root.join("big.ngc");
    let mut text = String::from("G21 G90\n");
    while text.len() < 8 * 1024 {
        text.push_str("G1 X1 Y2 F100\n");
    }
    text.push_str("M2\n");
    std::fs::write(&path, &text).unwrap();
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(&root),
            "capabilities": {},
            "workspaceFolders": [{"uri": uri_of(&root), "name": "ws"}],
            "initializationOptions": {"maxRunFileSize": 4096},
        }),
    );
    c.notify("initialized", json!({}));
    let uri = open(&mut c, &path, "ngc");
    c.diagnostics_become(&uri, 1, &[("F004", 0)]);
    let lens = c.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": uri}}),
    );
    let title = lens[0]["command"]["title"].as_str().unwrap();
    assert!(
        title.starts_with("No dry run: the file (8 KB) is above the dry-run size limit (4 KB"),
        "{title}"
    );
    assert!(c.shutdown().success());
}

/// A called file obeys the size limit of the main program, in `check` and in
/// the editor: the call gets one warning naming the file and the limit, and the
/// run goes on without it.
#[test]
fn a_called_file_above_the_size_limit_is_not_read() {
    let root = workspace("large_sub");
    let main = root.join("main.ngc");
    std::fs::write(&main, "G21 G90\no<big> call\nG0 X1\nM2\n").unwrap();
    let mut big = String::from("o<big> sub\n");
    while big.len() < (1 << 20) + 4096 {
        big.push_str("G1 X1 Y2 F100\n");
    }
    big.push_str("o<big> endsub\nM2\n");
    std::fs::write(root.join("big.ngc"), &big).unwrap();

    let out = bin()
        .args(["check", "--format", "json", "--max-file-size", "1"])
        .arg(&main)
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let found: Vec<(&str, u64, &str, &str)> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap(),
                d["line"].as_u64().unwrap(),
                d["severity"].as_str().unwrap(),
                d["message"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        found,
        vec![(
            "F002",
            2,
            "warning",
            "the called file was not read, so the dry run skips the call: big.ngc: too large to analyse: 2 MB, above the limit of 1 MB (raise it with --max-file-size, or split the program)"
        )]
    );

    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(&root),
            "capabilities": {},
            "workspaceFolders": [{"uri": uri_of(&root), "name": "ws"}],
            "initializationOptions": {"maxRunFileSize": 4096},
        }),
    );
    c.notify("initialized", json!({}));
    let uri = open(&mut c, &main, "ngc");
    c.diagnostics_become(&uri, 1, &[("F002", 1)]);
    assert!(c.shutdown().success());
}
