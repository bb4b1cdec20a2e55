//! The editor dry run is bounded and live (issue 20 item 1): the toolpath of
//! `partscope/dryRun` is decimated to the view's tolerance and capped in size,
//! and a newer request for a document supersedes the older one.

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use harness::Client;
use serde_json::{json, Value};

fn workspace(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "partscope-lsp-bounds-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.canonicalize().unwrap()
}

fn uri_of(p: &Path) -> String {
    format!("file://{}", p.display())
}

fn start(root: &Path, options: Value) -> Client {
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(root),
            "capabilities": {},
            "initializationOptions": options,
        }),
    );
    c.notify("initialized", json!({}));
    c
}

fn open(c: &mut Client, uri: &str, text: &str) {
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": text}}),
    );
}

/// A sine wave of `n` feed moves, 0.05 mm apart in X (1000 mm for 20 000),
/// 10 mm high: the end point of every line that moves, by 0-based line.
fn sine(n: usize) -> (String, Vec<(u32, [f64; 3])>) {
    let mut text = String::from("G21 G90 G17 F1000\nG0 X0 Y0 Z1\nG1 Z0\n");
    let mut ends = vec![(2, [0.0, 0.0, 0.0])];
    for i in 1..=n {
        let (x, y) = (
            format!("{:.4}", i as f64 * 0.05),
            format!("{:.4}", (i as f64 * 0.05).sin() * 10.0),
        );
        text.push_str(&format!("G1 X{x} Y{y}\n"));
        ends.push((2 + i as u32, [x.parse().unwrap(), y.parse().unwrap(), 0.0]));
    }
    text.push_str("M2\n");
    (text, ends)
}

