//! The control signature (P010) must stay silent on every FANUC mill program the
//! repository holds: the rule fixtures, the hold-out programs, the examples and
//! the robustness seeds. Only the P010 fixtures named `invalid_*` may match.

use std::path::{Path, PathBuf};

use analyzer::{analyze, control_signature, Dialect, Settings};

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// The FANUC programs: `.fnc` files anywhere, and every `.nc` of the FANUC hold-out.
fn fanuc_programs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        "tests/rules",
        "../tests/holdout/fanuc",
        "../examples",
        "../tests/robustness",
    ] {
        walk(&root.join(dir), &mut files);
    }
    files.retain(|p| {
        let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
        ext == "fnc" || (ext == "nc" && p.components().any(|c| c.as_os_str() == "holdout"))
    });
    files.sort();
    files
}

#[test]
fn no_fanuc_mill_program_of_the_repository_looks_like_another_control() {
    let files = fanuc_programs();
    assert!(
        files.len() > 100,
        "FANUC programs not found: {}",
        files.len()
    );
    let mut fired = Vec::new();
    let mut p010 = 0;
    for path in &files {
        let text = std::fs::read(path).expect("read program");
        let program = analyze(text, &Settings::new(Dialect::Fanuc)).program;
        let name = path.to_string_lossy();
        let expected = name.contains("rules/P010/invalid_");
        let sig = control_signature(&program);
        if sig.is_some() != expected {
            fired.push(format!("{name}: {sig:?}"));
        }
        p010 += usize::from(expected);
    }
    assert_eq!(p010, 3, "the three P010 invalid fixtures");
    assert!(fired.is_empty(), "{}", fired.join("\n"));
}
