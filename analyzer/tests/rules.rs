//! Data-driven rule fixtures: `tests/rules/<CODE>/{valid,invalid}_*.<ext>`.
//!
//! The extension chooses the dialect (`.ngc` RS274/NGC, `.sw` ServoWorks,
//! `.fnc` FANUC) unless the first line holds a `(partscope: dialect=…)`
//! directive. A sibling `<stem>.toml` is read as a `partscope.toml` (variant,
//! machine axes, custom codes). The rule under test is selected on top of the
//! default rules, so off-by-default style rules run too.
//!
//! `valid_*` files must produce no diagnostic at all; `invalid_*` files must
//! produce the directory's code, and their whole diagnostic list is an insta
//! snapshot (`tests/rules/snapshots/`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use analyzer::dialect::Dialect;
use analyzer::{analyze, Config, LineIndex, Settings};

fn fixture_dialect(path: &Path, text: &[u8]) -> Option<Dialect> {
    if let Some(d) = analyzer::settings::dialect_directive(text) {
        return Some(d);
    }
    match path.extension()?.to_str()? {
        "ngc" => Some(Dialect::Rs274ngc),
        "sw" => Some(Dialect::Servoworks),
        "fnc" => Some(Dialect::Fanuc),
        _ => None,
    }
}

fn settings_for(path: &Path, dialect: Dialect, code: &str) -> Settings {
    let cfg_path = path.with_extension("toml");
    let mut settings = if cfg_path.exists() {
        let text = std::fs::read_to_string(&cfg_path).expect("read fixture config");
        let config =
            Config::from_toml(&text).unwrap_or_else(|e| panic!("{}: {e}", cfg_path.display()));
        Settings::from_config(&config, Some(dialect)).expect("fixture settings")
    } else {
        Settings::new(dialect)
    };
    settings.select = vec!["ALL".to_string(), code.to_string()];
    settings
}

/// One line per diagnostic: `line:col code severity message` (1-based).
pub fn render(text: &[u8], diags: &[analyzer::Diagnostic]) -> String {
    let index = LineIndex::new(text);
    let mut out = String::new();
    for d in diags {
        let (l, c) = index.line_col(d.span.start);
        let _ = writeln!(
            out,
            "{}:{} {} {} {}",
            l + 1,
            c + 1,
            d.code,
            d.severity.as_str(),
            d.message
        );
        for r in &d.related {
            let (l, c) = index.line_col(r.span.start);
            let _ = writeln!(out, "    related {}:{} {}", l + 1, c + 1, r.message);
        }
        for f in &d.fixes {
            let _ = writeln!(out, "    fix: {}", f.title);
        }
    }
    out
}

fn fixtures() -> Vec<(String, PathBuf)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/rules");
    let mut out = Vec::new();
    let mut dirs: Vec<_> = std::fs::read_dir(&root)
        .expect("tests/rules")
        .flatten()
        .map(|e| e.path())
        .collect();
    dirs.sort();
    for dir in dirs {
        let Some(code) = dir.file_name().and_then(|n| n.to_str()).map(str::to_string) else {
            continue;
        };
        if !dir.is_dir() || code == "snapshots" {
            continue;
        }
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .expect("rule dir")
            .flatten()
            .map(|e| e.path())
            .collect();
        files.sort();
        for f in files {
            let name = f.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if (name.starts_with("valid_") || name.starts_with("invalid_"))
                && !name.ends_with(".toml")
            {
                out.push((code.clone(), f));
            }
        }
    }
    out
}

#[test]
fn rule_fixtures() {
    let files = fixtures();
    assert!(files.len() > 20, "fixtures not found");
    let mut failures = Vec::new();
    for (code, path) in &files {
        assert!(
            analyzer::rules::registry::lookup(code).is_some(),
            "{}: directory names an unregistered code",
            path.display()
        );
        let text = std::fs::read(path).expect("read fixture");
        let Some(dialect) = fixture_dialect(path, &text) else {
            failures.push(format!(
                "{}: unknown dialect (extension or directive)",
                path.display()
            ));
            continue;
        };
        let settings = settings_for(path, dialect, code);
        let analysis = analyze(text.clone(), &settings);
        let rendered = render(&text, &analysis.diagnostics);
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if name.starts_with("valid_") {
            if !analysis.diagnostics.is_empty() {
                failures.push(format!(
                    "{}: expected no diagnostics, got\n{rendered}",
                    path.display()
                ));
            }
            continue;
        }
        if !analysis.diagnostics.iter().any(|d| d.code == code.as_str()) {
            failures.push(format!(
                "{}: expected {code}, got\n{rendered}",
                path.display()
            ));
        }
        let snap = format!("{code}__{}", name.replace('.', "_"));
        insta::with_settings!({
            snapshot_path => Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/rules/snapshots"),
            prepend_module_to_snapshot => false,
            description => String::from_utf8_lossy(&text).into_owned(),
            omit_expression => true,
        }, {
            insta::assert_snapshot!(snap, rendered);
        });
    }
    assert!(
        failures.is_empty(),
        "{} fixture failure(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}
