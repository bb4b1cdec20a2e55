//! The spec-ledger rules (their checks in `runtime/src/rules/`): exact line, code
//! and severity on programs taken from the digests' test vectors.

mod common;

use analyzer::{Dialect, Severity};
use common::*;

/// (code, 1-based line, severity) of every diagnostic whose code is in `only`.
fn found(
    out: &runtime::RunOutput,
    text: &str,
    only: &[&str],
) -> Vec<(&'static str, usize, Severity)> {
    out.diagnostics
        .iter()
        .filter(|d| only.contains(&d.code))
        .map(|d| {
            let line = text[..d.span.start as usize].matches('\n').count() + 1;
            (d.code, line, d.severity)
        })
        .collect()
}

#[test]
fn involute_seed_example_is_clean_and_off_involute_end_is_flagged() {
    // fanuc.md §8.6: end point 0.0021 mm off the start involute, within the 0.01 mm default.
    let ok = "G00 X-1. Y0\nG02.2 X1. Y9.425 I1. J0 R1. F100\nM30\n";
    assert_eq!(found(&run_fanuc(ok, ""), ok, &["A012"]), vec![]);
    // A tighter parameter 5610 turns the same block into PS0243.
    let out = run_fanuc(ok, "involute_tolerance = 0.001");
    assert_eq!(
        found(&out, ok, &["A012"]),
        vec![("A012", 2, Severity::Error)]
    );
    // Start inside the base circle (radius 2 around (0.5, 0)).
    let inside = "G00 X0 Y0\nG03.2 X5. Y5. I0.5 J0 R2. F100\nM30\n";
    assert_eq!(
        found(&run_fanuc(inside, ""), inside, &["A012"]),
        vec![("A012", 2, Severity::Error)]
    );
    // G40 inside involute mode.
    let g40 = "G00 X-1. Y0\nG02.2 X1. Y9.425 I1. J0 R1. F100\nG40 X2.\nM30\n";
    assert_eq!(
        found(&run_fanuc(g40, ""), g40, &["A012"]),
        vec![("A012", 3, Severity::Error)]
    );
}

#[test]
fn servoworks_tlc_type_vectors() {
    // servoworks.md TV-35: G37 without G43 → SW077; with type 2 → SW078.
    let no_g43 = "G37 Z20.\nM02\n";
    assert_eq!(
        found(&run_sw(no_g43, ""), no_g43, &["T005"]),
        vec![("T005", 1, Severity::Error)]
    );
    let typ2 = "G43 A H2\nG37 Z20.\nM02\n";
    assert_eq!(
        found(&run_sw(typ2, "tlc_type = 2"), typ2, &["T005"]),
        vec![("T005", 2, Severity::Error)]
    );
    // TV-32: type 0, `G43 X5. H3` → SW092; `G43 Z50.5 H3` is fine.
    let t0 = "G43 Z50.5 H3\nG49\nG43 X5. H3\nM02\n";
    assert_eq!(
        found(&run_sw(t0, ""), t0, &["T005"]),
        vec![("T005", 3, Severity::Error)]
    );
    // TV-33: type 1, `G17 G43 Y0 H1` → SW093 (G18 Y is fine).
    let t1 = "G18 G43 Y0 H1\nG17 G43 Y0 H1\nM02\n";
    assert_eq!(
        found(&run_sw(t1, "tlc_type = 1"), t1, &["T005"]),
        vec![("T005", 2, Severity::Error)]
    );
    // TV-34: type 2, G49 without H0 → SW094.
    let t2 = "G43 A0 H2\nG49\nG43 A0 H2\nG49 H0\nM02\n";
    assert_eq!(
        found(&run_sw(t2, "tlc_type = 2"), t2, &["T005"]),
        vec![("T005", 2, Severity::Error)]
    );
}

