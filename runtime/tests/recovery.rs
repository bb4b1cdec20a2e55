//! Recovery after runtime errors (issue #17): every independent fault reported once,
//! on its line, with no diagnostics that follow from it; errors that leave the state
//! undefined stop the run and say so; the cap on runtime errors; canonical output
//! still stops where rs274 stops.

mod common;

use analyzer::{Dialect, LineIndex, Settings, Severity};
use common::{codes, ends, run_fanuc, run_ngc, run_sw, run_with, MapResolver};
use runtime::{run, RunInput, RunOutput};

const NGC: &str = include_str!("../../tests/recovery/runtime_errors.ngc");
const FANUC: &str = include_str!("../../tests/recovery/runtime_errors.fnc");
const SW: &str = include_str!("../../tests/recovery/runtime_errors.sw");

/// (code, 1-based line, severity) of every runtime diagnostic.
fn located(text: &str, out: &RunOutput) -> Vec<(&'static str, u32, Severity)> {
    let idx = LineIndex::new(text.as_bytes());
    out.diagnostics
        .iter()
        .map(|d| (d.code, idx.line_col(d.span.start).0 + 1, d.severity))
        .collect()
}

fn errors(list: &[(&'static str, u32)]) -> Vec<(&'static str, u32, Severity)> {
    list.iter()
        .map(|(c, l)| (*c, *l, Severity::Error))
        .collect()
}

/// Runs with a runtime-error cap and optionally canonical output.
fn run_capped(dialect: Dialect, text: &str, cap: usize, canon: bool) -> RunOutput {
    let mut settings = Settings::new(dialect);
    settings.max_runtime_errors = cap;
    let a = analyzer::analyze(text.as_bytes().to_vec(), &settings);
    let machine = analyzer::config::MachineConfig::default();
    let resolver = MapResolver(Default::default());
    run(&RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &resolver,
        step_budget: 100_000,
        motion_budget: u64::MAX,
        emit_canon: canon,
        tool_table: None,
        var_file: None,
    })
}

#[test]
fn rs274ngc_fixture_reports_each_of_its_six_errors_on_its_line() {
    let out = run_ngc(NGC);
    assert_eq!(
        located(NGC, &out),
        errors(&[
            ("F001", 5),
            ("A001", 7),
            ("A002", 9),
            ("C001", 11),
            ("F002", 13),
            ("X001", 14),
        ])
    );
    // The run reached M2: the last move is the retract to Z10.
    assert!(out.stopped.is_none());
    let last = *ends(&out).last().unwrap();
    assert_eq!(last[2], 10.0);
}

#[test]
fn fanuc_fixture_reports_each_of_its_six_errors_on_its_line() {
    let out = run_fanuc(FANUC, "");
    assert_eq!(
        located(FANUC, &out),
        errors(&[
            ("A001", 7),
            ("A002", 9),
            ("C001", 11),
            ("F002", 13),
            ("X001", 14),
            ("X001", 17),
        ])
    );
    assert!(out.stopped.is_none());
    assert_eq!(ends(&out).last().unwrap()[2], 10.0);
}

#[test]
fn servoworks_fixture_reports_each_of_its_five_errors_on_its_line() {
    let out = run_sw(SW, "");
    assert_eq!(
        located(SW, &out),
        errors(&[
            ("A001", 6),
            ("A002", 8),
            ("C001", 10),
            ("F002", 12),
            ("X001", 14),
        ])
    );
    assert!(out.stopped.is_none());
    assert_eq!(ends(&out).last().unwrap()[2], 10.0);
}

#[test]
fn an_arc_off_its_circle_moves_straight_to_its_end() {
    let out = run_ngc("G21 G17 G90\nG0 X0 Y0\nG2 X10 Y0 I4 J0 F100\nG1 X10 Y5\nM2\n");
    assert_eq!(codes(&out), vec!["A001"]);
    let m = &out.motions[1];
    assert!(matches!(m.kind, runtime::MotionKind::Feed));
    assert_eq!(m.end[0], 10.0);
    assert_eq!(ends(&out)[2], [10.0, 5.0, 0.0]);
}

#[test]
fn an_arc_without_centre_leaves_the_tool_at_its_end_without_a_move() {
    let out = run_ngc("G21 G17 G90\nG0 X0 Y0\nG2 X30 Y0 F100\nG91 G1 X1\nM2\n");
    assert_eq!(codes(&out), vec!["A005"]);
    // The incremental move after the skipped arc starts at its end.
    assert_eq!(ends(&out), vec![[0.0, 0.0, 0.0], [31.0, 0.0, 0.0]]);
}

#[test]
fn a_missing_subprogram_call_is_skipped() {
    let out = run_with(
        Dialect::Fanuc,
        "G21 G90;\nM98 P1234;\nG00 X5.;\nM30;\n",
        "",
        &[],
        None,
    );
    assert_eq!(codes(&out), vec!["F002"]);
    assert_eq!(ends(&out), vec![[5.0, 0.0, 0.0]]);
}

/// A called file in another control's macro language (here Syntec's: `%@MACRO`,
/// `//` comments, `@` variables, `END_IF`) is one `P010` in that file and one
/// skipped-call warning in the caller, whose later calls of it are the same fault
/// (related locations), not a syntax error on every line of the called file.
#[test]
fn a_called_file_for_another_control_is_one_finding_and_the_call_is_skipped() {
    let syntec = "%@MACRO;  //O9810 move\nWAIT();\nIF #24 <> #0 THEN\n  @100 := #24;\nEND_IF;\nG01 X@100 F#9;\nM99;\n";
    let text = "O1000;\nG21 G90;\nG65 P9810 X5. F300.;\nG00 X7.;\nG65 P9810 X1. F300.;\nM30;\n";
    let out = run_with(Dialect::Fanuc, text, "", &[("9810", syntec)], None);
    let found: Vec<(&str, u32)> = out.diagnostics.iter().map(|d| (d.code, d.file.0)).collect();
    assert_eq!(
        found,
        vec![("P010", 1), ("F002", 0)],
        "{:#?}",
        out.diagnostics
    );
    let skipped = &out.diagnostics[1];
    let index = LineIndex::new(text.as_bytes());
    assert_eq!(index.line_col(skipped.span.start).0, 2);
    assert_eq!(
        skipped.message,
        "O9810 looks written for another control (P010 in its file): the dry run skips the call, so what it would set and move is unknown (the same fault on 1 later block)"
    );
    let again: Vec<(u32, u32)> = skipped
        .related
        .iter()
        .map(|r| (r.file.0, index.line_col(r.span.start).0))
        .collect();
    assert_eq!(again, vec![(0, 4)]);
    // The caller runs on past both calls.
    assert_eq!(ends(&out), vec![[7.0, 0.0, 0.0]]);
    assert!(out.stopped.is_none());
}

#[test]
fn a_value_an_error_left_unknown_reports_nothing_more() {
    // #1 is unknown after line 2; line 3 divides by it and line 4 moves by it: both
    // would be reported again without the taint.
    let text =
        "G21 G90\n#1 = #<nowhere>\n#2 = [10 / #1]\nG1 X#2 F100\n#1 = 2\n#3 = [10 / [#1 - 2]]\nM2\n";
    let out = run_ngc(text);
    // Once #1 is assigned again its value is known, and a real fault is reported.
    assert_eq!(located(text, &out), errors(&[("X001", 2), ("X001", 6)]));
    assert!(out.stopped.is_none());
}

#[test]
fn a_branch_an_unknown_value_decides_gets_a_note() {
    let text = "G21 G90\n#1 = #<nowhere>\no1 if [#1 GT 0]\nG0 X1\no1 endif\nM2\n";
    let out = run_ngc(text);
    assert_eq!(
        located(text, &out),
        vec![("X001", 2, Severity::Error), ("X001", 3, Severity::Info)]
    );
    assert!(out.diagnostics[1]
        .message
        .starts_with("this condition reads a value an earlier error left unknown"));
    let text = "#1 = #1000000;\nIF [#1 GT 0] GOTO 5;\nG00 X1.;\nN5 M30;\n";
    let out = run_fanuc(text, "");
    assert_eq!(
        located(text, &out),
        vec![("X001", 1, Severity::Error), ("X001", 2, Severity::Info)]
    );
}

#[test]
fn an_error_that_leaves_the_state_undefined_stops_the_run_and_says_so() {
    let text = "G21 G90;\nG00 X1.;\nGOTO 99;\nG00 X2.;\nM30;\n";
    let out = run_fanuc(text, "");
    assert_eq!(located(text, &out), errors(&[("F007", 3)]));
    assert!(out.diagnostics[0]
        .message
        .ends_with(runtime::interp::STOP_SUFFIX));
    let stop = out.stopped.as_ref().expect("stopped");
    assert_eq!((stop.line, stop.code), (2, "F007"));
    assert!(!stop.reason.ends_with(runtime::interp::STOP_SUFFIX));
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0]]);
}

