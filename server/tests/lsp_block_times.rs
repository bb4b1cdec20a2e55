//! Per-block time in inlay hints and hover, and where the time goes in the
//! first line's hover (where the cycle-time lens sits) and the dry-run
//! command's result, over stdio as an editor sees them.
//!
//! The program runs on the built-in FANUC machine (trapezoid planner, X and Y
//! at 100 mm/s and 1000 mm/s², TRAJ 100 mm/s), in exact-stop mode, so every
//! move runs from rest to rest and its time is d/v + v/a (a triangle,
//! 2·sqrt(d/a), when v²/a > d), by 0-based line as LSP counts:
//! - line 3, G0 X10: 2·sqrt(10/1000) = 0.2 s;
//! - line 4, G1 X57 F3000: 47/50 + 50/1000 = 0.99 s (0.94 s at feed);
//! - line 5, G04 X2: 2 s of dwell;
//! - line 6, G1 Y100 F12000 (200 mm/s, capped to 100 by TRAJ): 1 + 0.1 s,
//!   of which 0.5 s at feed and 0.5 s for the cap.
//!
//! Blocks end at 0.2, 1.19, 3.19 and 4.29 s.

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::{Path, PathBuf};

use harness::Client;
use serde_json::{json, Value};

const PROGRAM: &str = "%
O1000;
G21 G90 G94 G61;
G0 X10.;
G1 X57. F3000.;
G04 X2.;
G1 Y100. F12000.;
M30;
%
";

fn folder(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("partscope-lsp-times-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.canonicalize().unwrap()
}

fn uri_of(p: &Path) -> String {
    format!("file://{}", p.display())
}

/// A session with `options` as initializationOptions and the program open.
fn session(name: &str, options: Value) -> (Client, String) {
    let root = folder(name);
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(&root),
            "capabilities": {"textDocument": {"hover": {"contentFormat": ["markdown"]}}},
            "workspaceFolders": [{"uri": uri_of(&root), "name": "ws"}],
            "initializationOptions": options,
        }),
    );
    c.notify("initialized", json!({}));
    let path = root.join("O1000.fnc");
    std::fs::write(&path, PROGRAM).unwrap();
    let uri = uri_of(&path);
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": PROGRAM}}),
    );
    assert_eq!(c.diagnostics(&uri, 1), vec![]);
    (c, uri)
}

/// (line, character, label, tooltip) of every inlay hint in the document.
fn hints(c: &mut Client, uri: &str) -> Vec<(u64, u64, String, String)> {
    let r = c.request(
        "textDocument/inlayHint",
        json!({
            "textDocument": {"uri": uri},
            "range": {"start": {"line": 0, "character": 0}, "end": {"line": 9, "character": 0}}
        }),
    );
    r.as_array()
        .unwrap()
        .iter()
        .map(|h| {
            (
                h["position"]["line"].as_u64().unwrap(),
                h["position"]["character"].as_u64().unwrap(),
                h["label"].as_str().unwrap().to_string(),
                h["tooltip"].as_str().unwrap_or_default().to_string(),
            )
        })
        .collect()
}

fn labels(h: &[(u64, u64, String, String)]) -> Vec<(u64, u64, &str)> {
    h.iter()
        .map(|(l, ch, s, _)| (*l, *ch, s.as_str()))
        .collect()
}

#[test]
fn inlay_hints_show_each_blocks_time() {
    let (mut c, uri) = session("block", json!({}));
    let h = hints(&mut c, &uri);
    // At the end of each line (after the `;`), the block's own time.
    assert_eq!(
        labels(&h),
        vec![
            (3, 8, "0.200 s"),
            (4, 15, "0.990 s"),
            (5, 8, "2.000 s"),
            (6, 17, "1.100 s"),
        ]
    );
    assert_eq!(
        h[1].3,
        "0.940 s at feed, 0.050 s acceleration; ends at 0:01.2"
    );
    assert_eq!(
        h[3].3,
        "0.500 s at feed, 0.100 s acceleration, 0.500 s TRAJ velocity cap; ends at 0:04.3"
    );
    assert_eq!(h[0].3, "0.200 s rapid; ends at 0:00.2");
    assert_eq!(h[2].3, "2.000 s dwell; ends at 0:03.2");

    // Hover on a block adds its time; on the first line, where the time goes.
    let hover = |c: &mut Client, line: u32| {
        let r = c.request(
            "textDocument/hover",
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": 1}}),
        );
        r["contents"]["value"]
            .as_str()
            .unwrap_or_default()
            .to_string()
    };
    let md = hover(&mut c, 4);
    assert!(
        md.contains("Time: 0.990 s (0.940 s at feed, 0.050 s acceleration), ends at 0:01.2"),
        "{md}"
    );
    let md = hover(&mut c, 0);
    for line in [
        "**Where the time goes**",
        "- cutting at programmed feed: 1.440 s",
        "- limited by acceleration: 0.150 s",
        "- limited by the TRAJ velocity cap: 0.500 s",
        "- rapids: 0.200 s",
        "- dwell: 2.000 s",
        "1 move programmed above the TRAJ velocity cap of F6000 cost 0.500 s: 24 % of cutting time",
    ] {
        assert!(md.contains(line), "{line}\n{md}");
    }

    // The lens's command returns the breakdown.
    let r = c.request(
        "workspace/executeCommand",
        json!({"command": "partscope.dryRun", "arguments": [uri]}),
    );
    let parts = &r["breakdown"]["parts"];
    let close = |k: &str, want: f64| {
        let got = parts[k].as_f64().unwrap_or(f64::NAN);
        assert!((got - want).abs() < 1e-9, "{k}: {got} vs {want}");
    };
    close("feed_s", 1.44);
    close("accel_s", 0.15);
    close("traj_cap_s", 0.5);
    close("rapid_s", 0.2);
    close("dwell_s", 2.0);
    close("corner_s", 0.0);
    assert_eq!(
        r["breakdown"]["top_causes"][0],
        "1 move programmed above the TRAJ velocity cap of F6000 cost 0.500 s: 24 % of cutting time"
    );

    // Turned off through the configuration, only the tool-change hints stay
    // (none here).
    c.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"partscope": {"blockTimes": "off"}}}),
    );
    assert_eq!(hints(&mut c, &uri), vec![]);
    assert!(c.shutdown().success());
}

