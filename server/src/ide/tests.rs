//! The features in process, on cursor fixtures: `$0` marks the cursor and
//! each `$1…$1` pair a span the answer must name. The document is analysed as
//! the language server analyses it (`document::analyze`, the built-in
//! machine profile of the dialect), without a path or workspace.

use analyzer::names::Sym;
use analyzer::{Dialect, Span};
use ropey::Rope;

use super::completion::{self, ItemKind};
use super::goto::{self, Definition};
use super::highlight::{self, Class};
use super::lens::{self, BlockTimes};
use super::rename;
use super::symbols::{self, RegionKind};
use super::{hover, signature, Analysis};
use crate::document::config::ClientOptions;
use crate::document::run::{default_runner, CancelFlag};
use crate::document::{analyze, Document, Inputs};

/// A fixture's text without its markers, the cursor and the marked spans.
struct Fixture {
    snap: Document,
    cursor: u32,
    marks: Vec<Span>,
}

fn fixture(dialect: Dialect, marked: &str, run: bool) -> Fixture {
    let mut text = String::new();
    let mut cursor = None;
    let mut open: Option<u32> = None;
    let mut marks = Vec::new();
    let mut rest = marked;
    while let Some(i) = rest.find('$') {
        text.push_str(&rest[..i]);
        let at = text.len() as u32;
        match rest.as_bytes().get(i + 1) {
            Some(b'0') => cursor = Some(at),
            Some(b'1') => match open.take() {
                Some(start) => marks.push(Span::new(start, at)),
                None => open = Some(at),
            },
            _ => panic!("a `$` in a fixture is a marker: {marked:?}"),
        }
        rest = &rest[i + 2..];
    }
    text.push_str(rest);
    let inputs = Inputs {
        version: 1,
        rope: Rope::from_str(&text),
        path: None,
        roots: Vec::new(),
        client: ClientOptions {
            dialect: Some(dialect),
            ..ClientOptions::default()
        },
        runner: default_runner(),
        files: Default::default(),
        previous: None,
    };
    let snap = analyze(inputs);
    if run {
        assert!(snap.run_report(&CancelFlag::default()).is_some());
    }
    Fixture {
        snap,
        cursor: cursor.unwrap_or(0),
        marks,
    }
}

impl Fixture {
    fn analysis(&self) -> Analysis<'_> {
        Analysis::of(&self.snap)
    }

    fn hover(&self) -> (String, Span) {
        let h = hover::hover(&self.analysis(), self.cursor).expect("a hover");
        (h.markdown, h.span)
    }

    fn mark(&self, i: usize) -> Span {
        self.marks[i]
    }

    fn text(&self, span: Span) -> String {
        self.snap.program().str_of(span).into_owned()
    }
}

fn labels(items: &[completion::CompletionItem]) -> Vec<&str> {
    items.iter().map(|i| i.label.as_str()).collect()
}

const NGC_RUN: &str = "G21 G90 G17\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10$0 F600\nT2 M6\nG2 X20 Y0 R5\nM2\n";
const FANUC_RUN: &str = "%\nO0001;\nG21 G90 G17;\nT1 M06;\nS1000 M03;\nG00 X0 Y0 Z5.;\nG01 Z-1. F300.;\nG01 X10.$0 F600.;\nT2 M06;\nG02 X20. Y0 R5.;\nM30;\n%\n";
const SW_RUN: &str = "G21 G90 G17\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10$0 F600\nT2 M6\nG2 X20 Y0 R5\nM30\n";

// Hover.

#[test]
fn hover_on_a_word_with_the_run_shows_the_block_state_and_time() {
    let f = fixture(Dialect::Rs274ngc, NGC_RUN, true);
    assert_eq!(
        f.hover(),
        (
            "**X** — X axis coordinate\n\nIn **G1**: X end point\n\n---\n\n\
             After this block: `G1 G17 G21 G90 G94 G54 G40 G49 G64 G99`  \n\
             Position: `X10.000 Y0.000 Z-1.000 A0.000 B0.000 C0.000`  \n\
             F600 S1000 T1  \n\
             Time: 0.997 s (0.987 s at feed, 0.010 s acceleration), ends at 0:02.3"
                .to_string(),
            Span::new(54, 57)
        )
    );
    let f = fixture(Dialect::Fanuc, FANUC_RUN, true);
    let (md, span) = f.hover();
    assert_eq!(f.text(span), "X10.");
    assert!(md.ends_with(
        "F600 S1000 T1  \nTime: 1.006 s (1.000 s at feed, 0.006 s acceleration), ends at 0:02.4"
    ));
    let f = fixture(Dialect::Servoworks, SW_RUN, true);
    let (md, span) = f.hover();
    assert_eq!(f.text(span), "X10");
    assert!(md.starts_with("**X** — X coordinate (end point, centre, offset); G04 dwell"));
    assert!(md.ends_with("ends at 0:02.4"));
}