#[test]
fn servoworks_smoothing_time_by_servo_rate() {
    // servoworks.md TV-30: R1000 is fine at 1 kHz; R3000 at 2 kHz → SW064.
    let text = "G04\nG10 L108 P1 R1000\nG04\nG10 L108 P1 R3000\nM02\n";
    assert_eq!(found(&run_sw(text, ""), text, &["D003"]), vec![]);
    assert_eq!(
        found(&run_sw(text, "servo_rate_khz = 2"), text, &["D003"]),
        vec![("D003", 4, Severity::Error)]
    );
}

#[test]
fn fanuc_thread_lead_and_speed() {
    // fanuc.md: `G33 Z10. F60000` (no decimal point = 600 mm) → FAN055;
    // Fmax 10000 mm/min, lead 1.5 → S ≤ 6666.7, so S7000 → FAN056.
    let lead = "S500 M03\nG33 Z10. F60000\nM30\n";
    assert_eq!(
        found(&run_fanuc(lead, ""), lead, &["F018"]),
        vec![("F018", 2, Severity::Error)]
    );
    let speed = "S7000 M03\nG33 Z10. F1.5\nS6600\nG33 Z20. F1.5\nM30\n";
    assert_eq!(
        found(
            &run_fanuc(speed, "max_cutting_feed = 10000.0"),
            speed,
            &["F018"]
        ),
        vec![("F018", 2, Severity::Warning)]
    );
}

#[test]
fn rs274_unused_words_match_the_reference_interpreter() {
    // Each line is refused by LinuxCNC 2.9's rs274 with "<letter> word with no … to use it".
    for (text, line) in [
        ("G0 X1 D2\nM2\n", 1),
        ("G1 X1 F10 H2\nM2\n", 1),
        ("G0 X1 P2\nM2\n", 1),
        ("G0 X1 Q2\nM2\n", 1),
        ("G0 X1 R2\nM2\n", 1),
        ("G1 X1 F10 I2\nM2\n", 1),
        ("G0 X1 L2\nM2\n", 1),
        ("G0 $1 X1\nM2\n", 1),
        ("M3 $1 S100\nM2\n", 1),
    ] {
        let out = run_ngc(text);
        assert_eq!(
            found(&out, text, &["X008"]),
            vec![("X008", line, Severity::Error)],
            "{text}"
        );
    }
    // rs274: "Unknown m code used: M101", "missing M70/M73?", "Cannot use G5.3 without G5.2 first",
    // "G71.0 can only be used in XZ plane (G18)".
    for (text, code) in [
        ("M101\nM2\n", "X009"),
        ("M72\nM2\n", "F013"),
        ("G5.3\nM2\n", "A010"),
        ("G71 X1 Z1 D1 Q1\nM2\n", "C007"),
    ] {
        let out = run_ngc(text);
        assert_eq!(
            found(&out, text, &[code]),
            vec![(code, 1, Severity::Error)],
            "{text}"
        );
    }
}

#[test]
fn file_lints() {
    let tools = "T1 P1 D0.125 Z+0.511 ;ok\nT2 P1 D0.25\nT3 D0.5\n";
    let out = run_with(Dialect::Rs274ngc, "M2\n", "", &[], Some(tools));
    let got: Vec<(Severity, &str)> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "T008")
        .map(|d| (d.severity, d.message.as_str()))
        .collect();
    assert_eq!(
        got,
        vec![
            (Severity::Warning, "tool table line 2: pocket P1 is already used on line 1: the last line wins"),
            (Severity::Error, "tool table line 3: a tool line needs both T (tool number) and P (pocket): `T3 D0.5`"),
        ]
    );
    let out = run_full(
        Dialect::Rs274ngc,
        "M2\n",
        "",
        &[],
        None,
        Some("5220 1.0\n5221 x\n5210 0\n"),
    );
    let msgs: Vec<&str> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "X011")
        .map(|d| d.message.as_str())
        .collect();
    assert_eq!(
        msgs,
        vec![
            "parameter file line 2: `5221 x` is not `number value`: LinuxCNC cannot read the parameter file",
            "parameter file line 3: parameter 5210 is out of order (after 5220): LinuxCNC requires increasing numbers",
        ]
    );
}

