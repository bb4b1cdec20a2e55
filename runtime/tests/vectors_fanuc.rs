//! FANUC test vectors (fanuc.md §8 and Macro B rules) with their exact numbers.

mod common;

use common::*;
use runtime::EventKind;

const OFFSETS: &str =
    "[tools]\n11 = { length = 200.0 }\n15 = { length = 190.0 }\n31 = { length = 150.0 }\n";

const EXAMPLE_8_1: &str = "%
N001 G92 X0 Y0 Z0;
N002 G90 G00 Z250.0 T11 M6;
N003 G43 Z0 H11;
N004 S30 M3;
N005 G99 G81 X400.0 Y-350.0 Z-153.0 R-97.0 F120;
N006 Y-550.0;
N007 G98 Y-750.0;
N008 G99 X1200.0;
N009 Y-550.0;
N010 G98 Y-350.0;
N011 G00 X0 Y0 M5;
N012 G49 Z250.0 T15 M6;
N013 G43 Z0 H15;
N014 S20 M3;
N015 G99 G82 X550.0 Y-450.0 Z-130.0 R-97.0 P300 F70;
N016 G98 Y-650.0;
N017 G99 X1050.0;
N018 G98 Y-450.0;
N019 G00 X0 Y0 M5;
N020 G49 Z250.0 T31 M6;
N021 G43 Z0 H31;
N022 S10 M3;
N023 G85 G99 X800.0 Y-350.0 Z-153.0 R47.0 F50;
N024 G91 Y-200.0 K2;
N025 G28 X0 Y0 M5;
N026 G49 Z0;
N027 M0;
M30;
%
";

#[test]
fn example_8_1_canned_cycles() {
    let out = run_fanuc(EXAMPLE_8_1, OFFSETS);
    // N011/N019 G00 while a cycle is modal cancels it (FAN023, info); N023 puts
    // R47 above the initial level Z0 (FAN081); N024 switches to G91 in cycle mode
    // without R and Z (FAN082); N025 G28 while G85 is modal (no G80 in the
    // example): PS0044, the cycle is cancelled.
    assert_eq!(
        codes(&out),
        vec!["C006", "C006", "C006", "C006", "C003"],
        "{:?}",
        out.diagnostics
    );
    let c006: Vec<&str> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "C006")
        .map(|d| d.message.as_str())
        .collect();
    assert_eq!(
        c006[2],
        "point R (47) is above the initial level (0): the tool retracts upward to R before drilling"
    );
    let by_tool = |t: u32| {
        out.motions
            .iter()
            .filter(move |m| m.tool == t && is_feed(m))
    };
    // T11: 6 holes of 56 mm at F120.
    let t11: Vec<_> = by_tool(11).collect();
    assert_eq!(t11.len(), 6);
    let holes: Vec<[f64; 2]> = t11.iter().map(|m| [m.end[0], m.end[1]]).collect();
    assert_eq!(
        holes,
        vec![
            [400.0, -350.0],
            [400.0, -550.0],
            [400.0, -750.0],
            [1200.0, -750.0],
            [1200.0, -550.0],
            [1200.0, -350.0]
        ]
    );
    let feed11: f64 = t11.iter().map(|m| length(m)).sum();
    assert!(close(feed11, 336.0, 1e-9));
    assert!(t11.iter().all(|m| m.feed == 120.0));
    // Machine Z at the bottom: program −153 + H11 200.
    assert!(close(t11[0].end[2], 47.0, 1e-9));
    // G98 after hole 3 returns to the initial level (program 0 = machine 200).
    let after3 = out
        .motions
        .iter()
        .position(|m| m.tool == 11 && m.end[1] == -750.0 && is_feed(m))
        .unwrap_or(0)
        + 1;
    assert!(close(out.motions[after3].end[2], 200.0, 1e-9));
    // T15: 4 holes of 33 mm at F70, 0.3 s dwell each.
    let t15: Vec<_> = by_tool(15).collect();
    assert_eq!(t15.len(), 4);
    let feed15: f64 = t15.iter().map(|m| length(m)).sum();
    assert!(close(feed15, 132.0, 1e-9));
    let dwell: f64 = out
        .events
        .iter()
        .filter_map(|e| {
            if let EventKind::Dwell(s) = e.kind {
                Some(s)
            } else {
                None
            }
        })
        .sum();
    assert!(close(dwell, 1.2, 1e-12));
    // T31 G85: R47 above the initial level; holes at Y −350, −550, −750 (K2 in G91), 200 mm in and out.
    let t31: Vec<_> = by_tool(31).collect();
    assert_eq!(
        t31.len(),
        6,
        "{:?}",
        t31.iter().map(|m| (m.start, m.end)).collect::<Vec<_>>()
    );
    assert!(t31.iter().all(|m| close(length(m), 200.0, 1e-9)));
    let ys: Vec<f64> = t31.iter().step_by(2).map(|m| m.end[1]).collect();
    assert_eq!(ys, vec![-350.0, -550.0, -750.0]);
    let stops = out
        .events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Stop { optional: false }))
        .count();
    assert_eq!(stops, 1);
}

