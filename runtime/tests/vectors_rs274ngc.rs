//! RS274/NGC test vectors (rs274ngc.md §10) with their exact numbers.

mod common;

use analyzer::{Dialect, Settings, Variant};
use common::*;
use runtime::{run, MotionKind, NoResolver, RunInput, RunOutput};

fn run_profile(text: &str, variant: Variant, machine: &str) -> RunOutput {
    let mut settings = Settings::new(Dialect::Rs274ngc);
    settings.variant = variant;
    let a = analyzer::analyze(text.as_bytes().to_vec(), &settings);
    let machine = analyzer::config::MachineConfig::from_toml(machine).expect("toml");
    let input = RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 100_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    };
    run(&input)
}

/// The X of the first motion of `G0 X[expr]` after `setup`.
fn value(setup: &str, expr: &str) -> Result<f64, Vec<&'static str>> {
    let out = run_ngc(&format!("G21\n{setup}\nG0 X[{expr}]\nM2\n"));
    if !out.diagnostics.is_empty() {
        return Err(codes(&out));
    }
    Ok(out.motions.last().map(|m| m.end[0]).unwrap_or(f64::NAN))
}

#[test]
fn tv_p1_p2_parameters_set_after_the_line() {
    let out = run_ngc("#3=15\n#3=6 G1 x#3 F10\nG0 Y#3\nM2\n");
    assert_eq!(ends(&out), vec![[15.0, 0.0, 0.0], [15.0, 6.0, 0.0]]);
    let out = run_ngc("#3=15 #3=6\nG0 X#3\n#3=6 #3=15\nG0 Y#3\nM2\n");
    assert_eq!(ends(&out), vec![[6.0, 0.0, 0.0], [6.0, 15.0, 0.0]]);
}

#[test]
fn tv_p3_indirection() {
    let out = run_ngc("#1=2\n#2=3\n#3=7\nG0 X[#1+2]\nG0 X#[1+2]\nG0 Y##2\nM2\n");
    assert_eq!(
        ends(&out),
        vec![[4.0, 0.0, 0.0], [7.0, 0.0, 0.0], [7.0, 7.0, 0.0]]
    );
}

#[test]
fn tv_p4_to_p13_expression_values() {
    let cases: &[(&str, &str, f64)] = &[
        ("", "2.0 / 3 * 1.5 - 5.5 / 11.0", 0.5),
        ("", "0 AND 0 + 1", 0.0),
        ("#3=2", "1 + acos[0] - [#3 ** [4.0/2]]", 87.0),
        ("", "FIX[2.8]", 2.0),
        ("", "FIX[-2.8]", -3.0),
        ("", "FUP[2.8]", 3.0),
        ("", "FUP[-2.8]", -2.0),
        ("", "ROUND[2.5]", 3.0),
        ("", "ROUND[-2.5]", -3.0),
        ("", "ROUND[2.4999]", 2.0),
        ("", "ATAN[1]/[-1]", 135.0),
        ("", "SIN[90]", 1.0),
        ("", "COS[180]", -1.0),
        ("", "SQRT[16]", 4.0),
        ("", "EXP[0]", 1.0),
        ("", "LN[1]", 0.0),
        ("", "ABS[-3]", 3.0),
        ("", "-7 MOD 3", 2.0),
        ("", "7 MOD -3", 1.0),
        ("", "7.5 MOD 2", 1.5),
        ("", "2 ** 3 ** 2", 64.0),
        ("", "-8 ** 2", 64.0),
        ("", "1 EQ 1.0000001", 1.0),
        ("", "1 EQ 1.00001", 0.0),
        ("", "3 GT 2", 1.0),
        ("", "2 GE 2", 1.0),
        ("", "1 OR 0", 1.0),
        ("", "1 XOR 1", 0.0),
        ("", "5 AND 2", 1.0),
    ];
    for (setup, e, want) in cases {
        let got = value(setup, e).unwrap_or(f64::NAN);
        assert!(close(got, *want, 1e-9), "[{e}] = {got}, want {want}");
    }
    let atan = value("", "ATAN[2]/[1+3]").unwrap_or(f64::NAN);
    assert!(close(atan, 26.565051177, 1e-9));
}

#[test]
fn tv_p14_evaluation_errors() {
    for e in ["1/0", "SQRT[-1]", "LN[0]", "ACOS[1.5]", "-8 ** 0.5"] {
        assert_eq!(value("", e), Err(vec!["X001"]), "[{e}]");
    }
}

fn arc(out: &RunOutput, i: usize) -> ([f64; 3], f64) {
    match out.motions[i].kind {
        MotionKind::Arc { center, radius, .. } => (center, radius),
        _ => panic!("motion {i} is not an arc"),
    }
}

#[test]
fn tv_a1_radius_format() {
    for (block, c, sweep) in [
        ("G2 X10 Y15 R20", [19.855069, -2.403379], 53.5764f64),
        ("G2 X10 Y15 R-20", [-9.855069, 17.403379], 306.4236),
        ("G3 X10 Y15 R20", [-9.855069, 17.403379], 53.5764),
    ] {
        let out = run_ngc(&format!("G21 F100\n{block}\nM2\n"));
        let (center, radius) = arc(&out, 0);
        assert!(
            close(center[0], c[0], 1e-6) && close(center[1], c[1], 1e-6),
            "{block}: {center:?}"
        );
        let len = length(&out.motions[0]);
        assert!(
            close(len / radius, sweep.to_radians(), 1e-6),
            "{block}: {}",
            (len / radius).to_degrees()
        );
    }
    let out = run_ngc("G21 F100\nG2 X10 Y15 R20\nM2\n");
    assert!(close(length(&out.motions[0]), 18.701701, 1e-6));
}

#[test]
fn tv_a2_helix() {
    let out = run_ngc("G21 F100\nG0 X7 Y7 Z7\nG17 G2 X10 Y16 I3 J4 Z9\nM2\n");
    let (center, radius) = arc(&out, 1);
    assert_eq!([center[0], center[1], radius], [10.0, 11.0, 5.0]);
    assert!(close(length(&out.motions[1]), 12.649567, 1e-6));
}