/// F014 in a subprogram: the first call moves the tool, the second call's
/// rapid goes nowhere. A block that moves on some pass is not flagged; a block
/// that never moves is flagged once.
#[test]
fn rapid_no_motion_in_a_subprogram_is_judged_over_every_pass() {
    let sub = "o100 sub\nG0 X[#1] Y[#2]\nG0 Z5\no100 endsub\n";
    let out = run_ngc(&format!(
        "{sub}G0 X0 Y0 Z10\no100 call [10] [20]\no100 call [10] [20]\nM2\n"
    ));
    assert_eq!(codes(&out), Vec::<&str>::new());
    // Called only at the position it goes to: `G0 Z5` never moves, one note. The
    // first motion, `G0 X[#1] Y[#2]`, positions the tool for each call and is not
    // flagged although this caller is already there.
    let out = run_ngc(&format!(
        "{sub}G0 X10 Y20 Z5\no100 call [10] [20]\no100 call [10] [20]\nM2\n"
    ));
    let notes: Vec<u32> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "F014")
        .map(|d| d.span.start)
        .collect();
    assert_eq!(notes, vec![24], "{:?}", out.diagnostics);
}

/// A subprogram whose first rapid goes where the caller already stands, called
/// once: that rapid positions every call, and only a later useless rapid is noted.
#[test]
fn rapid_no_motion_spares_a_subprograms_positioning_move() {
    let sub = "o100 sub\nG0 X10 Y20\nG1 Z-1 F100\nG0 Z5\nG0 Z5\no100 endsub\n";
    let out = run_ngc(&format!("{sub}G0 X10 Y20 Z5\no100 call\nM2\n"));
    let notes: Vec<u32> = out
        .diagnostics
        .iter()
        .filter(|d| d.code == "F014")
        .map(|d| d.span.start)
        .collect();
    // Only the second `G0 Z5` (offset 38) does nothing.
    assert_eq!(notes, vec![38], "{:?}", out.diagnostics);
}

/// LinuxCNC reads an I word with the G71/G72 lathe cycles (rs274 checks
/// "I word with no …" against them too), so it is not an unused word there.
#[test]
fn i_word_is_used_by_lathe_roughing_cycles() {
    for g in ["G71", "G71.1", "G72", "G72.2"] {
        let out = run_ngc(&format!(
            "G18 G7 G21 G90\nG0 X30 Z5\n{g} Q100 X30 Z5 D0.5 I0.2 R0.3 F100\nM2\no100 sub\nG1 X10 Z0\no100 endsub\n"
        ));
        assert!(!codes(&out).contains(&"X008"), "{g}: {:?}", out.diagnostics);
    }
    let out = run_ngc("G21 G90\nG1 X1 I0.2 F100\nM2\n");
    assert!(codes(&out).contains(&"X008"), "{:?}", out.diagnostics);
}

#[test]
fn servoworks_arc_mismatch_below_the_machine_unit_is_not_reported() {
    // CAM output rounded to 0.001 mm: r1 = 12.346, r2 = 12.34545, 0.0006 mm apart, under the
    // machine-unit bound √2 · 0.001 of §6.3.3, so the control runs the arc as written.
    let cam = "G90 G17 G21\nG00 X12.346 Y0.\nG03 X8.729 Y8.73 I-12.346 J0. F1500.\nM30\n";
    let out = run_sw(cam, "circle_error_allowance = 0.01");
    assert_eq!(found(&out, cam, &["A003", "A004"]), vec![]);
    // r2 = 12.34255: 0.0035 mm off, beyond the machine unit and within the allowance (SW039).
    let off = "G90 G17 G21\nG00 X12.346 Y0.\nG03 X8.725 Y8.73 I-12.346 J0. F1500.\nM30\n";
    let out = run_sw(off, "circle_error_allowance = 0.01");
    assert_eq!(
        found(&out, off, &["A003", "A004"]),
        vec![("A004", 3, Severity::Warning)]
    );
}

