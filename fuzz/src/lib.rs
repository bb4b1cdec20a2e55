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
        base: 0,
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
    let machine = analyzer::config::MachineConfig::default();
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

/// A program built from the bytes by a small grammar of the constructs whose depth or
/// length input controls: bracket nesting, operator chains, `##…#` references,
/// nested loops (O-word `while` / Macro B `WHILE … DOm`), loops with huge counts,
/// canned cycles with huge repeat counts, recursive calls, backward GOTOs, and plain
/// motion between them. Random bytes rarely reach these shapes; this makes every
/// input one of them. Returns the dialect and the text.
pub fn structured_program(data: &[u8]) -> Option<(Dialect, u8, String)> {
    let (dialect, variant, rest) = split_dialect(data)?;
    let mut bytes = rest.iter().copied();
    let mut next = move || bytes.next();
    let mut out = String::new();
    let ngc = dialect == Dialect::Rs274ngc;
    if !ngc {
        out.push_str("%\nO1000\n");
    }
    let mut open: Vec<(u8, u32)> = Vec::new();
    let mut label = 100u32;
    while let Some(op) = next() {
        let n = u32::from(next().unwrap_or(0));
        match op % 10 {
            0 => {
                let d = (n * 3) as usize;
                out.push_str(&format!("G1 X{}1{} F100\n", "[".repeat(d), "]".repeat(d)));
            }
            1 => {
                let terms = (n * 4) as usize;
                out.push_str(&format!("#1 = 1{}\n", "+1".repeat(terms)));
            }
            2 => {
                let d = (n * 2) as usize;
                out.push_str(&format!("#2 = {}1\n", "#".repeat(d.max(1))));
            }
            3 => {
                // Open a loop counting #(10+depth) up to 10^(n % 7).
                let var = 10 + open.len() as u32;
                let limit = 10u32.pow(n % 7);
                out.push_str(&format!("#{var} = 0\n"));
                if ngc {
                    out.push_str(&format!("o{label} while [#{var} LT {limit}]\n"));
                } else {
                    let m = (open.len() % 3) + 1;
                    out.push_str(&format!("WHILE [#{var} LT {limit}] DO{m}\n"));
                }
                out.push_str(&format!("#{var} = [#{var} + 1]\n"));
                open.push((0, label));
                label += 1;
            }
            4 => {
                if let Some((_, l)) = open.pop() {
                    if ngc {
                        out.push_str(&format!("o{l} endwhile\n"));
                    } else {
                        out.push_str(&format!("END{}\n", (open.len() % 3) + 1));
                    }
                }
            }
            5 => {
                let l = 10u64.pow(n % 9);
                out.push_str(&format!("G91 G81 X1 Y1 Z-1 R1 L{l} F100\nG80 G90\n"));
            }
            6 => {
                if ngc {
                    out.push_str(&format!(
                        "o{label} sub\no{label} call\no{label} endsub\no{label} call\n"
                    ));
                    label += 1;
                } else {
                    out.push_str(&format!("N{n} G1 X{n} F100\nGOTO {n}\n"));
                }
            }
            7 => out.push_str(&format!("G2 X{} Y0 R{}\n", n % 7, f64::from(n) * 1e3)),
            8 => out.push_str(&format!(
                "G1 X{}.{} Y-{} Z{} F{}\n",
                n,
                n % 10,
                n / 3,
                n % 5,
                n * 7 + 1
            )),
            _ => out.push_str(&format!(
                "#{} = #{} * 2 + {}\n",
                100 + n % 50,
                100 + n % 7,
                n
            )),
        }
        if out.len() > 64 * 1024 {
            break;
        }
    }
    out.push_str(if ngc { "M2\n" } else { "M30\n%\n" });
    Some((dialect, variant, out))
}