#[test]
fn tv_a3_full_circle_and_r_error() {
    let out = run_ngc("G21 F100\nG0 X-0.1\nG3 X-0.1 Y0 I0.1 J0\nM2\n");
    assert!(close(length(&out.motions[1]), 0.6283185, 1e-7));
    let bad = run_ngc("G21 F100\nG0 X-0.1\nG3 X-0.1 Y0 R0.1\nM2\n");
    assert_eq!(codes(&bad), vec!["A006"]);
}

#[test]
fn tv_a5_two_arcs_same_centre() {
    let out = run_ngc("G21\nG2 X0 Y1 I1 J0.5 F25\nG3 X0 Y0 I1 J-0.5\nM2\n");
    for i in 0..2 {
        let (c, r) = arc(&out, i);
        assert!(close(c[0], 1.0, 1e-12) && close(c[1], 0.5, 1e-12) && close(r, 1.118034, 1e-6));
        assert!(close(
            length(&out.motions[i]) / r,
            53.1301f64.to_radians(),
            1e-5
        ));
    }
}

#[test]
fn tv_a6_centre_tolerances_per_profile() {
    let prog = |b: &str| format!("G20 F10\n{b}\nM2\n");
    let cases = [
        ("G2 X2.0001 Y0 I1 J0", true, true),
        ("G2 X2.001 Y0 I1 J0", true, false),
        ("G2 X2.003 Y0 I1 J0", false, false),
        ("G2 X200.05 Y0 I100 J0", true, false),
        ("G2 X2000.3 Y0 I1000 J0", false, false),
    ];
    for (b, ok_linuxcnc, ok_emc2) in cases {
        assert_eq!(
            run_profile(&prog(b), Variant::Linuxcnc, "")
                .diagnostics
                .is_empty(),
            ok_linuxcnc,
            "linuxcnc {b}"
        );
        assert_eq!(
            run_profile(&prog(b), Variant::Emc2, "")
                .diagnostics
                .is_empty(),
            ok_emc2,
            "emc2 {b}"
        );
    }
    let mm = "G21 F10\nG2 X20.02 Y0 I10 J0\nM2\n";
    assert!(run_profile(mm, Variant::Linuxcnc, "")
        .diagnostics
        .is_empty());
    assert_eq!(codes(&run_profile(mm, Variant::Emc2, "")), vec!["A001"]);
}

#[test]
fn tv_a7_radius_too_small() {
    assert_eq!(
        codes(&run_ngc("G20 F10\nG2 X10 Y0 R4.9\nM2\n")),
        vec!["A002"]
    );
    let out = run_ngc("G20 F10\nG2 X10 Y0 R4.99996\nM2\n");
    assert!(out.diagnostics.is_empty());
    let (c, _) = arc(&out, 0);
    assert!(close(c[0], 5.0 * 25.4, 1e-9) && close(c[1], 0.0, 1e-9));
}

#[test]
fn tv_a9_full_circle_linuxcnc() {
    let out = run_ngc("G21 F10\nG2 I1 J0\nM2\n");
    assert!(close(length(&out.motions[0]), std::f64::consts::TAU, 1e-12));
}

#[test]
fn tv_a10_p_turns() {
    let out = run_ngc("G21\nG2 X0 Y1 Z-1 I1 J0.5 P2 F25\nM2\n");
    let MotionKind::Arc { turns, radius, .. } = out.motions[0].kind else {
        panic!("arc")
    };
    assert_eq!(turns, 1);
    let planar = (53.1301f64.to_radians() + std::f64::consts::TAU) * radius;
    assert!(close(length(&out.motions[0]), planar.hypot(1.0), 1e-3));
}

fn moves(out: &RunOutput) -> Vec<(char, [f64; 3])> {
    out.motions
        .iter()
        .map(|m| {
            (
                if is_rapid(m) { 'r' } else { 'f' },
                [m.end[0], m.end[1], m.end[2]],
            )
        })
        .collect()
}

#[track_caller]
fn assert_moves(out: &RunOutput, want: &[(char, [f64; 3])]) {
    let got = moves(out);
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            g.0 == w.0 && (0..3).all(|i| close(g.1[i], w.1[i], 1e-9)),
            "{got:?}\nwant {want:?}"
        );
    }
}

#[test]
fn tv_c1_to_c4_g81() {
    let c1 = run_ngc("G21\nG0 X1 Y2 Z3\nG90 G81 G98 X4 Y5 Z1.5 R2.8 F10\nM2\n");
    assert_moves(
        &c1,
        &[
            ('r', [1., 2., 3.]),
            ('r', [4., 5., 3.]),
            ('r', [4., 5., 2.8]),
            ('f', [4., 5., 1.5]),
            ('r', [4., 5., 3.]),
        ],
    );
    let c2 = run_ngc("G21\nG0 X1 Y2 Z3\nG91 G81 G98 X4 Y5 Z-0.6 R1.8 L3 F10\nM2\n");
    assert_moves(
        &c2,
        &[
            ('r', [1., 2., 3.]),
            ('r', [1., 2., 4.8]),
            ('r', [5., 7., 4.8]),
            ('f', [5., 7., 4.2]),
            ('r', [5., 7., 4.8]),
            ('r', [9., 12., 4.8]),
            ('f', [9., 12., 4.2]),
            ('r', [9., 12., 4.8]),
            ('r', [13., 17., 4.8]),
            ('f', [13., 17., 4.2]),
            ('r', [13., 17., 4.8]),
        ],
    );
    let c3 = run_ngc("G21 F10\nG0 X1 Y2 Z3\nG90 G99 G81 X4 Y5 Z1.5 R2.8\nM2\n");
    assert_moves(
        &c3,
        &[
            ('r', [1., 2., 3.]),
            ('r', [4., 5., 3.]),
            ('r', [4., 5., 2.8]),
            ('f', [4., 5., 1.5]),
            ('r', [4., 5., 2.8]),
        ],
    );
    let c4 = run_ngc("G21 F10\nG90 G98 G81 X4 Y5 Z1.5 R2.8\nM2\n");
    assert_moves(
        &c4,
        &[
            ('r', [0., 0., 2.8]),
            ('r', [4., 5., 2.8]),
            ('f', [4., 5., 1.5]),
            ('r', [4., 5., 2.8]),
        ],
    );
}