#[test]
fn inlay_hints_show_cumulative_time_when_asked() {
    let (mut c, uri) = session("cumulative", json!({"blockTimes": "cumulative"}));
    assert_eq!(
        labels(&hints(&mut c, &uri)),
        vec![
            (3, 8, "ends at 0:00.2"),
            (4, 15, "ends at 0:01.2"),
            (5, 8, "ends at 0:03.2"),
            (6, 17, "ends at 0:04.3"),
        ]
    );
    assert!(c.shutdown().success());
}

#[test]
fn the_lens_shows_the_breakdown_when_clicked() {
    let (mut c, uri) = session("breakdown", json!({}));
    let lens = c.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": uri}}),
    );
    let cmd = &lens[0]["command"];
    assert_eq!(
        cmd["title"],
        "Cycle time 0:04.3 (cutting 0:02.1, rapid 0:00.2, tool change 0:00.0)"
    );
    assert_eq!(cmd["command"], "partscope.showBreakdown");
    assert_eq!(cmd["arguments"], json!([uri]));

    // Clicking runs the lens's own command: the server shows the breakdown
    // and answers with it.
    let r = c.request(
        "workspace/executeCommand",
        json!({"command": cmd["command"], "arguments": cmd["arguments"]}),
    );
    let want = "O1000.fnc: cycle time 0:04.3 (4.290 s)
  cutting         0:02.1
  rapid           0:00.2
  dwell           0:02.0
  tool change     0:00.0
  distance         157.0 mm
where the time goes
  cutting at programmed feed             1.440 s  33.6 %
  limited by acceleration                0.150 s   3.5 %
  limited by the TRAJ velocity cap       0.500 s  11.7 %
  rapids                                 0.200 s   4.7 %
  dwell                                  2.000 s  46.6 %
  - 1 move programmed above the TRAJ velocity cap of F6000 cost 0.500 s: 24 % of cutting time
  - ramps at the acceleration limit (2 moves, at starts, stops and short moves) cost 0.150 s: 7.2 % of cutting time";
    assert_eq!(r["text"], want, "{}", r["text"].as_str().unwrap_or(""));
    assert_eq!(r["uri"], uri);
    assert!(
        (r["cycle_time_s"].as_f64().unwrap() - 4.29).abs() < 1e-9,
        "{r}"
    );
    assert_eq!(r["complete"], true);
    assert_eq!(r["distance_mm"], 157.0);
    let shown = c.wait_for("window/showMessage", |p| p["message"] == want);
    assert_eq!(shown["type"], 3);

    // A client that shows the answer itself asks for no message; without a
    // document the command takes the one last opened or edited.
    let quiet = c.request(
        "workspace/executeCommand",
        json!({"command": "partscope.showBreakdown", "arguments": [null, {"show": false}]}),
    );
    assert_eq!(quiet, r);
    let none = c.wait_within(
        "window/showMessage",
        &|_| true,
        std::time::Duration::from_millis(300),
    );
    assert_eq!(none, None);
    // Helix sends the command with no arguments at all.
    let bare = c.request(
        "workspace/executeCommand",
        json!({"command": "partscope.showBreakdown"}),
    );
    assert_eq!(bare, r);
    c.wait_for("window/showMessage", |p| p["message"] == want);
    let bad = c.request_full(
        "workspace/executeCommand",
        json!({"command": "partscope.showBreakdown", "arguments": [42]}),
    );
    assert_eq!(bad["error"]["code"], -32602, "{bad}");
    assert!(c.shutdown().success());
}
