//! Formatting never changes what the control executes: every rule fixture and
//! every example program, formatted with each kind of option, runs (interpreter
//! and planner) to the same motions, times and diagnostics as before.

use std::path::{Path, PathBuf};

use analyzer::format::{format_edits, FormatOptions, Numbers, Spacing};
use analyzer::{Dialect, FileId, Settings};
use runtime::{run, ResolvedFile, Resolver, RunInput};

/// Both runs see the same (absent) subprogram files.
struct NoFiles;

impl Resolver for NoFiles {
    fn resolve(&self, _: &str, _: FileId) -> Option<ResolvedFile> {
        None
    }
}

fn programs() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p
                .extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| ["ngc", "nc", "fnc", "sw", "dat"].contains(&x))
            {
                out.push(p);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out = Vec::new();
    walk(&root.join("analyzer/tests/rules"), &mut out);
    walk(&root.join("examples"), &mut out);
    out.sort();
    out
}

fn dialect_of(path: &Path, text: &[u8]) -> Dialect {
    let name = path.file_name().and_then(|n| n.to_str());
    analyzer::settings::sniff_file_dialect_why(name, text)
        .map(|(d, _)| d)
        .unwrap_or(Dialect::Rs274ngc)
}

/// What a run shows the user, rounded to what the output prints.
fn run_summary(text: &[u8], settings: &Settings) -> String {
    let a = analyzer::analyze(text.to_vec(), settings);
    let machine = analyzer::config::MachineConfig::default();
    let input = RunInput {
        program: &a.program,
        settings,
        machine: &machine,
        resolver: &NoFiles,
        step_budget: 200_000,
        motion_budget: 200_000,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    };
    let out = run(&input);
    let index = analyzer::LineIndex::new(text);
    let line = |s: analyzer::Span| index.line_col(s.start).0 + 1;
    let mut s = String::new();
    for m in &out.motions {
        s += &format!("{:?} {:?} -> {:?} F{:.4}\n", m.kind, m.start, m.end, m.feed);
    }
    let profile = runtime::dryrun::profile_from_table(&machine, settings.dialect);
    let dry = runtime::dryrun::plan_run(&out, &profile);
    s += &format!("cycle {:.6} s\n", dry.totals.cycle_time_s);
    for d in &out.diagnostics {
        s += &format!(
            "run {} {} line {} {}\n",
            d.code,
            d.severity.as_str(),
            line(d.span),
            d.message
        );
    }
    // Static errors (warnings such as lower case or blanks are what formatting mends).
    for d in a
        .diagnostics
        .iter()
        .filter(|d| d.severity == analyzer::Severity::Error)
    {
        s += &format!("static {} line {}\n", d.code, line(d.span));
    }
    s
}

#[test]
fn formatting_keeps_every_run() {
    let option_sets = [
        FormatOptions {
            numbers: Numbers::Renumber {
                start: 10,
                step: 10,
            },
            spacing: Spacing::One,
            uppercase: true,
        },
        FormatOptions {
            numbers: Numbers::Add { start: 1, step: 1 },
            spacing: Spacing::None,
            uppercase: true,
        },
        FormatOptions {
            numbers: Numbers::Remove,
            spacing: Spacing::One,
            uppercase: false,
        },
    ];
    let mut compared = 0;
    let mut changed = 0;
    let mut failures = Vec::new();
    for path in programs() {
        let text = std::fs::read(&path).expect("read program");
        let dialect = dialect_of(&path, &text);
        let settings = Settings::new(dialect);
        let a = analyzer::analyze(text.clone(), &settings);
        let before = run_summary(&text, &settings);
        for opts in &option_sets {
            let Ok(edits) = format_edits(&a.program, opts) else {
                continue;
            };
            let formatted = analyzer::fixes::apply_edits(&text, &edits);
            compared += 1;
            changed += usize::from(formatted != text);
            let after = run_summary(&formatted, &settings);
            if after != before {
                failures.push(format!(
                    "{} ({dialect:?}, {opts:?}):\n--- formatted\n{}\n--- before\n{before}\n--- after\n{after}",
                    path.display(),
                    String::from_utf8_lossy(&formatted)
                ));
            }
        }
    }
    assert!(
        compared > 300,
        "only {compared} formatted programs compared"
    );
    assert!(
        changed > 200,
        "only {changed} programs changed by formatting"
    );
    let names: Vec<&str> = failures.iter().filter_map(|f| f.lines().next()).collect();
    assert!(
        failures.is_empty(),
        "{}\n\n{} of {compared} differ:\n{}",
        failures[..failures.len().min(3)].join("\n\n"),
        failures.len(),
        names.join("\n")
    );
}