#[test]
fn tv_c5_g83_inch() {
    let out = run_ngc("G20\nG0 X0 Y0 Z1\nG90 G98 G83 X0 Y0 Z-1 R0.1 Q0.5 F10\nM2\n");
    let z: Vec<(char, f64)> = moves(&out)
        .iter()
        .skip(1)
        .map(|(k, p)| (*k, p[2] / 25.4))
        .collect();
    let want = [
        ('r', 1.0),
        ('r', 0.1),
        ('f', -0.4),
        ('r', 0.1),
        ('r', -0.39),
        ('f', -0.9),
        ('r', 0.1),
        ('r', -0.89),
        ('f', -1.0),
        ('r', 1.0),
    ];
    assert_eq!(z.len(), want.len(), "{z:?}");
    for (g, w) in z.iter().zip(want) {
        assert!(g.0 == w.0 && close(g.1, w.1, 1e-9), "{z:?}");
    }
    let feed: f64 = out.motions.iter().filter(|m| is_feed(m)).map(length).sum();
    assert!(close(feed / 25.4, 1.12, 1e-9));
}

#[test]
fn tv_c6_incremental_repeats() {
    let out = run_ngc("G21 F10\nG0 Z1\nG91 G99 G81 X1 Y0 Z-0.5 R-0.9 L3\nM2\n");
    assert_moves(
        &out,
        &[
            ('r', [0., 0., 1.]),
            ('r', [1., 0., 1.]),
            ('r', [1., 0., 0.1]),
            ('f', [1., 0., -0.4]),
            ('r', [1., 0., 0.1]),
            ('r', [2., 0., 0.1]),
            ('f', [2., 0., -0.4]),
            ('r', [2., 0., 0.1]),
            ('r', [3., 0., 0.1]),
            ('f', [3., 0., -0.4]),
            ('r', [3., 0., 0.1]),
        ],
    );
}

#[test]
fn tv_c7_cycle_errors() {
    let cases = [
        ("G91 G81 X1 Z0.5 R0.1", "C003"),
        ("G81 X1 Y1 R1", "C001"),
        ("G81 X1 Y1 Z-1", "C001"),
        ("G81 X1 Z-1 R1 L0", "C003"),
        ("G83 X0 Z-1 R1 Q0", "C002"),
        ("G82 X1 Z-1 R1", "C001"),
    ];
    for (b, code) in cases {
        let out = run_ngc(&format!("G21 F10\n{b}\nM2\n"));
        assert_eq!(codes(&out), vec![code], "{b}");
    }
}

#[test]
fn tv_c8_sticky_cycle() {
    let out = run_ngc("G21\nG0 Z5\nG90 G98 G81 X1 Y1 Z-1 R0.1 F10\nX2\nM2\n");
    let feeds: Vec<[f64; 3]> = out
        .motions
        .iter()
        .filter(|m| is_feed(m))
        .map(|m| [m.end[0], m.end[1], m.end[2]])
        .collect();
    assert_eq!(feeds, vec![[1.0, 1.0, -1.0], [2.0, 1.0, -1.0]]);
}

#[test]
fn tv_c10_g85() {
    let out = run_ngc("G21\nG0 Z1\nG90 G98 G85 X0 Y0 Z-1 R0.1 F10\nM2\n");
    let feed: f64 = out.motions.iter().filter(|m| is_feed(m)).map(length).sum();
    assert!(close(feed, 2.2, 1e-12));
    assert_eq!(out.motions.last().map(|m| m.end[2]), Some(1.0));
}

#[test]
fn tv_g1_g92_offsets() {
    let mm = "machine_units = \"mm\"";
    let out = run_profile(
        "G21\nG0 X4\nG92 X7\nG0 Y#5211\nG92 X9\nG0 Y#5211\nG92.1\nG0 Y#5211\nG0 X4\nM2\n",
        Variant::Linuxcnc,
        mm,
    );
    let y: Vec<f64> = out.motions.iter().map(|m| m.end[1]).collect();
    assert_eq!(&y[1..4], &[-3.0, -5.0, 0.0]);
    // After G92.1 the program X reads the machine X again.
    assert_eq!(out.motions.last().map(|m| m.end[0]), Some(4.0));
}

#[test]
fn tv_g3_g4_work_offsets() {
    let mm = "machine_units = \"mm\"";
    let out = run_profile(
        "G21\nG10 L2 P1 X3.5 Y17.2\nG0 X#5221 Y#5222 Z#5223\nM2\n",
        Variant::Linuxcnc,
        mm,
    );
    // G54 is active, so the move lands at offset + value in machine coordinates.
    assert_pt(out.motions[0].end, &[7.0, 34.4, 0.0], 1e-12);
    let out = run_profile(
        "G21\n#5241=2\n#5242=1\n#5243=-2\nG55 G0 X0 Y0 Z0\nM2\n",
        Variant::Linuxcnc,
        mm,
    );
    assert_pt(out.motions[0].end, &[2.0, 1.0, -2.0], 1e-12);
}

#[test]
fn tv_o1_sawtooth_loop() {
    let prog = "G21 F10\n#1 = 0\no101 while [#1 LT 10]\n  G1 X0 Y[#1/10]\n  G1 X1\n  #1 = [#1+1]\no101 endwhile\nG0 Z#1\nM2\n";
    let out = run_ngc(prog);
    assert_eq!(out.motions.iter().filter(|m| is_feed(m)).count(), 20);
    let last_feed = out
        .motions
        .iter()
        .rfind(|m| is_feed(m))
        .map(|m| m.end)
        .unwrap_or_default();
    assert_pt(last_feed, &[1.0, 0.9], 1e-12);
    assert_eq!(out.motions.last().map(|m| m.end[2]), Some(10.0));
}