#[test]
fn the_step_budget_marks_the_run_stopped() {
    let out = run_fanuc("WHILE [1 EQ 1] DO1;\nG91 G00 X1.;\nEND1;\nM30;\n", "");
    assert_eq!(codes(&out), vec!["F004"]);
    let stop = out.stopped.as_ref().expect("stopped");
    assert_eq!(stop.code, "F004");
}

#[test]
fn the_runtime_error_cap_stops_a_flood_with_one_diagnostic() {
    let mut text = String::from("G21 G17 G90 F100\n");
    // Independent faults (a repeat of one is folded into its first report).
    for i in 0..150 {
        text.push_str(&format!("G0 X#[100000+{i}]\nG0 X{} Y0\n", i + 1));
    }
    text.push_str("M2\n");
    let out = run_capped(Dialect::Rs274ngc, &text, 100, false);
    let c = codes(&out);
    assert_eq!(c.iter().filter(|c| **c == "X001").count(), 100, "{c:?}");
    assert_eq!(c.last(), Some(&"F004"));
    assert_eq!(c.len(), 101);
    let stop = out.stopped.as_ref().expect("stopped");
    assert_eq!((stop.code, stop.line), ("F004", 199));
    assert!(stop.reason.contains("100 runtime errors"));
    assert!(stop.reason.contains("--max-runtime-errors"));
}