#[test]
fn hover_on_codes_and_address_letters_speaks_the_dialect() {
    // FANUC hands an M code it does not know to the machine.
    let f = fixture(Dialect::Fanuc, "O0001;\nG00 X0;\nM19$00;\nM30;\n", false);
    assert_eq!(
        f.hover(),
        (
            "**M190** — machine M code: the control passes it to the machine (PMC), whose builder defines it.".to_string(),
            Span::new(15, 19)
        )
    );
    let f = fixture(Dialect::Servoworks, "G0 X1\nM9$0\nM30\n", false);
    assert_eq!(
        f.hover(),
        (
            "**M9** — not a code of servoworks.".to_string(),
            Span::new(6, 8)
        )
    );
    let f = fixture(
        Dialect::Servoworks,
        "G0 X0 Y0\nG2 X1 Y1 R$01 F100\nM30\n",
        false,
    );
    assert_eq!(
        f.hover(),
        (
            "**R** — M98 repetitions; arc radius; G02.3/G03.3 exponential constant; G10 value; \
             G68 angle in degrees; canned-cycle R level\n\n\
             In **G2**: radius instead of I/J/K; positive = arc up to 180°, negative = 180° or more"
                .to_string(),
            Span::new(18, 20)
        )
    );
    let f = fixture(
        Dialect::Rs274ngc,
        "G0 X0 Y0 Z5\nG$02 X1 Y0 R1 F600\nM2\n",
        false,
    );
    let (md, span) = f.hover();
    assert_eq!(span, Span::new(12, 14));
    assert!(md.starts_with("**G2** — Clockwise arc or helix\n\nModal group 1.\n\n"));
}

#[test]
fn hover_on_a_diagnostic_shows_the_rule() {
    let f = fixture(Dialect::Rs274ngc, "G0 X0\nG0 G$01 X1 F100\nM2\n", false);
    let (md, _) = f.hover();
    let first = md.split("\n\n---\n\n").next().unwrap_or_default();
    assert!(first.starts_with(
        "**G001** (error): Two G codes used from same modal group: G0 and G1 are both in group 1, \
         and the interpreter refuses the line. Keep one, or put them on separate lines.\n\n\
         *modal-group-conflict* — Two G codes of one modal group in a block\n\n## What it does"
    ));
}

#[test]
fn hover_on_names_and_variables() {
    let f = fixture(
        Dialect::Rs274ngc,
        "o<drill> sub\nG81 Z-1 R1\no<drill> endsub\no<dr$0ill> call\nM2\n",
        false,
    );
    assert_eq!(
        f.hover(),
        (
            "**o<drill>** — O-word label, defined on line 1".to_string(),
            Span::new(40, 48)
        )
    );
    let f = fixture(
        Dialect::Fanuc,
        "O0001;\n#100=5;\nG00 X#10$00;\nM30;\n",
        true,
    );
    let (md, span) = f.hover();
    assert_eq!(f.text(span), "#100");
    assert!(md.starts_with(
        "**#100** — variable, first assigned on line 2\n\n\
         *common variable, cleared at power-off*\n\nValue in the dry run: `5`\n\n---\n\n"
    ));
    let f = fixture(Dialect::Servoworks, "#1=5\nG0 X#$01\nG0 Y#1\nM30\n", false);
    assert_eq!(
        f.hover(),
        (
            "**#1** — variable, first assigned on line 1\n\n\
             *local variable of the current macro level; G65/G66 argument A (Argument Specification I)*"
                .to_string(),
            Span::new(9, 11)
        )
    );
}

