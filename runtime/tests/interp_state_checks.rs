//! State checks against the digests' test vectors: cutter-compensation
//! conflicts (T002), modes left on at the end (F008), inverse-time feed (F009),
//! spindle state (F010, C005).

mod common;

use analyzer::Severity;
use common::*;
use runtime::RunOutput;

/// The (code, severity) pairs of a run, in emission order.
fn found(out: &RunOutput, code: &str) -> Vec<Severity> {
    out.diagnostics
        .iter()
        .filter(|d| d.code == code)
        .map(|d| d.severity)
        .collect()
}

#[test]
fn inverse_time_vectors() {
    // rs274ngc.md TV-F1b: G93 then G1 X20 without F.
    let out = run_ngc("G93\nG1 X20\nM2\n");
    assert_eq!(found(&out, "F009"), vec![Severity::Error]);
    // TV-F1c: F alone is ignored.
    let out = run_ngc("G93\nF2\nG1 X1 F2\nM2\n");
    assert_eq!(found(&out, "F009"), vec![Severity::Info]);
    // NGC310: a canned cycle in G93.
    let out = run_ngc("G93\nG81 X1 Z-1 R1\nM2\n");
    assert_eq!(found(&out, "F009"), vec![Severity::Error]);
    // G94 on the same line leaves inverse time before the move.
    let out = run_ngc("G93\nG94 G1 X1 F100\nM2\n");
    assert!(found(&out, "F009").is_empty(), "{:?}", out.diagnostics);
}

#[test]
fn spindle_vectors() {
    // NGC220 / NGC338: G33 and G76 need the spindle turning.
    let out = run_ngc("G0 X0 Z0\nG33 Z-1 K0.1\nM2\n");
    assert_eq!(found(&out, "F010"), vec![Severity::Error]);
    let out = run_ngc("S500 M3\nG0 X0 Z0\nG33 Z-1 K0.1\nM2\n");
    assert!(found(&out, "F010").is_empty(), "{:?}", out.diagnostics);
    // NGC506: M3 with S never set.
    let out = run_ngc("M3\nM5\nM2\n");
    assert_eq!(found(&out, "F010"), vec![Severity::Warning]);
    // SW049: G95 with no spindle speed is a warning in ServoWorks.
    let out = run_sw("G95 F0.1\nG01 X1\nM30\n", "");
    assert_eq!(found(&out, "F010"), vec![Severity::Warning]);
    let out = run_sw("S1000 M03\nG95 F0.1\nG01 X1\nM30\n", "");
    assert!(found(&out, "F010").is_empty(), "{:?}", out.diagnostics);
}

#[test]
fn cycle_spindle_vectors() {
    // servoworks.md TV-59: M4 suits G74; M3 before it raises SW120.
    let cyc = "G90 G99 G74 X200 Y200 Z-100 R-20 P500 F200\nG80\nM30\n";
    let ok = run_sw(&format!("M4 S500\n{cyc}"), "");
    assert!(found(&ok, "C005").is_empty(), "{:?}", ok.diagnostics);
    let bad = run_sw(&format!("M3 S500\n{cyc}"), "");
    assert_eq!(found(&bad, "C005"), vec![Severity::Warning]);
    // SW119 / FAN077: no spindle at all; FAN078: G84 with M04.
    let none = run_fanuc("G90 G99 G81 X10 Y10 Z-5 R2 F100\nG80\nM30\n", "");
    assert_eq!(found(&none, "C005"), vec![Severity::Warning]);
    let rev = run_fanuc("M04 S300\nG90 G99 G84 X10 Y10 Z-5 R2 F300\nG80\nM30\n", "");
    assert_eq!(found(&rev, "C005"), vec![Severity::Warning]);
}

#[test]
fn comp_conflict_vectors() {
    let pre = "G0 X0 Y0\nG41.1 D0.4\nG1 X1 F100\n";
    for (line, what) in [
        ("G28", "G28"),
        ("G30", "G30"),
        ("G53 G0 X0", "G53"),
        ("G92 X0", "G92"),
        ("G55", "G55"),
        ("G18", "plane"),
        ("G20", "units"),
        ("G42.1 D0.4", "G42"),
        ("G10 L1 P1 R0.1", "G10"),
        ("T1 M6", "M6"),
    ] {
        let out = run_ngc(&format!("{pre}{line}\nG40 G1 X2\nM2\n"));
        assert_eq!(
            found(&out, "T002"),
            vec![Severity::Error],
            "{what}: {:?}",
            out.diagnostics
        );
    }
    // Codes that leave the active system or the plane alone are fine.
    for line in ["G17", "G21", "G10 L2 P2 X1"] {
        let out = run_ngc(&format!("{pre}{line}\nG40 G1 X2\nM2\n"));
        assert!(
            found(&out, "T002").is_empty(),
            "{line}: {:?}",
            out.diagnostics
        );
    }
    // FANUC PS0037: plane change during G41.
    let out = run_fanuc("G41 G01 X10 Y0 D1 F100\nG18\nG40 G01 X0\nM30\n", "");
    assert_eq!(found(&out, "T002"), vec![Severity::Error]);
}

#[test]
fn modes_left_on_at_end() {
    let out = run_ngc("G92 X1\nG0 X2\nM2\n");
    assert_eq!(found(&out, "F008"), vec![Severity::Warning]);
    let out = run_ngc("G92 X1\nG0 X2\nG92.1\nM2\n");
    assert!(found(&out, "F008").is_empty(), "{:?}", out.diagnostics);
    // FANUC: rotation and scaling both left on give one warning each.
    let out = run_fanuc("G51 X0 Y0 P2\nG68 X0 Y0 R30\nG01 X1 F100\nM30\n", "");
    assert_eq!(
        found(&out, "F008"),
        vec![Severity::Warning, Severity::Warning]
    );
    // ServoWorks: a modal canned cycle at M30.
    let out = run_sw("M3 S500\nG99 G81 X1 Y1 Z-5 R2 F100\nM30\n", "");
    assert_eq!(found(&out, "F008"), vec![Severity::Warning]);
}