#[test]
fn canonical_output_stops_at_the_first_error_as_rs274_does() {
    let out = run_capped(Dialect::Rs274ngc, NGC, 100, true);
    assert_eq!(codes(&out), vec!["F001"]);
    assert_eq!(
        out.canon_error.as_deref(),
        Some("Cannot do g1 with zero feed rate\nG1 X1")
    );
    assert_eq!(out.stopped.as_ref().map(|s| s.line), Some(4));
}

/// One fault, one diagnostic: the same recovered error on later blocks (every
/// feed move of a program that never gives F) is one report that counts the
/// repeats and points at them; it does not use up the runtime-error cap.
#[test]
fn a_repeated_fault_is_one_report() {
    let mut text = String::from("G21 G90\n");
    for i in 1..=150 {
        text.push_str(&format!("G1 X{i}\n"));
    }
    text.push_str("G0 Y1\nM2\n");
    let out = run_ngc(&text);
    assert_eq!(located(&text, &out), errors(&[("F001", 2)]));
    let d = &out.diagnostics[0];
    assert!(
        d.message.ends_with("(the same fault on 149 later blocks)"),
        "{}",
        d.message
    );
    assert_eq!(d.related.len(), 20);
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    // The run went on to the end: the closing rapid starts at X150.
    assert_eq!(out.motions.last().map(|m| m.start[0]), Some(150.0));
}

/// A call skipped because its subroutine is missing leaves the globals it would
/// have set unknown: reading one reports nothing more.
#[test]
fn globals_of_a_skipped_call_are_unknown() {
    let text = "G21\no<setup> call\nG0 X#<_safe_x>\nG0 X#<_never_set>\nM2\n";
    let out = run_ngc(text);
    assert_eq!(located(text, &out), errors(&[("F002", 2)]));
}
