//! The two-thread parse of large files gives exactly the serial parse: same tokens,
//! blocks (with their line numbers), items, expression ids and diagnostics,
//! whether the guessed state at the split holds or not.

use analyzer::dialect::Dialect;
use analyzer::syntax::{
    parse_in_two, parse_lean, parse_lean_in_two, parse_serial, ParseOptions, Program,
};
use proptest::prelude::*;

fn assert_same(a: &Program, b: &Program, what: &str) {
    assert_eq!(a.tokens, b.tokens, "tokens: {what}");
    assert_eq!(a.blocks, b.blocks, "blocks: {what}");
    // Compared through their debug text: a malformed number's value is NaN, which
    // is never equal to itself.
    assert_eq!(
        format!("{:?}", a.items),
        format!("{:?}", b.items),
        "items: {what}"
    );
    assert_eq!(
        format!("{:?}", a.exprs),
        format!("{:?}", b.exprs),
        "exprs: {what}"
    );
    assert_eq!(a.expr_lists, b.expr_lists, "expr lists: {what}");
    assert_eq!(a.diagnostics, b.diagnostics, "diagnostics: {what}");
}

fn check(dialect: Dialect, text: &str) {
    let opts = ParseOptions::new(dialect);
    let serial = parse_serial(opts, text.as_bytes().to_vec());
    let two = parse_in_two(opts, text.as_bytes().to_vec());
    assert_same(
        &serial,
        &two,
        &format!("{dialect:?}: {:?}", &text[..text.len().min(80)]),
    );
    // The lean two-thread parse gives the lean serial tree (no tokens).
    let lean = parse_lean(opts, text.as_bytes().to_vec());
    let lean_two = parse_lean_in_two(opts, text.as_bytes().to_vec());
    assert!(lean_two.tokens.is_empty());
    assert_same(
        &lean,
        &lean_two,
        &format!("lean, {dialect:?}: {:?}", &text[..text.len().min(80)]),
    );
}

/// Lines with expressions, O-words, macro statements and errors in both halves, so
/// the ids of the second half are rebased.
const BODY: &str = "\
G1 X1.5 Y-2 F200 (cut)
#1 = [#2 + SIN[30] * 2]
o100 if [#1 GT 2]
  G0 X#1 Y[#3 - 1]
o100 endif
o<sub> call [1] [#5 + 2]
IF [#1 EQ 2] GOTO 10
WHILE [#4 LT 3] DO 1
#[#1 + 1] = ATAN[1]/[2]
X1 X2 G2 G3 M3 M4 @1
N10 X-.5 Z 1 2.5 ;tail
/X1 Q[ ( unclosed
\r\n\rX1\r\n";

#[test]
fn two_halves_equal_serial_parse() {
    for dialect in Dialect::ALL {
        let mut text = String::new();
        for i in 0..200 {
            text.push_str(BODY);
            text.push_str(&format!("X{i}.25 Z-{i}\n"));
        }
        check(dialect, &text);
        // Tape marks: at the start (the usual guess), in the middle (a wrong guess),
        // and nowhere.
        check(dialect, &format!("%\n{text}%\n"));
        check(dialect, &format!("%\n{text}%\n{text}"));
        check(dialect, &format!("{text}%\n{text}"));
        check(dialect, &format!("\n\n{text}"));
        // Only blank lines before the split.
        check(dialect, &format!("{}{text}", "\n".repeat(text.len() * 2)));
        // FANUC `;` ends and CRLF everywhere.
        check(dialect, &text.replace('\n', ";\r\n"));
    }
}

/// Texts of 4 MiB and more are parsed leanly with their tree prefaulted on a second
/// thread (`memory::prefault_while`); the tree is the serial parse's all the same.
#[test]
fn large_lean_parse_equals_serial_parse() {
    let mut text = String::new();
    let mut i = 0;
    while text.len() < (4 << 20) + 65536 {
        if i % 97 == 0 {
            text.push_str(BODY);
        }
        text.push_str(&format!("X{}.{} Z-{}\n", i % 1000, i % 7, i % 13));
        i += 1;
    }
    for dialect in Dialect::ALL {
        let opts = ParseOptions::new(dialect);
        let serial = parse_serial(opts, text.as_bytes().to_vec());
        let mut lean = parse_lean(opts, text.as_bytes().to_vec());
        assert!(lean.tokens.is_empty());
        lean.tokens = serial.tokens.clone();
        assert_same(&serial, &lean, &format!("large lean parse, {dialect:?}"));
    }
}

#[test]
fn tiny_inputs() {
    for dialect in Dialect::ALL {
        for text in [
            "", "\n", "X1", "X1\n", "\nX1", "X1\nY2", "%\n%\n", "\r\n\r\n",
        ] {
            check(dialect, text);
        }
    }
}

fn gcode_bytes() -> impl Strategy<Value = Vec<u8>> {
    let alphabet: Vec<u8> =
        b"GMXYZIJKRFPSTNOgmxyz0123456789.+-*/#[]()<>=;% \t\r\n\n\n_,:ABCDEHLQUVWabcdehlqw$@^!"
            .to_vec();
    prop::collection::vec(
        prop_oneof![9 => prop::sample::select(alphabet), 1 => any::<u8>()],
        0..400,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn arbitrary_bytes_parse_the_same_in_two(bytes in gcode_bytes(), d in 0usize..3) {
        let dialect = Dialect::ALL[d];
        let opts = ParseOptions::new(dialect);
        let serial = parse_serial(opts, bytes.clone());
        let two = parse_in_two(opts, bytes.clone());
        assert_same(&serial, &two, &format!("{dialect:?}: {:?}", String::from_utf8_lossy(&bytes)));
        let lean = parse_lean(opts, bytes.clone());
        let lean_two = parse_lean_in_two(opts, bytes.clone());
        assert_same(&lean, &lean_two, &format!("lean, {dialect:?}: {:?}", String::from_utf8_lossy(&bytes)));
    }
}
