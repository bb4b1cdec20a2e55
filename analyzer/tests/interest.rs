//! Rule interests: the dispatcher calls a block rule only on blocks whose contents
//! match the rule's declared [`Interest`], so a rule must report nothing on any
//! block outside it, in every dialect, variant and machine set-up. Random blocks
//! of every kind (codes, words, expressions, comments, statements) test the claims.

use analyzer::dialect::{Dialect, Variant};
use analyzer::rules::context::block_words;
use analyzer::rules::registry::STATIC_RULES;
use analyzer::rules::{BlockCx, BlockWords};
use analyzer::syntax::{parse, ParseOptions};
use analyzer::Settings;

/// A small deterministic generator so the test input never changes.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 33) % n as u64) as usize
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

/// G and M codes that rules look for, in both spellings.
const CODES: &[&str] = &[
    "G0", "G1", "G01", "G2", "G3", "G4", "G04", "G10", "G17", "G20", "G21", "G28", "G30", "G33",
    "G38.2", "G40", "G41", "G43", "G43.1", "G49", "G50.1", "G52", "G53", "G54", "G54.1", "G65",
    "G66", "G68", "G73", "G76", "G80", "G81", "G83", "G90", "G91", "G92", "G93", "G98", "M0", "M3",
    "M5", "M6", "M7", "M8", "M30", "M61", "M66", "M98", "M99", "G5", "G7", "G1.5", "G-1", "M100",
];

/// Non-literal items: expressions, comments, comma words, statements.
const OTHERS: &[&str] = &[
    "X#1",
    "#1=2",
    "#1 = [#2 + 1]",
    "Z[1 + 2]",
    "(cut)",
    "(MSG, hi)",
    ";tail",
    ",C1",
    ",R2",
    "IF [#1 GT 1] GOTO 10",
    "WHILE [#1 LT 3] DO1",
    "END1",
    "o100 call [1]",
    "O1000",
    "P#5",
    "Xsin[30]",
];

/// Blocks of one to six items: mostly literal words of any letter, some codes and
/// some non-literal items, and now and then a block-skip mark.
fn blocks(rng: &mut Lcg, n: usize) -> String {
    let letters = b"ABCDEFGHIJKLMNPQRSTUVWXYZxyzfr@^$";
    let mut s = String::new();
    for _ in 0..n {
        if rng.next(20) == 0 {
            s.push('/');
        }
        for w in 0..1 + rng.next(6) {
            if w > 0 && rng.next(3) != 0 {
                s.push(' ');
            }
            match rng.next(10) {
                0..=1 => s.push_str(CODES[rng.next(CODES.len())]),
                2 => s.push_str(OTHERS[rng.next(OTHERS.len())]),
                _ => {
                    s.push(letters[rng.next(letters.len())] as char);
                    s.push_str(VALUES[rng.next(VALUES.len())]);
                }
            }
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
fn rules_report_nothing_outside_their_interest() {
    let variants = [
        (Dialect::Rs274ngc, Variant::Linuxcnc),
        (Dialect::Rs274ngc, Variant::Emc2),
        (Dialect::Servoworks, Variant::S100M),
        (Dialect::Servoworks, Variant::S140M),
        (Dialect::Fanuc, Dialect::Fanuc.default_variant()),
    ];
    let mut rng = Lcg(7);
    let (mut skipped, mut calls) = (0usize, 0usize);
    for (dialect, variant) in variants {
        // A modal arc, a cycle and a lathe cycle before the blocks: the rules see
        // single blocks, but some look at the whole program.
        let mut text = String::from("G17 G2 X1 Y1 R5\nG81 Z-1 R1\nG4 P1\n");
        text.push_str(&blocks(&mut rng, 4000));
        let program = parse(ParseOptions::new(dialect), text.into_bytes());
        for imu in [false, true] {
            for axes in [
                &['X', 'Y', 'Z'][..],
                &['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W', 'E'],
            ] {
                let settings = settings(dialect, variant, imu, axes);
                let interests: Vec<_> = STATIC_RULES
                    .iter()
                    .map(|r| (*r, r.interest(&settings)))
                    .collect();
                let mut codes = Vec::new();
                for i in 0..program.blocks.len() {
                    let cx = BlockCx::new(&program, i, &settings, &mut codes).unwrap();
                    for (rule, interest) in &interests {
                        calls += 1;
                        if interest.matches(&cx.contents) {
                            continue;
                        }
                        skipped += 1;
                        let mut out = Vec::new();
                        rule.check_block(&cx, &mut out);
                        assert!(
                            out.is_empty(),
                            "{} reported {:?} outside its interest on {:?} ({dialect:?}, {variant:?}, axes {axes:?})",
                            rule.meta().code,
                            out,
                            program.str_of(cx.block.span)
                        );
                    }
                }
            }
        }
    }
    // The claims must skip most calls, or they are not worth making.
    assert!(skipped * 2 > calls, "{skipped} skipped of {calls}");
}

/// What one pass over a block records.
#[test]
fn block_contents() {
    let bit = |l: u8| 1u128 << l;
    let cases: &[(&str, u128, u128, u128, u16, bool)] = &[
        (
            "X1 Y-2 Z3",
            bit(b'X') | bit(b'Y') | bit(b'Z'),
            0,
            bit(b'Y'),
            1,
            false,
        ),
        (
            "G1 X1.25 X2 G2",
            bit(b'G') | bit(b'X'),
            bit(b'G') | bit(b'X'),
            0,
            3,
            false,
        ),
        ("X#1", bit(b'X'), 0, 0, 0, true),
        ("X1 (comment)", bit(b'X'), 0, 0, 1, true),
        ("/X1", bit(b'X'), 0, 0, 1, true),
        ("", 0, 0, 0, 0, true),
    ];
    for &(text, letters, repeated, negative, max_digits, other) in cases {
        let program = parse(
            ParseOptions::new(Dialect::Rs274ngc),
            format!("{text}\n").into_bytes(),
        );
        let want = BlockWords {
            letters,
            repeated,
            negative,
            max_digits,
            other,
        };
        assert_eq!(block_words(&program, &program.blocks[0]), want, "{text}");
    }
}
