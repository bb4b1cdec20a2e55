//! RS274/NGC test vectors (rs274ngc.md §10) with their exact numbers.

mod common;

use analyzer::{Dialect, Settings, Variant};
use common::*;
use runtime::{run, MotionKind, NoResolver, RunInput, RunOutput};

fn run_profile(text: &str, variant: Variant, machine: &str) -> RunOutput {
    let mut settings = Settings::new(Dialect::Rs274ngc);
    settings.variant = variant;
    let a = analyzer::analyze(text.as_bytes().to_vec(), &settings);
    let machine: toml::Table = toml::from_str(machine).expect("toml");
    let input = RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 100_000,
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
        s.modal,
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
    let machine = toml::Table::new();
    let out = run(&RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 1000,
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
