//! Structure of parsed programs in each dialect.

use analyzer::dialect::Dialect;
use analyzer::syntax::*;

fn p(d: Dialect, s: &str) -> Program {
    parse(ParseOptions::new(d), s.as_bytes().to_vec())
}

fn words(prog: &Program, block: usize) -> Vec<(char, f64)> {
    prog.words(&prog.blocks[block])
        .filter_map(|(_, w)| w.num().map(|n| (w.letter as char, n.value)))
        .collect()
}

fn codes(prog: &Program) -> Vec<&'static str> {
    prog.diagnostics.iter().map(|d| d.code).collect()
}

#[test]
fn ngc_whitespace_inside_numbers_and_case() {
    // The seed's example: `g0x +0. 12 34y 7` means `g0 x+0.1234 y7`.
    let prog = p(Dialect::Rs274ngc, "g0x +0. 12 34y 7\n");
    assert_eq!(words(&prog, 0), vec![('G', 0.0), ('X', 0.1234), ('Y', 7.0)]);
    assert!(prog.diagnostics.is_empty(), "{:?}", prog.diagnostics);
}

#[test]
fn ngc_expressions_use_five_precedence_levels() {
    let prog = p(
        Dialect::Rs274ngc,
        "#1 = [0 AND 0 + 1]\n#2=[2**3**2]\n#3 = ATAN[1]/[1]\n",
    );
    assert!(prog.diagnostics.is_empty(), "{:?}", prog.diagnostics);
    let items = prog.items_of(&prog.blocks[0]);
    let ItemKind::Assign { value, .. } = items[0].kind else {
        panic!("not an assignment: {items:?}")
    };
    // value = Group(Binary(And, 0, Binary(Add, 0, 1)))
    let Expr::Group { inner } = prog.expr(value).expr else {
        panic!()
    };
    let Expr::Binary { op, rhs, .. } = prog.expr(inner).expr else {
        panic!()
    };
    assert_eq!(op, BinOp::And);
    assert!(matches!(
        prog.expr(rhs).expr,
        Expr::Binary { op: BinOp::Add, .. }
    ));
    // `**` is left-associative: (2**3)**2.
    let items = prog.items_of(&prog.blocks[1]);
    let ItemKind::Assign { value, .. } = items[0].kind else {
        panic!()
    };
    let Expr::Group { inner } = prog.expr(value).expr else {
        panic!()
    };
    let Expr::Binary {
        op: BinOp::Pow,
        lhs,
        ..
    } = prog.expr(inner).expr
    else {
        panic!()
    };
    assert!(matches!(
        prog.expr(lhs).expr,
        Expr::Binary { op: BinOp::Pow, .. }
    ));
    let items = prog.items_of(&prog.blocks[2]);
    let ItemKind::Assign { value, .. } = items[0].kind else {
        panic!()
    };
    assert!(matches!(
        prog.expr(value).expr,
        Expr::Call {
            func: Func::Atan,
            arg2: Some(_),
            ..
        }
    ));
}

#[test]
fn ngc_owords_and_named_parameters() {
    let prog = p(Dialect::Rs274ngc, "o<drill> sub\n#<depth> = #1\no<drill> endsub\no<drill> call [1.5] [#<x>]\no100 while [#1 LT 3]\n");
    assert!(prog.diagnostics.is_empty(), "{:?}", prog.diagnostics);
    let ow: Vec<(Option<OKeyword>, usize)> = prog
        .items
        .iter()
        .filter_map(|i| match i.kind {
            ItemKind::OWord(o) => Some((o.keyword, prog.expr_list(o.args()).len())),
            _ => None,
        })
        .collect();
    assert_eq!(
        ow,
        vec![
            (Some(OKeyword::Sub), 0),
            (Some(OKeyword::Endsub), 0),
            (Some(OKeyword::Call), 2),
            (Some(OKeyword::While), 1)
        ]
    );
    let ItemKind::OWord(o) = prog.items_of(&prog.blocks[0])[0].kind else {
        panic!()
    };
    assert_eq!(o.label, OLabel::Name);
    assert_eq!(&*prog.str_of(o.name_span()), "drill");
    assert_eq!(&*prog.str_of(o.label_span), "<drill>");
}

#[test]
fn ngc_semicolon_comment_and_percent_demarcation() {
    let prog = p(
        Dialect::Rs274ngc,
        "%\nG0 X1 ; go (there)\n%\nthis is ignored\n",
    );
    assert!(prog.diagnostics.is_empty(), "{:?}", prog.diagnostics);
    assert_eq!(prog.blocks[0].kind, BlockKind::Percent);
    assert_eq!(prog.blocks[2].kind, BlockKind::Percent);
    assert_eq!(prog.blocks[3].kind, BlockKind::Ignored);
    let prog = p(Dialect::Rs274ngc, "G0 X1\n%\nM2\n");
    assert_eq!(codes(&prog), vec!["L011"]);
}