#[test]
fn fanuc_move_between_m29_and_the_tap_is_ps0203() {
    // fanuc.md §8.3 negative test: `M29 S1000; G00 X10.; G84 …` → FAN100 (PS0203).
    let bad = "G21 G90\nM03 S500\nM29 S500\nG00 X20. Y20.\nG84 Z-15. R5. F625.\nG80\nM30\n";
    assert_eq!(
        found(&run_fanuc(bad, ""), bad, &["C004"]),
        vec![("C004", 4, Severity::Error)]
    );
    // Positioned before M29, the tap right after it, further holes in the cycle: no alarm.
    let ok = "G21 G90\nG00 X20. Y20.\nM03 S500\nM29 S500\nG84 Z-15. R5. F625.\nX40.\nG80\nM30\n";
    assert_eq!(found(&run_fanuc(ok, ""), ok, &["C004"]), vec![]);
}

/// LinuxCNC's G43 without H takes the tool in the spindle (spec/rs274ngc.md 3.12):
/// after `T1 M6` that is tool 1; before any M6 it is tool 0, whose offset is zero.
#[test]
fn g43_without_h_before_any_tool_change_has_no_offset() {
    let tools = "T1 P1 Z+25.0 D6.0\n";
    let t003 = |text: &str| -> Vec<(String, u32)> {
        run_with(Dialect::Rs274ngc, text, "", &[], Some(tools))
            .diagnostics
            .iter()
            .filter(|d| d.code == "T003")
            .map(|d| (d.message.clone(), d.span.start))
            .collect()
    };
    // Invalid: no tool loaded yet, the offset is zero.
    let got = t003("G21 G90\nG0 X0 Y0\nG43 Z10\nG0 Z5\nM2\n");
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].1, 17, "at the G43 word");
    assert!(got[0].0.starts_with(
        "G43 without H applies the length of the tool in the spindle, and none is loaded (tool 0)"
    ));
    // Valid: after a tool change G43 without H applies that tool's offset.
    assert_eq!(
        t003("G21 G90\nT1 M6\nG0 X0 Y0\nG43 Z10\nG0 Z5\nM2\n"),
        vec![]
    );
    // Valid: M6 on the G43 line runs first (order of execution).
    assert_eq!(
        t003("G21 G90\nG0 X0 Y0\nT1 M6 G43 Z10\nG0 Z5\nM2\n"),
        vec![]
    );
    // Valid: the H says which offset.
    let with_h = t003("G21 G90\nT1 M6\nG0 X0 Y0\nG43 H1 Z10\nG0 Z5\nM2\n");
    assert_eq!(with_h, vec![]);
}

#[test]
fn fanuc_vacant_local_copy_and_called_macro_checked_alone() {
    // A plain copy passes the vacancy on (`#10 = #1` leaves #10 vacant): no finding.
    // Arithmetic on a vacant local at level 0 of a main program is a warning.
    let main = "%\nO1000\n#10 = #1\n#11 = [#2]\n#12 = #3 + 1.\nM30\n%\n";
    assert_eq!(
        found(&run_fanuc(main, ""), main, &["X010"]),
        vec![("X010", 5, Severity::Warning)]
    );
    // A program that returns with M99 somewhere is a macro checked without its
    // caller: its locals may be arguments, so the same read is information.
    let called = "%\nO9390\n#26 = #5003 + #26\nIF [#26 GT 0] GOTO 8\nM30\nN8 M99\n%\n";
    assert_eq!(
        found(&run_fanuc(called, ""), called, &["X010"]),
        vec![("X010", 3, Severity::Info)]
    );
}

#[test]
fn ngc_feed_after_a_call_the_run_cannot_follow_is_unknown() {
    // The subroutine is not here (no search path configured): it may set F, so the
    // G1 after it is no zero-feed error; a G1 before any call still is.
    let text = "G21 G90\nF0\no<engrave_plunge> call [10] [30] [-5]\nG1 X10 Y30 Z-5\nM2\n";
    assert_eq!(found(&run_ngc(text), text, &["F001"]), vec![]);
    let plain = "G21 G90\nF0\nG1 X10 Y30 Z-5\nM2\n";
    assert_eq!(
        found(&run_ngc(plain), plain, &["F001"]),
        vec![("F001", 3, Severity::Error)]
    );
}
