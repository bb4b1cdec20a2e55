//! Incremental re-analysis equals a full analysis: random edit sequences on
//! the rule fixtures of every dialect, compared after each edit with
//! `analyzer::analyze` (and with the syntax-only analysis) of the same text.

use std::path::PathBuf;
use std::sync::Arc;

use analyzer::incremental::{diff, reference, Edit, Incremental};
use analyzer::rules::{self, ProgramCx};
use analyzer::{Dialect, Settings};
use proptest::prelude::*;

/// The fixtures of one dialect joined into one program (several thousand bytes
/// of varied syntax: O-words, macros, `%` lines, comments, errors).
fn corpus(ext: &str) -> Vec<u8> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/rules");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&root)
        .expect("fixtures")
        .flatten()
        .flat_map(|d| std::fs::read_dir(d.path()).into_iter().flatten().flatten())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    files.sort();
    let mut out = Vec::new();
    for f in files {
        out.extend(std::fs::read(f).expect("fixture"));
    }
    out
}

/// Fragments an edit inserts: line and block breaks, comment and `%`
/// delimiters, words, statements that change whole-file structure.
const FRAGMENTS: &[&str] = &[
    "\n",
    "\r\n",
    "\r",
    ";",
    "%",
    "%\n",
    "(",
    ")",
    "(partscope: allow W001)",
    " ",
    "G1 X1.5 ",
    "G2",
    "G10 L2 P1 X0\n",
    "G04 P1\n",
    "X",
    "#1=2\n",
    "#<a>=[1+2]",
    "[",
    "]",
    "o100 sub\n",
    "o100 endsub\n",
    "o<x> if [#1 GT 0]\n",
    "o<x> endif\n",
    "IF [#1 GT 2] GOTO 10;\n",
    "N10 ",
    "GOTO 20\n",
    "WHILE [#1 LT 3] DO 1\n",
    "END 1\n",
    "/",
    "M30\n",
    "M2",
    "M99\n",
    "O1234\n",
    "G81 Z-1 R1\n",
    "T1 M6\n",
    "Ä",
    "\u{0}",
    // Runs of plain blocks (the whole-file rules visit a run once), one
    // just over the 80-byte bound of a plain block and lines over the
    // ServoWorks and LinuxCNC length limits.
    "G1 X1 Y2 F300\nG1 X2 Y3\nG0 Z5\n",
    "M2\nG1 X1\nG1 Y1\n",
    "G1 X1.000000000000000000000000000000000000000000000000000000000000000000000000 Y2\n",
    "G1 X1.0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000 Y2\n",
];

#[derive(Debug, Clone)]
enum Op {
    /// Replace bytes `[at, at + len)` (positions as fractions of the length) with a fragment.
    Replace { at: f64, len: usize, frag: usize },
    /// Delete whole lines.
    DeleteLines { at: f64, lines: usize },
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        4 => (0.0..1.0f64, 0usize..4, 0..FRAGMENTS.len()).prop_map(|(at, len, frag)| Op::Replace { at, len, frag }),
        1 => (0.0..1.0f64, 1usize..4).prop_map(|(at, lines)| Op::DeleteLines { at, lines }),
    ]
}

fn apply(text: &[u8], op: &Op) -> Vec<u8> {
    let n = text.len();
    match op {
        Op::Replace { at, len, frag } => {
            let a = ((*at * n as f64) as usize).min(n);
            let b = (a + len).min(n);
            let mut out = text[..a].to_vec();
            out.extend_from_slice(FRAGMENTS[*frag].as_bytes());
            out.extend_from_slice(&text[b..]);
            out
        }
        Op::DeleteLines { at, lines } => {
            let a = ((*at * n as f64) as usize).min(n);
            let a = text[..a]
                .iter()
                .rposition(|b| *b == b'\n')
                .map_or(0, |i| i + 1);
            let mut b = a;
            for _ in 0..*lines {
                b = text[b..]
                    .iter()
                    .position(|c| *c == b'\n')
                    .map_or(n, |i| b + i + 1);
            }
            let mut out = text[..a].to_vec();
            out.extend_from_slice(&text[b..]);
            out
        }
    }
}

/// Compares two vectors, showing only the first difference (elements that
/// differ only by holding NaN, which is not equal to itself, are equal).
fn same<T: PartialEq + std::fmt::Debug>(a: &[T], b: &[T], what: &str) {
    let differ = |i: &usize| a[*i] != b[*i] && format!("{:?}", a[*i]) != format!("{:?}", b[*i]);
    if let Some(i) = (0..a.len().min(b.len())).find(differ) {
        panic!(
            "{what} differ at {i}: incremental {:?}, full {:?}",
            a[i], b[i]
        );
    }
    assert_eq!(a.len(), b.len(), "{what}: lengths");
}

fn check_equal(inc: &Incremental, text: &[u8], settings: &Settings, syntax_only: bool) {
    let full = reference(Arc::from(text), settings, syntax_only);
    let (a, b) = (&inc.analysis.program, &full.program);
    assert_eq!(&a.text[..], &b.text[..]);
    same(&a.tokens, &b.tokens, "tokens");
    same(&a.blocks, &b.blocks, "blocks");
    same(&a.items, &b.items, "items");
    same(&a.exprs, &b.exprs, "exprs");
    same(&a.expr_lists, &b.expr_lists, "expr lists");
    same(&a.diagnostics, &b.diagnostics, "syntax diagnostics");
    same(&inc.analysis.diagnostics, &full.diagnostics, "diagnostics");
    if !syntax_only {
        plain_runs_change_nothing(&full.program, settings);
    }
}