#[test]
fn polar_bolt_hole_circle_absolute_and_incremental() {
    let abs = "G00 Z10.;\nN1 G17 G90 G16;\nN2 G81 X100.0 Y30.0 Z-20.0 R-5.0 F200.0;\nN3 Y150.0;\nN4 Y270.0;\nN5 G15 G80;\nM30;\n";
    let inc = "G00 Z10.;\nN1 G17 G90 G16;\nN2 G81 X100.0 Y30.0 Z-20.0 R-5.0 F200.0;\nN3 G91 Y120.0;\nN4 Y120.0;\nN5 G15 G80;\nM30;\n";
    for prog in [abs, inc] {
        let out = run_fanuc(prog, "");
        let holes: Vec<[f64; 3]> = out
            .motions
            .iter()
            .filter(|m| is_feed(m))
            .map(|m| [m.end[0], m.end[1], m.end[2]])
            .collect();
        let want = [
            [86.6025, 50.0, -20.0],
            [-86.6025, 50.0, -20.0],
            [0.0, -100.0, -20.0],
        ];
        assert_eq!(holes.len(), 3, "{prog}");
        for (h, w) in holes.iter().zip(want.iter()) {
            assert!((0..3).all(|i| close(h[i], w[i], 1e-4)), "{prog}: {holes:?}");
        }
        // G98 is the FANUC default: each hole returns to the initial level Z10.
        let last = out.motions.last().map(|m| m.end[2]).unwrap_or_default();
        assert_eq!(last, 10.0);
    }
}

#[test]
fn g65_argument_specification_mixing() {
    // #1=1, #2=2, #3 vacant, #4=-3, #5 and #6 vacant, #7=5 (I4.0 set #7, then D5.0 overwrote it).
    let prog = "G65 A1.0 B2.0 I-3.0 I4.0 D5.0 P1000;\nM30;\nO1000;\n#110 = 0;\nIF [#3 EQ #0] THEN #110 = 1;\nIF [#5 EQ #0] THEN #111 = 1;\nG00 X#1 Y#2 Z#4;\nG00 X#7 Y#110 Z#111;\nM99;\n";
    let out = run_fanuc(prog, "");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    assert_eq!(ends(&out), vec![[1.0, 2.0, -3.0], [5.0, 1.0, 1.0]]);
}

#[test]
fn vacant_semantics() {
    // #1 vacant: Y#1 is omitted; #1 + 1 = 1; #1 EQ 0 is false; #1 GE 0 compares as 0.
    let prog = "G90 G00 X100. Y5.;\nG00 X100. Y#1;\n#2 = #1 + 1;\nIF [#1 EQ 0] GOTO 10;\n#3 = 7;\nN10 IF [#1 GE #0] THEN #4 = 9;\nG00 X#2 Y#3 Z#4;\nM30;\n";
    let out = run_fanuc(prog, "");
    assert_eq!(
        ends(&out),
        vec![[100.0, 5.0, 0.0], [100.0, 5.0, 0.0], [1.0, 7.0, 9.0]]
    );
}

#[test]
fn while_loop_and_goto() {
    let prog = "#1 = 0;\nWHILE [#1 LT 3] DO 1;\n#1 = #1 + 1;\nG91 G00 X1.;\nEND 1;\nGOTO 20;\nG00 X100.;\nN20 G90 G00 Y#1;\nM30;\n";
    let out = run_fanuc(prog, "");
    assert_eq!(
        ends(&out),
        vec![
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 3.0, 0.0]
        ]
    );
}

