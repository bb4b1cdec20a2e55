//! Measures parse and static-lint throughput on a file:
//! `cargo run --release -p analyzer --example parse_speed FILE [dialect] [runs]`.
//! (The criterion benchmark is the reference; this is a quick check on real files.)
//!
//! Prints the best of `runs` (default 5) for the parse alone, for the static rules
//! alone (on an already parsed program) and for both, as `analyze` runs them.

use std::time::Instant;

use analyzer::dialect::Dialect;
use analyzer::syntax::{parse, parse_in_two, ParseOptions};
use analyzer::Settings;

// The allocator the `partscope` binary installs, so the figures are the product's.
#[global_allocator]
static ALLOC: analyzer::memory::LargePages = analyzer::memory::LargePages;

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        eprintln!("usage: parse_speed FILE [servoworks|rs274ngc|fanuc] [runs]");
        std::process::exit(2);
    };
    let dialect = args
        .next()
        .and_then(|d| Dialect::parse(&d))
        .unwrap_or(Dialect::Rs274ngc);
    let runs: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(5);
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{path}: {e}");
            std::process::exit(2);
        }
    };
    let text: std::sync::Arc<[u8]> = bytes.into();
    let settings = Settings::new(dialect);
    let mb = text.len() as f64 / 1e6;

    let mut best_parse = f64::INFINITY;
    let mut blocks = 0;
    for _ in 0..runs {
        let t = Instant::now();
        let p = parse(ParseOptions::new(dialect), text.clone());
        best_parse = best_parse.min(t.elapsed().as_secs_f64());
        blocks = p.blocks.len();
    }

    // The same parse in two halves on two threads.
    let mut best_two = f64::INFINITY;
    for _ in 0..runs {
        let t = Instant::now();
        let p = parse_in_two(ParseOptions::new(dialect), text.clone());
        best_two = best_two.min(t.elapsed().as_secs_f64());
        drop(p);
    }

    // Without tokens, as the command line parses.
    let mut best_lean = f64::INFINITY;
    for _ in 0..runs {
        let t = Instant::now();
        let p = analyzer::syntax::parse_lean(ParseOptions::new(dialect), text.clone());
        best_lean = best_lean.min(t.elapsed().as_secs_f64());
        drop(p);
    }

    // Lean, in two halves, as `partscope check` parses large files.
    let mut best_lean_two = f64::INFINITY;
    for _ in 0..runs {
        let t = Instant::now();
        let p = analyzer::syntax::parse_lean_in_two(ParseOptions::new(dialect), text.clone());
        best_lean_two = best_lean_two.min(t.elapsed().as_secs_f64());
        drop(p);
    }

    // The static rules alone, on one parsed program.
    let parsed = analyzer::parse_text(text.clone(), &settings);
    let mut best_lint = f64::INFINITY;
    let mut diags = 0;
    for _ in 0..runs {
        let t = Instant::now();
        let d = analyzer::lint(&parsed, &settings);
        best_lint = best_lint.min(t.elapsed().as_secs_f64());
        diags = d.len();
    }
    drop(parsed);

    let mut best_both = f64::INFINITY;
    for _ in 0..runs {
        let t = Instant::now();
        let a = analyzer::analyze(text.clone(), &settings);
        best_both = best_both.min(t.elapsed().as_secs_f64());
        diags = a.diagnostics.len();
    }
    println!(
        "{} {blocks} blocks, {mb:.1} MB, {diags} diagnostics, best of {runs}: parse {:.1} ms {:.0} MB/s | lean parse {:.1} ms {:.0} MB/s | two-thread parse {:.1} ms {:.0} MB/s | lean two-thread {:.1} ms {:.0} MB/s | lint {:.1} ms {:.0} MB/s | parse+lint {:.1} ms {:.0} MB/s",
        dialect.as_str(),
        best_parse * 1e3,
        mb / best_parse,
        best_lean * 1e3,
        mb / best_lean,
        best_two * 1e3,
        mb / best_two,
        best_lean_two * 1e3,
        mb / best_lean_two,
        best_lint * 1e3,
        mb / best_lint,
        best_both * 1e3,
        mb / best_both
    );
}
