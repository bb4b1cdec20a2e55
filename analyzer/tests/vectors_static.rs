//! Lexical and static test vectors of the three digests (`shared/spec/*.md`):
//! each test names its vector and asserts the exact diagnostics (line, code,
//! severity) that `analyze()` reports. Runtime effects of the same vectors are
//! in `runtime/tests/vectors_*.rs`; `tests/VECTORS.md` maps every id to its test.

use analyzer::{analyze, Dialect, LineIndex, Settings, Variant};

/// `(line, code, severity)` of every static diagnostic, 1-based lines.
fn diags_v(
    dialect: Dialect,
    variant: Option<Variant>,
    text: &str,
) -> Vec<(u32, &'static str, &'static str)> {
    let mut settings = Settings::new(dialect);
    if let Some(v) = variant {
        settings.variant = v;
    }
    let a = analyze(text.as_bytes().to_vec(), &settings);
    let index = LineIndex::new(text.as_bytes());
    a.diagnostics
        .iter()
        .map(|d| {
            (
                index.line_col(d.span.start).0 + 1,
                d.code,
                d.severity.as_str(),
            )
        })
        .collect()
}

fn sw(text: &str) -> Vec<(u32, &'static str, &'static str)> {
    diags_v(Dialect::Servoworks, None, text)
}

fn ngc(text: &str) -> Vec<(u32, &'static str, &'static str)> {
    diags_v(Dialect::Rs274ngc, None, text)
}

fn emc2(text: &str) -> Vec<(u32, &'static str, &'static str)> {
    diags_v(Dialect::Rs274ngc, Some(Variant::Emc2), text)
}

// ---------------------------------------------------------------- ServoWorks §11

#[test]
fn tv06_percent_in_column_one_deletes_the_line_elsewhere_sw003() {
    let text = "% This is a line of block delete code\nG01 X5 % Y7 F100\nM30\n";
    assert_eq!(sw(text), vec![(2, "L011", "warning")]);
}

#[test]
fn tv07_comment_with_lower_case_is_not_sw004() {
    assert_eq!(sw("N01 G00 X0 Z0 (This is a comment)\nM30\n"), vec![]);
}

#[test]
fn tv08_slash_only_in_column_one_sw002() {
    assert_eq!(
        sw("/G01 X10. F100\nG01 /X10.\nM30\n"),
        vec![(2, "L007", "error")]
    );
}

/// The digest reports the lower-case `x` (SW004) and the orphan `10.` (SW008)
/// separately; the analyser reports the whole `x10.` word once as L008, which
/// tells the same thing (the word is not executed).
#[test]
fn tv09_lower_case_letter_is_ignored_sw004() {
    assert_eq!(sw("G01 x10. Y5. F100\nM30\n"), vec![(1, "L008", "warning")]);
}

#[test]
fn tv10_line_length_limit_85_sw001() {
    // `G01 X1. F100 ` is 13 characters; the comment fills the rest.
    let line = |n: usize| format!("G01 X1. F100 ({})", "a".repeat(n - 15));
    assert_eq!(line(85).len(), 85);
    assert_eq!(sw(&format!("{}\nM30\n", line(85))), vec![]);
    assert_eq!(
        sw(&format!("{}\nM30\n", line(86))),
        vec![(1, "W011", "error")]
    );
}

#[test]
fn tv12_g3_without_leading_zero_is_clean() {
    assert_eq!(sw("X10 Y10\nG17 G3 Y30 I5 J10 F100\nM30\n"), vec![]);
    // The manual's literal form ends with `%` and no M02/M30 (SW019).
    assert_eq!(
        sw("X10 Y10\nG17 G3 Y30 I5 J10 F100\n%\n"),
        vec![(2, "P005", "warning")]
    );
}

#[test]
fn tv14_m98_words_and_repeat_count_sw024_sw022() {
    assert_eq!(
        sw("M98 P100 X10.\nM98 P100 R1000000\nM30\n"),
        vec![(1, "W010", "warning"), (2, "W007", "error")]
    );
}

#[test]
fn tv15_g65_must_come_first_sw029() {
    assert_eq!(
        sw("Z20.0 G65 P100\nM30\nO100\nG00 X1\nM99\n"),
        vec![(1, "W012", "error")]
    );
    assert_eq!(
        sw("G65 P100 Z20.0 R2.5 F500\nM30\nO100\nG00 X1\nM99\n"),
        vec![]
    );
}

#[test]
fn tv21_arc_word_errors_sw031_sw032_sw033() {
    assert_eq!(
        sw("G18 G02 X30.5 Z-5.0 R10.5 I1. F10\nM30\n"),
        vec![(1, "W002", "error")]
    );
    assert_eq!(sw("G02 X10. F10\nM30\n"), vec![(1, "W003", "error")]);
    // SW033 (K in G17) needs the plane in force: runtime/tests/vectors_servoworks.rs.
}

