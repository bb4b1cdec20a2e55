//! Soak test: thousands of seeded random edits to open documents in all three
//! dialects through the real `partscope lsp` over stdio. After each batch the
//! diagnostics the server published for each document's latest version must
//! equal what `partscope check` reports for the same text, and the server's
//! resident memory must stay bounded (no growth with the number of edits).
//!
//! `cargo test -p partscope --test lsp_soak` runs a short version (CI);
//! `cargo test -p partscope --test lsp_soak -- --ignored` the 10 000-edit one.
//! `PARTSCOPE_SOAK_EDITS=N` overrides the number of edits of the long run.

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use harness::Client;
use serde_json::{json, Value};

#[path = "../../tests/common/rng.rs"]
mod rng;
use rng::Rng;

/// Text the edits insert: words, whole blocks, broken syntax, expressions
/// and a non-ASCII comment (positions are UTF-16 on the wire). No loops,
/// jumps or subprogram calls, so every version runs to its end quickly.
const FRAGMENTS: &[&str] = &[
    "G1 X10 Y5 F300\n",
    "G0 Z5\n",
    "G2 X0 Y0 I5 J0\n",
    "G3 X1 Y1 R0.5\n",
    "G2 X0 Y0 R0\n",
    "G17 G90 G21\n",
    "G41 D1\n",
    "G40\n",
    "T2 M6\n",
    "S1200 M3\n",
    "M5\n",
    "G81 R2 Z-3 F100\n",
    "G80\n",
    " X",
    " Y-1.5",
    " Z1e308",
    " F0",
    "G4 P1\n",
    "(comment)",
    "(unclosed ",
    "(é€ ü)\n",
    "#1=[1/0]\n",
    "#2=#1+3\n",
    "X[#2*2]\n",
    "G1 G0 X1\n",
    "\n",
    "%",
    ";",
    "]",
    "[",
    "G",
    "1",
    ".",
    "-",
];

struct Doc {
    uri: String,
    path: PathBuf,
    text: String,
    version: i64,
    /// The diagnostics received for `version`, once received. The server
    /// publishes each version once: a document that no edit of a batch
    /// touched (it happens: seed 2026 leaves part.ngc alone for the 25 edits
    /// up to edit 7925) has nothing new to wait for, and waiting for a second
    /// publish of the same version would time out.
    received: Option<(i64, Vec<Key>)>,
}

/// The LSP position (line, UTF-16 column) of byte offset `at`.
fn position(text: &str, at: usize) -> Value {
    let before = &text[..at];
    let line = before.matches('\n').count();
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let character: usize = before[line_start..].chars().map(char::len_utf16).sum();
    json!({"line": line, "character": character})
}

/// A random character boundary of `text`.
fn boundary(rng: &mut Rng, text: &str) -> usize {
    let mut at = rng.below(text.len() + 1);
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// One random edit: replace a short range (often empty: an insertion) with a
/// fragment or nothing (a deletion). Applied to our copy and sent.
fn edit(c: &mut Client, rng: &mut Rng, doc: &mut Doc) {
    let a = boundary(rng, &doc.text);
    let span = match rng.below(4) {
        0 => 0,
        1 => rng.below(4),
        2 => rng.below(16),
        _ => rng.below(48),
    };
    let mut b = (a + span).min(doc.text.len());
    while !doc.text.is_char_boundary(b) {
        b += 1;
    }
    // Deletions only while the document is large, so it neither vanishes nor
    // grows without bound over thousands of edits.
    let insert = if rng.below(3) == 0 && doc.text.len() > 1500 {
        ""
    } else {
        FRAGMENTS[rng.below(FRAGMENTS.len())]
    };
    let range = json!({"start": position(&doc.text, a), "end": position(&doc.text, b)});
    doc.text.replace_range(a..b, insert);
    doc.version += 1;
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc.uri, "version": doc.version},
               "contentChanges": [{"range": range, "text": insert}]}),
    );
}

/// A diagnostic as both sides can state it: code, 0-based start and end line,
/// severity (LSP numbering).
type Key = (String, u64, u64, u64);

/// User + system CPU time of a process in clock ticks, from /proc.
fn cpu_ticks(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
}

