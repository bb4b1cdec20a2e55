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

/// M3 with no S is one fault however often the program turns the spindle (or a
/// sprayer's valve) on and off: reported at the first M3, and again only after an
/// S word set the speed to 0 once more.
#[test]
fn m3_at_s0_is_reported_once_until_an_s_word() {
    let out = run_ngc("G1 M3 X1 F100\nM5\nG1 M3 X2\nM5\nM4\nS0 M3\nM5\nS1000 M3\nM2\n");
    let lines: Vec<u32> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "F010")
        .map(|d| d.span.start)
        .collect();
    assert_eq!(lines.len(), 2, "{:?}", out.diagnostics);
    let text = "G1 M3 X1 F100\nM5\nG1 M3 X2\nM5\nM4\nS0 M3\n";
    assert_eq!(lines, vec![3, text.len() as u32 - 3]);
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
    // The sequence: feed down turning CCW, dwell 500 ms, CW, feed up, back to CCW.
    let seq: Vec<String> = {
        let mut v = Vec::new();
        let mut e = ok.events.iter().peekable();
        for (i, m) in ok.motions.iter().enumerate() {
            while let Some(ev) = e.next_if(|ev| ev.motion_index <= i) {
                v.push(format!("{:?}", ev.kind));
            }
            v.push(format!("{:?} to Z{}", m.kind, m.end[2]));
        }
        v.extend(e.map(|ev| format!("{:?}", ev.kind)));
        v
    };
    assert_eq!(
        seq,
        vec![
            "Spindle { rpm: 500.0, dir: -1 }",
            "Rapid to Z0",
            "Rapid to Z-20",
            "Feed to Z-100",
            "Dwell(0.5)",
            "Spindle { rpm: 500.0, dir: 1 }",
            "Feed to Z-20",
            "Spindle { rpm: 500.0, dir: -1 }",
            "ProgramEnd",
        ]
    );
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
        ("G42.1 D0.4", "G42"),
        ("G10 L2 P0 X1", "G10"),
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
    // Codes LinuxCNC 2.9's rs274 accepts under compensation (EMC2 refused
    // G20 and G10 L1), and codes that leave the active system or the plane alone.
    for line in [
        "G17",
        "G21",
        "G20",
        "G10 L1 P1 R0.1",
        "G92.1",
        "G10 L2 P2 X1",
    ] {
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

/// The messages of one code, in emission order.
fn messages<'o>(out: &'o RunOutput, code: &str) -> Vec<&'o str> {
    out.diagnostics
        .iter()
        .filter(|d| d.code == code)
        .map(|d| d.message.as_str())
        .collect()
}

