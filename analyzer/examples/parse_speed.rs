//! Measures parse throughput on a file: `cargo run --release -p analyzer --example parse_speed FILE [dialect]`.
//! (The criterion benchmark is the reference; this is a quick check on real files.)

use std::time::Instant;

use analyzer::dialect::Dialect;
use analyzer::syntax::{parse, ParseOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        eprintln!("usage: parse_speed FILE [servoworks|rs274ngc|fanuc]");
        std::process::exit(2);
    };
    let dialect = args
        .next()
        .and_then(|d| Dialect::parse(&d))
        .unwrap_or(Dialect::Rs274ngc);
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{path}: {e}");
            std::process::exit(2);
        }
    };
    let text: std::sync::Arc<[u8]> = bytes.into();
    let mut best = f64::INFINITY;
    let mut blocks = 0;
    for _ in 0..5 {
        let t = Instant::now();
        let p = parse(ParseOptions::new(dialect), text.clone());
        best = best.min(t.elapsed().as_secs_f64());
        blocks = p.blocks.len();
    }
    let mb = text.len() as f64 / 1e6;
    println!(
        "{blocks} blocks, {mb:.1} MB, best {:.1} ms, {:.0} MB/s",
        best * 1e3,
        mb / best
    );
}
