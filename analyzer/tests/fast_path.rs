//! The parser's fast path for plain lines (`X1.25 Y-0.5 F300`) builds exactly what
//! the general path builds: same tokens, blocks, items, expressions and diagnostics,
//! in every dialect, on lines that qualify and on near misses that must not.

use std::sync::Arc;

use analyzer::dialect::Dialect;
use analyzer::syntax::{ParseOptions, Parser, Program};
use proptest::prelude::*;

fn parse_with(dialect: Dialect, text: &[u8], fast: bool, lean: bool) -> Program {
    let opts = ParseOptions::new(dialect);
    let text: Arc<[u8]> = text.into();
    let mut program = analyzer::syntax::parse(opts, Arc::<[u8]>::from(&b""[..]));
    program.text = text.clone();
    let parser = Parser::new(opts, text);
    let parser = if lean {
        parser.without_tokens()
    } else {
        parser
    };
    let mut parser = if fast {
        parser
    } else {
        parser.without_fast_path()
    };
    parser.parse_blocks(&mut program, usize::MAX);
    program
}

fn assert_same(dialect: Dialect, text: &[u8]) {
    let general = parse_with(dialect, text, false, false);
    // With tokens (editors) and without them (the command line, whose lean parse
    // also skips the general block bookkeeping for plain lines).
    for lean in [false, true] {
        let fast = parse_with(dialect, text, true, lean);
        same_tree(&fast, &general, dialect, text, lean);
    }
}

fn same_tree(fast: &Program, general: &Program, dialect: Dialect, text: &[u8], lean: bool) {
    let what = format!(
        "{dialect:?}, lean {lean}: {:?}",
        String::from_utf8_lossy(text)
    );
    if lean {
        assert!(fast.tokens.is_empty(), "tokens: {what}");
    } else {
        assert_eq!(fast.tokens, general.tokens, "tokens: {what}");
    }
    assert_eq!(fast.blocks, general.blocks, "blocks: {what}");
    // Debug text: a malformed number's NaN is never equal to itself.
    assert_eq!(
        format!("{:?}", fast.items),
        format!("{:?}", general.items),
        "items: {what}"
    );
    assert_eq!(
        format!("{:?}", fast.exprs),
        format!("{:?}", general.exprs),
        "exprs: {what}"
    );
    assert_eq!(fast.diagnostics, general.diagnostics, "diagnostics: {what}");
}

/// Lines that take the fast path, and lines one byte away from it.
const LINES: &[&str] = &[
    "X1.25 Y-0.5 F300",
    "G1X1Y2Z3",
    "  X.5 Z-.25  ",
    "\tN10 G01 X+1. Y-2.000",
    "X1 5",
    "X1 .5",
    "X 1",
    "X-",
    "X.",
    "X1.2.3",
    "x1 y2",
    "O100",
    "P1 M98",
    "M98 P100",
    "S2_1500",
    "G1 X1 (comment)",
    "G1 X1 ; tail",
    "GOTO10",
    "IF[#1EQ1]GOTO5",
    "X1234567890123456",
    "X123456789012345",
    "X0.00000000000001",
    "/X1",
    "X1 /Y2",
    "%",
    "% X1",
    "X1%",
    "#1=2",
    "X#1",
    "X[1+2]",
    "$1 M3",
    "@1 ^2",
    "X1,R2",
    ",C1",
    "<NAME>",
    ":100",
    "N1 X1 Y2 Z3 A4 B5 C6 U7 V8 W9 I1 J2 K3 R4 Q5 L6 D7 H8 T9 S10 F11 E12",
    "X1\u{0b}Y2\u{0c}Z3",
    "Xsin[30]",
    "X1é",
    // Digit runs around the eight-byte steps of the number reader.
    "X12345678",
    "X12345678.1234567",
    "X1234567.12345678",
    "X123456789012345.",
    "X.123456789012345",
    "X.1234567890123456",
    "X00000000000000001",
    "X-0000000.0000000",
    "X1234567Y12345678Z123456789",
    "X1/2",
    "X9:",
    "X12345678:",
    "X1234567@",
    "Y7.5\u{7f}",
];

#[test]
fn plain_lines_parse_as_the_general_path_does() {
    for dialect in Dialect::ALL {
        for line in LINES {
            for ending in ["\n", "\r\n", ";\n", ";", ""] {
                let text = format!("{line}{ending}G0 X1\n{line}{ending}");
                assert_same(dialect, text.as_bytes());
            }
        }
        // Whole files: opening and closing `%`, FANUC leader and text after the end.
        let text = format!("%\nO1000\n{}\nM30\n%\nX1 Y2\n", LINES.join("\n"));
        assert_same(dialect, text.as_bytes());
    }
}

fn plainish_line() -> impl Strategy<Value = Vec<u8>> {
    // Mostly the bytes of plain lines, with a few that break them.
    let byte = prop::sample::select(
        b"XYZGMFNOPSIJKR0123456789012345678901234567890.-+ \t..;(x#%/_\r\n".to_vec(),
    );
    prop::collection::vec(byte, 0..120)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]
    #[test]
    fn fast_path_agrees_on_random_lines(input in plainish_line(), d in 0usize..3) {
        assert_same(Dialect::ALL[d], &input);
    }
}

/// Every rule fixture, and each dialect's fuzz-style soup, lints the same whether the
/// tree was read with tokens (editors) or without (the command line).
#[test]
fn lean_parse_lints_as_the_full_parse() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/rules");
    let mut files = Vec::new();
    for rule in std::fs::read_dir(&dir).expect("fixtures") {
        for f in std::fs::read_dir(rule.expect("entry").path()).expect("rule dir") {
            let path = f.expect("entry").path();
            if path.extension().is_some_and(|e| e != "toml") {
                files.push(path);
            }
        }
    }
    assert!(files.len() > 300, "{} fixtures", files.len());
    let mut nested = 0;
    for path in files {
        let bytes = std::fs::read(&path).expect("fixture");
        for dialect in Dialect::ALL {
            let settings = analyzer::Settings::new(dialect);
            let full = analyzer::parse_text(bytes.clone(), &settings);
            let lean = analyzer::parse_text_lean(bytes.clone(), &settings);
            assert!(lean.program.tokens.is_empty() || bytes.is_empty());
            let a = analyzer::lint(&full, &settings);
            let b = analyzer::lint(&lean, &settings);
            nested += a.iter().filter(|d| d.code == "W014").count();
            assert_eq!(a, b, "{} as {dialect:?}", path.display());
        }
    }
    // The one rule that reads tokens is exercised.
    assert!(nested > 0);
}

/// [`block_tokens`] gives each block's slice of the full token list.
#[test]
fn block_tokens_are_the_full_parse_tokens() {
    let text = format!(
        "%\nO1000 (T)\n#1=[[1]+SIN[2]];\nIF[#1GT2]GOTO5;G1 X1;\n{}\nM30\n%\nleader [x]\n",
        LINES.join("\n")
    );
    for dialect in Dialect::ALL {
        let p = analyzer::syntax::parse(ParseOptions::new(dialect), text.as_bytes().to_vec());
        let mut joined = Vec::new();
        for b in &p.blocks {
            joined.extend(analyzer::syntax::block_tokens(&p, b));
        }
        assert_eq!(joined, p.tokens, "{dialect:?}");
    }
}