#[test]
fn tv26_exponential_interpolation_angles_sw045_sw044() {
    let s120 = |t: &str| diags_v(Dialect::Servoworks, Some(Variant::S120M), t);
    assert_eq!(
        s120("G02.3 X10. I0 J30. R1. F20 Q10\nM30\n"),
        vec![(1, "W007", "error")]
    );
    assert_eq!(
        s120("G02.3 X10. I95. J30. R1. F20 Q10\nM30\n"),
        vec![(1, "W007", "error")]
    );
}

#[test]
fn tv29_g10_axis_type_sw062() {
    let text =
        "G10 L20 P2 R10\nG10 L20 X2 Y10\nG10 L20 P2 R5\nG10 L30 P2 R0.1\nG10 L30 X0.2 Y0.1\nM30\n";
    assert_eq!(sw(text), vec![(3, "W007", "error")]);
}

#[test]
fn tv50_g54_1_range_and_g54_words_sw110_sw109() {
    assert_eq!(
        sw("G54.1 P18\nG54.1 P59\nG54 X10.\nM30\n"),
        vec![(2, "W007", "error"), (3, "W009", "warning")]
    );
}

/// TV-51's word errors: P with I/J/K (SW100), no factor at all (SW101), a factor
/// out of 0.001–999.999 (SW102).
#[test]
fn tv51_scaling_word_errors_sw100_sw101_sw102() {
    assert_eq!(
        sw("G51 P2. I2.\nG50\nG51 X0 Y0\nG50\nG51 P1000.\nG50\nM30\n"),
        vec![
            (1, "W002", "error"),
            (3, "W003", "error"),
            (5, "W007", "error")
        ]
    );
}

#[test]
fn tv63_group01_code_in_cycle_block_sw116() {
    let text = "G90 G0 Z50\nM3 S100\nG81 G01 X10. Y10. Z-5. R1. F100\nG80\nM30\n";
    assert_eq!(sw(text), vec![(3, "G001", "warning")]);
}

#[test]
fn tv64_negative_q_and_g88_sw122_sw133() {
    let text = "G90 G0 Z50\nM3 S100\nG73 X1 Y1 Z-5. R1. Q10 F100\nG73 X2 Y2 Q-5\nG80\nG88 X0 Y0 Z-5 R1\nG80\nM30\n";
    assert_eq!(
        sw(text),
        vec![(4, "W007", "warning"), (6, "G004", "warning")]
    );
}

/// SW137 (integer of at most five digits) and SW012 (decimal point) are one
/// finding here: W006 on the `S1500.5` word.
#[test]
fn tv65_spindle_words_sw136_sw137() {
    assert_eq!(
        sw("S2000\nS2_1500\nS17_100\nS1500.5\nM30\n"),
        vec![(3, "W007", "error"), (4, "W006", "warning")]
    );
}

#[test]
fn tv66_tool_number_range_sw140() {
    assert_eq!(sw("T300\nM30\n"), vec![(1, "W007", "error")]);
}

#[test]
fn tv67_direct_digital_output_range_sw141() {
    let text = "G01 X100.0 F1000.0 L500\nG10 L20 P2 R10\nL70000\nM30\n";
    assert_eq!(sw(text), vec![(3, "W007", "error")]);
}

// ---------------------------------------------------------------- RS274/NGC §10

#[test]
fn tv_l1_blanks_inside_numbers_are_clean() {
    assert_eq!(ngc("g0x +0. 12 34y 7\nM2\n"), vec![]);
}

#[test]
fn tv_l2_six_digit_line_number_ngc009() {
    assert_eq!(emc2("N000009 G0 X1\nM2\n"), vec![(1, "P007", "warning")]);
}

#[test]
fn tv_l3_g_code_decimals() {
    assert_eq!(ngc("G1.0001 X1 F1\nM2\n"), vec![]);
    assert_eq!(ngc("G1.05 X1 F1\nM2\n"), vec![(1, "G004", "error")]);
}

#[test]
fn tv_l4_m_code_integer_tolerance() {
    assert_eq!(ngc("M3.00005 S1\nM2\n"), vec![]);
    assert_eq!(ngc("M3.001 S1\nM2\n"), vec![(1, "W006", "error")]);
}

#[test]
fn tv_l5_l6_only_the_last_comment_counts_ngc023() {
    assert_eq!(ngc("G0 X1 (first) (MSG,second)\nM2\n"), vec![]);
    assert_eq!(ngc("(MSG,first) (second)\nM2\n"), vec![(1, "W019", "info")]);
}

#[test]
fn tv_l7_unclosed_and_nested_comments() {
    assert_eq!(ngc("G1 X1 F1 (open\nM2\n"), vec![(1, "L001", "error")]);
    assert_eq!(ngc("G1 (a (b) c) X1 F1\nM2\n"), vec![(1, "L002", "error")]);
}

