//! One fault, one diagnostic: every rule fixture, every rule doc example and every
//! shipped example goes through `partscope check` (static rules and dry run), and no
//! two diagnostics of a file may point at the same text for one root cause — a
//! declared twin pair (`analyzer::twins::TWINS`), or one code twice on one span or
//! with one message at one place.

use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_partscope"))
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

fn check(args: &[&Path], config: Option<&Path>) -> Vec<Value> {
    let mut cmd = bin();
    cmd.args(["check", "--format", "json"]);
    if let Some(c) = config {
        cmd.arg("--config").arg(c);
    }
    let out = cmd.args(args).output().expect("run partscope");
    assert!(
        out.status.code().is_some_and(|c| c <= 1),
        "check failed on {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON diagnostics")
}

/// Every rule doc's fenced blocks, written as files of their dialect (a `gcode` block,
/// the runtime rules' examples, in all three) into `dir`, one folder each so a
/// `variant=` fence gets its own `partscope.toml`.
fn write_doc_examples(dir: &Path) -> usize {
    let out = bin()
        .args(["rule", "--all", "--json"])
        .output()
        .expect("rule --all");
    let rules: Vec<Value> = serde_json::from_slice(&out.stdout).expect("rule JSON");
    let mut n = 0;
    for r in &rules {
        let code = r["code"].as_str().unwrap_or("");
        let doc = r["doc"].as_str().unwrap_or("");
        let mut fence: Option<(Vec<String>, String)> = None;
        for line in doc.lines() {
            let t = line.trim();
            let Some(tag) = t.strip_prefix("```") else {
                if let Some((_, body)) = fence.as_mut() {
                    body.push_str(t);
                    body.push('\n');
                }
                continue;
            };
            match fence.take() {
                None => {
                    fence = Some((
                        tag.split_whitespace().map(String::from).collect(),
                        String::new(),
                    ))
                }
                Some((tag, body)) => {
                    let exts: &[&str] = match tag.first().map(String::as_str) {
                        Some("ngc") => &["ngc"],
                        Some("servoworks") => &["sw"],
                        Some("fanuc") => &["fnc"],
                        _ => &["ngc", "fnc", "sw"],
                    };
                    for ext in exts {
                        n += 1;
                        let sub = dir.join(format!("{code}_{n}"));
                        std::fs::create_dir_all(&sub).unwrap();
                        if let Some(v) = tag.iter().find_map(|p| p.strip_prefix("variant=")) {
                            std::fs::write(
                                sub.join("partscope.toml"),
                                format!("variant = \"{v}\"\n"),
                            )
                            .unwrap();
                        }
                        std::fs::write(sub.join(format!("ex.{ext}")), &body).unwrap();
                    }
                }
            }
        }
    }
    n
}

type Pos = (u64, u64);

fn span(d: &Value) -> (Pos, Pos) {
    let g = |k: &str| d[k].as_u64().unwrap_or(0);
    ((g("line"), g("column")), (g("end_line"), g("end_column")))
}

/// The rule of `analyzer::twins::spans_meet`, on line/column positions.
fn meet(a: (Pos, Pos), b: (Pos, Pos)) -> bool {
    if a.0 == a.1 || b.0 == b.1 {
        return a.0 <= b.1 && b.0 <= a.1;
    }
    a.0 < b.1 && b.0 < a.1
}

fn duplicates(diags: &[Value]) -> Vec<String> {
    let mut by_file: BTreeMap<&str, Vec<&Value>> = BTreeMap::new();
    for d in diags {
        by_file
            .entry(d["path"].as_str().unwrap_or(""))
            .or_default()
            .push(d);
    }
    let mut found = Vec::new();
    for (path, ds) in by_file {
        for (i, a) in ds.iter().enumerate() {
            for b in &ds[i + 1..] {
                let (ca, cb) = (
                    a["code"].as_str().unwrap_or(""),
                    b["code"].as_str().unwrap_or(""),
                );
                let (sa, sb) = (span(a), span(b));
                let twin = analyzer::twins::are_twins(ca, cb) && meet(sa, sb);
                let same_code =
                    ca == cb && (sa == sb || (sa.0 == sb.0 && a["message"] == b["message"]));
                if twin || same_code {
                    found.push(format!(
                        "{path}:{}:{}: {ca} `{}` and {cb} `{}`",
                        sa.0 .0, sa.0 .1, a["message"], b["message"]
                    ));
                }
            }
        }
    }
    found
}