#[test]
fn tv_o2_if_else() {
    for (v, feed) in [(6.0, 100.0), (5.0, 200.0)] {
        let prog = format!(
            "G21\n#2 = {v}\no102 if [#2 GT 5]\n  F100\no102 else\n  F200\no102 endif\nG1 X1\nM2\n"
        );
        let out = run_ngc(&prog);
        assert_eq!(out.motions[0].feed, feed);
    }
}

#[test]
fn tv_o3_subroutine_locals() {
    let prog = "G21\no200 sub\n#31=[#1+#2+#3]\nG0 Y#4\n#1=99\no200 endsub\n#1=5\n#4=7\no200 call [1] [2] [3]\nG0 X#31 Z#1\nM2\n";
    let out = run_ngc(prog);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    // Inside the sub #4 is 0: LinuxCNC gives every call fresh #1-#30.
    assert_eq!(ends(&out), vec![[0.0, 0.0, 0.0], [6.0, 0.0, 5.0]]);
}

#[test]
fn tv_o4_recursion_limit() {
    let out = run_ngc("o1 sub\no1 call\no1 endsub\no1 call\nM2\n");
    assert_eq!(codes(&out), vec!["F003"]);
}

#[test]
fn tv_e4_f1_inverse_time() {
    let out = run_ngc("G21\nG93 G1 X10 F2\nM2\n");
    assert_eq!(out.motions[0].inverse_time, Some(2.0));
    assert!(close(out.motions[0].feed, 20.0, 1e-12), "10 mm in 0.5 min");
}

#[test]
fn tv_l9_to_l12_program_structure() {
    assert_eq!(codes(&run_ngc("%\nG0 X1\n")), vec!["F006"]);
    assert_eq!(codes(&run_ngc("G0 X1\n")), vec!["F006"]);
    let out = run_ngc("%\nG0 X1\n%\nG0 X99\n");
    assert!(out.diagnostics.is_empty());
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0]]);
    let out = run_ngc("G0 X1\nM2\nG0 X99\n");
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0]]);
}

#[test]
fn zero_feed_stops() {
    assert_eq!(codes(&run_ngc("G1 X10\nM2\n")), vec!["F001"]);
}

#[test]
fn snapshots_report_modal_state() {
    let out = run_ngc("G20 G91 G1 X1 F10\nM2\n");
    let s = out.snapshots[0].as_ref().expect("snapshot");
    assert_eq!(
        s.modal.to_vec(),
        vec!["G1", "G17", "G20", "G91", "G94", "G54", "G40", "G49", "G64", "G99"]
    );
    assert_pt(s.position, &[25.4, 0.0, 0.0], 1e-12);
    assert_eq!(s.feed, 254.0);
}

#[test]
fn huge_cycle_repeat_count_is_bounded() {
    let out = run_ngc("G21 F10\nG0 Z1\nG91 G81 X1 Z-1 R0 L1000000000\nM2\n");
    assert!(codes(&out).contains(&"F004"));
    assert!(out.motions.len() < 500_000, "{}", out.motions.len());
}

#[test]
fn feed_per_revolution_becomes_mm_per_minute() {
    let out = run_ngc("G21 G95 S1000 M3\nG1 X10 F0.1\nM2\n");
    assert!(close(out.motions[0].feed, 100.0, 1e-9));
}

#[test]
fn tv_l1_blanks_inside_numbers() {
    let out = run_ngc("G21\ng0x +0. 12 34y 7\nM2\n");
    assert_eq!(ends(&out), vec![[0.1234, 7.0, 0.0]]);
}

#[test]
fn tv_l3_l4_code_numbers_within_tolerance() {
    let out = run_ngc("G21\nM3.00005 S1\nG1.0001 X1 F1\nM2\n");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0]]);
    assert!(is_feed(&out.motions[0]));
}

#[test]
fn tv_l5_l6_message_is_the_last_comment() {
    let messages = |text: &str| -> Vec<String> {
        run_ngc(text)
            .events
            .iter()
            .filter_map(|e| match &e.kind {
                runtime::EventKind::Message(m) => Some(m.clone()),
                _ => None,
            })
            .collect()
    };
    assert_eq!(
        messages("G0 X1 (first) (MSG,second)\nM2\n"),
        vec!["second".to_string()]
    );
    assert!(messages("(MSG,first) (second)\nM2\n").is_empty());
}

#[test]
fn tv_l8_call_arguments() {
    let prog = "G21\no100 sub\nG0 X#1 Y#2 Z#3\no100 endsub\no100 call [1] [2] [3]\nM2\n";
    assert_eq!(ends(&run_ngc(prog)), vec![[1.0, 2.0, 3.0]]);
}

#[test]
fn tv_a8_half_circle_radius_arc() {
    let out = run_ngc("G21\nG2 X10 Y0 R5 F1\nM2\n");
    assert_eq!(codes(&out), vec!["A009"]);
    let (c, _) = arc(&out, 0);
    assert_pt([c[0], c[1], 0.0, 0.0, 0.0, 0.0], &[5.0, 0.0], 1e-12);
}

#[test]
fn tv_a11_k_word_in_xy_plane() {
    let out = run_ngc("G21\nG17 G2 X1 Y0 K1 F1\nM2\n");
    assert_eq!(codes(&out), vec!["A008"]);
    assert!(out.motions.is_empty());
}

#[test]
fn tv_m2_g80_dropped_g1_runs() {
    let out = run_ngc("G21\nG1 G80 X1 F1\nM2\n");
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0]]);
    assert!(is_feed(&out.motions[0]));
}