#[test]
fn m98_repeat_count_in_p() {
    // P50010: O0010 five times; M98 shares the caller's locals.
    let prog = "#1 = 0;\nM98 P50010;\nG90 G00 X#1;\nM30;\nO0010;\n#1 = #1 + 1;\nM99;\n";
    let out = run_fanuc(prog, "");
    assert_eq!(ends(&out), vec![[5.0, 0.0, 0.0]]);
}

#[test]
fn decimal_point_rules() {
    let out = run_fanuc("G90 G00 X1 Y1.;\nM30;\n", "");
    assert_eq!(ends(&out), vec![[0.001, 1.0, 0.0]]);
    let calc = run_fanuc("G90 G00 X1 Y1.;\nM30;\n", "decimal_point_input = true");
    assert_eq!(ends(&calc), vec![[1.0, 1.0, 0.0]]);
}

#[test]
fn arc_tolerance_parameter_3410() {
    let prog = "G90 G00 X0 Y0;\nG02 X100. Y0 I49.99 J0 F100;\nM30;\n";
    assert!(codes(&run_fanuc(prog, "arc_radius_tolerance = 0.05")).is_empty());
    assert_eq!(
        codes(&run_fanuc(prog, "arc_radius_tolerance = 0.01")),
        vec!["A001"]
    );
}

#[test]
fn modal_rule_last_group01_wins_and_ijk_in_polar() {
    let out = run_fanuc("G00 G01 X10. F100;\nM30;\n", "");
    assert!(is_feed(&out.motions[0]));
    let polar = run_fanuc("G17 G16;\nG02 X50. Y90. I10. J0 F100;\nG15;\nM30;\n", "");
    assert!(codes(&polar).contains(&"A007"));
}

#[test]
fn division_by_zero_is_reported_and_the_run_goes_on() {
    let out = run_fanuc("#1 = 0;\n#2 = 1 / #1;\nG00 X1.;\nM30;\n", "");
    assert_eq!(codes(&out), vec!["X001"]);
    // The alarm is reported once; the dry run goes on with #2 unknown.
    assert_eq!(out.motions.len(), 1);
    assert!(out.stopped.is_none());
}

#[test]
fn macro_alarm_3000() {
    let out = run_fanuc("#3000 = 12 (TOOL BROKEN);\nG00 X1.;\nM30;\n", "");
    assert_eq!(codes(&out), vec!["X004"]);
}

#[test]
fn runaway_loop_hits_step_budget() {
    let out = run_fanuc("N1 GOTO 1;\nM30;\n", "");
    assert_eq!(codes(&out), vec!["F004"]);
}

#[test]
fn recursion_hits_depth_limit() {
    let out = run_fanuc("M98 P1;\nM30;\nO0001;\nM98 P1;\nM99;\n", "");
    assert_eq!(codes(&out), vec!["F003"]);
}

#[test]
fn system_variables_read_the_state() {
    // #5001 end point, #4003 distance mode, #4001 motion group, #5021 machine position.
    let prog = "G90 G54 G01 X12. Y3. F100;\n#1 = #5001;\n#2 = #4003;\n#3 = #4001;\nG92 X0 Y0;\nG00 X#1 Y#2 Z#3;\n#4 = #5021;\nG00 X#4;\nM30;\n";
    let out = run_fanuc(prog, "");
    assert_eq!(
        ends(&out),
        vec![[12.0, 3.0, 0.0], [24.0, 93.0, 1.0], [36.0, 93.0, 1.0]]
    );
}

#[test]
fn m99_in_main_stops_the_dry_run() {
    let out = run_fanuc("G00 X1.;\nM99;\n", "");
    assert_eq!(codes(&out), vec!["X003"]);
    assert_eq!(out.motions.len(), 1);
}