fn dist_to_segment(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab: Vec<f64> = (0..3).map(|k| b[k] - a[k]).collect();
    let ap: Vec<f64> = (0..3).map(|k| p[k] - a[k]).collect();
    let len2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if len2 > 0.0 {
        ((0..3).map(|k| ap[k] * ab[k]).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|k| (ap[k] - t * ab[k]).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn point(v: &Value) -> [f64; 3] {
    [0, 1, 2].map(|k| v[k].as_f64().unwrap())
}

/// Every programmed end point lies within `tolerance` of the piece of the
/// drawn polyline that holds its line (the piece ending at the first kept
/// point, after the first, whose line is at or after it).
fn assert_within(seg: &Value, ends: &[(u32, [f64; 3])], tolerance: f64) {
    let pts: Vec<[f64; 3]> = seg["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(point)
        .collect();
    let lines: Vec<u64> = seg["lines"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_u64().unwrap())
        .collect();
    assert_eq!(pts.len(), lines.len());
    for (line, p) in ends {
        // `lines[0]` is the line of the motion that starts at the first point.
        let j = 1 + lines[1..].partition_point(|l| *l < u64::from(*line));
        let d = dist_to_segment(p, &pts[j - 1], &pts[j]);
        // Output coordinates are rounded to 0.1 µm.
        assert!(
            d <= tolerance + 1e-4,
            "line {} at {p:?} is {d} mm from the drawn path (tolerance {tolerance})",
            line + 1
        );
    }
}

#[test]
fn the_toolpath_is_decimated_to_the_view_tolerance_and_capped() {
    let root = workspace("decimate");
    let (text, ends) = sine(20_000);
    let mut c = start(&root, json!({}));
    let uri = uri_of(&root.join("sine.ngc"));
    open(&mut c, &uri, &text);
    let dry_run = |c: &mut Client, extra: Value| {
        let mut params = json!({"textDocument": {"uri": uri}});
        params
            .as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        c.request("partscope/dryRun", params)
    };

    // The default: the part's extent (1000 mm along X) over 2000.
    let r = dry_run(&mut c, json!({}));
    assert_eq!(r["toolpath"]["bounds"]["max"][0], 1000.0);
    let d = &r["decimation"];
    assert_eq!(d["requested_tolerance_mm"], 0.5);
    assert_eq!(d["tolerance_mm"], 0.5);
    assert_eq!(d["motions"], 20_002);
    assert_eq!(d["points_in"], 40_004);
    assert_eq!(
        (d["decimated"].as_bool(), d["capped"].as_bool()),
        (Some(true), Some(false))
    );
    assert_eq!(d["truncated_at_line"], Value::Null);
    let segs = r["toolpath"]["segments"].as_array().unwrap();
    // The rapid alone, as before; the plunge and the wave are one feed run.
    assert_eq!(segs.len(), 2);
    assert_eq!(segs[0]["kind"], "rapid");
    assert_eq!(segs[0]["points"], json!([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]));
    assert!(segs[0].get("lines").is_none());
    assert_eq!(
        (segs[1]["kind"].as_str(), segs[1]["line"].as_u64()),
        (Some("feed"), Some(2))
    );
    let kept = segs[1]["points"].as_array().unwrap().len();
    assert_eq!(d["points_out"], kept as u64 + 2);
    assert_eq!(d["points_dropped"], 40_004 - 2 - kept as u64);
    assert_within(&segs[1], &ends, 0.5);
    // 159 periods of 6.3 mm, 20 mm from crest to trough: at 0.5 mm the
    // crests and troughs are nearly all it takes (a steep chord between them
    // stays within 0.33 mm of the wave).
    assert!((318..400).contains(&kept), "{kept} points kept");
    // Times and length are the whole run's.
    assert!(r["distance_mm"].as_f64().unwrap() > 1000.0);
    assert_eq!(r["complete"], true);

    // A view of 100 pixels: 10 mm.
    let r = dry_run(&mut c, json!({"viewSize": 100}));
    assert_eq!(r["decimation"]["tolerance_mm"], 10.0);
    let coarse = r["toolpath"]["segments"][1]["points"]
        .as_array()
        .unwrap()
        .len();
    assert!(coarse < kept, "{coarse} vs {kept}");
    assert_within(&r["toolpath"]["segments"][1], &ends, 10.0);

    // A cap below what 0.01 mm keeps raises the tolerance until it fits.
    let r = dry_run(&mut c, json!({"tolerance": 0.01, "maxPoints": 1000}));
    let d = &r["decimation"];
    assert_eq!(d["capped"], true);
    assert_eq!(d["requested_tolerance_mm"], 0.01);
    let t = d["tolerance_mm"].as_f64().unwrap();
    assert!(t > 0.01, "{t}");
    let cost = d["points_out"].as_u64().unwrap() + 3 * d["segments_out"].as_u64().unwrap();
    assert!((900..=1000).contains(&cost), "{d}");
    assert_within(&r["toolpath"]["segments"][1], &ends, t);

    // Tolerance 0: every motion whole, one segment each (the old answer).
    let r = dry_run(&mut c, json!({"tolerance": 0, "maxPoints": 1_000_000}));
    assert_eq!(r["decimation"]["decimated"], false);
    let segs = r["toolpath"]["segments"].as_array().unwrap();
    assert_eq!(segs.len(), 20_002);
    assert_eq!(segs[20_001]["line"], 20_002);
    assert_eq!(segs[20_001]["points"][1], json!([1000.0, 8.2688, 0.0]));
    assert!(c.shutdown().success());
}

#[test]
fn the_cap_is_a_setting() {
    let root = workspace("setting");
    let (text, _) = sine(5_000);
    let mut c = start(&root, json!({"maxToolpathPoints": 2000}));
    let uri = uri_of(&root.join("sine.ngc"));
    open(&mut c, &uri, &text);
    let r = c.request(
        "partscope/dryRun",
        json!({"textDocument": {"uri": uri}, "tolerance": 0}),
    );
    let d = &r["decimation"];
    assert_eq!(
        (d["max_points"].as_u64(), d["capped"].as_bool()),
        (Some(2000), Some(true))
    );
    let cost = d["points_out"].as_u64().unwrap() + 3 * d["segments_out"].as_u64().unwrap();
    assert!(cost <= 2000, "{d}");
    assert!(c.shutdown().success());
}

/// The answer to request `id`, also when it came while another was awaited.
fn answer(c: &mut Client, id: i64, timeout: Duration) -> Option<Value> {
    if let Some(i) = c
        .pending
        .iter()
        .position(|m| m.get("id") == Some(&json!(id)))
    {
        return Some(c.pending.remove(i));
    }
    c.response_within(id, timeout)
}

/// An RS274/NGC loop of `n` feed moves.
fn looping(n: u32) -> String {
    format!("#1=0\no100 while [#1 LT {n}]\n#1=[#1+1]\nG1 X[#1 MOD 100] F1000\no100 endwhile\nM2\n")
}

#[test]
fn a_newer_dry_run_supersedes_the_older() {
    let root = workspace("supersede");
    // The document's own run never starts: only the requests run.
    let mut c = start(&root, json!({"maxRunFileSize": 10}));
    let uri = uri_of(&root.join("loop.ngc"));
    open(&mut c, &uri, &looping(100_000));
    let doc = json!({"textDocument": {"uri": uri}});

    // Same version: the older answers -32802, the newer gets the run they share.
    let older = c.send_request("partscope/dryRun", doc.clone());
    let newer = c.send_request("partscope/dryRun", doc.clone());
    let wait = Duration::from_secs(120);
    let r = answer(&mut c, older, wait).expect("no answer to the older request");
    assert_eq!(r["error"]["code"], -32802, "{r}");
    let r = answer(&mut c, newer, wait).expect("no answer to the newer request");
    assert_eq!(r["result"]["version"], 1, "{r}");
    assert_eq!(r["result"]["decimation"]["motions"], 100_000);

    // A newer version: the older request's run (of a program that loops until
    // the step budget, far longer than this test waits) stops.
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": 2},
               "contentChanges": [{"text": looping(1_000_000_000)}]}),
    );
    let older = c.send_request("partscope/dryRun", doc.clone());
    std::thread::sleep(Duration::from_millis(300));
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": 3},
               "contentChanges": [{"text": "G1 X5 F100\nM2\n"}]}),
    );
    let t = Instant::now();
    let newer = c.send_request("partscope/dryRun", doc.clone());
    let r = answer(&mut c, newer, wait).expect("no answer to the newer request");
    assert_eq!(r["result"]["version"], 3, "{r}");
    assert_eq!(
        r["result"]["toolpath"]["segments"][0]["points"],
        json!([[0.0, 0.0, 0.0], [5.0, 0.0, 0.0]])
    );
    let r = answer(&mut c, older, Duration::from_secs(10))
        .expect("the superseded request never answered");
    let took = t.elapsed();
    assert_eq!(r["error"]["code"], -32802, "{r}");
    assert!(took < Duration::from_secs(10), "{took:?}");
    assert!(c.shutdown().success());
}
