//! Measures parse and static-lint throughput on a file:
//! `cargo run --release -p analyzer --example parse_speed FILE [dialect] [runs]`.
//! (The criterion benchmark is the reference; this is a quick check on real files.)
//!
//! Prints the best of `runs` (default 5) for the parse alone, for the static rules
//! alone (on an already parsed program) and for both, as `analyze` runs them.

use std::time::Instant;

use analyzer::dialect::Dialect;
use analyzer::syntax::{parse, ParseOptions};
use analyzer::Settings;

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

    let mut blocks = 0;
    let best_parse = best_of(
        runs,
        || parse(ParseOptions::new(dialect), text.clone()),
        |p| blocks = p.blocks.len(),
    );
    // Without tokens, as the command line parses.
    let best_lean = best_of(
        runs,
        || analyzer::syntax::parse_lean(ParseOptions::new(dialect), text.clone()),
        drop,
    );

    // The static rules alone, on one parsed program.
    let parsed = analyzer::parse_text(text.clone(), &settings);
    let mut diags = 0;
    let best_lint = best_of(
        runs,
        || analyzer::lint(&parsed, &settings),
        |d| diags = d.len(),
    );
    drop(parsed);

    let best_both = best_of(
        runs,
        || analyzer::analyze(text.clone(), &settings),
        |a| diags = a.diagnostics.len(),
    );
    println!(
        "{} {blocks} blocks, {mb:.1} MB, {diags} diagnostics, best of {runs}: parse {:.1} ms {:.0} MB/s | lean parse {:.1} ms {:.0} MB/s | lint {:.1} ms {:.0} MB/s | parse+lint {:.1} ms {:.0} MB/s",
        dialect.as_str(),
        best_parse * 1e3,
        mb / best_parse,
        best_lean * 1e3,
        mb / best_lean,
        best_lint * 1e3,
        mb / best_lint,
        best_both * 1e3,
        mb / best_both
    );
}

/// The shortest of `runs` timings of `f`, in seconds; each result is handed to
/// `after` once its time is taken (so dropping a tree is not timed).
fn best_of<T>(runs: usize, mut f: impl FnMut() -> T, mut after: impl FnMut(T)) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..runs {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        after(r);
    }
    best
}