#[test]
fn tv_m5_axis_words_go_to_g92() {
    let out = run_ngc("G21\nG1 X0 F1\nG92 X5\nG92.1\nM2\n");
    assert_eq!(codes(&out), vec!["F012"]);
    assert_eq!(ends(&out), vec![[0.0, 0.0, 0.0]]);
}

#[test]
fn tv_m10_motion_is_modal() {
    let out = run_ngc("G21\nG0 X1\nY2\nM2\n");
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0], [1.0, 2.0, 0.0]]);
    assert!(out.motions.iter().all(is_rapid));
}

#[test]
fn tv_m11_bare_g0_is_accepted() {
    // rs274 (LinuxCNC 2.9) emits a zero-length STRAIGHT_TRAVERSE(0, 0, 0) here.
    let out = run_ngc("G21\nG0\nM2\n");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    assert_eq!(ends(&out), vec![[0.0, 0.0, 0.0]]);
}

#[test]
fn tv_e2_dwell_before_motion() {
    let out = run_ngc("G21\nG4 P10 G1 X1 F10\nM2\n");
    let dwell = out
        .events
        .iter()
        .find(|e| matches!(e.kind, runtime::EventKind::Dwell(_)))
        .expect("dwell");
    assert_eq!(dwell.kind, runtime::EventKind::Dwell(10.0));
    assert_eq!(dwell.motion_index, 0, "before the move");
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0]]);
}

#[test]
fn tv_e3_units_change_before_motion() {
    let out = run_ngc("G21\nG20 G0 X1\nM2\n");
    assert_eq!(ends(&out), vec![[25.4, 0.0, 0.0]]);
}

#[test]
fn tv_e5_motion_then_program_end() {
    let out = run_ngc("G21\nM2 G1 X5 F10\n");
    assert_eq!(ends(&out), vec![[5.0, 0.0, 0.0]]);
    let end = out
        .events
        .iter()
        .find(|e| e.kind == runtime::EventKind::ProgramEnd)
        .expect("program end");
    assert_eq!(end.motion_index, 1, "after the move");
}

#[test]
fn tv_f2_inch_feed() {
    let out = run_ngc("G20 G94 F10 G1 X1\nM2\n");
    let m = &out.motions[0];
    assert!(close(length(m) / m.feed * 60.0, 6.0, 1e-12));
}

#[test]
fn tv_f4_g94_resets_feed_linuxcnc() {
    let out = run_ngc("G21\nG94 F100\nG94\nG1 X1\nM2\n");
    assert_eq!(codes(&out), vec!["F001"]);
    assert!(out.motions.is_empty());
}

#[test]
fn tv_a4_quarter_circle_cw() {
    let out = run_ngc("G21 G17 G90\nG2 X1 Y1 I1 F10\nM2\n");
    let m = &out.motions[0];
    match m.kind {
        MotionKind::Arc { center, radius, .. } => {
            assert_pt(
                [center[0], center[1], center[2], 0.0, 0.0, 0.0],
                &[1.0, 0.0, 0.0],
                1e-12,
            );
            assert!(close(radius, 1.0, 1e-12), "{radius}");
        }
        k => panic!("not an arc: {k:?}"),
    }
    assert!(
        close(length(m), std::f64::consts::FRAC_PI_2, 1e-9),
        "{}",
        length(m)
    );
    assert_pt(m.end, &[1.0, 1.0, 0.0], 1e-12);
}

/// The digest's reading of §8.4.2: from X = 2, `G92 X0` stores +2 (the
/// seed's prose says −2; see ⚠ SEED-INTERNAL in rs274ngc.md §3.20).
#[test]
fn tv_g2_g92_from_x2() {
    let mm = "machine_units = \"mm\"";
    for (g92, want) in [("X0", 2.0), ("X5", -3.0), ("X2", 0.0)] {
        let out = run_profile(
            &format!("G21\nG0 X2\nG92 {g92}\nG0 Y#5211\nM2\n"),
            Variant::Linuxcnc,
            mm,
        );
        assert_eq!(out.motions[1].end[1], want, "G92 {g92}");
    }
}

/// G53 moves in machine coordinates whatever the offsets; G53 needs G0/G1
/// (NGC404) and absolute mode (NGC406), both rule K003.
#[test]
fn tv_g6_g53() {
    let out = run_ngc("G21\nG10 L2 P1 X5\nG92 X1\nG53 G0 X0\nM2\n");
    assert_eq!(out.motions[0].end[0], 0.0);
    let out = run_ngc("G21 F10\nG2 X1 Y1 I1\nG53 X1\nM2\n");
    assert_eq!(codes(&out), vec!["K003"]);
    let out = run_ngc("G21\nG91 G53 G0 X1\nM2\n");
    assert_eq!(codes(&out), vec!["K003"]);
}

/// #5220 selects the coordinate system at start-up; out of range, the
/// `linuxcnc` profile falls back to G54 (as rs274 does: `SET_G5X_OFFSET(3, …)`
/// and `(1, …)` for these two `.var` files) and `emc2` faults. The `.var`
/// values are in the standalone interpreter's inch machine units.
#[test]
fn tv_g7_start_up_coordinate_system() {
    let prog = "G21\nG0 X0\nM2\n";
    let var = "5220 3.0\n5221 1.0\n5261 7.0\n";
    let out = run_full(Dialect::Rs274ngc, prog, "", &[], None, Some(var));
    assert!(close(out.motions[0].end[0], 7.0 * 25.4, 1e-9), "G56 active");
    let var = "5220 12.0\n5221 1.0\n5261 7.0\n";
    let out = run_full(Dialect::Rs274ngc, prog, "", &[], None, Some(var));
    assert!(
        close(out.motions[0].end[0], 25.4, 1e-9),
        "falls back to G54"
    );
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let mut settings = Settings::new(Dialect::Rs274ngc);
    settings.variant = Variant::Emc2;
    let a = analyzer::analyze(prog.as_bytes().to_vec(), &settings);
    let machine = analyzer::config::MachineConfig::default();
    let out = run(&RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 1000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: Some(var),
    });
    assert_eq!(codes(&out), vec!["X003"], "emc2: start-up fault");
}

