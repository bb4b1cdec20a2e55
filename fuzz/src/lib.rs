//! Shared properties checked by the fuzz targets. Each target feeds bytes in;
//! these functions panic (and so report a crash to libFuzzer) when a property
//! of the syntax tree or the analysis breaks.

use std::sync::Arc;

use analyzer::dialect::{variants_of, Dialect};
use analyzer::syntax::{parse, ParseOptions, Parser, Program};
use analyzer::Settings;

/// Asserts the lossless property and that every span stays inside the text.
pub fn check_tree(program: &Program, input: &[u8]) {
    assert_eq!(program.print(), input, "print(parse(s)) != s");
    if let Some(first) = program.tokens.first() {
        assert_eq!(first.start, 0, "first token must start at byte 0");
    }
    for w in program.tokens.windows(2) {
        assert!(w[0].start < w[1].start, "tokens not strictly increasing");
    }
    let len = input.len() as u32;
    for b in &program.blocks {
        assert!(b.span.start <= b.span.end && b.span.end <= b.end().end && b.end().end <= len);
        for it in program.items_of(b) {
            assert!(it.span.start >= b.span.start && it.span.end <= b.span.end);
        }
    }
    for e in &program.exprs {
        assert!(e.span.start <= e.span.end && e.span.end <= len);
    }
    for d in &program.diagnostics {
        assert!(d.span.start <= d.span.end && d.span.end <= len);
    }
}

/// Parses `data` whole and in small resumable chunks (the streaming path the
/// CLI uses on huge files); both must agree and satisfy [`check_tree`]. Then
/// runs the full static analysis, whose diagnostics must stay inside the text.
pub fn parse_and_analyze(dialect: Dialect, variant_pick: u8, data: &[u8]) {
    let variants = variants_of(dialect);
    let variant = variants[variant_pick as usize % variants.len()];
    let opts = ParseOptions { dialect, variant };
    let text: Arc<[u8]> = Arc::from(data);
    let whole = parse(opts, text.clone());
    check_tree(&whole, data);

    let mut chunked = Program {
        dialect,
        text: text.clone(),
        tokens: Vec::new(),
        blocks: Vec::new(),
        items: Vec::new(),
        exprs: Vec::new(),
        expr_lists: Vec::new(),
        diagnostics: Vec::new(),
    };
    let mut parser = Parser::new(opts, text.clone());
    while parser.parse_blocks(&mut chunked, 3) > 0 {}
    assert!(parser.is_done());
    assert_eq!(
        chunked.tokens.len(),
        whole.tokens.len(),
        "chunked parse differs"
    );
    assert_eq!(
        chunked.blocks.len(),
        whole.blocks.len(),
        "chunked parse differs"
    );
    assert_eq!(chunked.diagnostics.len(), whole.diagnostics.len());

    let mut settings = Settings::new(dialect);
    settings.variant = variant;
    let analysis = analyzer::analyze(text, &settings);
    for d in &analysis.diagnostics {
        if d.file == analyzer::FileId(0) {
            assert!(d.span.start <= d.span.end && d.span.end as usize <= data.len());
        }
    }
}

/// Picks a dialect from the first byte of the input, so one target explores
/// all three with one corpus.
pub fn split_dialect(data: &[u8]) -> Option<(Dialect, u8, &[u8])> {
    let (&first, rest) = data.split_first()?;
    let dialect = Dialect::ALL[(first % 3) as usize];
    Some((dialect, first / 3, rest))
}

/// Executes the program with no subprogram files, a small step budget and
/// the dialect's default machine, then plans it and samples the toolpath.
/// Every diagnostic must be located inside its file, and the cycle time must
/// be a finite, non-negative number whatever the input (1e308 coordinates,
/// division by zero, zero-length arcs).
pub fn interpret(dialect: Dialect, variant_pick: u8, data: &[u8]) {
    let variants = variants_of(dialect);
    let variant = variants[variant_pick as usize % variants.len()];
    let mut settings = Settings::new(dialect);
    settings.variant = variant;
    let program = parse(ParseOptions { dialect, variant }, Arc::<[u8]>::from(data));
    let machine = toml::Table::new();
    let input = runtime::RunInput {
        program: &program,
        settings: &settings,
        machine: &machine,
        resolver: &runtime::NoResolver,
        step_budget: 2_000,
        motion_budget: 20_000,
        emit_canon: variant_pick & 1 == 1,
        tool_table: None,
        var_file: None,
    };
    let out = runtime::run(&input);
    for d in &out.diagnostics {
        if d.file == analyzer::FileId(0) {
            assert!(d.span.start <= d.span.end && d.span.end as usize <= data.len());
        }
    }
    // The closed-form planner first: its cost does not grow with the motion
    // time. The servo-period simulation steps once per millisecond of motion,
    // so a fuzzed 1e6 mm move at F1 would spend seconds there; it runs only
    // when the program moves for under a minute, which covers its code paths
    // at a few thousand periods per input.
    let mut profile = runtime::machine::MachineProfile::default_for(dialect);
    profile.servo_simulation = false;
    let dry = runtime::dryrun::plan_run(&out, &profile);
    let t = dry.totals.cycle_time_s;
    assert!(t.is_finite() && t >= 0.0, "cycle time {t}");
    if t < 60.0 {
        profile.servo_simulation = true;
        let servo = runtime::dryrun::plan_run(&out, &profile)
            .totals
            .cycle_time_s;
        assert!(
            servo.is_finite() && servo >= 0.0,
            "servo cycle time {servo}"
        );
    }
    let _ = runtime::dryrun::toolpath(&out, 0.05);
}