#[test]
fn hover_on_the_first_line_names_the_dialect_and_its_reason() {
    let f = fixture(Dialect::Fanuc, "$0%\nO0001;\nM30;\n%\n", false);
    assert_eq!(
        f.hover(),
        (
            "*Checked as fanuc: the editor's `partscope.dialect` setting*".to_string(),
            Span::new(0, 0)
        )
    );
}

// Go-to-definition and references.

#[test]
fn definitions_in_the_document() {
    let cases = [
        (
            Dialect::Rs274ngc,
            "$1o<drill>$1 sub\nG81 Z-1 R1\no<drill> endsub\no<dr$0ill> call\nM2\n",
        ),
        (
            Dialect::Rs274ngc,
            "$1#<depth>$1 = 2\nG1 Z-#<de$0pth> F100\nM2\n",
        ),
        (
            Dialect::Fanuc,
            "%\nO0001;\nM98 P1$0234;\nM30;\n$1O1234$1;\nG01 X1. F100.;\nM99;\n%\n",
        ),
        (
            Dialect::Fanuc,
            "O0001;\n#100=0;\n$1N10$1 #100=#100+1;\nIF [#100 LT 3] GOTO1$00;\nM30;\n",
        ),
        (Dialect::Servoworks, "$1#1$1=5\nG0 X#$01\nM30\n"),
    ];
    for (dialect, text) in cases {
        let f = fixture(dialect, text, false);
        assert_eq!(
            goto::definition(&f.analysis(), f.cursor),
            Some(Definition::Here(f.mark(0))),
            "{text}"
        );
    }
}

#[test]
fn a_program_of_another_file_is_the_hosts_to_find() {
    let f = fixture(Dialect::Servoworks, "G0 X0\nM98 PMove$0XY\nM30\n", false);
    let a = f.analysis();
    assert_eq!(
        goto::definition(&a, f.cursor),
        Some(Definition::Elsewhere(Sym::Program("MOVEXY".into())))
    );
    let refs = goto::references(&a, f.cursor, true).expect("references");
    assert!(refs.crosses_files());
    assert_eq!(refs.spans, vec![Span::new(10, 17)]);
    // The host parses the file it found and asks for the definition there.
    let other = fixture(Dialect::Servoworks, "$1OMoveXY$1\nG1 X1 F100\nM99\n", false);
    assert_eq!(
        goto::definition_in(other.snap.program(), &refs.sym),
        Some(other.mark(0))
    );
}

#[test]
fn references_in_each_dialect() {
    let f = fixture(
        Dialect::Rs274ngc,
        "$1#<depth>$1 = 2\nG1 Z-$1#<de$0pth>$1 F100\nG1 Z-$1#<depth>$1\nM2\n",
        false,
    );
    let a = f.analysis();
    let refs = goto::references(&a, f.cursor, true).expect("references");
    assert_eq!(refs.sym, Sym::Var("#<depth>".into()));
    assert!(!refs.crosses_files());
    assert_eq!(refs.spans, f.marks);
    let without = goto::references(&a, f.cursor, false).expect("references");
    assert_eq!(without.spans, f.marks[1..].to_vec());

    let f = fixture(
        Dialect::Fanuc,
        "O0001;\n#100=0;\n$1N10$1 #100=#100+1;\nIF [#100 LT 3] GOTO$11$00$1;\nM30;\n",
        false,
    );
    let refs = goto::references(&f.analysis(), f.cursor, true).expect("references");
    assert_eq!(refs.sym, Sym::Seq(10));
    assert_eq!(refs.spans, f.marks);

    let f = fixture(
        Dialect::Servoworks,
        "$1#1$1=5\nG0 X$1#$01$1\nG0 Y$1#1$1\nM30\n",
        false,
    );
    let refs = goto::references(&f.analysis(), f.cursor, true).expect("references");
    assert_eq!(refs.sym, Sym::Var("#1".into()));
    assert_eq!(refs.spans, f.marks);
}

// Symbols and folding.

type Outline = Vec<(String, RegionKind, Span, Span, usize)>;

fn outline(f: &Fixture) -> Outline {
    fn walk(syms: &[symbols::Symbol], depth: usize, out: &mut Outline) {
        for s in syms {
            out.push((s.name.clone(), s.kind, s.span, s.selection, depth));
            walk(&s.children, depth + 1, out);
        }
    }
    let mut out = Vec::new();
    walk(&symbols::document_symbols(f.snap.program()), 0, &mut out);
    out
}