#[test]
fn tv_l8_call_arguments_need_brackets_ngc612() {
    let sub = "o100 sub\no100 endsub\n";
    assert_eq!(
        ngc(&format!("{sub}o100 call 1 2 3\nM2\n")),
        vec![(3, "L010", "error")]
    );
    assert_eq!(ngc(&format!("{sub}o100 call [1] [2] [3]\nM2\n")), vec![]);
}

#[test]
fn tv_l13_comments_between_words_but_not_inside() {
    assert_eq!(ngc("S100(set speed)F200(feed)\nM2\n"), vec![]);
    assert_eq!(
        ngc("S(speed)100\nM2\n"),
        vec![(1, "L003", "error"), (1, "L005", "error")]
    );
}

#[test]
fn tv_a12_mixed_radius_and_ijk() {
    assert_eq!(ngc("G2 X1 Y1 R1 I1 F1\nM2\n"), vec![(1, "W002", "error")]);
}

#[test]
fn tv_m1_two_group1_codes_ngc100() {
    assert_eq!(ngc("G0 G1 X1 F1\nM2\n"), vec![(1, "G001", "error")]);
}

/// NGC113 is reported on the G80; beside a plain motion code dropping it
/// changes nothing (the motion code ends the cycle too), so it is information
/// (`G0 G80` is how CAM posts write it); beside a cycle code the block drills
/// instead of cancelling, which is the warning the digest asks for.
#[test]
fn tv_m2_g80_with_g1_is_dropped_ngc113() {
    assert_eq!(ngc("G1 G80 X1 F1\nM2\n"), vec![(1, "G001", "info")]);
    assert_eq!(
        ngc("G0 Z5\nG80 G81 X1 Y1 Z-1 R1 F1\nG80\nM2\n"),
        vec![(2, "G001", "warning")]
    );
}

#[test]
fn tv_m3_axis_words_with_g80_ngc108() {
    assert_eq!(ngc("G80 X1\nM2\n"), vec![(1, "W004", "error")]);
}

#[test]
fn tv_m4_two_axis_users_ngc106() {
    assert_eq!(ngc("G1 X1 F1 G92 Y2\nM2\n"), vec![(1, "W004", "error")]);
}

#[test]
fn tv_m6_five_m_words_ngc101() {
    assert_eq!(
        ngc("M3 M8 M48 M62 P1 M0 S1\nM2\n"),
        vec![(1, "G003", "error")]
    );
}

#[test]
fn tv_m7_same_m_group_ngc102() {
    assert_eq!(ngc("M7 M8\nM2\n"), vec![(1, "G002", "error")]);
}

#[test]
fn tv_m8_repeated_axis_word_ngc103() {
    assert_eq!(ngc("G1 X1 X2 F1\nM2\n"), vec![(1, "W001", "error")]);
}

#[test]
fn tv_m9_words_after_an_o_statement_ngc111() {
    let d = ngc("o100 if [#1 GT 0] G1 X1\no100 endif\nM2\n");
    assert_eq!(d.first(), Some(&(1, "L005", "error")));
    assert!(d.iter().all(|x| x.0 == 1 && x.2 == "error"), "{d:?}");
}

#[test]
fn tv_m11_bare_motion_code_ngc109() {
    assert_eq!(ngc("G0\nM2\n"), vec![]);
    assert_eq!(emc2("G0\nM2\n"), vec![(1, "W003", "error")]);
}

#[test]
fn tv_o5_endwhile_label_mismatch_ngc602() {
    assert_eq!(
        ngc("o101 while [#1 LT 3]\n#1=[#1+1]\no102 endwhile\nM2\n"),
        vec![(3, "P001", "error")]
    );
}

#[test]
fn tv_o6_nested_sub_definition_ngc604() {
    assert_eq!(
        ngc("o100 sub\no110 sub\no110 endsub\no100 endsub\nM2\n"),
        vec![(2, "P001", "error")]
    );
}

#[test]
fn tv_p15_unary_minus_before_parameter_ngc033() {
    assert_eq!(ngc("#1=2\nG0 X-#1\nM2\n"), vec![]);
    assert_eq!(emc2("#1=2\nG0 X-#1\nM2\n"), vec![(2, "W017", "error")]);
}

/// TV-52's note (SW106, rule W023, off by default): the second `G51` gives I only, so
/// J keeps the 0.5 of the first.
#[test]
fn tv52_partial_scaling_factors_note_sw106() {
    let text = "G51 X0 Y0 I2. J0.5\nG01 X10. Y10. F100\nG50\nG51 X0 Y0 I3.\nG01 X10. Y10.\nM30\n";
    let mut settings = Settings::new(Dialect::Servoworks);
    settings.select = vec!["W023".into()];
    let a = analyze(text.as_bytes().to_vec(), &settings);
    let index = LineIndex::new(text.as_bytes());
    let found: Vec<(u32, &str)> = a
        .diagnostics
        .iter()
        .map(|d| (index.line_col(d.span.start).0 + 1, d.code))
        .collect();
    assert_eq!(found, vec![(1, "W023"), (4, "W023")]);
    assert!(sw(text).is_empty(), "off by default");
}