/// `M99 P<n>` in a main program jumps to block N<n> of that program
/// (fanuc.md §4.7), so it is not the endless restart a bare M99 is.
#[test]
fn m99_p_in_main_jumps_to_the_sequence_number() {
    let out = run_fanuc("G00 X1.;\nM99 P20;\nN10 G00 X5.;\nN20 G00 X2.;\nM30;\n", "");
    assert_eq!(codes(&out), Vec::<&str>::new());
    assert_eq!(ends(&out), vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
    // A missing target is alarm PS0078 and stops the run there.
    let out = run_fanuc("G00 X1.;\nM99 P30;\nN20 G00 X2.;\nM30;\n", "");
    assert_eq!(codes(&out), vec!["F007"]);
    assert_eq!(out.motions.len(), 1);
}

#[test]
fn g09_exact_stop_is_one_shot() {
    let out = run_fanuc("G64 G01 X10. F100;\nG09 X20.;\nX30.;\nM30;\n", "");
    let exact: Vec<bool> = out.motions.iter().map(|m| m.exact_stop).collect();
    assert_eq!(exact, vec![false, true, false]);
}

#[test]
fn g66_modal_call_after_each_move() {
    // The macro drills at each position: it feeds Z down by #26 and back.
    let prog = "G90 G00 Z10.;\nG66 P9000 Z-5.;\nG00 X10.;\nX20.;\nG67;\nX30.;\nM30;\nO9000;\nG91 G01 Z#26 F100.;\nG00 Z-#26;\nG90;\nM99;\n";
    let out = run_fanuc(prog, "");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let feeds: Vec<[f64; 3]> = out
        .motions
        .iter()
        .filter(|m| is_feed(m))
        .map(|m| [m.end[0], m.end[1], m.end[2]])
        .collect();
    assert_eq!(feeds, vec![[10.0, 0.0, 5.0], [20.0, 0.0, 5.0]]);
    assert_eq!(
        out.motions.last().map(|m| m.end),
        Some([30.0, 0.0, 10.0, 0.0, 0.0, 0.0])
    );
}

#[test]
fn g10_l10_sets_length_offset() {
    let out = run_fanuc(
        "G10 L10 P5 R100.;\nG43 H5 Z0;\nG91 G10 L10 P5 R-2.;\nG90 G43 H5 Z0;\nM30;\n",
        "",
    );
    let z: Vec<f64> = out.motions.iter().map(|m| m.end[2]).collect();
    assert_eq!(z, vec![100.0, 98.0]);
}

#[test]
fn group01_code_cancels_cycle_data() {
    // After G00 the cycle must be given R and Z again.
    let out = run_fanuc(
        "G00 Z10.;\nG81 X1. Z-1. R1. F100.;\nG00 X5.;\nG81 X6.;\nM30;\n",
        "",
    );
    assert!(codes(&out).contains(&"C001"), "{:?}", out.diagnostics);
}

#[test]
fn typical_program_is_clean() {
    let prog = "%
O1000 (BRACKET);
G21 G17 G40 G49 G80 G90;
T1 M6;
G54 G00 X0 Y0 S1200 M03;
G43 H1 Z50. M08;
G99 G81 X10. Y10. Z-5. R2. F150.;
X20.;
G98 Y20.;
G80;
G00 Z50.;
G01 Z-1. F100.;
G41 D1 G01 X30. Y0;
G03 X40. Y10. R10.;
G02 X50. Y20. I10. J0;
G40 G01 X60. Y20.;
G91 G28 Z0.;
G28 X0. Y0.;
G90;
M05;
M09;
M30;
%
";
    let out = run_fanuc(prog, "[tools]\n1 = { length = 100.0, diameter = 10.0 }\n");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    assert!(out.motions.len() > 15);
    // G91 G28 Z0. retracts Z to the machine reference point.
    assert!(out
        .motions
        .iter()
        .any(|m| m.end[2] == 0.0 && m.start[2] != 0.0));
}

/// M1 stops only when the machine's optional-stop switch is on; then it costs
/// `program_stop_time` like M0. Off (the default), the control runs through it.
#[test]
fn optional_stop_switch_decides_whether_m1_costs_time() {
    let prog = "G90 G0 X10.\nM01\nX20.\nM30\n";
    let other = |machine: &str| {
        let out = run_fanuc(prog, machine);
        let table = analyzer::config::MachineConfig::from_toml(machine).unwrap();
        let profile = runtime::dryrun::profile_from_table(&table, analyzer::Dialect::Fanuc);
        runtime::dryrun::plan_run(&out, &profile).totals.other_s
    };
    assert_eq!(other("program_stop_time = 30.0"), 0.0);
    assert_eq!(
        other("program_stop_time = 30.0\noptional_stop = true"),
        30.0
    );
}

/// §8.3 rigid tapping (Z feed 1000 mm/min, S1000, lead 1.0 mm), per minute
/// and per revolution: 80 mm in at 4.8 s and out at 4.8 s, no dwell, back to
/// the initial level (G98 by default).
#[test]
fn example_8_3_rigid_tapping() {
    for (mode, f) in [("G94", "F1000"), ("G95", "F1.0")] {
        let prog = format!(
            "G21 G90;\n{mode};\nG00 X120.0 Y100.0;\nM29 S1000;\nG84 Z-100.0 R-20.0 {f};\nG80;\nM30;\n"
        );
        let out = run_fanuc(&prog, "");
        assert!(
            !out.diagnostics
                .iter()
                .any(|d| d.severity == analyzer::Severity::Error
                    || d.severity == analyzer::Severity::Warning),
            "{mode}: {:?}",
            out.diagnostics
        );
        let feeds: Vec<_> = out.motions.iter().filter(|m| is_feed(m)).collect();
        assert_eq!(feeds.len(), 2, "{mode}");
        assert_pt(feeds[0].start, &[120.0, 100.0, -20.0], 1e-9);
        assert_pt(feeds[0].end, &[120.0, 100.0, -100.0], 1e-9);
        assert_pt(feeds[1].end, &[120.0, 100.0, -20.0], 1e-9);
        for m in &feeds {
            assert!(close(m.feed, 1000.0, 1e-9), "{mode}: feed {}", m.feed);
            assert!(close(length(m) / m.feed * 60.0, 4.8, 1e-12));
        }
        assert!(!out
            .events
            .iter()
            .any(|e| matches!(e.kind, runtime::EventKind::Dwell(_))));
        let last = out.motions.last().expect("motion");
        assert_pt(last.end, &[120.0, 100.0, 0.0], 1e-9);
    }
    // M29 given while the tapping cycle is already modal: PS0204 (rule C004).
    let out = run_fanuc(
        "G21 G90;\nM3 S1000;\nG84 X10. Z-100.0 R-20.0 F1000;\nM29 S1000;\nG80;\nM30;\n",
        "",
    );
    assert!(codes(&out).contains(&"C004"), "{:?}", out.diagnostics);
    // F0 in rigid tapping (rule C009).
    let out = run_fanuc(
        "G21 G90;\nM29 S1000;\nG84 X10. Z-100.0 R-20.0 F0;\nG80;\nM30;\n",
        "",
    );
    assert!(codes(&out).contains(&"C009"), "{:?}", out.diagnostics);
}

/// §8.2's cycle examples on their common hole pattern (six holes, the last
/// with G98): feed length per hole at F120 and dwell per hole.
#[test]
fn example_8_2_individual_cycles() {
    // (cycle words, spindle, feed mm per hole, dwell s per hole)
    let cases: &[(&str, &str, f64, f64)] = &[
        ("G81 Z-150. R-100.", "M3 S500", 50.0, 0.0),
        ("G82 Z-150. R-100. P1000", "M3 S500", 50.0, 1.0),
        ("G85 Z-150. R-120.", "M3 S500", 60.0, 0.0),
        ("G89 Z-150. R-120. P1000", "M3 S500", 60.0, 1.0),
        ("G86 Z-150. R-100.", "M3 S500", 50.0, 0.0),
        ("G74 Z-150. R-120.", "M4 S100", 60.0, 0.0),
        ("G84 Z-150. R-120. P300", "M3 S100", 60.0, 0.3),
    ];
    for (cycle, spindle, per_hole, dwell) in cases {
        let prog = format!(
            "G21 G90 G00 Z0.;\n{spindle};\nG90 G99 {} X300. Y-250. {} F120.;\nY-550.;\nY-750.;\nX1000.;\nY-550.;\nG98 Y-750.;\nG80 G28 G91 X0 Y0 Z0;\nM5;\nM30;\n",
            &cycle[..3],
            &cycle[4..]
        );
        let out = run_fanuc(&prog, "");
        let feed: f64 = out.motions.iter().filter(|m| is_feed(m)).map(length).sum();
        assert!(close(feed, 6.0 * per_hole, 1e-9), "{cycle}: feed {feed}");
        // At F120 mm/min: 25 s per 50 mm.
        assert!(close(per_hole / 120.0 * 60.0 * 6.0, feed / 2.0, 1e-9));
        let dwells: f64 = out
            .events
            .iter()
            .filter_map(|e| match e.kind {
                runtime::EventKind::Dwell(s) => Some(s),
                _ => None,
            })
            .sum();
        assert!(close(dwells, 6.0 * dwell, 1e-12), "{cycle}: dwell {dwells}");
        let errors: Vec<_> = out
            .diagnostics
            .iter()
            .filter(|d| {
                matches!(
                    d.severity,
                    analyzer::Severity::Error | analyzer::Severity::Warning
                )
            })
            .collect();
        assert!(errors.is_empty(), "{cycle}: {errors:?}");
    }
}

/// One hole of a §8.2 example at (300, −250) from Z0 under G99, with the
/// machine keys `machine`; returns the run and the Z ends after the rapid to
/// the hole.
fn one_hole(cycle: &str, machine: &str) -> (runtime::RunOutput, Vec<f64>) {
    let g99 = if cycle.starts_with("G87") { "" } else { "G99 " };
    let prog = format!(
        "G21 G90 G00 Z0.;\nM3 S500;\nG90 {g99}{} X300. Y-250. {} F120.;\nG80;\nM30;\n",
        &cycle[..3],
        &cycle[4..]
    );
    let out = run_fanuc(&prog, machine);
    let z = out.motions.iter().skip(2).map(|m| m.end[2]).collect();
    (out, z)
}

fn dwell_total(out: &runtime::RunOutput) -> f64 {
    out.events
        .iter()
        .filter_map(|e| match e.kind {
            runtime::EventKind::Dwell(s) => Some(s),
            _ => None,
        })
        .sum()
}

/// §8.2's G73 and G83 with Q15 over 50 mm: four pecks ending at −115, −130,
/// −145, −150. G73 backs off d (No. 5114) after each of the first three, so
/// the feed length is 50 + 3d; G83 rapids up to R (15, 30, 45) and back down
/// to d (No. 5115) above the last depth (90 − 3d). Both then return to R.
#[test]
fn example_8_2_peck_cycles() {
    for d in [1.0, 2.0] {
        let machine = format!("g73_retract = {d:.1}\ng83_clearance = {d:.1}");
        let (out, z) = one_hole("G73 Z-150. R-100. Q15.", &machine);
        assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
        let want = [
            -100.0,
            -115.0,
            -115.0 + d,
            -130.0,
            -130.0 + d,
            -145.0,
            -145.0 + d,
            -150.0,
            -100.0,
        ];
        assert_eq!(z, want, "G73 d {d}");
        let feed: f64 = out.motions.iter().filter(|m| is_feed(m)).map(length).sum();
        assert!(close(feed, 50.0 + 3.0 * d, 1e-9), "G73 feed {feed}");

        let (out, z) = one_hole("G83 Z-150. R-100. Q15.", &machine);
        assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
        let want = [
            -100.0,
            -115.0,
            -100.0,
            -115.0 + d,
            -130.0,
            -100.0,
            -130.0 + d,
            -145.0,
            -100.0,
            -145.0 + d,
            -150.0,
            -100.0,
        ];
        assert_eq!(z, want, "G83 d {d}");
        let feed: f64 = out.motions.iter().filter(|m| is_feed(m)).map(length).sum();
        assert!(close(feed, 50.0 + 3.0 * d, 1e-9), "G83 feed {feed}");
        // Rapid up to R after pecks 1–3: 15 + 30 + 45 = 90 (the Z list above
        // holds the rapids down, 90 − 3d in all).
        let up: f64 = out
            .motions
            .windows(2)
            .filter(|w| is_rapid(&w[1]) && is_feed(&w[0]) && w[1].end[2] == -100.0)
            .map(|w| -100.0 - w[0].end[2])
            .take(3)
            .sum();
        assert!(close(up, 90.0, 1e-9), "up {up}");
    }
}

/// §8.2's G76 (fine boring: 30 mm feed = 15 s at F120, 1 s dwell, a 5 mm shift
/// along +X, the default of No. 5148, then a rapid out), G88 (50 mm feed = 25 s,
/// 1 s dwell, then the manual-hold stop) and G87 as printed (R−120 above
/// Z−150: FAN079, rule C006).
#[test]
fn example_8_2_boring_cycles() {
    let (out, z) = one_hole("G76 Z-150. R-120. Q5. P1000", "");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    assert_eq!(z, [-120.0, -150.0, -150.0, -120.0, -120.0]);
    let feed: Vec<&runtime::Motion> = out.motions.iter().filter(|m| is_feed(m)).collect();
    assert_eq!(feed.len(), 1);
    assert!(close(length(feed[0]) / feed[0].feed * 60.0, 15.0, 1e-12));
    assert_eq!(dwell_total(&out), 1.0);
    let shift = &out.motions[4];
    assert!(is_rapid(shift));
    assert_eq!(shift.end[0] - shift.start[0], 5.0, "shift along +X");

    let (out, z) = one_hole("G88 Z-150. R-100. P1000", "");
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    assert_eq!(z, [-100.0, -150.0, -100.0]);
    let m = &out.motions[3];
    assert!(close(length(m) / m.feed * 60.0, 25.0, 1e-12));
    assert_eq!(dwell_total(&out), 1.0);
    let stop = out
        .events
        .iter()
        .position(|e| matches!(e.kind, runtime::EventKind::Stop { optional: false }))
        .expect("manual hold");
    assert_eq!(
        out.events[stop].motion_index, 4,
        "at the bottom, before the retract"
    );

    let (out, _) = one_hole("G87 Z-150. R-120. Q5. P1000", "");
    assert_eq!(codes(&out), vec!["C006"]);
}

/// §8.6's N203 in the XY plane: from (−1, 0) about (0, 0) with R 1 to
/// (1, 9.425). The end is φ = 9.4250 rad unwound (≈ 3π), the path is
/// R·φ²/2 = 44.41 mm (to the digest's two decimals) and takes that over F;
/// the toolpath follows the involute (every point R·√(1 + φ²) from the
/// centre, the φ = 3π point at (1, 9.42478)).
#[test]
fn example_8_6_involute_path() {
    let out = run_fanuc(
        "G17 G90 G00 X-1. Y0;\nG02.2 X1.0 Y9.425 I1.0 J0 R1.0 F100.;\nM30;\n",
        "",
    );
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    let m = &out.motions[1];
    let runtime::MotionKind::Involute { curve, .. } = m.kind else {
        panic!("not an involute: {:?}", m.kind);
    };
    assert_eq!(format!("{:.4}", curve.phi_end), "9.4250");
    let s = runtime::dryrun::segment_of(m, 0);
    assert!(close(s.length, 44.41, 0.01), "{}", s.length);
    assert!(close(s.length / s.feed, s.length / 100.0 * 60.0, 1e-9));
    // The planner runs the curve's length, not its chord, at F100.
    let profile = runtime::machine::MachineProfile::default_for(analyzer::Dialect::Fanuc);
    let dry = runtime::dryrun::plan_run(&out, &profile);
    assert!(
        close(dry.totals.cutting_s, s.length / 100.0 * 60.0, 0.05),
        "{}",
        dry.totals.cutting_s
    );
    let tp = runtime::dryrun::toolpath(&out, 0.001);
    let pts = &tp.segments[1].points;
    assert!(pts.len() > 100, "{}", pts.len());
    for p in &pts[..pts.len() - 1] {
        let rho = p[0].hypot(p[1]);
        let phi = (rho * rho - 1.0).max(0.0).sqrt();
        let q = curve.point(phi);
        assert!(close(q[0], p[0], 1e-9) && close(q[1], p[1], 1e-9), "{p:?}");
    }
    let p = curve.point(3.0 * std::f64::consts::PI);
    assert_eq!(format!("{:.5} {:.5}", p[0], p[1]), "1.00000 9.42478");
}

/// #500–#999 are kept in the machine (fanuc.md §4.1): a robot cell or an
/// operator sets them, so an alarm reached only because one read as vacant is
/// information that names the variable, not a certain error.
#[test]
fn alarm_behind_a_machine_variable_is_not_certain() {
    let text = "%\nO2\nIF[#890 NE 1] GOTO2\nM30\nN2 #3000=15 (NOT BY ROBOT)\n%\n";
    let out = run_fanuc(text, "");
    let alarms: Vec<_> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "X004")
        .map(|d| (d.severity, d.message.as_str()))
        .collect();
    assert_eq!(
        alarms,
        vec![(
            analyzer::Severity::Info,
            "macro alarm #3000 = 15 may not fire on the machine: the branch on line 3 read #890, a common variable kept in the machine (#500–#999), whose value this dry run does not know (read as vacant); give it in a variable file (--var-file) to decide (the dry run stops here)"
        )]
    );
    // Given by the variable file, the value is known: #890 = 1 skips the alarm,
    // #890 = 2 makes it certain.
    let with_var = |v: &str| {
        run_full(
            analyzer::Dialect::Fanuc,
            text,
            "",
            &[],
            None,
            Some(&format!("890 {v}\n")),
        )
    };
    assert!(
        codes(&with_var("1")).is_empty(),
        "{:?}",
        with_var("1").diagnostics
    );
    let certain = with_var("2");
    assert_eq!(
        certain
            .diagnostics
            .iter()
            .map(|d| (d.code, d.severity))
            .collect::<Vec<_>>(),
        vec![("X004", analyzer::Severity::Error)]
    );
    // Set by the program itself, it is known too.
    let set = run_fanuc("#890 = 0;\nIF[#890 NE 1] GOTO2;\nM30;\nN2 #3000=15;\n", "");
    assert_eq!(set.diagnostics[0].severity, analyzer::Severity::Error);
    // #100–#199 are cleared at power-off: vacant is what the program starts with.
    let common = run_fanuc("IF[#100 NE 1] GOTO2;\nM30;\nN2 #3000=15;\n", "");
    assert_eq!(common.diagnostics[0].severity, analyzer::Severity::Error);
}

