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
        Settings::from_config(&config, Some(dialect))
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

/// Applies one fix's edits to a text (edits do not overlap; applied back to front).
fn apply(text: &[u8], fix: &analyzer::Fix) -> Vec<u8> {
    let mut edits = fix.edits.clone();
    edits.sort_by_key(|e| std::cmp::Reverse(e.span.start));
    let mut out = text.to_vec();
    for e in edits {
        out.splice(e.span.range(), e.new_text.bytes());
    }
    out
}

#[test]
fn fixes_remove_their_diagnostic() {
    let mut checked = 0;
    let mut failures = Vec::new();
    for (code, path) in fixtures() {
        let text = std::fs::read(&path).expect("read fixture");
        let Some(dialect) = fixture_dialect(&path, &text) else {
            continue;
        };
        let settings = settings_for(&path, dialect, &code);
        let before = analyze(text.clone(), &settings).diagnostics;
        let count =
            |ds: &[analyzer::Diagnostic], c: &str| ds.iter().filter(|d| d.code == c).count();
        for d in &before {
            for fix in &d.fixes {
                checked += 1;
                let fixed = apply(&text, fix);
                let after = analyze(fixed.clone(), &settings).diagnostics;
                if count(&after, d.code) >= count(&before, d.code) {
                    failures.push(format!(
                        "{}: fix `{}` for {} leaves as many {} diagnostics:\n{}",
                        path.display(),
                        fix.title,
                        d.code,
                        d.code,
                        String::from_utf8_lossy(&fixed)
                    ));
                }
                let new_errors = after
                    .iter()
                    .filter(|a| a.severity == analyzer::Severity::Error)
                    .count();
                let old_errors = before
                    .iter()
                    .filter(|b| b.severity == analyzer::Severity::Error)
                    .count();
                if new_errors > old_errors {
                    failures.push(format!(
                        "{}: fix `{}` introduces errors:\n{}",
                        path.display(),
                        fix.title,
                        render(&fixed, &after)
                    ));
                }
            }
        }
    }
    assert!(checked >= 5, "only {checked} fixes exercised");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

mod robustness {
    use analyzer::dialect::{Dialect, Variant};
    use analyzer::{analyze, Settings};
    use proptest::prelude::*;

    /// Fragments that reach the rules' corner cases: codes, words, O-words, macro
    /// statements, comments, brackets, multi-byte text.
    const PIECES: &[&str] = &[
        "G0 ",
        "G1 ",
        "G2 ",
        "G3 ",
        "G4 ",
        "G10 L2 P1 ",
        "G28 ",
        "G43.2 ",
        "G65 P9010 ",
        "G81 ",
        "G83 ",
        "G80 ",
        "G92 ",
        "G54 ",
        "G02.3 ",
        "G05 ",
        "G51 ",
        "M98 ",
        "M99 ",
        "M3 ",
        "M30 ",
        "M2 ",
        "X1 ",
        "Y-2.5 ",
        "Z ",
        "R0 ",
        "I1 ",
        "K2 ",
        "P1.5 ",
        "Q-1 ",
        "L0 ",
        "D0.5 ",
        "E1 ",
        "@1 ",
        "N10 ",
        "N#1 ",
        "T1.5 ",
        "S2_100 ",
        "#1=",
        "#<a>=",
        "[1/0]",
        "SQRT[-1]",
        "EXISTS[#1]",
        "o100 sub",
        "o100 endsub",
        "o100 while [1]",
        "o100 endwhile",
        "o100 call [1]",
        "o1 do",
        "o1 while [1]",
        "o2 if [1]",
        "o2 else",
        "o2 endif",
        "WHILE [#1 LT 3] DO 1",
        "DO 4",
        "END 1",
        "GOTO 10",
        "IF [#1 EQ 0.5] GOTO 7",
        "(MSG hi)",
        "(DEBUG,%x)",
        ";(debug x)",
        "(ünïcödé 😀)",
        "(",
        ")",
        "[",
        "]",
        "%",
        "/",
        ";",
        "\n",
        "\r\n",
        "O0",
        "0100 sub",
    ];

    fn program() -> impl Strategy<Value = String> {
        prop::collection::vec(0..PIECES.len(), 0..40)
            .prop_map(|ix| ix.into_iter().map(|i| PIECES[i]).collect())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        #[test]
        fn rules_never_panic(text in program(), d in 0usize..3, v in 0usize..2, raw in prop::collection::vec(any::<u8>(), 0..64)) {
            let dialect = Dialect::ALL[d];
            let variants = [[Variant::S100M, Variant::S140M], [Variant::Linuxcnc, Variant::Emc2], [Variant::Fanuc30i, Variant::Fanuc30i]];
            let mut settings = Settings::new(dialect);
            settings.variant = variants[d][v];
            settings.select = vec!["ALL".into(), "S".into(), "W023".into()];
            settings.integer_machine_unit = v == 1;
            let a = analyze(text.into_bytes(), &settings);
            for diag in &a.diagnostics {
                prop_assert!(diag.span.start <= diag.span.end);
            }
            let _ = analyze(raw, &settings);
        }
    }
}

/// Ruff's rule for fixes, over mutated fixture programs in every dialect:
/// applying all fixes settles (a last round finds nothing to fix), and the
/// fixed program has no diagnostic code more often than the original had it.
mod fixes_converge {
    use super::{fixtures, settings_for};
    use analyzer::dialect::Dialect;
    use analyzer::fixes::fix_all;
    use analyzer::{analyze, Settings};
    use proptest::prelude::*;
    use std::collections::BTreeMap;
    use std::sync::OnceLock;

    fn corpus() -> &'static [(String, std::path::PathBuf, Vec<u8>)] {
        static C: OnceLock<Vec<(String, std::path::PathBuf, Vec<u8>)>> = OnceLock::new();
        C.get_or_init(|| {
            fixtures()
                .into_iter()
                .map(|(code, path)| {
                    let text = std::fs::read(&path).expect("read fixture");
                    (code, path, text)
                })
                .collect()
        })
    }

    /// Lines and words the mutations insert: fixable faults of every rule
    /// with a fix, and the end codes that a fix may duplicate.
    const INSERTS: &[&str] = &[
        "G04 P1.5",
        "g04 p2.5",
        "G05 P1",
        "G08 P3",
        "G04 X2",
        "M3.0 S1000.",
        "G1 X1 X2",
        "G0 G1 X1",
        "G0 G0 X1",
        "N10 G1 X1",
        "O100",
        "G65 P9010 A1 B2",
        "G1 X 1 . 5",
        "M98 POne2",
        "(open",
        "M30",
        "M2",
        "M99",
        "%",
        "x1.",
        "",
    ];

    #[derive(Debug, Clone)]
    enum Mutation {
        DeleteLine(usize),
        DuplicateLine(usize),
        InsertLine(usize, usize),
        AppendToLine(usize, usize),
        Lowercase(usize),
        DropEnd,
    }

    fn mutation() -> impl Strategy<Value = Mutation> {
        prop_oneof![
            any::<usize>().prop_map(Mutation::DeleteLine),
            any::<usize>().prop_map(Mutation::DuplicateLine),
            (any::<usize>(), 0..INSERTS.len()).prop_map(|(a, b)| Mutation::InsertLine(a, b)),
            (any::<usize>(), 0..INSERTS.len()).prop_map(|(a, b)| Mutation::AppendToLine(a, b)),
            any::<usize>().prop_map(Mutation::Lowercase),
            Just(Mutation::DropEnd),
        ]
    }

    fn mutate(text: &[u8], ms: &[Mutation]) -> Vec<u8> {
        let text = String::from_utf8_lossy(text).into_owned();
        let mut lines: Vec<String> = text.split('\n').map(str::to_string).collect();
        for m in ms {
            let n = lines.len().max(1);
            match m {
                Mutation::DeleteLine(i) if lines.len() > 1 => {
                    lines.remove(i % lines.len());
                }
                Mutation::DuplicateLine(i) if !lines.is_empty() => {
                    let l = lines[i % lines.len()].clone();
                    lines.insert(i % lines.len(), l);
                }
                Mutation::InsertLine(i, k) => lines.insert(i % n, INSERTS[*k].to_string()),
                Mutation::AppendToLine(i, k) if !lines.is_empty() => {
                    let j = i % lines.len();
                    lines[j] = format!("{} {}", lines[j], INSERTS[*k]);
                }
                Mutation::Lowercase(i) if !lines.is_empty() => {
                    let j = i % lines.len();
                    lines[j] = lines[j].to_ascii_lowercase();
                }
                Mutation::DropEnd => {
                    lines.retain(|l| {
                        let u = l.trim().trim_end_matches(';').to_ascii_uppercase();
                        !matches!(u.as_str(), "M30" | "M2" | "M02" | "%")
                    });
                }
                _ => {}
            }
        }
        lines.join("\n").into_bytes()
    }

    /// Where an offset of the text after `edits` was before them (an offset
    /// inside an inserted text maps to where the insertion began).
    fn map_back(offset: u32, edits: &[analyzer::TextEdit]) -> u32 {
        let mut delta: i64 = 0;
        for e in edits {
            let new_start = e.span.start as i64 + delta;
            let new_end = new_start + e.new_text.len() as i64;
            if (offset as i64) < new_start {
                break;
            }
            if (offset as i64) < new_end {
                return e.span.start;
            }
            delta += e.new_text.len() as i64 - e.span.len() as i64;
        }
        (offset as i64 - delta).max(0) as u32
    }

    /// One round of fixes must not add a diagnostic. A syntax error hides the
    /// block rules of its line, so a diagnostic on a line that held one before
    /// the round is unmasked by its fix, not added by it.
    fn round_adds(
        text: &[u8],
        before: &[analyzer::Diagnostic],
        edits: &[analyzer::TextEdit],
        after: &[analyzer::Diagnostic],
    ) -> Option<String> {
        let index = analyzer::LineIndex::new(text);
        let masked: std::collections::BTreeSet<u32> = before
            .iter()
            .filter(|d| d.code.starts_with('L') && d.severity == analyzer::Severity::Error)
            .map(|d| index.line_col(d.span.start).0)
            .collect();
        let mut had: BTreeMap<&str, usize> = BTreeMap::new();
        for d in before {
            *had.entry(d.code).or_insert(0) += 1;
        }
        let mut now: BTreeMap<&str, usize> = BTreeMap::new();
        for d in after {
            let line = index.line_col(map_back(d.span.start, edits)).0;
            if masked.contains(&line) && !d.code.starts_with('L') {
                continue;
            }
            // W023 notes explain correct code (`G04 P1500`: milliseconds); they
            // report no fault, so a fix that writes such code adds none.
            if d.code == "W023" {
                continue;
            }
            *now.entry(d.code).or_insert(0) += 1;
        }
        now.into_iter()
            .find(|(c, n)| *n > had.get(c).copied().unwrap_or(0))
            .map(|(c, n)| format!("{c} ({} -> {n})", had.get(c).copied().unwrap_or(0)))
    }

    fn check(text: &[u8], settings: &Settings) -> Result<(), String> {
        let mut text = text.to_vec();
        let original = text.clone();
        let mut diags = analyze(text.clone(), settings).diagnostics;
        for _ in 0..analyzer::fixes::MAX_ROUNDS {
            let edits = analyzer::fixes::compatible_edits(&diags);
            let next = analyzer::fixes::apply_edits(&text, &edits);
            if edits.is_empty() || next == text {
                // fix_all, which hosts call, takes the same rounds.
                let all = fix_all(&original, settings);
                if !all.settled || all.text != text {
                    return Err("fix_all does not take the same rounds".into());
                }
                return Ok(());
            }
            let after = analyze(next.clone(), settings).diagnostics;
            if let Some(added) = round_adds(&text, &diags, &edits, &after) {
                return Err(format!(
                    "fixes add {added}:\n--- before\n{}\n--- after\n{}",
                    String::from_utf8_lossy(&text),
                    String::from_utf8_lossy(&next)
                ));
            }
            text = next;
            diags = after;
        }
        Err(format!(
            "fixes did not settle in {} rounds:\n{}",
            analyzer::fixes::MAX_ROUNDS,
            String::from_utf8_lossy(&text)
        ))
    }

    /// Every fixture as it is, in every dialect.
    #[test]
    fn fixtures_as_they_are() {
        let mut failures = Vec::new();
        for (code, path, text) in corpus() {
            for dialect in Dialect::ALL {
                let settings = settings_for(path, dialect, code);
                if let Err(e) = check(text, &settings) {
                    failures.push(format!("{} as {dialect:?}: {e}", path.display()));
                }
            }
        }
        assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        #[test]
        fn mutated_fixtures(pick in any::<usize>(), d in 0usize..3, ms in prop::collection::vec(mutation(), 1..6)) {
            let corpus = corpus();
            let (code, path, text) = &corpus[pick % corpus.len()];
            let settings = settings_for(path, Dialect::ALL[d], code);
            let text = mutate(text, &ms);
            if let Err(e) = check(&text, &settings) {
                prop_assert!(false, "{} as {:?}: {}", path.display(), Dialect::ALL[d], e);
            }
        }
    }
}