/// `T2 M6 G43 H2 G0 Z1`: the tool change, then the length offset of tool 2,
/// then the rapid to program Z1 (order of execution).
#[test]
fn tv_e1_tool_change_offset_then_motion() {
    let tools = "T2 P2 Z3.0 D0.5\n";
    let out = run_full(
        Dialect::Rs274ngc,
        "G21\nT2 M6 G43 H2 G0 Z1\nM2\n",
        "machine_units = \"mm\"",
        &[],
        Some(tools),
        None,
    );
    let change = out
        .events
        .iter()
        .position(|e| matches!(e.kind, runtime::EventKind::ToolChange { tool: 2 }))
        .expect("tool change");
    assert_eq!(out.events[change].motion_index, 0, "before the rapid");
    assert_eq!(out.motions.len(), 1);
    assert!(is_rapid(&out.motions[0]));
    // Program Z1 with a 3 mm tool: machine Z 4.
    assert!(
        close(out.motions[0].end[2], 4.0, 1e-12),
        "{:?}",
        out.motions[0].end
    );
}

/// §9.3 with tool 1 one inch long: the machine Z carries the offset while
/// G43 is on; N05 dwells 10 s before its move.
#[test]
fn tv_t1_tool_length_offset_program() {
    let prog = "G20\nN01 G1 F15 X0 Y0 Z0\nN02 G43 H1 Z0 X1\nN03 G49 X0 Z0\nN04 G0 X2\nN05 G1 G43 H1 G4 P10 Z0 X3\nN06 G49 X2 Z0\nM2\n";
    let out = run_full(
        Dialect::Rs274ngc,
        prog,
        "machine_units = \"inch\"",
        &[],
        Some("T1 P1 Z1.0 D0.0\n"),
        None,
    );
    let inch = 25.4;
    let z: Vec<f64> = out.motions.iter().map(|m| m.end[2] / inch).collect();
    let x: Vec<f64> = out.motions.iter().map(|m| m.end[0] / inch).collect();
    for (got, want) in z.iter().zip([0.0, 1.0, 0.0, 0.0, 1.0, 0.0]) {
        assert!(close(*got, want, 1e-12), "machine Z {z:?}");
    }
    for (got, want) in x.iter().zip([0.0, 1.0, 0.0, 2.0, 3.0, 2.0]) {
        assert!(close(*got, want, 1e-12), "X {x:?}");
    }
    let dwell = out
        .events
        .iter()
        .find(|e| matches!(e.kind, runtime::EventKind::Dwell(_)))
        .expect("dwell");
    assert_eq!(dwell.kind, runtime::EventKind::Dwell(10.0));
    assert_eq!(dwell.motion_index, 4, "before the N05 move");
}

/// §9.4.1's contour without compensation: every arc has r1 = r2, sweeps of
/// 90, 90, 90, 143.1301 and 36.8699 degrees, and a path of 17.712389 from
/// (1, 4.5).
#[test]
fn tv_r1_contour_geometry() {
    let prog = "G20 G17 G90 F10\nG0 X1 Y4.5\nN0020 G1 Y3.5\nN0030 G3 X2 Y2.5 I1\nN0040 G2 X2.5 Y2 J-0.5\nN0050 G1 Y-1\nN0060 G2 X2 Y-1.5 I-0.5\nN0070 G1 X-2\nN0080 G2 X-2.3 Y-0.6 J0.5\nN0090 G1 X1.7 Y2.4\nN0100 G2 X2 Y2.5 I0.3 J-0.4\nM2\n";
    let out = run_ngc(prog);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let inch = 25.4;
    let total: f64 = out.motions.iter().skip(1).map(length).sum::<f64>() / inch;
    assert!(close(total, 17.712389, 1e-6), "{total}");
    let radii: Vec<f64> = out
        .motions
        .iter()
        .filter_map(|m| match m.kind {
            MotionKind::Arc { radius, .. } => Some(radius / inch),
            _ => None,
        })
        .collect();
    for (got, want) in radii.iter().zip([1.0, 0.5, 0.5, 0.5, 0.5]) {
        assert!(close(*got, want, 1e-12), "{radii:?}");
    }
    assert_eq!(radii.len(), 5);
}

/// Nominal time of a motion in seconds: the planner segment's length over its
/// feed, before acceleration.
fn nominal_seconds(m: &runtime::Motion) -> f64 {
    let s = runtime::dryrun::segment_of(m, 0);
    s.length / s.feed
}

/// The G76 example of the digest (`linuxcnc` pass depths): passes at
/// |I| + J·n^(1/R) while below |I| + K, then 1 + H passes at |I| + K. Each
/// pass's synchronised cut runs at X = 0.2 − depth (external thread).
#[test]
fn tv_c9_g76_pass_depths() {
    let cycle = "G76 P0.05 Z-1 I-.075 J0.008 K0.045 Q29.5 L2 E0.045";
    let depths = |extra: &str| -> Vec<f64> {
        let out = run_ngc(&format!(
            "G20 G18 G90\nS100 M3\nG0 X0.2 Z-0.5\n{cycle}{extra}\nM2\n"
        ));
        assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
        out.motions
            .iter()
            .filter(|m| matches!(m.kind, MotionKind::Thread) && m.start[0] == m.end[0])
            .map(|m| 0.2 - m.end[0] / 25.4)
            .collect()
    };
    let d = depths("");
    let want = [0.083, 0.091, 0.099, 0.107, 0.115, 0.120];
    assert_eq!(d.len(), 6, "{d:?}");
    for (got, want) in d.iter().zip(want) {
        assert!(close(*got, want, 1e-12), "{d:?}");
    }
    assert_eq!(depths(" R2").len(), 32);
    let d = depths(" H2");
    assert_eq!(d.len(), 8, "{d:?}");
    for got in &d[5..] {
        assert!(close(*got, 0.120, 1e-12), "{d:?}");
    }
}