fn folds(f: &Fixture) -> Vec<(u32, u32, String)> {
    symbols::folding_ranges(&f.analysis())
        .into_iter()
        .map(|f| (f.start_line, f.end_line, f.name))
        .collect()
}

#[test]
fn symbols_and_folds_in_each_dialect() {
    let f = fixture(
        Dialect::Rs274ngc,
        "o<pocket> sub\no100 while [#1 LT 3]\nG1 X#1\no100 endwhile\no<pocket> endsub\nT1 M6\nG0 X0\nT2 M6\nG0 X1\nM2\n",
        false,
    );
    let s = |a, b| Span::new(a, b);
    assert_eq!(
        outline(&f),
        vec![
            ("o<pocket>".into(), RegionKind::Sub, s(0, 72), s(0, 13), 0),
            (
                "o100 while".into(),
                RegionKind::Control,
                s(14, 55),
                s(14, 34),
                1
            ),
            ("T1 M6".into(), RegionKind::Tool, s(73, 84), s(73, 78), 0),
            ("T2 M6".into(), RegionKind::Tool, s(85, 99), s(85, 90), 0),
        ]
    );
    assert_eq!(
        folds(&f),
        vec![
            (0, 4, "o<pocket>".into()),
            (1, 3, "o100 while".into()),
            (5, 6, "T1 M6".into()),
            (7, 9, "T2 M6".into())
        ]
    );
    let f = fixture(
        Dialect::Fanuc,
        "%\nO0001;\nT1 M6;\nM98 P1234;\nM30;\nO1234;\nG1 X1.;\nM99;\n%\n",
        false,
    );
    assert_eq!(
        outline(&f),
        vec![
            ("O0001".into(), RegionKind::Program, s(2, 30), s(2, 7), 0),
            ("T1 M6".into(), RegionKind::Tool, s(9, 30), s(9, 14), 1),
            ("O1234".into(), RegionKind::Program, s(32, 53), s(32, 37), 0),
        ]
    );
    assert_eq!(
        folds(&f),
        vec![
            (1, 4, "O0001".into()),
            (2, 4, "T1 M6".into()),
            (5, 8, "O1234".into()) // to the closing `%`
        ]
    );
    let f = fixture(
        Dialect::Servoworks,
        "T1 M6\nG0 X0\nG1 X1 F100\nT2 M6\nG0 X2\nM30\n",
        false,
    );
    assert_eq!(
        outline(&f),
        vec![
            ("T1 M6".into(), RegionKind::Tool, s(0, 22), s(0, 5), 0),
            ("T2 M6".into(), RegionKind::Tool, s(23, 38), s(23, 28), 0),
        ]
    );
    assert_eq!(
        folds(&f),
        vec![(0, 2, "T1 M6".into()), (3, 5, "T2 M6".into())]
    );
}

// Completion.

#[test]
fn completion_of_names() {
    let f = fixture(
        Dialect::Rs274ngc,
        "#<depth> = 2\n#<dwell> = 1\nG1 Z-#<d$0\nM2\n",
        false,
    );
    let items = completion::complete(&f.analysis(), f.cursor as usize, &Vec::new);
    assert_eq!(labels(&items), ["#<depth>", "#<dwell>"]);
    assert!(items
        .iter()
        .all(|i| i.kind == ItemKind::Variable && i.replace == Span::new(31, 34)));

    let f = fixture(
        Dialect::Rs274ngc,
        "o<drill> sub\no<drill> endsub\n$1o<$0$1\nM2\n",
        false,
    );
    let beside = || vec!["drill".to_string(), "probe".to_string()];
    let items = completion::complete(&f.analysis(), f.cursor as usize, &beside);
    let got: Vec<(&str, ItemKind, Option<&str>)> = items
        .iter()
        .map(|i| (i.label.as_str(), i.kind, i.detail.as_deref()))
        .collect();
    assert_eq!(
        got,
        [
            ("o<drill>", ItemKind::Function, Some("subprogram")),
            (
                "o<probe>",
                ItemKind::File,
                Some("subprogram file probe.ngc")
            ),
        ]
    );
    assert_eq!(items[1].replace, f.mark(0));
    assert_eq!(items[1].text, "o<probe>");

    let f = fixture(
        Dialect::Fanuc,
        "O0001;\nM98 P$0\nM30;\nO1234;\nM99;\n",
        false,
    );
    let items = completion::complete(&f.analysis(), f.cursor as usize, &Vec::new);
    assert_eq!(labels(&items), ["P1", "P1234"]);
    assert!(items.iter().all(|i| i.kind == ItemKind::Module));
}