#[test]
fn one_fault_gives_one_diagnostic() {
    let root = repo();
    let fixtures_dir = root.join("analyzer/tests/rules");
    let mut plain = Vec::new();
    let mut diags = Vec::new();
    let mut fixtures = 0;
    for code in std::fs::read_dir(&fixtures_dir).unwrap() {
        let code = code.unwrap().path();
        for f in std::fs::read_dir(&code).unwrap() {
            let f = f.unwrap().path();
            let ext = f.extension().and_then(|e| e.to_str()).unwrap_or("");
            if !matches!(ext, "ngc" | "fnc" | "sw" | "nc" | "dat") {
                continue;
            }
            fixtures += 1;
            // A fixture's sibling `<stem>.toml` is its configuration.
            let cfg = f.with_extension("toml");
            if cfg.exists() {
                diags.extend(check(&[&f], Some(&cfg)));
            } else {
                plain.push(f);
            }
        }
    }
    let plain: Vec<&Path> = plain.iter().map(PathBuf::as_path).collect();
    diags.extend(check(&plain, None));

    let docs = std::env::temp_dir().join(format!("partscope-one-fault-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&docs);
    std::fs::create_dir_all(&docs).unwrap();
    let examples = write_doc_examples(&docs);
    diags.extend(check(&[&docs], None));
    diags.extend(check(&[&root.join("examples")], None));
    let _ = std::fs::remove_dir_all(&docs);

    // The inputs are all there: the test cannot pass by checking nothing.
    assert!(fixtures > 200, "{fixtures} fixtures");
    assert!(examples > 400, "{examples} doc examples");
    assert!(diags.len() > 1500, "{} diagnostics", diags.len());
    let found = duplicates(&diags);
    assert!(
        found.is_empty(),
        "one fault, several diagnostics:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_listed_faults_give_one_diagnostic_each() {
    // The pairs of issue #17, each one fault: the code that stays.
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "arc.ngc",
            "G21 G17 G90\nG0 X0 Y0\nG2 X20 Y0 F100\nM30\n",
            &["W003"],
        ),
        ("dwell.ngc", "G21\nG4\nM30\n", &["W003"]),
        ("hash.ngc", "G21\n#\nM30\n", &["L003"]),
        ("after.sw", "G21\nG0 X1\nM30\nG0 X2\n", &["P006"]),
        ("noend.ngc", "G21\nG0 X1\n", &["P005"]),
        ("percent.ngc", "G21\nG0 X1\n%\n", &["L011"]),
        (
            "thread.ngc",
            "G21 G18\nM3 S100\nG0 X1 Z1\nG76 Z-1\nM30\n",
            &["W003"],
        ),
        ("div.ngc", "G21\n#1=[1/0]\nM30\n", &["W015"]),
    ];
    let dir =
        std::env::temp_dir().join(format!("partscope-one-fault-cases-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text, want) in cases {
        let f = dir.join(name);
        std::fs::write(&f, text).unwrap();
        let got: Vec<String> = check(&[&f], None)
            .iter()
            .map(|d| d["code"].as_str().unwrap_or("").to_string())
            .collect();
        assert_eq!(&got, want, "{name}");
    }
    // The kept diagnostic says the run stopped when its dropped twin did.
    let f = dir.join("dwell.ngc");
    let d = check(&[&f], None);
    assert!(
        d[0]["message"]
            .as_str()
            .unwrap_or("")
            .ends_with(" (the dry run stops here)"),
        "{d:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn both_rules_of_a_twin_say_who_reports() {
    let doc = |code: &str| {
        analyzer::rules::registry::lookup(code)
            .or_else(|| {
                runtime::rules::REGISTRY
                    .iter()
                    .copied()
                    .find(|m| m.code == code)
            })
            .map(|m| m.doc)
            .unwrap_or_else(|| panic!("{code} is not a rule"))
    };
    for t in analyzer::twins::TWINS {
        let owner = format!(
            "Reported by this rule, not {}, when both see {}",
            t.drop, t.fault
        );
        let other = format!(
            "Reported by {}, not this rule, when both see {}",
            t.keep, t.fault
        );
        assert!(
            doc(t.keep).contains(&owner),
            "{} doc lacks: {owner}",
            t.keep
        );
        assert!(
            doc(t.drop).contains(&other),
            "{} doc lacks: {other}",
            t.drop
        );
    }
}