/// §8.5's five circles: the G10 lines set the G55–G58 offsets and each
/// `G3 X-.1 Y0 I.1 J0` is a full circle of radius 0.1 about program (0,0), so
/// the centres in machine XY are the offsets.
#[test]
fn tv_g5_five_circles() {
    let mut prog = String::from("G20\nG10 L2 P1 x0 y0 z0\nG10 L2 P2 x0.5\nG10 L2 P3 x-0.5\nG10 L2 P4 y0.5\nG10 L2 P5 y-0.5\n");
    for g in ["g54", "g55", "g56", "g57", "g58"] {
        prog.push_str(&format!(
            "{g} g0 x-.1 y0 z0\ng1 f1 z-.25\ng3 x-.1 y0 i.1 j0\ng0 z0\n"
        ));
    }
    prog.push_str("#1=#5241\n#2=#5261\n#3=#5282\n#4=#5302\ng54 g0 x#1 y#2 z0\ng0 x#3 y#4\nm2\n");
    let out = run_ngc(&prog);
    let inch = 25.4;
    let centres: Vec<[f64; 2]> = out
        .motions
        .iter()
        .filter_map(|m| match m.kind {
            MotionKind::Arc { center, radius, .. } => {
                assert!(close(radius / inch, 0.1, 1e-12), "r {radius}");
                assert!(close(length(m) / inch, 0.2 * std::f64::consts::PI, 1e-9));
                Some([center[0] / inch, center[1] / inch])
            }
            _ => None,
        })
        .collect();
    let want = [[0.0, 0.0], [0.5, 0.0], [-0.5, 0.0], [0.0, 0.5], [0.0, -0.5]];
    assert_eq!(centres.len(), 5);
    for (got, want) in centres.iter().zip(want) {
        assert!(
            close(got[0], want[0], 1e-12) && close(got[1], want[1], 1e-12),
            "{centres:?}"
        );
    }
    // #5241 = 0.5, #5261 = −0.5, #5282 = 0.5, #5302 = −0.5.
    let n = out.motions.len();
    assert_pt(out.motions[n - 2].end, &[0.5 * inch, -0.5 * inch], 1e-12);
    assert_pt(out.motions[n - 1].end, &[0.5 * inch, -0.5 * inch], 1e-12);
}

/// Feeds of moves of rotary axes only are in degrees per minute along the
/// combined rotary distance: 90° at F90 and D = √(30² + 40²) = 50° at F50 both
/// take one minute.
#[test]
fn tv_f3_rotary_only_feed_time() {
    let out = run_ngc("G21 G94 F90 G1 A90\nM2\n");
    assert!(close(nominal_seconds(&out.motions[0]), 60.0, 1e-9));
    let out = run_ngc("G21 G94 G1 A30 B40 F50\nM2\n");
    let s = runtime::dryrun::segment_of(&out.motions[0], 0);
    assert!(close(s.length, 50.0, 1e-12), "{}", s.length);
    assert!(close(nominal_seconds(&out.motions[0]), 60.0, 1e-9));
}

/// G33 at K0.0625 in/rev and 100 rpm over one inch: 16 revolutions, 0.16 min = 9.6 s
/// (the wait for the spindle index is not modelled).
#[test]
fn tv_f5_g33_time() {
    let out = run_ngc("G20 G18 G90\nS100 M3\nG0 X0 Z0\nG33 Z-1 K0.0625\nM2\n");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let m = &out.motions[1];
    assert!(matches!(m.kind, MotionKind::Thread));
    assert!(close(m.feed / 25.4, 0.0625, 1e-15));
    assert!(
        close(nominal_seconds(m), 9.6, 1e-9),
        "{}",
        nominal_seconds(m)
    );
}

/// Runs a G20 program with the cutter-compensation tools of §9.4 (inch table:
/// tool 1 diameter 1.0, tool 2 0.5, tool 4 0.489 — Jon Elson's — and tool 5
/// −0.03) and returns its motions' XY ends in inches.
fn comp_run(prog: &str, variant: Variant) -> (RunOutput, Vec<[f64; 2]>) {
    let mut settings = Settings::new(Dialect::Rs274ngc);
    settings.variant = variant;
    let a = analyzer::analyze(prog.as_bytes().to_vec(), &settings);
    let machine =
        analyzer::config::MachineConfig::from_toml("machine_units = \"inch\"").expect("toml");
    let tools = "T1 P1 D1.0 Z0\nT2 P2 D0.5 Z0\nT4 P4 D0.489 Z0\nT5 P5 D-0.03 Z0\n";
    let out = run(&RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 100_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: Some(tools),
        var_file: None,
    });
    let xy = out
        .motions
        .iter()
        .map(|m| [m.end[0] / 25.4, m.end[1] / 25.4])
        .collect();
    (out, xy)
}

#[track_caller]
fn assert_xy(got: &[[f64; 2]], want: &[[f64; 2]], tol: f64) {
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            close(g[0], w[0], tol) && close(g[1], w[1], tol),
            "got {got:?}\nwant {want:?}"
        );
    }
}

/// §9.4.1's tool-path contour with a −0.03 diameter: the 0.015 offset goes to
/// the right of the path despite G41 (rs274 prints the same points).
#[test]
fn tv_r1_negative_diameter_runs_on_the_right() {
    let prog = "G20 G17 G90 F10\nT5 M6\nG0 X1 Y5\nN0010 G1 X1 Y4.5\nN0020 G41 G1 Y3.5\nN0030 G3 X2 Y2.5 I1\nN0040 G2 X2.5 Y2 J-0.5\nN0050 G1 Y-1\nN0060 G2 X2 Y-1.5 I-0.5\nN0070 G1 X-2\nN0080 G2 X-2.3 Y-0.6 J0.5\nN0090 G1 X1.7 Y2.4\nN0100 G2 X2 Y2.5 I0.3 J-0.4\nN0110 G40\nM2\n";
    let (out, xy) = comp_run(prog, Variant::Linuxcnc);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    // The hypotenuse (direction (4,3)/5) is offset by 0.015·(0.6, −0.8).
    let want = [
        [1.0, 5.0],
        [1.0, 4.5],
        [0.985, 3.5],
        [2.0, 2.485],
        [2.485, 2.0],
        [2.485, -1.0],
        [2.0, -1.485],
        [-2.0, -1.485],
        [-2.291, -0.612],
        [1.709, 2.388],
        [2.0, 2.485],
    ];
    assert_xy(&xy, &want, 1e-12);
}