#[test]
fn completion_of_parameters_keywords_and_codes() {
    let f = fixture(Dialect::Rs274ngc, "G81 X1 Z-1 $0\nM2\n", false);
    let items = completion::complete(&f.analysis(), f.cursor as usize, &Vec::new);
    assert_eq!(labels(&items), ["Y", "R", "L", "F"]);
    assert_eq!(
        items[1].detail.as_deref(),
        Some("G81: retract plane (sticky; G91: relative to the start height); required on the first cycle block")
    );
    assert!(items.iter().all(|i| i.kind == ItemKind::Property));

    let f = fixture(Dialect::Servoworks, "G2 X1 Y1 $0\nM30\n", false);
    let items = completion::complete(&f.analysis(), f.cursor as usize, &Vec::new);
    assert_eq!(labels(&items)[..6], ["Z", "A", "I", "J", "K", "R"]);

    let f = fixture(Dialect::Fanuc, "O0001;\n$1WH$0$1\nM30;\n", false);
    let items = completion::complete(&f.analysis(), f.cursor as usize, &Vec::new);
    assert_eq!(labels(&items), ["WHILE"]);
    assert_eq!(items[0].kind, ItemKind::Keyword);
    assert_eq!(
        items[0].detail.as_deref(),
        Some("WHILE [cond] DO m … END m")
    );
    assert_eq!(items[0].replace, f.mark(0));

    // ServoWorks writes its M codes with two digits.
    let f = fixture(Dialect::Servoworks, "G0 X1\nM9$0\nM30\n", false);
    let items = completion::complete(&f.analysis(), f.cursor as usize, &Vec::new);
    assert_eq!(labels(&items)[..4], ["M00", "M01", "M02", "M03"]);
    assert_eq!(items[0].detail.as_deref(), Some("Program stop"));
    assert_eq!(items[0].sort_text.as_deref(), Some("M00000000"));
    assert!(items.iter().all(|i| i.kind == ItemKind::Event));
}

// Signature help.

#[test]
fn signature_help_in_each_dialect() {
    let f = fixture(Dialect::Rs274ngc, "G81 X1 R$0\nM2\n", false);
    let help = signature::signature_help(&f.analysis(), f.cursor).expect("help");
    let sig = &help.signatures[0];
    assert_eq!(sig.label, "G81 [X] [Y] [Z] [R] [L] [F]");
    assert_eq!(help.active_parameter, Some(3));
    assert_eq!(&sig.label[sig.parameters[3].label.clone()], "R");
    assert!(sig.documentation.starts_with("Drilling cycle\n\n"));

    let f = fixture(Dialect::Fanuc, "%\nO0001;\nM98 P1$0234;\nM30;\n%\n", false);
    let help = signature::signature_help(&f.analysis(), f.cursor).expect("help");
    let sig = &help.signatures[0];
    assert_eq!(sig.label, "M98 P [L]");
    assert_eq!(
        sig.parameters
            .iter()
            .map(|p| p.label.clone())
            .collect::<Vec<_>>(),
        [4..5, 7..8]
    );
    assert_eq!(help.active_parameter, Some(0));

    let f = fixture(Dialect::Servoworks, "G0 X0\nM98 PMove$0XY\nM30\n", false);
    let help = signature::signature_help(&f.analysis(), f.cursor).expect("help");
    assert_eq!(help.signatures[0].label, "M98 P [R]");
    assert_eq!(
        help.signatures[0].parameters[1].doc,
        "number of repetitions, integer 1–999,999 (default 1)"
    );
}

// The cycle-time lens and the inlay hints.

fn hints(f: &Fixture, mode: BlockTimes) -> Vec<(String, String, Option<String>)> {
    lens::inlay_hints(&f.analysis(), 0, u32::MAX, mode)
        .into_iter()
        .map(|h| {
            // Where the hint sits: the end of its line's content.
            let line_start = f.snap.program().text[..h.offset]
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |i| i + 1);
            let line = f.text(Span::new(line_start as u32, h.offset as u32));
            (line, h.label, h.tooltip)
        })
        .collect()
}

