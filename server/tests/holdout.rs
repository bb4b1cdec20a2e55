//! Hold-out programs (`tests/holdout/`): `partscope check --format json` reports what the
//! manuals call for on each program, on its line with its severity, and nothing on clean
//! programs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// One expected diagnostic: line and severity.
type Expected = (u64, String);

fn folder(dialect: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/holdout")
        .join(dialect)
}

fn expected(dir: &Path) -> BTreeMap<String, Vec<Expected>> {
    let text = std::fs::read_to_string(dir.join("expected.tsv")).unwrap();
    let mut out: BTreeMap<String, Vec<Expected>> = BTreeMap::new();
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let cols: Vec<&str> = line.split('\t').collect();
        assert!(cols.len() >= 3, "bad expected.tsv row: {line}");
        out.entry(cols[0].to_string())
            .or_default()
            .push((cols[1].parse().unwrap(), cols[2].to_string()));
    }
    out
}

/// The error and warning diagnostics `check` reports, per file name.
fn reported(dir: &Path) -> BTreeMap<String, Vec<(u64, String, String)>> {
    let out = Command::new(env!("CARGO_BIN_EXE_partscope"))
        .args(["check", "--format", "json"])
        .arg(dir)
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}): {}", String::from_utf8_lossy(&out.stderr)));
    let mut map: BTreeMap<String, Vec<(u64, String, String)>> = BTreeMap::new();
    for d in v.as_array().cloned().unwrap_or_default() {
        let sev = d["severity"].as_str().unwrap_or("").to_string();
        if sev != "error" && sev != "warning" {
            continue;
        }
        let path = d["path"].as_str().unwrap_or("");
        let name = Path::new(path)
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        map.entry(name).or_default().push((
            d["line"].as_u64().unwrap_or(0),
            sev,
            d["code"].as_str().unwrap_or("").to_string(),
        ));
    }
    map
}

fn check_folder(dialect: &str) {
    let dir = folder(dialect);
    let want = expected(&dir);
    let got = reported(&dir);
    let mut programs: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".nc") && !n.starts_with('O'))
        .collect();
    programs.sort();
    assert!(
        programs.len() >= 15,
        "{dialect}: only {} programs",
        programs.len()
    );
    let mut failures = Vec::new();
    for p in &programs {
        let rows = want.get(p).cloned().unwrap_or_default();
        let diags = got.get(p).cloned().unwrap_or_default();
        for (line, sev) in &rows {
            if !diags.iter().any(|(l, s, _)| l == line && s == sev) {
                failures.push(format!("{p}: missed {sev} on line {line} (got {diags:?})"));
            }
        }
        let first = rows.iter().map(|r| r.0).min().unwrap_or(u64::MAX);
        for (line, sev, code) in &diags {
            if *line < first {
                failures.push(format!("{p}: unexpected {sev} {code} on line {line}"));
            }
        }
    }
    for (file, diags) in &got {
        if !programs.contains(file) {
            failures.push(format!("{file}: diagnostics on a called file: {diags:?}"));
        }
    }
    for name in want.keys() {
        assert!(
            programs.contains(name),
            "{dialect}: expected.tsv names {name}, which does not exist"
        );
    }
    assert!(failures.is_empty(), "{dialect}:\n{}", failures.join("\n"));
}

#[test]
fn servoworks_holdout() {
    check_folder("servoworks");
}

#[test]
fn fanuc_holdout() {
    check_folder("fanuc");
}
