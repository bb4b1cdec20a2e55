//! The axis/feed early-out of the block rules: a rule that says it cannot report
//! on an axis/feed block must really report nothing on any such block, in every
//! dialect and variant, so skipping it does not change any result.

use analyzer::dialect::{Dialect, Variant};
use analyzer::rules::context::{collect_codes, is_axis_feed_block};
use analyzer::rules::registry::STATIC_RULES;
use analyzer::rules::BlockCx;
use analyzer::syntax::{parse, ParseOptions};
use analyzer::Settings;

/// A small deterministic generator so the test input never changes.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self, n: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) % n
    }
}

/// Literal values in the forms a CAM post or a hand writes them, with edge cases.
const VALUES: &[&str] = &[
    "0",
    "1",
    "-1",
    "0.",
    "-0",
    "+2",
    ".5",
    "-.5",
    "1.5",
    "-12.3456",
    "100000",
    "99999.999",
    "123456789",
    "1234567890123",
    "0.0001",
    "360",
    "2 5.4",
    "-3 .25",
];

/// Blocks of one to six axis/feed words (repeats and lower case included).
fn blocks(rng: &mut Lcg, n: usize) -> String {
    let letters = b"XYZABCUVWIJKRFxyzijkrf";
    let mut s = String::new();
    for _ in 0..n {
        let words = 1 + rng.next(6);
        for w in 0..words {
            if w > 0 && rng.next(2) == 0 {
                s.push(' ');
            }
            s.push(letters[rng.next(letters.len() as u64) as usize] as char);
            s.push_str(VALUES[rng.next(VALUES.len() as u64) as usize]);
        }
        s.push('\n');
    }
    s
}

fn settings(dialect: Dialect, variant: Variant, imu: bool, axes: &[char]) -> Settings {
    let mut s = Settings::new(dialect);
    s.variant = variant;
    s.integer_machine_unit = imu;
    s.axes = axes.to_vec();
    s
}

#[test]
fn skipped_rules_report_nothing_on_axis_feed_blocks() {
    let variants = [
        (Dialect::Rs274ngc, Variant::Linuxcnc),
        (Dialect::Rs274ngc, Variant::Emc2),
        (Dialect::Servoworks, Variant::S100M),
        (Dialect::Servoworks, Variant::S140M),
        (Dialect::Fanuc, Dialect::Fanuc.default_variant()),
    ];
    let mut rng = Lcg(7);
    let mut checked_blocks = 0;
    for (dialect, variant) in variants {
        // A modal arc and a cycle before the blocks: the rules see single blocks only.
        let mut text = String::from("G17 G2 X1 Y1 R5\nG81 Z-1 R1\nG4 P1\n");
        text.push_str(&blocks(&mut rng, 3000));
        let program = parse(ParseOptions::new(dialect), text.into_bytes());
        for imu in [false, true] {
            for axes in [
                &['X', 'Y', 'Z'][..],
                &['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'],
            ] {
                let settings = settings(dialect, variant, imu, axes);
                for (i, block) in program.blocks.iter().enumerate() {
                    if !is_axis_feed_block(&program, block) {
                        continue;
                    }
                    checked_blocks += 1;
                    let mut codes = Vec::new();
                    collect_codes(&program, block, &mut codes);
                    assert!(codes.is_empty());
                    let cx = BlockCx {
                        program: &program,
                        block,
                        index: i,
                        settings: &settings,
                        codes: &codes,
                    };
                    for rule in STATIC_RULES {
                        if rule.reports_on_axis_feed_blocks() {
                            continue;
                        }
                        let mut out = Vec::new();
                        rule.check_block(&cx, &mut out);
                        assert!(
                            out.is_empty(),
                            "{} reported {:?} on the axis/feed block {:?} ({dialect:?})",
                            rule.meta().code,
                            out,
                            program.str_of(block.span)
                        );
                    }
                }
            }
        }
    }
    // Nearly every generated block qualifies (a lower-case letter in ServoWorks does not).
    assert!(checked_blocks > 40_000, "{checked_blocks}");
}

#[test]
fn axis_feed_block_recognition() {
    let cases: &[(&str, bool)] = &[
        ("X1 Y2 Z3", true),
        ("X1. F200", true),
        ("I1 J-2 R3 K0", true),
        ("G1 X1", false),
        ("X1 M3", false),
        ("X#1", false),
        ("X1 (comment)", false),
        ("X1 S100", false),
        ("N10 X1", false),
        ("/X1", false),
        ("", false),
    ];
    for (text, expected) in cases {
        let program = parse(
            ParseOptions::new(Dialect::Rs274ngc),
            format!("{text}\n").into_bytes(),
        );
        let block = &program.blocks[0];
        assert_eq!(is_axis_feed_block(&program, block), *expected, "{text}");
    }
}