fn lens_title(f: &Fixture) -> Option<String> {
    let a = f.analysis();
    lens::cycle_time_title(a.run.as_deref(), f.snap.run_skipped_reason())
}

#[test]
fn lens_and_inlay_hints_rs274ngc() {
    let f = fixture(Dialect::Rs274ngc, NGC_RUN, true);
    assert_eq!(
        lens_title(&f).as_deref(),
        Some("Cycle time 0:04.0 (cutting 0:03.8, rapid 0:00.1, tool change 0:00.0)")
    );
    let tip = |s: &str| Some(s.to_string());
    assert_eq!(
        hints(&f, BlockTimes::Block),
        vec![
            ("T1 M6".into(), "tool change at 0:00.0".into(), None),
            (
                "G0 X0 Y0 Z5".into(),
                "0.142 s".into(),
                tip("0.142 s rapid; ends at 0:00.1")
            ),
            (
                "G1 Z-1 F300".into(),
                "1.200 s".into(),
                tip("1.195 s at feed, 0.003 s acceleration, 0.002 s corners; ends at 0:01.3")
            ),
            (
                "G1 X10 F600".into(),
                "0.997 s".into(),
                tip("0.987 s at feed, 0.010 s acceleration; ends at 0:02.3")
            ),
            ("T2 M6".into(), "tool change at 0:02.3".into(), None),
            (
                "G2 X20 Y0 R5".into(),
                "1.611 s".into(),
                tip("1.571 s at feed, 0.040 s acceleration; ends at 0:04.0")
            ),
        ]
    );
    let cumulative: Vec<String> = hints(&f, BlockTimes::Cumulative)
        .into_iter()
        .map(|h| h.1)
        .collect();
    assert_eq!(
        cumulative,
        [
            "tool change at 0:00.0",
            "ends at 0:00.1",
            "ends at 0:01.3",
            "ends at 0:02.3",
            "tool change at 0:02.3",
            "ends at 0:04.0"
        ]
    );
    let off: Vec<String> = hints(&f, BlockTimes::Off)
        .into_iter()
        .map(|h| h.1)
        .collect();
    assert_eq!(off, ["tool change at 0:00.0", "tool change at 0:02.3"]);
    // Only the lines asked for.
    let some = lens::inlay_hints(&f.analysis(), 5, 6, BlockTimes::Block);
    let labels: Vec<&str> = some.iter().map(|h| h.label.as_str()).collect();
    assert_eq!(labels, ["0.997 s", "tool change at 0:02.3"]);
}

#[test]
fn lens_and_inlay_hints_fanuc_and_servoworks() {
    for (dialect, text, first) in [
        (Dialect::Fanuc, FANUC_RUN, "T1 M06;"),
        (Dialect::Servoworks, SW_RUN, "T1 M6"),
    ] {
        let f = fixture(dialect, text, true);
        assert_eq!(
            lens_title(&f).as_deref(),
            Some("Cycle time 0:03.9 (cutting 0:03.8, rapid 0:00.1, tool change 0:00.0)")
        );
        let got: Vec<(String, String)> = hints(&f, BlockTimes::Block)
            .into_iter()
            .map(|h| (h.0, h.1))
            .collect();
        assert_eq!(got.len(), 6, "{got:?}");
        assert_eq!(
            got[0],
            (first.to_string(), "tool change at 0:00.0".to_string())
        );
        assert_eq!(got[1].1, "0.141 s");
        assert_eq!(got[2].1, "1.202 s");
        assert_eq!(got[3].1, "1.006 s");
        assert_eq!(got[4].1, "tool change at 0:02.4");
        assert_eq!(got[5].1, "1.581 s");
    }
}

/// A call the run cannot follow leaves its time out: the lens says the figure is
/// partial, as `partscope run` does.
#[test]
fn a_skipped_call_makes_the_lens_partial() {
    let f = fixture(
        Dialect::Rs274ngc,
        "G21 G90\nG1 X10 F600\no<not_here> call\nG1 X20\nM2\n",
        true,
    );
    assert_eq!(
        lens_title(&f).as_deref(),
        Some("Cycle time 0:02.0 partial (cutting 0:02.0, rapid 0:00.0, tool change 0:00.0): a called program was not run")
    );
}