fn published(c: &mut Client, doc: &mut Doc, done: usize) -> Vec<Key> {
    if let Some((v, keys)) = &doc.received {
        if *v == doc.version {
            return keys.clone();
        }
    }
    let cpu_before = cpu_ticks(c.pid());
    let p = c
        .wait_within(
            "textDocument/publishDiagnostics",
            &|p| p["uri"] == doc.uri.as_str() && p["version"] == doc.version,
            Duration::from_secs(60),
        )
        .unwrap_or_else(|| {
            let last = c.pending.iter().rev().find(|m| {
                m["method"] == "textDocument/publishDiagnostics"
                    && m["params"]["uri"] == doc.uri.as_str()
            });
            let last = last.map_or("none".to_string(), |m| m["params"]["version"].to_string());
            // Whether the server was busy (a slow or endless analysis) or idle
            // (a lost publish) while we waited, and whether it still answers a
            // request (not a deadlock), tell the failures apart.
            let cpu = cpu_ticks(c.pid()).zip(cpu_before).map(|(a, b)| a - b);
            let id = c.send_request(
                "textDocument/documentSymbol",
                json!({"textDocument": {"uri": doc.uri}}),
            );
            let answer: String = c.response(id).to_string().chars().take(200).collect();
            panic!(
                "after {done} edits: no diagnostics for {} v{} within 60 s; last publish for it: \
                 {last}; server CPU ticks during the wait: {cpu:?}; documentSymbol answered: \
                 {answer}; text:\n{}",
                doc.uri, doc.version, doc.text
            )
        });
    let mut keys: Vec<Key> = p["diagnostics"]
        .as_array()
        .expect("diagnostics array")
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap_or("").to_string(),
                d["range"]["start"]["line"].as_u64().expect("line"),
                d["range"]["end"]["line"].as_u64().expect("line"),
                d["severity"].as_u64().expect("severity"),
            )
        })
        .collect();
    keys.sort();
    // Publishes of this document's earlier versions can no longer be asked
    // for; dropping them keeps the client's backlog from growing.
    c.pending.retain(|m| {
        !(m["method"] == "textDocument/publishDiagnostics"
            && m["params"]["uri"] == doc.uri.as_str()
            && m["params"]["version"]
                .as_i64()
                .is_some_and(|v| v <= doc.version))
    });
    doc.received = Some((doc.version, keys.clone()));
    keys
}

