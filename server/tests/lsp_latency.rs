//! Edit latency (didChange → publishDiagnostics) on a large generated
//! program. Prints the numbers; asserts only that each edit's diagnostics are
//! the right ones (timings depend on the machine).
//!
//! Default: 100 000 lines. For the 1M-line figure:
//! `LSP_LATENCY_LINES=1000000 cargo test --release -p partscope --test lsp_latency -- --nocapture`

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::fmt::Write as _;
use std::time::Instant;

use harness::Client;
use serde_json::json;

/// A 3D-surfacing-like program: a raster of short G1 moves, as CAM writes them.
fn generate(lines: usize) -> String {
    let mut s = String::with_capacity(lines * 32);
    s.push_str("(generated surfacing program)\nG21 G90 G17\nT1 M6\nS12000 M3\nG0 X0 Y0 Z5\n");
    for i in 5..lines.saturating_sub(1) {
        let x = (i % 500) as f64 * 0.1;
        let y = (i / 500) as f64 * 0.1;
        let z = -((x * 0.3).sin() + (y * 0.2).cos()) * 0.5;
        let _ = writeln!(s, "G1 X{x:.3} Y{y:.3} Z{z:.4} F1200");
    }
    s.push_str("M2\n");
    s
}

#[test]
fn edit_latency_on_a_large_program() {
    let lines: usize = std::env::var("LSP_LATENCY_LINES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(100_000);
    let text = generate(lines);
    let uri = "file:///latency/big.ngc";
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {}}),
    );
    c.notify("initialized", json!({}));
    let t = Instant::now();
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": text}}),
    );
    assert_eq!(c.diagnostics(uri, 1), vec![]);
    let open_ms = t.elapsed().as_secs_f64() * 1e3;

    // Each edit inserts an `A` without a value somewhere in the file (L003),
    // and the next one removes it; diagnostics must follow exactly.
    let mut times = Vec::new();
    for k in 0..6u32 {
        let line = (lines as u32 / 7) * (k / 2 + 1);
        let version = 2 + k as i64;
        let (change, expected) = if k % 2 == 0 {
            (
                json!({"range": {"start": {"line": line, "character": 3}, "end": {"line": line, "character": 3}}, "text": "A "}),
                vec![("L003".to_string(), line as u64)],
            )
        } else {
            (
                json!({"range": {"start": {"line": line, "character": 3}, "end": {"line": line, "character": 5}}, "text": ""}),
                vec![],
            )
        };
        let t = Instant::now();
        c.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri, "version": version}, "contentChanges": [change]}),
        );
        assert_eq!(c.diagnostics(uri, version), expected);
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "lsp latency: {lines} lines, {:.1} MB: open→diagnostics {open_ms:.0} ms; edit→diagnostics min {:.0} ms, median {:.0} ms, max {:.0} ms (includes the 50 ms debounce)",
        text.len() as f64 / 1e6,
        times[0],
        times[times.len() / 2],
        times[times.len() - 1]
    );
    assert!(c.shutdown().success());
}