/// §9.4.1 example 1: the material-edge triangle with a 1.0 diameter tool runs
/// clockwise around the outside with three inserted arcs of radius 0.5 and no
/// errors. From (0, 3) the entry move ends 0.5 from (2, 2), perpendicular to it.
#[test]
fn tv_r2_material_edge_triangle() {
    let prog = "G20 G17 G90\nT1 M6\nG0 X0 Y3\nN0010 G41 G1 X2 Y2 F10\nN0020 Y-1\nN0030 X-2\nN0040 X2 Y2\nN0050 G40\nM2\n";
    let (out, xy) = comp_run(prog, Variant::Linuxcnc);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let s5 = 5f64.sqrt();
    let want = [
        [0.0, 3.0],
        [2.0 + 0.5 / s5, 2.0 + 1.0 / s5],
        [2.5, 2.0],
        [2.5, -1.0],
        [2.0, -1.5],
        [-2.0, -1.5],
        [-2.3, -0.6],
        [1.7, 2.4],
    ];
    assert_xy(&xy, &want, 1e-12);
    let arcs: Vec<(f64, f64)> = out
        .motions
        .iter()
        .filter_map(|m| match m.kind {
            MotionKind::Arc { radius, normal, .. } => Some((radius / 25.4, normal[2])),
            _ => None,
        })
        .collect();
    // The radius is the tool table's diameter over rs274's external unit 0.03937007874016
    // and 25.4, which is 0.5 to within 1e-13.
    assert_eq!(arcs.len(), 3, "three arcs");
    for (r, n) in arcs {
        assert!(
            (r - 0.5).abs() < 1e-12 && n == -1.0,
            "clockwise arc of r 0.5: {r} {n}"
        );
    }
}

/// A concave corner for a tool on the left: `linuxcnc` pulls the end point
/// back and the tool stops at (1.75, 0.25) before going up; `emc2` stops
/// with NGC416 (X003) at the corner.
#[test]
fn tv_r3_concave_corner() {
    let prog = "G20\nT2 M6\nG17 G40 G0 X0 Y-1\nG41 D2 G1 X0 Y0 F10\nX2 Y0\nX2 Y2\nG40\nM2\n";
    let (out, xy) = comp_run(prog, Variant::Linuxcnc);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let want = [
        [0.0, -1.0],
        [-0.25, 0.0],
        [0.0, 0.25],
        [1.75, 0.25],
        [1.75, 2.0],
    ];
    assert_xy(&xy, &want, 1e-12);
    let (out, _) = comp_run(prog, Variant::Emc2);
    assert_eq!(codes(&out), vec!["X003"]);
    assert_eq!(
        out.diagnostics[0].message,
        "Concave corner with cutter radius comp (the dry run stops here)"
    );
}

/// r = 0.5 inside an arc of radius 0.4 → NGC418 (X003, rs274's message).
#[test]
fn tv_r4_tool_inside_a_smaller_arc() {
    let prog = "G20 G17\nT1 M6\nG0 X-2 Y0\nG41 D1 G1 X0 Y0 F10\nG3 X0.8 Y0 I0.4 J0\nG40\nM2\n";
    let (out, _) = comp_run(prog, Variant::Linuxcnc);
    assert_eq!(codes(&out), vec!["X003"]);
    assert_eq!(
        out.diagnostics[0].message,
        "Tool radius not less than arc radius with comp (the dry run stops here)"
    );
}

/// r = 0.5 and an entry move of 0.3 → NGC417 (X003).
#[test]
fn tv_r5_entry_move_shorter_than_the_radius() {
    let prog = "G20 G17\nT1 M6\nG0 X0 Y0\nG41 D1 G1 X0.3 Y0 F10\nX2\nM2\n";
    let (out, xy) = comp_run(prog, Variant::Linuxcnc);
    assert_eq!(codes(&out), vec!["X003"]);
    assert_eq!(xy, vec![[0.0, 0.0]], "no compensated move");
}

/// Jon Elson's program passes with tool 4 (diameter 0.489): the lead-in and
/// lead-out nip the corner. The points are rs274's (printed to 4 decimals);
/// the straight cuts run 0.2445 above Y3.1875. The seed gives no feed before
/// N10, so F10 comes first.
#[test]
fn tv_r6_jon_elson_lead_in_and_out() {
    let prog = "G20 F10\nT4 M6\nN10 G01 G40 X-1.3531 Y3.4\nN15 F10 G17 G41 D4 X-0.7 Y3.1875\nN20 X0. Y3.1875\nN40 X0.5667 F10\nN50 G03 X0.8225 Y3.3307 R0.3\nN60 G02 X2.9728 Y4.3563 R2.1875\nN70 G01 X7.212 Y3.7986\nN80 G02 X8.1985 Y3.2849 R1.625\nN90 G03 X8.4197 Y3.1875 R0.3\nN100 G01 X9.\nN110 G40 X10.1972 Y3.432\nN220 M02\n";
    let (out, xy) = comp_run(prog, Variant::Linuxcnc);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let want = [
        [-1.3531, 3.4],
        [-0.6612, 3.432],
        [0.0, 3.432],
        [0.5667, 3.432],
        [0.6141, 3.4585],
        [3.0047, 4.5987],
        [7.2439, 4.0410],
        [8.3788, 3.4500],
        [8.4197, 3.4320],
        [9.0, 3.432],
        [10.1972, 3.432],
    ];
    assert_xy(&xy, &want, 5e-5);
}
