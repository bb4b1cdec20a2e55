//! The lossless property: every byte belongs to exactly one token and printing
//! the tokens gives back the input, for arbitrary bytes in every dialect.

use analyzer::dialect::Dialect;
use analyzer::syntax::{parse, ParseOptions, Program};
use proptest::prelude::*;

fn check_lossless(program: &Program, input: &[u8]) {
    assert_eq!(program.print(), input);
    if input.is_empty() {
        assert!(program.tokens.is_empty());
        return;
    }
    assert_eq!(
        program.tokens.first().map(|t| t.start),
        Some(0),
        "first token must start at 0"
    );
    for w in program.tokens.windows(2) {
        assert!(
            w[0].start < w[1].start,
            "tokens must be strictly increasing: {:?}",
            w
        );
    }
    for b in &program.blocks {
        assert!(b.span.start <= b.span.end && b.span.end <= b.end().end);
        for it in program.items_of(b) {
            assert!(
                it.span.start >= b.span.start && it.span.end <= b.span.end,
                "item outside block: {it:?} {b:?}"
            );
        }
    }
    for d in &program.diagnostics {
        assert!(d.span.end as usize <= input.len());
    }
}

/// Bytes biased towards the characters G-code uses.
fn gcode_bytes() -> impl Strategy<Value = Vec<u8>> {
    let alphabet: Vec<u8> =
        b"GMXYZIJKRFPSTNOgmxyz0123456789.+-*/#[]()<>=;% \t\r\n_,:ABCDEHLQUVWabcdehlqw$@^!".to_vec();
    prop::collection::vec(
        prop_oneof![9 => prop::sample::select(alphabet), 1 => any::<u8>()],
        0..200,
    )
}

fn keyword_soup() -> impl Strategy<Value = Vec<u8>> {
    let words = vec![
        "G1 ",
        "X1.5",
        "#1=",
        "[",
        "]",
        "ATAN",
        "/",
        "SIN",
        "o100 ",
        "sub",
        "endsub",
        "while",
        "if",
        "IF",
        "GOTO",
        "WHILE",
        "DO1",
        "END1",
        "THEN",
        "#<a>",
        "(msg,x)",
        "; c",
        "\n",
        "%\n",
        "/1",
        "M98 PMoveXY",
        "S2_1500",
        "EQ",
        "MOD",
        "**",
        "O100",
        "<prog>",
        ",C1.",
        "N10",
        "-",
        "+",
        "1 2 .3",
    ];
    prop::collection::vec(prop::sample::select(words), 0..40).prop_map(|v| v.concat().into_bytes())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    #[test]
    fn print_parse_is_identity(input in gcode_bytes()) {
        for d in Dialect::ALL {
            let p = parse(ParseOptions::new(d), input.clone());
            check_lossless(&p, &input);
        }
    }

    #[test]
    fn print_parse_is_identity_on_keywords(input in keyword_soup()) {
        for d in Dialect::ALL {
            let p = parse(ParseOptions::new(d), input.clone());
            check_lossless(&p, &input);
        }
    }

    #[test]
    fn print_parse_is_identity_on_any_bytes(input in prop::collection::vec(any::<u8>(), 0..300)) {
        for d in Dialect::ALL {
            let p = parse(ParseOptions::new(d), input.clone());
            check_lossless(&p, &input);
        }
    }
}

#[test]
fn deep_nesting_does_not_overflow() {
    let mut s = String::from("#1=");
    s.push_str(&"[".repeat(100_000));
    s.push('1');
    s.push_str(&"]".repeat(100_000));
    s.push('\n');
    for d in Dialect::ALL {
        let p = parse(ParseOptions::new(d), s.clone().into_bytes());
        check_lossless(&p, s.as_bytes());
        assert!(p.diagnostics.iter().any(|d| d.code == "L014"));
    }
}

/// The height of the highest expression tree, walked with an explicit stack.
fn max_expr_height(p: &Program) -> u32 {
    use analyzer::syntax::{Expr, ExprId};
    let mut below = vec![0u32; p.exprs.len()];
    // Children are pushed before their parents, so one pass in id order sees
    // every child's height before its parent's.
    for (i, node) in p.exprs.iter().enumerate() {
        let kids: Vec<ExprId> = match node.expr {
            Expr::Var { index } => vec![index],
            Expr::Neg { arg } | Expr::Plus { arg } => vec![arg],
            Expr::Binary { lhs, rhs, .. } => vec![lhs, rhs],
            Expr::Call { arg, arg2, .. } => std::iter::once(arg).chain(arg2).collect(),
            Expr::Group { inner } => vec![inner],
            Expr::Num(_) | Expr::Named { .. } | Expr::Error => Vec::new(),
        };
        below[i] = 1 + kids.iter().map(|k| below[k.0 as usize]).max().unwrap_or(0);
    }
    below.into_iter().max().unwrap_or(0)
}

#[test]
fn every_expression_tree_is_lower_than_the_walkers_allow() {
    let kinds = [
        format!("G1 X[{}1]\n", "1+".repeat(20_000)),
        format!("G1 X[{}1]\n", "1**".repeat(20_000)),
        format!("G1 X{}1\n", "#".repeat(20_000)),
        format!("G1 X[{}1]\n", "-".repeat(20_000)),
        format!("G1 X{}1{}\n", "SIN[".repeat(5000), "]".repeat(5000)),
        format!("G1 X{}1{}\n", "[1+".repeat(5000), "]".repeat(5000)),
        format!(
            "G1 X[{}] Y[{}]\n",
            vec!["[1+1]"; 200].join("*"),
            vec!["1"; 200].join("-")
        ),
    ];
    for d in Dialect::ALL {
        for s in &kinds {
            let p = parse(ParseOptions::new(d), s.clone().into_bytes());
            check_lossless(&p, s.as_bytes());
            let h = max_expr_height(&p);
            assert!(h <= analyzer::syntax::MAX_EXPR_HEIGHT, "{d:?}: height {h}");
            assert!(
                p.diagnostics.iter().any(|d| d.code == "L014"),
                "{d:?}: no L014"
            );
        }
    }
}

#[test]
fn a_block_reads_up_to_256_operators() {
    for d in Dialect::ALL {
        let ok = format!("G1 X[{}1]\n", "1+".repeat(256));
        let p = parse(ParseOptions::new(d), ok.into_bytes());
        assert!(!p.diagnostics.iter().any(|d| d.code == "L014"), "{d:?}");
        let over = format!("G1 X[{}1]\n", "1+".repeat(257));
        let p = parse(ParseOptions::new(d), over.into_bytes());
        let l014: Vec<_> = p.diagnostics.iter().filter(|d| d.code == "L014").collect();
        assert_eq!(l014.len(), 1, "{d:?}");
        // At the 257th operator: `G1 X[` then 256 times `1+`, then `1`.
        assert_eq!(l014[0].span.start, 5 + 2 * 256 + 1, "{d:?}");
    }
}