#[test]
fn no_run_no_lens_and_no_hints() {
    let f = fixture(Dialect::Rs274ngc, NGC_RUN, false);
    assert_eq!(lens_title(&f), None);
    assert!(lens::inlay_hints(&f.analysis(), 0, u32::MAX, BlockTimes::Block).is_empty());
}

// Highlighting.

/// The highlighted tokens starting inside the fixture's first marked span
/// (the whole text without one): each token's text, byte offset and class.
fn highlighted(f: &Fixture) -> Vec<(String, u32, Class)> {
    let range = f.marks.first().copied().unwrap_or(Span::new(0, u32::MAX));
    highlight::highlights(f.snap.program(), range.start, range.end)
        .map(|h| (f.text(h.span), h.span.start, h.class))
        .collect()
}

fn classes(f: &Fixture) -> Vec<(String, Class)> {
    highlighted(f).into_iter().map(|(t, _, c)| (t, c)).collect()
}

fn own(v: &[(&str, Class)]) -> Vec<(String, Class)> {
    v.iter().map(|(t, c)| (t.to_string(), *c)).collect()
}

#[test]
fn highlighting_a_fanuc_macro_line() {
    let f = fixture(
        Dialect::Fanuc,
        "%\nO0001;\n$1#1=SIN[30];\n$1M30;\n%\n",
        false,
    );
    assert_eq!(
        highlighted(&f),
        vec![
            ("#".to_string(), 9, Class::Variable),
            ("1".to_string(), 10, Class::Number),
            ("=".to_string(), 11, Class::Operator),
            ("SIN".to_string(), 12, Class::Keyword),
            ("[".to_string(), 15, Class::Operator),
            ("30".to_string(), 16, Class::Number),
            ("]".to_string(), 18, Class::Operator),
            (";".to_string(), 19, Class::Mark),
        ]
    );
    let whole = fixture(Dialect::Fanuc, "%\nO0001;\n#1=SIN[30];\nM30;\n%\n", false);
    let all = classes(&whole);
    assert_eq!(
        all[..3],
        own(&[
            ("%", Class::Mark),
            ("O", Class::Address),
            ("0001", Class::Name)
        ])[..]
    );
    assert_eq!(
        all[all.len() - 4..],
        own(&[
            ("M", Class::Code),
            ("30", Class::Number),
            (";", Class::Mark),
            ("%", Class::Mark)
        ])[..]
    );
}

#[test]
fn highlighting_an_ngc_o_word_and_comments() {
    let f = fixture(
        Dialect::Rs274ngc,
        "o100 sub (probe)\nG38.2 Z-#<depth> F[#1*2] ; rest\no100 endsub\n",
        false,
    );
    assert_eq!(
        classes(&f),
        own(&[
            ("o", Class::Address),
            ("100", Class::Number),
            ("sub", Class::Keyword),
            ("(probe)", Class::Comment),
            ("G", Class::Code),
            ("38.2", Class::Number),
            ("Z", Class::Address),
            ("-", Class::Operator),
            ("#<depth>", Class::Variable),
            ("F", Class::Address),
            ("[", Class::Operator),
            ("#", Class::Variable),
            ("1", Class::Number),
            ("*", Class::Operator),
            ("2", Class::Number),
            ("]", Class::Operator),
            ("; rest", Class::Comment),
            ("o", Class::Address),
            ("100", Class::Number),
            ("endsub", Class::Keyword),
        ])
    );
}

#[test]
fn highlighting_g_and_m_codes_and_a_range() {
    // Only tokens starting inside the range: the second line.
    let f = fixture(
        Dialect::Servoworks,
        "G90 G1 X1.5 F100\n$1M3 S1000 T2\n$1M30\n",
        false,
    );
    assert_eq!(
        highlighted(&f),
        vec![
            ("M".to_string(), 17, Class::Code),
            ("3".to_string(), 18, Class::Number),
            ("S".to_string(), 20, Class::Address),
            ("1000".to_string(), 21, Class::Number),
            ("T".to_string(), 26, Class::Address),
            ("2".to_string(), 27, Class::Number),
        ]
    );
    let f = fixture(Dialect::Rs274ngc, "/G0 X1\n", false);
    assert_eq!(
        classes(&f),
        own(&[
            ("/", Class::Mark),
            ("G", Class::Code),
            ("0", Class::Number),
            ("X", Class::Address),
            ("1", Class::Number),
        ])
    );
}