/// The whole-file rules give the same diagnostics when they visit each run
/// of plain blocks once as when they visit every block (no block plain).
fn plain_runs_change_nothing(p: &analyzer::syntax::Program, settings: &Settings) {
    let enabled = rules::enabled_rules(settings);
    let mut grouped = Vec::new();
    rules::check_whole_program(&ProgramCx::new(p, settings), &enabled, &mut grouped);
    let none = vec![false; p.blocks.len()];
    let mut each = Vec::new();
    rules::check_whole_program(
        &ProgramCx::with_plain(p, settings, &none),
        &enabled,
        &mut each,
    );
    same(
        &grouped,
        &each,
        "whole-file diagnostics (plain runs vs every block)",
    );
    assert_eq!(
        rules::skipped_blocks(p),
        rules::skipped_blocks_in(p, ProgramCx::with_plain(p, settings, &none).segments()),
        "skipped blocks (plain runs vs every block)"
    );
}

fn run_sequence(dialect: Dialect, ext: &str, ops: &[Op], syntax_only: bool) {
    let mut settings = Settings::new(dialect);
    // Style rules too: they are whole-file scans with the most cross-block logic.
    settings.select = vec!["ALL".into()];
    let mut text = corpus(ext);
    // In two steps, as the language server analyses an opened file.
    let parse = Incremental::parse(Arc::from(&text[..]), &settings, syntax_only);
    let rules = parse.rules(&settings);
    let mut inc = parse.with_rules(rules);
    check_equal(&inc, &text, &settings, syntax_only);
    for (i, op) in ops.iter().enumerate() {
        text = apply(&text, op);
        // Every other edit updates the parts without taking them.
        inc = if i % 2 == 0 {
            inc.update_owned(Arc::from(&text[..]), &settings, syntax_only)
        } else {
            let (parse, rules) = inc.into_parts();
            parse.update(&rules, Arc::from(&text[..]), &settings, syntax_only)
        };
        check_equal(&inc, &text, &settings, syntax_only);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn rs274ngc_edits(ops in prop::collection::vec(op(), 1..12)) {
        run_sequence(Dialect::Rs274ngc, "ngc", &ops, false);
    }

    #[test]
    fn fanuc_edits(ops in prop::collection::vec(op(), 1..12)) {
        run_sequence(Dialect::Fanuc, "fnc", &ops, false);
    }

    #[test]
    fn servoworks_edits(ops in prop::collection::vec(op(), 1..12)) {
        run_sequence(Dialect::Servoworks, "sw", &ops, false);
    }

    #[test]
    fn syntax_only_edits(ops in prop::collection::vec(op(), 1..12), d in 0..3usize) {
        let (dialect, ext) = [(Dialect::Rs274ngc, "ngc"), (Dialect::Fanuc, "fnc"), (Dialect::Servoworks, "sw")][d];
        run_sequence(dialect, ext, &ops, true);
    }
}

#[test]
fn diff_finds_the_changed_bytes() {
    assert_eq!(diff(b"G1 X1\n", b"G1 X1\n"), None);
    assert_eq!(
        diff(b"G1 X1\nG1 X2\n", b"G1 X1\nG1 A X2\n"),
        Some(Edit {
            start: 9,
            old_end: 9,
            new_end: 11
        })
    );
    // Repeated bytes: the prefix wins, the suffix never overlaps it.
    assert_eq!(
        diff(b"aaaa", b"aa"),
        Some(Edit {
            start: 2,
            old_end: 4,
            new_end: 2
        })
    );
    assert_eq!(
        diff(b"", b"x"),
        Some(Edit {
            start: 0,
            old_end: 0,
            new_end: 1
        })
    );
}

#[test]
fn an_edit_reparses_only_its_neighbourhood() {
    // A 3000-line program: an edit on line 1500 must leave the tail's parse
    // equal to the full one (checked) and the result must show the new error.
    let settings = Settings::new(Dialect::Rs274ngc);
    let mut text = String::new();
    for i in 0..3000 {
        text.push_str(&format!("G1 X{i} Y1 F100\n"));
    }
    text.push_str("M2\n");
    let inc = Incremental::new(Arc::from(text.as_bytes()), &settings, false);
    let at = text
        .match_indices('\n')
        .nth(1499)
        .map(|(i, _)| i + 1)
        .unwrap();
    let mut edited = text.clone();
    edited.insert_str(at + 3, "A ");
    let inc = inc.update(Arc::from(edited.as_bytes()), &settings, false);
    check_equal(&inc, edited.as_bytes(), &settings, false);
    let codes: Vec<(&str, u32)> = inc
        .analysis
        .diagnostics
        .iter()
        .map(|d| (d.code, d.span.start))
        .collect();
    // L003 points at the missing value, just after the letter.
    assert_eq!(codes, vec![("L003", at as u32 + 4)]);
}

#[test]
fn a_binary_file_parsed_in_two_steps_is_reported_once() {
    let settings = Settings::new(Dialect::Fanuc);
    let text: Vec<u8> = b"G1 X1\n\x00\x01\x02\xff\xfe\x00\x00binary".to_vec();
    let full = analyzer::analyze(text.clone(), &settings);
    let parse = Incremental::parse(Arc::from(&text[..]), &settings, false);
    let rules = parse.rules(&settings);
    assert_eq!(parse.program().blocks.len(), 0);
    let codes: Vec<&str> = rules.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, vec!["L009"]);
    same(&rules.diagnostics, &full.diagnostics, "binary file");
    // An edit of a binary file is a full analysis again.
    let mut edited = text.clone();
    edited.extend_from_slice(b"\x00more");
    let inc = parse.update(&rules, Arc::from(&edited[..]), &settings, false);
    check_equal(&inc, &edited, &settings, false);
}