#[test]
fn ngc_malformed_numbers() {
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X.\n")), vec!["L004"]);
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X1.2.3\n")), vec!["L004"]);
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X F100\n")), vec!["L003"]);
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X1 (open\n")), vec!["L001"]);
    assert_eq!(
        codes(&p(Dialect::Rs274ngc, "G1 X1 (a (b) c)\n")),
        vec!["L002"]
    );
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X[1+2 F1\n")), vec!["L006"]);
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X1 /Y2\n")), vec!["L007"]);
    assert_eq!(codes(&p(Dialect::Rs274ngc, "G1 X#1+2\n")), vec!["L005"]);
}

#[test]
fn servoworks_lexical_rules() {
    let prog = p(Dialect::Servoworks, "%\n% This is a line of block delete code\n/N10 G01 X1.0 F100.\nM98 PMoveXY R5\nS2_1500\nOMoveXY\n#101 = #101 + 1.0 (count)\nG80; then prose\n");
    assert_eq!(prog.blocks[0].kind, BlockKind::Percent);
    assert_eq!(prog.blocks[1].kind, BlockKind::Deleted);
    assert!(prog.blocks[2].skip().is_some());
    let (_, p98) = prog
        .words(&prog.blocks[3])
        .find(|(_, w)| w.letter == b'P')
        .unwrap();
    let WordValue::Name(n) = p98.value else {
        panic!("{p98:?}")
    };
    assert_eq!(&*prog.str_of(n), "MoveXY");
    let (_, s) = prog.words(&prog.blocks[4]).next().unwrap();
    assert_eq!(s.spindle, Some(2));
    assert!(matches!(s.value, WordValue::Num(n) if n.value == 1500.0));
    assert!(matches!(
        prog.items_of(&prog.blocks[5])[0].kind,
        ItemKind::ProgramHead { number: None, .. }
    ));
    assert!(matches!(
        prog.items_of(&prog.blocks[6])[0].kind,
        ItemKind::Assign { .. }
    ));
    assert_eq!(codes(&prog), vec!["L013"]);
    // Lower case is ignored; `/` must be in column 1; `%` elsewhere is ignored.
    assert_eq!(codes(&p(Dialect::Servoworks, "G01 x10.0\n")), vec!["L008"]);
    assert_eq!(codes(&p(Dialect::Servoworks, " /G01 X1\n")), vec!["L007"]);
    assert_eq!(
        codes(&p(Dialect::Servoworks, "G01 X1 % Y2\n")),
        vec!["L011"]
    );
    // Duplicate words stay in the tree (rules decide what they mean).
    let prog = p(Dialect::Servoworks, "N100 G00 X13.0 Z3.0 X2.0 X9.5\n");
    assert_eq!(words(&prog, 0).len(), 6);
}

#[test]
fn fanuc_blocks_and_macro_b() {
    let prog = p(
        Dialect::Fanuc,
        "%\nO1000 (MAIN);\nG90 G00 X0. Y0.; G01 X10. F100.\n#1 = 0;\nWHILE [#1 LT 10] DO1;\n#1 = #1 + 1;\nEND1;\nIF [#1 EQ 10] GOTO 100;\nIF [#1 GT 5] THEN #2 = 1;\nN100 G65 P9100 A1. B2.;\n/2 M01;\n,C1.\nM30;\n%\n",
    );
    assert!(prog.diagnostics.is_empty(), "{:?}", prog.diagnostics);
    // `;` followed by more text starts a new block on the same line.
    let lines: Vec<u32> = prog.blocks.iter().map(|b| b.line).collect();
    assert_eq!(lines, vec![0, 1, 2, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13]);
    assert!(matches!(
        prog.items_of(&prog.blocks[1])[0].kind,
        ItemKind::ProgramHead {
            number: Some(1000),
            ..
        }
    ));
    let stmts: Vec<&MacroStmt> = prog
        .items
        .iter()
        .filter_map(|i| match &i.kind {
            ItemKind::Macro(m) => Some(m),
            _ => None,
        })
        .collect();
    assert!(matches!(stmts[0], MacroStmt::While { .. }));
    assert!(matches!(stmts[1], MacroStmt::End { .. }));
    assert!(matches!(stmts[2], MacroStmt::IfGoto { .. }));
    assert!(matches!(stmts[3], MacroStmt::IfThen { .. }));
    assert_eq!(prog.blocks[11].skip().map(|s| s.1), Some(2));
    assert_eq!(prog.blocks[14].kind, BlockKind::Percent);
    let (_, c) = prog.words(&prog.blocks[12]).next().unwrap();
    assert!(c.comma && c.letter == b'C');
}

#[test]
fn ngc_bare_o_number_is_a_subprogram_head() {
    let prog = p(Dialect::Rs274ngc, "O100\nG0 X1\nM99\n");
    assert!(prog.diagnostics.is_empty(), "{:?}", prog.diagnostics);
    assert_eq!(
        codes(&p(Dialect::Rs274ngc, "o100 frobnicate\n")),
        vec!["L010"]
    );
}