// Rename.

/// The edits of a rename as (the span they replace, new text).
fn edit_texts(edits: &[analyzer::TextEdit]) -> Vec<(Span, String)> {
    edits.iter().map(|e| (e.span, e.new_text.clone())).collect()
}

fn program_of(dialect: Dialect, text: &str) -> analyzer::syntax::Program {
    analyzer::syntax::parse(
        analyzer::syntax::ParseOptions::new(dialect),
        text.as_bytes().to_vec(),
    )
}

#[test]
fn renaming_a_local_named_parameter() {
    let f = fixture(
        Dialect::Rs274ngc,
        "#<$1depth$1> = 2\nG1 Z-#<$1de$0pth$1> F100\nM2\n",
        false,
    );
    let program = f.snap.program();
    let span = rename::prepare(program, f.cursor).and_then(Result::ok);
    assert_eq!(span, Some(Span::new(18, 26)));
    assert_eq!(f.text(Span::new(18, 26)), "#<depth>");
    let r = rename::rename(program, f.cursor, "#<cut>")
        .expect("renamed")
        .expect("a name");
    assert_eq!(r.sym, Sym::Var("#<depth>".to_string()));
    assert_eq!(
        edit_texts(&r.edits),
        vec![
            (f.mark(0), "cut".to_string()),
            (f.mark(1), "cut".to_string())
        ]
    );
    assert_eq!(r.subroutine, None);
    // Nothing to rename on a blank.
    assert_eq!(rename::prepare(program, 12), None);
    assert_eq!(rename::rename(program, 12, "x"), Ok(None));
}

#[test]
fn renaming_an_o_word_subroutine_in_this_and_another_program() {
    let f = fixture(
        Dialect::Rs274ngc,
        "o$1<drill>$1 sub\nG81 Z-1 R1\no$1<drill>$1 endsub\no$1<dr$0ill>$1 call\nM2\n",
        false,
    );
    let r = rename::rename(f.snap.program(), f.cursor, "bore")
        .expect("renamed")
        .expect("a name");
    assert_eq!(
        edit_texts(&r.edits),
        vec![
            (f.mark(0), "<bore>".to_string()),
            (f.mark(1), "<bore>".to_string()),
            (f.mark(2), "<bore>".to_string())
        ]
    );
    assert_eq!(
        r.subroutine,
        Some(rename::SubroutineFile {
            old: "drill.ngc".to_string(),
            new: Some("bore.ngc".to_string())
        })
    );
    let caller = program_of(Dialect::Rs274ngc, "G0 X0\no<drill> call\nM2\n");
    assert_eq!(
        r.edits_in(&caller),
        Ok(Some(vec![analyzer::TextEdit {
            span: Span::new(7, 14),
            new_text: "<bore>".to_string()
        }]))
    );
    let unrelated = program_of(Dialect::Rs274ngc, "o<other> call\nM2\n");
    assert_eq!(r.edits_in(&unrelated), Ok(None));
    // A numbered label is no file's name.
    let f = fixture(Dialect::Rs274ngc, "o1$000 sub\no100 endsub\nM2\n", false);
    let r = rename::rename(f.snap.program(), f.cursor, "o200")
        .expect("renamed")
        .expect("a name");
    assert_eq!(r.edits.len(), 2);
    assert_eq!(r.subroutine, None);
}

#[test]
fn renames_refused_with_their_reason() {
    let f = fixture(Dialect::Fanuc, "%\nO0001;\n#1$00=1.;\nM30;\n%\n", false);
    let why = "numbered variables are memory cells, not names: #100 is the same cell in every program and macro, so it cannot be renamed";
    assert_eq!(
        rename::prepare(f.snap.program(), f.cursor),
        Some(Err(why.to_string()))
    );
    assert_eq!(
        rename::rename(f.snap.program(), f.cursor, "#<x>"),
        Err(why.to_string())
    );
    let f = fixture(Dialect::Rs274ngc, "#<a> = 1\n#<b> = #<$0a>\nM2\n", false);
    assert_eq!(
        rename::rename(f.snap.program(), f.cursor, "b"),
        Err("`#<b>` is already used in this file".to_string())
    );
}
