//! Edit latency (didChange → publishDiagnostics) on a large generated
//! program. Prints the numbers; asserts only that each edit's diagnostics are
//! the right ones (timings depend on the machine).
//!
//! Default: 20 000 lines and 6 edits (debug builds are slow). For the 100k and
//! 1M figures (a benchmark, not a timed test: it prints median and p90):
//! `LSP_LATENCY_LINES=1000000 LSP_LATENCY_EDITS=40 cargo test --release -p partscope --test lsp_latency -- --nocapture`
//! (1M generated lines are 33 MB, below the default 64 MB `maxFileSize`, so
//! that run measures the full analysis). `LSP_LATENCY_BASE=/path/to/partscope`
//! measures that binary (another build, e.g. of main) too, on the same
//! program, base first, and prints the ratio of the medians.

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

/// Opens the program in `partscope lsp` of `bin`, then edits it: the time
/// from didOpen to its diagnostics, and each edit's (sorted).
fn measure(bin: &std::ffi::OsStr, text: &str, lines: usize, edits: u32) -> (f64, Vec<f64>) {
    let uri = "file:///latency/big.ngc";
    let mut c = Client::spawn_binary(bin, &[]);
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
    assert!(c.diagnostics(uri, 1).iter().all(|d| d.0 != "L003"));
    let open_ms = t.elapsed().as_secs_f64() * 1e3;

    // Each edit inserts an `A` without a value somewhere in the file (L003),
    // and the next one removes it; diagnostics must follow exactly.
    let mut times = Vec::new();
    for k in 0..edits {
        // Pairs of edits at lines spread over the file.
        let line = (lines as u32 / (edits / 2 + 1)) * (k / 2 + 1);
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
        // The first publish for the version: the static diagnostics (the
        // interpreter's may follow in a second one).
        let got = c.diagnostics(uri, version);
        let l003: Vec<(String, u64)> = got.into_iter().filter(|d| d.0 == "L003").collect();
        assert_eq!(l003, expected);
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    assert!(c.shutdown().success());
    times.sort_by(f64::total_cmp);
    (open_ms, times)
}

fn percentile(times: &[f64], p: f64) -> f64 {
    times[((times.len() - 1) as f64 * p).round() as usize]
}

#[test]
fn edit_latency_on_a_large_program() {
    let lines: usize = std::env::var("LSP_LATENCY_LINES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20_000);
    let edits: u32 = std::env::var("LSP_LATENCY_EDITS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6);
    let text = generate(lines);
    let mut servers = Vec::new();
    if let Some(base) = std::env::var_os("LSP_LATENCY_BASE") {
        servers.push(("base", base));
    }
    servers.push(("this build", env!("CARGO_BIN_EXE_partscope").into()));
    let mut medians = Vec::new();
    for (name, bin) in &servers {
        let (open_ms, times) = measure(bin, &text, lines, edits);
        println!(
            "lsp latency ({name}): {lines} lines, {:.1} MB: open→diagnostics {open_ms:.0} ms; {} edits→diagnostics min {:.1} ms, median {:.1} ms, p90 {:.1} ms, max {:.1} ms",
            text.len() as f64 / 1e6,
            times.len(),
            times[0],
            percentile(&times, 0.5),
            percentile(&times, 0.9),
            times[times.len() - 1]
        );
        medians.push(percentile(&times, 0.5));
    }
    if let [base, this] = medians[..] {
        println!(
            "median edit latency: base / this build = {:.2}",
            base / this
        );
    }
}
