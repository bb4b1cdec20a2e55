//! Times each enabled whole-file rule, `dead_blocks`, the suppression scan and
//! `finish` on FILE (RS274/NGC): `cargo run --release -p analyzer --example rule_times FILE`.
//! Shows which whole-file passes an incremental update pays for.

use std::sync::Arc;
use std::time::Instant;

use analyzer::rules::{self, ProgramCx};
use analyzer::{Dialect, Settings};

fn main() {
    let path = std::env::args().nth(1).expect("usage: rule_times FILE");
    let text: Arc<[u8]> = Arc::from(std::fs::read(&path).expect("read FILE"));
    let settings = Settings::new(Dialect::Rs274ngc);
    let a = analyzer::analyze(text, &settings);
    let p = &a.program;
    let cx = ProgramCx::new(p, &settings);
    let mut rows = Vec::new();
    for r in rules::enabled_rules(&settings) {
        let mut out = Vec::new();
        let t = Instant::now();
        r.check_program(&cx, &mut out);
        rows.push((t.elapsed(), r.meta().code, out.len()));
    }
    let t = Instant::now();
    let sk = rules::skipped_blocks(p);
    rows.push((t.elapsed(), "skipped_blocks", sk.len()));
    let t = Instant::now();
    let f = analyzer::finish(p, &settings, a.diagnostics.clone());
    rows.push((t.elapsed(), "finish", f.len()));
    rows.sort();
    for (t, code, n) in rows.iter().rev().take(20) {
        println!("{code:>16} {t:>12.2?} ({n})");
    }
}