/// A handshake loop on a machine variable is waiting, not running away.
#[test]
fn wait_loop_on_a_machine_variable() {
    let out = run_fanuc("N1 IF[#890 EQ 3] GOTO2;\nG04 P1000;\nGOTO1;\nN2 M30;\n", "");
    let f004: Vec<_> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "F004")
        .collect();
    assert_eq!(f004.len(), 1, "{:?}", out.diagnostics);
    assert_eq!(f004[0].severity, analyzer::Severity::Info);
    assert!(
        f004[0]
            .message
            .contains("a loop that waits for #890 (tested on line 1)"),
        "{}",
        f004[0].message
    );
    // A loop that reads nothing from the machine is still a runaway warning.
    let out = run_fanuc("N1 GOTO 1;\nM30;\n", "");
    assert_eq!(out.diagnostics[0].severity, analyzer::Severity::Warning);
}

/// Real shops' macros (corpus classes N3–N6, hold-out fn39/fn51): a machine value
/// the dry run cannot know is neither vacant nor a certain alarm, also after it
/// was copied into a local; M29 without any tap in the file is a builder's M code.
#[test]
fn machine_values_copied_and_used_are_not_certain_faults() {
    let found = |text: &str| -> Vec<(String, u32, analyzer::Severity)> {
        let out = run_fanuc(text, "");
        let idx = analyzer::LineIndex::new(text.as_bytes());
        out.diagnostics
            .iter()
            .map(|d| {
                (
                    d.code.to_string(),
                    idx.line_col(d.span.start).0 + 1,
                    d.severity,
                )
            })
            .collect()
    };
    use analyzer::Severity::Info;
    // A feed from a retained common: no zero-feed alarm, no vacant word, here or
    // on the next feed move; a vacant #100-range common still is both.
    assert_eq!(found("%\nO1\nG91 G01 X5. F#610\nG01 X5.\nM30\n%\n"), vec![]);
    let vacant = found("%\nO1\nG91 G01 X5. F#111\nM30\n%\n");
    let codes: Vec<&str> = vacant.iter().map(|(c, _, _)| c.as_str()).collect();
    assert_eq!(codes, vec!["X005", "F001"]);
    // The skip position after G31, copied into a common, decides a branch: the
    // alarm behind it depends on the machine.
    let skip = "%\nO4\nG90 G0 X0 Y0\nG31 X30. F200.\n#110 = #5061\nIF [#110 EQ 30.] GOTO 10\n#3000 = 1 (NO TOUCH)\nN10 M30\n%\n";
    assert_eq!(found(skip), vec![("X004".to_string(), 7, Info)]);
    // A local set from a retained common is assigned, not read before it is.
    assert_eq!(
        found("%\nO5\n#24 = #516\nG91 G01 X[#24] F100.\nM30\n%\n"),
        vec![]
    );
    // M29 in a file without G84/G74 is not rigid tapping (parameter 5210's default
    // code is a conveyor on some machines).
    assert_eq!(
        found("%\nO6\nM29 (CONVEYOR)\nG91 G01 X5. F300.\nM30\n%\n"),
        vec![]
    );
}

/// Variable numbers of control options beyond the modelled table (#100000…) are the
/// machine's: one note, no out-of-range errors (corpus class N12).
#[test]
fn extended_variable_ranges_are_the_machines() {
    let out = run_fanuc(
        "%\nO2011\n#100000 = 1068\n#1 = #100010\n#2 = #100000\nM30\n%\n",
        "",
    );
    let found: Vec<_> = out
        .diagnostics
        .iter()
        .map(|d| (d.code, d.severity))
        .collect();
    assert_eq!(found, vec![("X001", analyzer::Severity::Info)]);
}