/// `partscope check --format json` on the same text.
fn checked(doc: &Doc) -> Vec<Key> {
    std::fs::write(&doc.path, &doc.text).expect("write document copy");
    let out = Command::new(env!("CARGO_BIN_EXE_partscope"))
        .args(["check", "--format", "json"])
        .arg(&doc.path)
        .output()
        .expect("run partscope check");
    assert!(
        matches!(out.status.code(), Some(0 | 1)),
        "check failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("check JSON");
    let mut keys: Vec<Key> = v
        .as_array()
        .expect("array")
        .iter()
        .map(|d| {
            let sev = match d["severity"].as_str() {
                Some("error") => 1,
                Some("warning") => 2,
                Some("info") => 3,
                _ => 4,
            };
            (
                d["code"].as_str().unwrap_or("").to_string(),
                d["line"].as_u64().expect("line") - 1,
                d["end_line"].as_u64().expect("end_line") - 1,
                sev,
            )
        })
        .collect();
    keys.sort();
    keys
}

/// Resident set size of a process in kB, from /proc (Linux only).
fn rss_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

const SERVOWORKS: &str = "G90 G17 G21\nG0 X0 Y0 Z5\nM3 S1000\nG1 Z-1 F200\nG1 X20 Y0\nG2 X20 Y10 I0 J5\nG1 X0 Y10\nG1 X0 Y0\nG0 Z5\nM5\nM2\n";
const RS274NGC: &str = "(partscope soak)\nG21 G90 G17\nT1 M6\nS1200 M3\nG0 X0 Y0 Z5\nG1 Z-1 F150\n#1 = 5\nG1 X[#1*2] Y0\nG3 X10 Y10 R5\nG1 X0\nG0 Z5\nM5\nM2\n";
const FANUC: &str = "O1000\nG21 G90 G17\nT1 M6\nS1500 M3\nG0 X0 Y0 Z5.\nG1 Z-1. F100.\n#100=2.5\nG1 X#100 Y0\nG2 X5. Y2.5 R2.5\nG1 X0\nG0 Z5.\nM5\nM30\n";

/// `text` with `filler` pairs of plain feed blocks before its last block (the
/// program end): a long single-pass program, where the server's interpreter
/// reruns from a checkpoint and stops where the state meets the last run.
fn with_filler(text: &str, filler: usize) -> String {
    let body = text.trim_end_matches('\n');
    let cut = body.rfind('\n').map_or(0, |i| i + 1);
    format!(
        "{}{}{}\n",
        &body[..cut],
        "G1 X1 Y1\nG1 X2 Y1.5\n".repeat(filler),
        &body[cut..]
    )
}

fn soak(edits: usize, batch: usize, seed: u64) {
    soak_with(edits, batch, seed, 0, true);
}

/// `memory`: assert that RSS stays flat. Too short a run of long documents
/// measures the allocator filling its per-thread arenas (the same growth with
/// and without reruns), not a leak, so that test leaves it out.
fn soak_with(edits: usize, batch: usize, seed: u64, filler: usize, memory: bool) {
    let dir =
        std::env::temp_dir().join(format!("partscope-lsp-soak-{seed}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("check")).expect("temp dir");
    let dir = dir.canonicalize().expect("canonical temp dir");
    let root_uri = format!("file://{}", dir.display());

    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({"processId": null, "rootUri": root_uri, "capabilities": {},
               "workspaceFolders": [{"uri": root_uri, "name": "soak"}]}),
    );
    c.notify("initialized", json!({}));

    let mut docs: Vec<Doc> = [
        ("part.nc", "servoworks", SERVOWORKS),
        ("part.ngc", "rs274ngc", RS274NGC),
        ("part.fnc", "fanuc", FANUC),
    ]
    .into_iter()
    .map(|(name, dialect, text)| Doc {
        // The server's copy is only in memory; `check` reads a twin file in
        // a subfolder. No partscope.toml anywhere: both sides take the
        // dialect from the first-line comment, or (once an edit breaks it)
        // from the same extension and content sniffing.
        uri: format!("{root_uri}/{name}"),
        path: dir.join("check").join(name),
        text: format!(
            "(partscope: dialect={dialect})\n{}",
            with_filler(text, filler)
        ),
        version: 1,
        received: None,
    })
    .collect();
    for d in &docs {
        c.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": d.uri, "languageId": "gcode", "version": 1, "text": d.text}}),
        );
    }

    let mut rng = Rng(seed);
    let mut rss = Vec::new();
    let mut done = 0;
    let mut compared = 0;
    let start = Instant::now();
    while done < edits {
        for _ in 0..batch.min(edits - done) {
            let i = rng.below(docs.len());
            edit(&mut c, &mut rng, &mut docs[i]);
            done += 1;
        }
        for d in &mut docs {
            let got = published(&mut c, d, done);
            let want = checked(d);
            assert_eq!(
                got, want,
                "after {done} edits, {} v{}: LSP vs check differ; text:\n{}",
                d.uri, d.version, d.text
            );
            compared += 1;
        }
        if let Some(kb) = rss_kb(c.pid()) {
            rss.push(kb);
        }
        // The long run reports progress so a slow machine is told apart from
        // a hang.
        if rss.len() % 50 == 0 {
            eprintln!(
                "soak: {done} edits, {:.0} s, server RSS {:?} kB",
                start.elapsed().as_secs_f64(),
                rss.last()
            );
        }
    }
    eprintln!(
        "soak: {done} edits, {compared} comparisons, {:.1} s; server RSS kB first/max/last: {:?}/{:?}/{:?}",
        start.elapsed().as_secs_f64(),
        rss.first(),
        rss.iter().max(),
        rss.last()
    );
    // Bounded growth: after the first tenth of the run (allocator warm-up,
    // caches filled), RSS may not grow by more than 32 MB, whatever the
    // number of edits. A leak of one copy of a document per edit would
    // exceed this within a few thousand edits.
    if memory && rss.len() >= 10 {
        let warm = rss[rss.len() / 10];
        let max = rss.iter().copied().max().unwrap_or(0);
        assert!(
            max <= warm + 32 * 1024,
            "server RSS grew from {warm} kB to {max} kB over {done} edits: {rss:?}"
        );
    }
    assert!(c.shutdown().success());
    let _ = std::fs::remove_dir_all(Path::new(&dir));
}

/// Long documents (over 6 000 blocks, several interpreter checkpoints):
/// each version's diagnostics, flow-sensitive ones included, come from a
/// rerun of the previous run and must equal a full `partscope check`.
#[test]
fn random_edits_to_long_documents_rerun_exactly() {
    soak_with(120, 4, 2027, 3000, false);
}

#[test]
fn random_edits_keep_diagnostics_exact_and_memory_flat() {
    soak(600, 20, 7);
}

/// One edit per batch: the two documents it leaves alone are compared again
/// without a new publish (the case that made the 10 000-edit run wait for a
/// publish the server had already sent, at edit 7925).
#[test]
fn documents_left_alone_by_a_batch_keep_their_diagnostics() {
    soak(45, 1, 11);
}

#[test]
#[ignore = "10 000 edits: minutes; run with --ignored and report"]
fn ten_thousand_random_edits() {
    let edits = std::env::var("PARTSCOPE_SOAK_EDITS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    soak(edits, 25, 2026);
}