#[test]
fn cycle_hygiene_vectors() {
    // FAN075: K3 in G90 drills one hole three times.
    let out = run_fanuc(
        "M3 S500\nG90 G0 Z10\nG81 X0 Y0 Z-5 R2 K3 F100\nG80\nM30\n",
        "",
    );
    assert_eq!(found(&out, "C006"), vec![Severity::Warning]);
    // NGC316: L2 in G90, and NGC319: G98 from Z1 below R2.
    let out = run_ngc("G0 Z1\nG98 G81 X0 Y0 Z-1 R2 L2 F100\nG80\nM2\n");
    assert_eq!(
        messages(&out, "C006"),
        vec![
            "L2 repeats the cycle in absolute mode (G90): every repeat drills the same hole; use G91 to step between holes",
            "G98 has no effect here: the start height 1 is below R 2, so the cycle retracts to R",
        ]
    );
    // SW115: G87 with G99 is an error in ServoWorks, a warning in FANUC (FAN080).
    let g87 = "M3 S500\nG90 G0 Z10\nG99 G87 X0 Y0 Z-5 R-20 Q1 F100\nG80\nM30\n";
    assert_eq!(found(&run_sw(g87, ""), "C006"), vec![Severity::Error]);
    assert_eq!(found(&run_fanuc(g87, ""), "C006"), vec![Severity::Warning]);
    // SW117: a cycle block with no position; SW118: plane change under a cycle.
    let out = run_sw(
        "M3 S500\nG0 Z10\nG81 Z-5 R2 F100\nG81 F100\nG18\nG80\nM30\n",
        "",
    );
    assert_eq!(
        found(&out, "C006"),
        vec![Severity::Warning, Severity::Error],
        "{:?}",
        out.diagnostics
    );
    // FAN079: Z above R.
    let out = run_fanuc(
        "M3 S500\nG90 G0 Z10.\nG81 X0 Y0 Z5. R2. F100\nG80\nM30\n",
        "",
    );
    assert_eq!(
        messages(&out, "C006"),
        vec!["point Z (5) is above point R (2): R must lie between the initial level and Z"]
    );
    // FAN081: R above the initial level is advice (the cycle rapids up to R).
    let out = run_fanuc(
        "M3 S500\nG90 G0 Z0.1\nG99 G81 X0 Y0 Z-1. R0.25 F100\nG80\nM30\n",
        "",
    );
    assert_eq!(found(&out, "C006"), vec![Severity::Info]);
    // FANUC: G91 under a modal cycle reads the stored R and Z incrementally.
    let switch = |start: &str, r: &str| {
        let text =
            format!("M3 S500\nG90 G0 X0 Y0 Z{start}\nG82 Z-0.2 {r} F10.\nG91 X0.5 L2\nG80\nM30\n");
        messages(&run_fanuc(&text, ""), "C006")
            .iter()
            .map(|m| m.to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        switch("1.", "R0.1"),
        vec!["G90/G91 changes in canned-cycle mode without R and Z on the line: the stored R and Z are now read in the other mode; give R and Z again"]
    );
    // From the surface (initial level 0) with no R, both readings give R0 and Z-0.2.
    assert!(switch("0", "").is_empty());
}

/// FAN090: a FANUC cycle without R goes on with the feed starting at the
/// initial level. In a program that never gave R that is its choice
/// (information, as a Haas program feeding to the surface and drilling from
/// there does); after a cancel cleared an earlier R it is a warning.
/// ServoWorks (SW126) and LinuxCNC stop.
#[test]
fn cycle_without_r() {
    let text = "M3 S500\nG90 G0 X0 Y0 Z1.\nG81 Z-0.1 F10.\nX1.\nG80\nM30\n";
    let out = run_fanuc(text, "");
    assert_eq!(found(&out, "C001"), vec![Severity::Info]);
    let cleared = "M3 S500\nG90 G0 X0 Y0 Z1.\nG81 Z-0.1 R0.1 F10.\nG80\nG81 X1. Z-0.1\nG80\nM30\n";
    assert_eq!(
        found(&run_fanuc(cleared, ""), "C001"),
        vec![Severity::Warning]
    );
    // Two holes, each fed from the initial level Z1 to Z-0.1.
    let feeds: Vec<_> = out
        .motions
        .iter()
        .filter(|m| m.kind == runtime::MotionKind::Feed)
        .map(|m| (m.start[2], m.end[2]))
        .collect();
    assert_eq!(feeds, vec![(1.0, -0.1), (1.0, -0.1)], "{:?}", out.motions);
    assert_eq!(found(&run_sw(text, ""), "C001"), vec![Severity::Error]);
    let out = run_ngc("M3 S500\nG0 Z1\nG81 Z-0.1 F10\nM2\n");
    assert_eq!(found(&out, "C001"), vec![Severity::Error]);
}

#[test]
fn tool_offset_vectors() {
    // NGC504: M6 with no T; LinuxCNC 2.9's rs274 runs it, so a warning.
    let out = run_ngc("M6\nM2\n");
    assert_eq!(found(&out, "T003"), vec![Severity::Warning]);
    // NGC505: T2 replaces T1 before any M6; NGC415: H differs from the spindle tool.
    let out = run_ngc("T1\nT2 M6\nG43 H3\nM2\n");
    assert_eq!(
        messages(&out, "T003"),
        vec!["G43 H3 applies the length of tool 3, but tool 2 is in the spindle"]
    );
    let out = run_ngc("T1\nT2\nM6\nM2\n");
    assert_eq!(found(&out, "T003"), vec![Severity::Info]);
    // NGC510: M6 under G43 and then Z moves with the old offset.
    let out = run_ngc("T1 M6\nG43 H1\nT2 M6\nG0 Z1\nM2\n");
    assert_eq!(found(&out, "T003"), vec![Severity::Info]);
    let out = run_ngc("T1 M6\nG43 H1\nT2 M6\nG43 H2\nG0 Z1\nM2\n");
    assert!(found(&out, "T003").is_empty(), "{:?}", out.diagnostics);
    // SW146: T while G43 is on, without H.
    let out = run_sw("G43 H1 Z0\nT2\nM30\n", "");
    assert_eq!(found(&out, "T003"), vec![Severity::Info]);
}

#[test]
fn coordinate_mode_vectors() {
    // rs274ngc.md: `G91 G53 G0 X1` → NGC406; NGC404: G53 with G2.
    assert_eq!(
        found(&run_ngc("G91 G53 G0 X1\nM2\n"), "K003"),
        vec![Severity::Error]
    );
    assert_eq!(
        found(&run_ngc("G53 G2 X1 Y1 R1 F10\nM2\n"), "K003"),
        vec![Severity::Error]
    );
    // ServoWorks: G29 with no G28 (SW072), G52 in G91 (SW107).
    let out = run_sw("G29 X1\nG91 G52 X1\nG90\nM30\n", "");
    assert_eq!(
        found(&out, "K003"),
        vec![Severity::Warning, Severity::Warning]
    );
    // SW103: mirror while scaling; SW081: cutter comp with scaling.
    let out = run_sw("G51 X0 Y0 P2.0\nG51.1 X0\nG50.1\nG41 D0.5\nG50\nM30\n", "");
    assert_eq!(
        found(&out, "K003"),
        vec![Severity::Error, Severity::Error],
        "{:?}",
        out.diagnostics
    );
}

#[test]
fn comp_motion_vectors() {
    // NGC217: an arc as the first move after G40.
    let out = run_ngc("G0 X0 Y0\nG41.1 D0.2\nG1 X1 F100\nG40\nG2 X2 Y0 R0.5\nM2\n");
    assert_eq!(found(&out, "T004"), vec![Severity::Error]);
    // SW082: the entry move is an arc; SW083: G17 in compensation mode.
    let out = run_sw(
        "G0 X0 Y0\nG41 D1.0\nG02 X10 Y0 R5 F100\nG01 X20\nG17\nG40 G01 X30\nM30\n",
        "",
    );
    assert_eq!(
        messages(&out, "T004"),
        vec![
            "the first motion of tool radius compensation cannot be G02: use G00 or G01 to start and end it",
            "G17 is not allowed in tool radius compensation mode (only G00–G03, G04, M, S, B and F): cancel with G40 first",
        ]
    );
}

#[test]
fn probe_vectors() {
    // NGC226: target = current position; NGC227: cutter comp on; NGC229: G95.
    assert_eq!(
        found(&run_ngc("G0 X0 Y0 Z0\nG38.2 Z0 F10\nM2\n"), "F011"),
        vec![Severity::Error]
    );
    assert_eq!(
        found(
            &run_ngc("G0 X0 Y0\nG41.1 D0.2\nG1 X1 F10\nG38.2 X2 F10\nM2\n"),
            "F011"
        ),
        vec![Severity::Error]
    );
    assert_eq!(
        found(&run_ngc("S100 M3\nG95 G38.2 Z-1 F0.1\nM2\n"), "F011"),
        vec![Severity::Error]
    );
}

#[test]
fn arc_word_vectors() {
    // NGC210: K under G17; NGC205: R-format arc with no in-plane end point.
    assert_eq!(
        messages(&run_ngc("G17 G0 X0 Y0\nG2 X1 Y1 K1 F100\nM2\n"), "A008"),
        vec!["K is the centre offset along the axis normal to the G17 plane: an arc in G17 takes I and J"]
    );
    assert_eq!(
        found(&run_ngc("G0 X0 Y0\nG2 Z1 R1 F100\nM2\n"), "A008"),
        vec![Severity::Error]
    );
    // NGC216: G90.1 with only I.
    assert_eq!(
        found(&run_ngc("G90.1 G0 X0 Y0\nG2 X2 Y0 I1 F100\nM2\n"), "A008"),
        vec![Severity::Error]
    );
    // SW034: G17 arc with X and Z but no Y.
    assert_eq!(
        found(
            &run_sw("G17 G00 X0 Y0\nG02 X10 Z5 R10 F100\nM30\n", ""),
            "A008"
        ),
        vec![Severity::Error]
    );
}

#[test]
fn ill_conditioned_arc_vectors() {
    // Chord 1.99 on R1: sweep 2·asin(0.995) = 168.5°, inside [165°, 195°].
    let out = run_ngc("G0 X0 Y0\nG2 X1.99 Y0 R1 F100\nM2\n");
    assert_eq!(
        messages(&out, "A009"),
        vec!["this radius-format arc sweeps 168.5°: near 180° a tiny change of the end point moves the centre a lot; program the centre with I/J"]
    );
    // R negative on a short chord: 360° − 2·asin(0.1) = 348.5° (NGC213, ≥ 345°).
    let out = run_ngc("G0 X0 Y0\nG2 X0.2 Y0 R-1 F100\nM2\n");
    assert_eq!(found(&out, "A009"), vec![Severity::Info]);
    // Chord √2 on R1 is a quarter circle: fine.
    let out = run_ngc("G0 X0 Y0\nG2 X1 Y-1 R1 F100\nM2\n");
    assert!(found(&out, "A009").is_empty());
    // FANUC: about 180° is advice (FAN034), near 360° is not flagged. The
    // controls run such arcs, so it is information (issue 21), also for an exact
    // half circle of a CAM post.
    let out = run_fanuc("G00 X0 Y0\nG02 X1.99 Y0 R1. F100\nM30\n", "");
    assert_eq!(found(&out, "A009"), vec![Severity::Info]);
    let out = run_fanuc("G00 X0. Y0.\nG03 X0. Y10. R5. F500.\nM30\n", "");
    assert_eq!(found(&out, "A009"), vec![Severity::Info]);
}

#[test]
fn g76_vectors() {
    let pre = "G18\nS100 M3\nG0 X0 Z0\n";
    // NGC336: E6 on a 10 mm thread (half = 5); LinuxCNC 2.9 runs it, so a warning.
    let out = run_ngc(&format!("{pre}G76 P0.1 Z-10 I-0.1 J0.05 K0.2 E6\nM2\n"));
    assert_eq!(
        messages(&out, "C003"),
        vec!["G76 taper length E is longer than half the thread: shorten E"]
    );
    assert_eq!(found(&out, "C003"), vec![Severity::Warning]);
    let out = run_ngc(&format!("{pre}G76 P0.1 Z-10 I-0.1 J0.05 K0.2 E5\nM2\n"));
    assert!(found(&out, "C003").is_empty(), "{:?}", out.diagnostics);
    // NGC337: rotary words are refused ("Cannot move rotary axes with G76");
    // X and a plane other than G18 (NGC330/331) are accepted by LinuxCNC 2.9.
    let out = run_ngc(&format!("{pre}G76 P0.1 Z-10 A1 I-0.1 J0.05 K0.2\nM2\n"));
    assert_eq!(found(&out, "C003"), vec![Severity::Error]);
    let out = run_ngc(&format!("{pre}G76 P0.1 X1 Z-10 I-0.1 J0.05 K0.2\nM2\n"));
    assert!(found(&out, "C003").is_empty(), "{:?}", out.diagnostics);
    let out = run_ngc("G17\nS100 M3\nG0 X0 Z0\nG76 P0.1 Z-10 I-0.1 J0.05 K0.2\nM2\n");
    assert!(found(&out, "C003").is_empty(), "{:?}", out.diagnostics);
}

#[test]
fn cycle_modal_data_vectors() {
    // SW124: Q on a cycle block without a position is not stored.
    let out = run_sw(
        "M3 S500\nG0 Z10\nG83 X0 Y0 Z-5 R2 Q1 F100\nQ2\nG80\nM30\n",
        "",
    );
    assert_eq!(
        messages(&out, "C006"),
        vec!["Q in a canned-cycle block that makes no hole is not stored as cycle data: give it with the hole position"]
    );
    // FAN088: Q stored by G83 (peck depth) reused by G76 as the shift amount.
    let out = run_fanuc(
        "M3 S500\nG90 G0 Z10.\nG83 X0 Y0 Z-5. R2. Q1. F100\nG76 X10. Z-5. R2.\nG80\nM30\n",
        "",
    );
    assert_eq!(
        messages(&out, "C006"),
        vec!["G76 reuses Q stored by G83: the peck depth becomes the shift amount; give Q on this block"]
    );
    // FAN084 / FAN085: G43 and G45 in cycle mode.
    let out = run_fanuc(
        "M3 S500\nG90 G0 Z10.\nG81 X0 Y0 Z-5. R2. F100\nG43 H1 X10.\nG45 X20. D1\nG80\nM30\n",
        "",
    );
    assert_eq!(
        found(&out, "C006"),
        vec![Severity::Warning, Severity::Warning],
        "{:?}",
        out.diagnostics
    );
    // SW131: compensation is ignored in a cycle.
    let out = run_sw(
        "M3 S500\nG0 X0 Y0 Z10\nG41 D1.0 G01 X5 F100\nG81 X10 Y0 Z-5 R2 F100\nG80\nG40 G01 X0\nM30\n",
        "",
    );
    assert!(
        messages(&out, "C006")
            .contains(&"tool radius compensation is ignored inside canned cycles: the holes are drilled at the programmed points"),
        "{:?}",
        out.diagnostics
    );
}

#[test]
fn comp_mode_and_g10_vectors() {
    // NGC421 (rs274: "Cannot change retract mode with cutter radius compensation on").
    let out = run_ngc("G0 X0 Y0\nG41.1 D0.4\nG1 X1 F100\nG98\nG40 G1 X2\nM2\n");
    assert_eq!(
        messages(&out, "T002"),
        vec!["cannot change the retract mode (G98) while cutter radius compensation is on: LinuxCNC stops; cancel it with G40 first (the dry run stops here)"]
    );
    // NGC412: compensation in G19 ("allowed only in XY, XZ planes"); G18 is fine.
    let out = run_ngc("G19\nG41.1 D0.4\nG1 Z1 F100\nG40\nM2\n");
    assert_eq!(found(&out, "T004"), vec![Severity::Error]);
    let out = run_ngc("G18\nG41.1 D0.4\nG1 X1 F100\nG40\nM2\n");
    assert!(found(&out, "T004").is_empty(), "{:?}", out.diagnostics);
    // NGC400: G10 L5; NGC821: G10 L0 with tool 1 loaded.
    assert_eq!(
        messages(&run_ngc("G10 L5 P1 X1\nM2\n"), "K003"),
        vec!["G10 needs one of L0, L1, L2, L10, L11, L20: LinuxCNC stops (the dry run stops here)"]
    );
    assert_eq!(
        found(&run_ngc("T1 M6\nG10 L0 P1\nM2\n"), "K003"),
        vec![Severity::Error]
    );
}

#[test]
fn no_effect_vectors() {
    // NGC107: G1 is modal, but X belongs to G92 on this line.
    let out = run_ngc("G1 X1 F100\nG92 X0\nG92.1\nM2\n");
    assert_eq!(
        messages(&out, "F012"),
        vec!["the axis words of this line belong to G92: the modal motion G1 does not run here"]
    );
    // SW059: G08 P0 while 3D-DLACC is already off.
    let out = run_sw("G08 P0\nG01 X1 F100\nM30\n", "");
    assert_eq!(found(&out, "F012"), vec![Severity::Info]);
    // FAN062: angle without radius in G16.
    let out = run_fanuc("G17 G90 G16\nG01 X10. Y30. F100\nY60.\nG15\nM30\n", "");
    assert_eq!(found(&out, "F012"), vec![Severity::Warning]);
}

#[test]
fn remaining_hint_vectors() {
    // FAN060: G92 words in G16 are Cartesian.
    let out = run_fanuc("G17 G90 G16\nG92 X10. Y5.\nG15\nM30\n", "");
    assert_eq!(
        messages(&out, "F012"),
        vec!["in polar mode (G16) the axis words of G92 are Cartesian, not radius and angle"]
    );
    // FAN107: M03 after the rigid tap was cancelled, without S.
    let out = run_fanuc(
        "S500 M3\nG90 G0 Z10.\nM29 S500\nG84 X0 Y0 Z-5. R2. F500\nG80\nM03\nM30\n",
        "",
    );
    assert_eq!(
        found(&out, "F012"),
        vec![Severity::Info],
        "{:?}",
        out.diagnostics
    );
    // SW084: G41 with no D/H and no tool radius; SW112: Z centre word under G17.
    let out = run_sw(
        "G17 G00 X0 Y0\nG41 G01 X10 F100\nG40 G01 X0\nG68 X0 Y0 Z1 R30\nG69\nM30\n",
        "",
    );
    assert_eq!(found(&out, "T004"), vec![Severity::Warning]);
    assert_eq!(found(&out, "K003"), vec![Severity::Warning]);
    // NGC427: A moves under compensation (info).
    let out = run_ngc("G0 X0 Y0\nG41.1 D0.2\nG1 X1 A10 F100\nG40 G1 X2\nM2\n");
    assert_eq!(found(&out, "T004"), vec![Severity::Info]);
    // SW058 / SW086 / SW111 / NGC422: each mode left on gives its own warning.
    let out = run_sw("G05 P10000\nG52 X5\nG01 X10 F100\nM30\n", "");
    assert_eq!(
        messages(&out, "F008"),
        vec![
            "the program ends with 3D-DLACC look-ahead (cancel with G08) still active: the next program or MDI command starts in that mode",
            "the program ends with a G52 local coordinate system (cancel with G52 and zero axes) still active: the next program or MDI command starts in that mode",
        ]
    );
    let out = run_sw("G41 D1.0 G01 X10 F100\nM30\n", "");
    assert_eq!(found(&out, "F008"), vec![Severity::Warning]);
    let out = run_ngc("G0 X0 Y0\nG41.1 D0.2\nG1 X1 F100\nM2\n");
    assert_eq!(found(&out, "F008"), vec![Severity::Warning]);
}

#[test]
fn vacant_word_vectors() {
    // FAN141: Y#2 with #2 vacant drops the Y word: the move ends at Y0.
    let out = run_fanuc("#1 = 5\nG01 X#1 Y#2 F100\nM30\n", "");
    assert_eq!(
        messages(&out, "X005"),
        vec!["the value of Y is vacant (an unset variable): the control omits the whole Y word; set the variable or leave the word out"]
    );
    assert_eq!(ends(&out), vec![[5.0, 0.0, 0.0]]);
    // #0 is always vacant; a plain number never is.
    let out = run_fanuc("G01 X1. Z#0 F100\nM30\n", "");
    assert_eq!(found(&out, "X005"), vec![Severity::Warning]);
    assert!(found(&run_fanuc("G01 X1. F100\nM30\n", ""), "X005").is_empty());
}

/// M61 Q<n> (set the tool number without a change) stops, like M6, at a tool
/// the configured table lacks: rs274 says "Requested tool 4 not found in the
/// tool table".
#[test]
fn m61_with_a_tool_the_table_lacks_stops() {
    let tools = Some("T1 P1 D6 Z10\n");
    let out = run_with(
        analyzer::Dialect::Rs274ngc,
        "G21\nM61 Q4\nG0 X1\nM2\n",
        "",
        &[],
        tools,
    );
    assert_eq!(codes(&out), vec!["T001"]);
    assert!(out.motions.is_empty());
    let out = run_with(
        analyzer::Dialect::Rs274ngc,
        "G21\nM61 Q1\nG0 X1\nM2\n",
        "",
        &[],
        tools,
    );
    assert_eq!(codes(&out), Vec::<&str>::new());
}
