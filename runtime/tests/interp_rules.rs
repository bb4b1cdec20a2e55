//! Every runtime rule's documented examples: the invalid one produces the
//! rule's code, the fixed one does not.

mod common;

use analyzer::Dialect;
use common::*;
use runtime::rules::REGISTRY;

/// The `gcode` blocks of a rule doc, in order.
fn examples(doc: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur: Option<String> = None;
    for line in doc.lines() {
        let t = line.trim();
        if t.starts_with("```") {
            match cur.take() {
                Some(block) => out.push(block),
                None => cur = Some(String::new()),
            }
            continue;
        }
        if let Some(b) = cur.as_mut() {
            b.push_str(t);
            b.push('\n');
        }
    }
    out
}

/// Dialect and machine profile under which a rule's examples are written.
fn setup(code: &str) -> (Dialect, &'static str, Option<&'static str>) {
    match code {
        "A003" | "A004" => (Dialect::Servoworks, "circle_error_allowance = 2.5", None),
        "A007" | "C004" | "C006" | "X004" | "X005" | "F005" | "F007" | "A012" | "K004" | "F018"
        | "C009" | "T007" | "K005" | "X010" => (Dialect::Fanuc, "", None),
        "D001" | "D002" | "K001" | "C005" | "T005" | "D003" | "F016" | "T006" | "F017" => {
            (Dialect::Servoworks, "", None)
        }
        "T008" => (Dialect::Rs274ngc, "", Some("T1 P1 D0.125\nT2 P1 D0.25\n")),
        "T001" => (Dialect::Rs274ngc, "", Some("T1 P1 D0.125 Z+0.511\n")),
        "K002" => (
            Dialect::Rs274ngc,
            "[[axes]]\nletter = \"X\"\nmin_travel = -100.0\nmax_travel = 100.0\n",
            None,
        ),
        _ => (Dialect::Rs274ngc, "", None),
    }
}

#[test]
fn documented_examples_behave() {
    let mut checked = 0;
    for meta in REGISTRY {
        let ex = examples(meta.doc);
        assert_eq!(
            ex.len(),
            2,
            "{}: needs an invalid and a valid example",
            meta.code
        );
        let (dialect, machine, tools) = setup(meta.code);
        // Rules about input files: the invalid run reads a bad file, the valid one a good one.
        let (files, var): (&[(&str, &str)], _) = match meta.code {
            "F017" => (
                &[
                    ("NoReturn", "%\nONoReturn\nG01 X1. F100.\n%\n"),
                    ("MoveXY", "%\nOMoveXY\nG01 X1. F100.\nM99\n%\n"),
                ],
                None,
            ),
            "X011" => (&[], Some("5221 1.0\n5220 1.0\n")),
            _ => (&[], None),
        };
        // Rules that are off by default are selected for their examples.
        let select = (!meta.default_enabled).then_some(meta.code);
        let bad = run_full_sel(dialect, &ex[0], machine, files, tools, var, select);
        assert!(
            codes(&bad).contains(&meta.code),
            "{}: invalid example gives {:?}",
            meta.code,
            bad.diagnostics
        );
        let good_tools = if meta.code == "T008" { None } else { tools };
        let good = run_full_sel(dialect, &ex[1], machine, files, good_tools, None, select);
        assert!(
            !codes(&good).contains(&meta.code),
            "{}: valid example gives {:?}",
            meta.code,
            good.diagnostics
        );
        checked += 1;
    }
    assert_eq!(checked, REGISTRY.len());
}

#[test]
fn registry_is_consistent() {
    let mut seen = std::collections::HashSet::new();
    for meta in REGISTRY {
        assert!(seen.insert(meta.code), "duplicate {}", meta.code);
        assert!(
            analyzer::rules::registry::lookup(meta.code).is_none(),
            "{} collides with a static rule",
            meta.code
        );
        for section in [
            "## What it does",
            "## Why is this bad?",
            "## Example",
            "Use instead:",
            "## Dialects",
            "Implements:",
        ] {
            assert!(meta.doc.contains(section), "{} lacks {section}", meta.code);
        }
        assert_eq!(
            runtime::rules::lookup(meta.name).map(|m| m.code),
            Some(meta.code)
        );
    }
}
