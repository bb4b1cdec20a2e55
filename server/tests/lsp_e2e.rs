//! End-to-end: spawn `partscope lsp`, speak LSP over stdio with a tiny
//! harness (Content-Length framing), and check what an editor would see.
//! Fixtures: `tests/lsp/ws` (see its README), copied to a temporary folder.

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::{Path, PathBuf};

use harness::Client;
use serde_json::{json, Value};

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let dest = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &dest);
        } else {
            std::fs::copy(e.path(), dest).unwrap();
        }
    }
}

/// A fresh copy of the fixture workspace.
fn workspace(name: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/lsp/ws");
    let dir = std::env::temp_dir().join(format!("partscope-lsp-e2e-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy_dir(&src, &dir);
    dir.canonicalize().unwrap()
}

fn uri_of(p: &Path) -> String {
    format!("file://{}", p.display())
}

fn initialize(c: &mut Client, root: &Path, options: Value) -> Value {
    let caps = json!({
        "workspace": {"configuration": false, "didChangeWatchedFiles": {"dynamicRegistration": true}},
        "textDocument": {"hover": {"contentFormat": ["markdown"]}}
    });
    let r = c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(root),
            "capabilities": caps,
            "workspaceFolders": [{"uri": uri_of(root), "name": "ws"}],
            "initializationOptions": options,
        }),
    );
    c.notify("initialized", json!({}));
    r
}

fn open(c: &mut Client, path: &Path, language: &str) -> (String, String) {
    let text = std::fs::read_to_string(path).unwrap();
    let uri = uri_of(path);
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": language, "version": 1, "text": text}}),
    );
    (uri, text)
}

fn pos(line: u32, character: u32) -> Value {
    json!({"line": line, "character": character})
}

#[test]
fn editor_session_over_stdio() {
    let root = workspace("session");
    let mut c = Client::spawn();
    let init = initialize(&mut c, &root, json!({}));
    let caps = &init["capabilities"];
    for key in [
        "hoverProvider",
        "completionProvider",
        "definitionProvider",
        "referencesProvider",
        "documentSymbolProvider",
        "semanticTokensProvider",
        "codeActionProvider",
        "inlayHintProvider",
        "foldingRangeProvider",
        "signatureHelpProvider",
        "executeCommandProvider",
    ] {
        assert!(
            caps.get(key).is_some_and(|v| !v.is_null()),
            "capability {key} missing: {caps}"
        );
    }
    assert_eq!(
        caps["executeCommandProvider"]["commands"],
        json!(["partscope.dryRun", "partscope.showBreakdown"])
    );
    assert_eq!(caps["textDocumentSync"]["change"], json!(2));

    // Diagnostics: the unclosed comment on line 3 (0-based 2), and from the
    // interpreter, drill.ngc's G81 running before any F word: reported on the
    // call in this file.
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    assert_eq!(
        c.diagnostics(&uri, 1),
        vec![("F001".to_string(), 1), ("L001".to_string(), 2)]
    );
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 3)}),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.starts_with("**F001** (error): "), "{md}");
    assert!(md.contains("(in drill.ngc, line 2)"), "{md}");

    // The published diagnostic carries its rule link.
    let r = c.request(
        "textDocument/codeAction",
        json!({
            "textDocument": {"uri": uri},
            "range": {"start": pos(2, 0), "end": pos(2, 15)},
            "context": {"diagnostics": []}
        }),
    );
    let actions = r.as_array().unwrap();
    assert_eq!(actions.len(), 1, "{r}");
    assert_eq!(actions[0]["kind"], "quickfix");
    assert_eq!(
        actions[0]["diagnostics"][0]["codeDescription"]["href"],
        "https://partscope.dev/rules/L001"
    );
    let edits = &actions[0]["edit"]["changes"][&uri];
    assert_eq!(edits[0]["newText"], ")");
    assert_eq!(edits[0]["range"]["start"], pos(2, 15));
    // On save, `source.fixAll`: every fix of the file in one action.
    let r = c.request(
        "textDocument/codeAction",
        json!({
            "textDocument": {"uri": uri},
            "range": {"start": pos(0, 0), "end": pos(0, 0)},
            "context": {"diagnostics": [], "only": ["source.fixAll"]}
        }),
    );
    let actions = r.as_array().unwrap();
    assert_eq!(actions.len(), 1, "{r}");
    assert_eq!(actions[0]["kind"], "source.fixAll");
    assert_eq!(
        actions[0]["edit"]["changes"][&uri],
        json!([{"range": {"start": pos(2, 15), "end": pos(2, 15)}, "newText": ")"}])
    );

    // Hover on the G1 of line 4: the code's documentation for rs274ngc.
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(3, 1)}),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.starts_with("**G1** — "), "{md}");
    assert_eq!(h["range"], json!({"start": pos(3, 0), "end": pos(3, 2)}));
    // Hover on the diagnostic: the rule's documentation.
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(2, 8)}),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.starts_with("**L001** (error):"), "{md}");
    assert!(md.contains("unclosed-comment"), "{md}");
    // Hover on an address letter: its meaning in the dialect.
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(3, 7)}),
    );
    assert!(
        h["contents"]["value"]
            .as_str()
            .unwrap()
            .starts_with("**F** — "),
        "{h}"
    );

    // Completion after `G` on line 4 lists G codes (sorted numerically) and no M codes.
    let r = c.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": uri}, "position": pos(3, 1)}),
    );
    let labels: Vec<&str> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    for want in ["G0", "G1", "G2", "G81"] {
        assert!(labels.contains(&want), "{want} not in {labels:?}");
    }
    assert!(labels.iter().all(|l| l.starts_with('G')), "{labels:?}");
    // Completion after `#<` lists the variables of the file.
    let r = c.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": uri}, "position": pos(5, 6)}),
    );
    let labels: Vec<&str> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, vec!["#<depth>"]);

    // Completion after `o<` offers the subroutine files of the folder.
    let r = c.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 2)}),
    );
    let labels: Vec<&str> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, vec!["o<drill>", "o<path>"]);

    // Definition across files: `o<drill> call` → drill.ngc's `o<drill> sub`.
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 3)}),
    );
    assert_eq!(r["uri"], uri_of(&root.join("drill.ngc")));
    assert_eq!(r["range"], json!({"start": pos(0, 0), "end": pos(0, 8)}));
    // A variable's definition is its assignment.
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(5, 8)}),
    );
    assert_eq!(r["range"]["start"], pos(4, 0));
    let r = c.request("textDocument/references", json!({
        "textDocument": {"uri": uri}, "position": pos(5, 8), "context": {"includeDeclaration": true}
    }));
    let lines: Vec<u64> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["range"]["start"]["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, vec![4, 5]);

    // References of the subprogram: the call here and the definition in drill.ngc.
    let r = c.request("textDocument/references", json!({
        "textDocument": {"uri": uri}, "position": pos(1, 3), "context": {"includeDeclaration": true}
    }));
    let locs: Vec<(String, u64)> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|l| {
            (
                l["uri"]
                    .as_str()
                    .unwrap()
                    .rsplit('/')
                    .next()
                    .unwrap()
                    .to_string(),
                l["range"]["start"]["line"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        locs,
        vec![
            ("main.ngc".to_string(), 1),
            ("drill.ngc".to_string(), 0),
            ("drill.ngc".to_string(), 3)
        ]
    );

    // Symbols, folding and semantic tokens answer for the file.
    let (druri, _) = open(&mut c, &root.join("drill.ngc"), "ngc");
    assert_eq!(c.diagnostics(&druri, 1), vec![]);
    let syms = c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": druri}}),
    );
    assert_eq!(syms[0]["name"], "o<drill>");
    assert_eq!(syms[0]["range"]["end"]["line"], 3);
    let folds = c.request(
        "textDocument/foldingRange",
        json!({"textDocument": {"uri": druri}}),
    );
    assert_eq!(folds[0]["startLine"], 0);
    assert_eq!(folds[0]["endLine"], 3);
    let toks = c.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": druri}}),
    );
    let data = toks["data"].as_array().unwrap();
    assert_eq!(data.len() % 5, 0);
    // The first token is the `o` letter at 0:0, one unit long.
    assert_eq!(&data[..3], &[json!(0), json!(0), json!(1)]);
    let hints = c.request(
        "textDocument/inlayHint",
        json!({
            "textDocument": {"uri": druri}, "range": {"start": pos(0, 0), "end": pos(4, 0)}
        }),
    );
    assert_eq!(hints, json!([]));

    // Edits: close the comment (version 2: clean), then break line 4 (version 3).
    c.notify(
        "textDocument/didChange",
        json!({
            "textDocument": {"uri": uri, "version": 2},
            "contentChanges": [{"range": {"start": pos(2, 15), "end": pos(2, 15)}, "text": ")"}]
        }),
    );
    // A request right after the change sees the new text (it waits for the
    // scheduled analysis): the comment is closed, so no L001 under the cursor.
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(2, 8)}),
    );
    assert!(
        h.is_null() || !h["contents"]["value"].as_str().unwrap().contains("L001"),
        "{h}"
    );
    assert_eq!(c.diagnostics(&uri, 2), vec![("F001".to_string(), 1)]);
    c.notify(
        "textDocument/didChange",
        json!({
            "textDocument": {"uri": uri, "version": 3},
            "contentChanges": [
                {"range": {"start": pos(3, 4), "end": pos(3, 5)}, "text": ""},
                {"range": {"start": pos(0, 0), "end": pos(0, 0)}, "text": "(ünïcödé 😀)\n"}
            ]
        }),
    );
    // `G1 X F100` now on line 5: X has no value.
    assert_eq!(
        c.diagnostics(&uri, 3),
        vec![("F001".to_string(), 2), ("L003".to_string(), 4)]
    );

    // Robustness: malformed JSON, an unknown method, out-of-range positions.
    c.send_raw(b"{this is not json");
    let r = c.request_full("partscope/noSuchMethod", json!({}));
    assert_eq!(r["error"]["code"], -32601);
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(999, 999)}),
    );
    assert!(h.is_null() || h["contents"].is_object());
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": "file:///not/open.ngc"}, "position": pos(0, 0)}),
    );
    assert!(h.is_null());
    let r = c.request_full("textDocument/hover", json!({"textDocument": {"uri": uri}}));
    assert_eq!(r["error"]["code"], -32602);
    // Still alive: a normal request after all that.
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": pos(3, 1)}),
    );
    assert!(
        h["contents"]["value"]
            .as_str()
            .unwrap()
            .starts_with("**G0** — "),
        "{h}"
    );

    // The dry run of a clean program: segments, bounds and path length.
    let (puri, _) = open(&mut c, &root.join("path.ngc"), "ngc");
    assert_eq!(c.diagnostics(&puri, 1), vec![]);
    let r = c.request("partscope/dryRun", json!({"textDocument": {"uri": puri}}));
    assert_eq!(r["version"], 1);
    let segs = r["toolpath"]["segments"].as_array().unwrap();
    let kinds: Vec<(&str, u64)> = segs
        .iter()
        .map(|s| (s["kind"].as_str().unwrap(), s["line"].as_u64().unwrap()))
        .collect();
    assert_eq!(
        kinds,
        vec![("rapid", 1), ("feed", 2), ("arc", 3), ("rapid", 4)]
    );
    assert_eq!(segs[0]["points"], json!([[0.0, 0.0, 0.0], [0.0, 0.0, 5.0]]));
    assert_eq!(segs[1]["feed"], 100.0);
    // G2 from (0,0) to (10,0) about (5,0): clockwise, so over the top (Y up to 5).
    let top = segs[2]["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p[1].as_f64().unwrap())
        .fold(f64::MIN, f64::max);
    assert!((top - 5.0).abs() < 0.01, "{top}");
    assert_eq!(r["toolpath"]["bounds"]["min"][2], -1.0);
    assert_eq!(r["toolpath"]["bounds"]["max"][0], 10.0);
    // 5 down + 6 down + a half circle of radius 5 + 6 up (arcs by their true length).
    let d = r["distance_mm"].as_f64().unwrap();
    assert!(
        (d - (17.0 + 5.0 * std::f64::consts::PI)).abs() < 1e-9,
        "{d}"
    );
    // Times from the planner (default rs274ngc machine): 6 + 5π mm of cutting at
    // F100 take at least 13.02 s; the cycle is at least cutting plus rapids.
    eprintln!(
        "dry run times: {}",
        json!({"cycle": r["cycle_time_s"], "cutting": r["cutting_s"], "rapid": r["rapid_s"]})
    );
    let cutting = r["cutting_s"].as_f64().unwrap();
    assert!((13.02..13.3).contains(&cutting), "{cutting}");
    let cycle = r["cycle_time_s"].as_f64().unwrap();
    assert!(
        cycle >= cutting + r["rapid_s"].as_f64().unwrap() - 1e-9,
        "{r}"
    );
    // The code lens shows the cycle time and its breakdown when clicked; the
    // dry-run command returns the whole run.
    let lens = c.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": puri}}),
    );
    assert!(
        lens[0]["command"]["title"]
            .as_str()
            .unwrap()
            .starts_with("Cycle time 0:1"),
        "{lens}"
    );
    assert_eq!(lens[0]["command"]["command"], "partscope.showBreakdown");
    let r2 = c.request(
        "workspace/executeCommand",
        json!({"command": "partscope.dryRun", "arguments": [puri]}),
    );
    assert_eq!(r2, r);
    // Hover shows the state after the block from the interpreter's run.
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": puri}, "position": pos(2, 4)}),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.contains("Position: `X0.000 Y0.000 Z-1.000"), "{md}");

    assert!(c.shutdown().success());
}

#[test]
fn fanuc_subfolder_config_and_program_calls() {
    let root = workspace("fanuc");
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({"dialect": "servoworks"}));
    let (uri, _) = open(&mut c, &root.join("fanuc/O0001.nc"), "gcode");
    assert_eq!(c.diagnostics(&uri, 1), vec![]);
    // The nearest partscope.toml says fanuc: M98 P1234 goes to O1234.nc.
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(3, 5)}),
    );
    assert_eq!(r["uri"], uri_of(&root.join("fanuc/O1234.nc")));
    assert_eq!(r["range"]["start"], pos(1, 0));
    // GOTO 20 → N20.
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(4, 5)}),
    );
    assert_eq!(r["range"], json!({"start": pos(5, 0), "end": pos(5, 3)}));
    // The planned time of the tool change shows at the end of its line.
    let hints = c.request(
        "textDocument/inlayHint",
        json!({
            "textDocument": {"uri": uri}, "range": {"start": pos(0, 0), "end": pos(9, 0)}
        }),
    );
    assert_eq!(hints[0]["position"], pos(2, 7), "{hints}");
    assert_eq!(hints[0]["label"], "tool change at 0:00.0");
    // FANUC writes codes with two digits: completion and hover follow.
    let (suri, _) = open(&mut c, &root.join("fanuc/O1234.nc"), "gcode");
    assert_eq!(c.diagnostics(&suri, 1), vec![]);
    let r = c.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": suri}, "position": pos(2, 1)}),
    );
    let labels: Vec<&str> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert!(
        labels.contains(&"G01") && labels.contains(&"G65"),
        "{labels:?}"
    );
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": suri}, "position": pos(2, 1)}),
    );
    assert!(
        h["contents"]["value"]
            .as_str()
            .unwrap()
            .starts_with("**G01** — "),
        "{h}"
    );
    // Tool sections nest inside the program symbol.
    let syms = c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": uri}}),
    );
    assert_eq!(syms[0]["name"], "O0001");
    assert_eq!(syms[0]["children"][0]["name"], "T1 M6");
    assert!(c.shutdown().success());
}

#[test]
fn config_file_changes_reanalyse_open_documents() {
    let root = workspace("watch");
    std::fs::write(
        root.join("partscope.toml"),
        "dialect = \"rs274ngc\"\n[rules]\nignore = [\"L001\"]\n",
    )
    .unwrap();
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    // The server registers a watcher for partscope.toml.
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    assert_eq!(c.diagnostics(&uri, 1), vec![("F001".to_string(), 1)]);
    std::fs::write(root.join("partscope.toml"), "dialect = \"rs274ngc\"\n").unwrap();
    c.notify(
        "workspace/didChangeWatchedFiles",
        json!({"changes": [{"uri": uri_of(&root.join("partscope.toml")), "type": 2}]}),
    );
    assert_eq!(
        c.diagnostics(&uri, 1),
        vec![("F001".to_string(), 1), ("L001".to_string(), 2)]
    );
    assert!(c.shutdown().success());
}

#[test]
fn size_limit_degrades_to_syntax_only() {
    let root = workspace("limit");
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({"maxFileSize": 100}));
    // main.ngc is above 100 bytes: parsed only, no interpreter (no F001), no
    // dry run, and the editor says so at the top of the file.
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    assert_eq!(
        c.diagnostics(&uri, 1),
        vec![("F004".to_string(), 0), ("L001".to_string(), 2)]
    );
    let r = c.request_full("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    assert_eq!(r["error"]["code"], -32603, "{r}");
    assert!(
        r["error"]["message"]
            .as_str()
            .unwrap()
            .contains("partscope.maxFileSize"),
        "{r}"
    );
    let lens = c.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": uri}}),
    );
    assert!(
        lens[0]["command"]["title"].as_str().unwrap().starts_with(
            "No analysis: the file (0 KB) is above the size limit (0 KB, partscope.maxFileSize)"
        ),
        "{lens}"
    );
    // Navigation still works on the syntax.
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(5, 8)}),
    );
    assert_eq!(r["range"]["start"], pos(4, 0));
    assert!(c.shutdown().success());
}

#[test]
fn workspace_configuration_section_is_read_and_refreshed() {
    let root = workspace("wsconfig");
    let mut c = Client::spawn();
    c.configuration = json!([{"ignore": ["L001"]}]);
    c.request(
        "initialize",
        json!({
            "processId": null,
            "capabilities": {"workspace": {"configuration": true}},
            "workspaceFolders": [{"uri": uri_of(&root), "name": "ws"}],
        }),
    );
    c.notify("initialized", json!({}));
    // The section arrives asynchronously; the server re-analyses open
    // documents when it does.
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    c.diagnostics_become(&uri, 1, &[("F001", 1)]);
    // A pushed configuration replaces the pulled one.
    c.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"partscope": {"ignore": ["F001"]}}}),
    );
    c.diagnostics_become(&uri, 1, &[("L001", 2)]);
    assert!(c.shutdown().success());
}

#[test]
fn servoworks_named_subprogram_file() {
    let root = workspace("sw");
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    let (uri, _) = open(&mut c, &root.join("sw/main.nc"), "gcode");
    // The interpreter runs OMoveXY.dat through the workspace resolver: no diagnostics.
    assert_eq!(c.diagnostics(&uri, 1), vec![]);
    // `M98 PMoveXY` → OMoveXY.dat in the same folder.
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 6)}),
    );
    assert_eq!(r["uri"], uri_of(&root.join("sw/OMoveXY.dat")));
    assert_eq!(r["range"]["start"], pos(0, 0));
    // The dry run includes the subprogram's move.
    let r = c.request("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    let segs = r["toolpath"]["segments"].as_array().unwrap();
    assert_eq!(segs.len(), 1, "{r}");
    assert_eq!(segs[0]["points"][1], json!([10.0, 5.0, 0.0]));
    assert_eq!(segs[0]["feed"], 500.0);
    assert!(c.shutdown().success());
}

#[test]
fn files_outside_the_workspace_are_not_read_until_the_folder_is_added() {
    let root = workspace("folders");
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({"processId": null, "capabilities": {}, "workspaceFolders": []}),
    );
    c.notify("initialized", json!({}));
    // No workspace folder: drill.ngc is not read, so the call cannot be resolved.
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    assert_eq!(
        c.diagnostics(&uri, 1),
        vec![("F002".to_string(), 1), ("L001".to_string(), 2)]
    );
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 3)}),
    );
    assert!(r.is_null(), "{r}");
    c.notify(
        "workspace/didChangeWorkspaceFolders",
        json!({"event": {"added": [{"uri": uri_of(&root), "name": "ws"}], "removed": []}}),
    );
    c.diagnostics_become(&uri, 1, &[("F001", 1), ("L001", 2)]);
    let r = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 3)}),
    );
    assert_eq!(r["uri"], uri_of(&root.join("drill.ngc")));
    assert!(c.shutdown().success());
}

#[test]
fn cancelled_dry_run_answers_request_cancelled_and_the_server_goes_on() {
    let root = workspace("cancel");
    // A program long enough that analysis and run take far longer than the
    // round trip of a cancel notification.
    let mut text = String::from("G21 G90 F1000\n");
    for i in 0..30_000 {
        text.push_str(&format!("G1 X{} Y{}\n", i % 100, i / 100));
    }
    text.push_str("M2\n");
    std::fs::write(root.join("long.ngc"), &text).unwrap();
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    let (uri, _) = open(&mut c, &root.join("long.ngc"), "ngc");
    let id = c.send_request("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    c.notify("$/cancelRequest", json!({"id": id}));
    let r = c.response(id);
    assert_eq!(r["error"]["code"], -32800, "{r}");
    // The document's diagnostics still arrive, and a new dry run completes.
    assert_eq!(c.diagnostics(&uri, 1), vec![]);
    let r = c.request("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    // Every motion ran; the rows' collinear points are left out of the toolpath sent.
    assert_eq!(r["decimation"]["motions"], 30_000);
    assert_eq!(r["decimation"]["points_in"], 60_000);
    assert_eq!(r["decimation"]["decimated"], true);
    assert!(c.shutdown().success());
}

#[test]
fn empty_and_odd_documents_are_served() {
    let root = workspace("odd");
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    for (name, text) in [
        ("empty.ngc", ""),
        (
            "odd.ngc",
            "\u{0}\u{1}G\u{7f}😀\r\r\n#<\n(((\no<\n[[[[\nG1 X#[#[#[1]]]\n",
        ),
    ] {
        let uri = uri_of(&root.join(name));
        c.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": text}}),
        );
        c.wait_for("textDocument/publishDiagnostics", |p| {
            p["uri"] == uri.as_str()
        });
        let doc = json!({"uri": uri});
        for (method, params) in [
            ("textDocument/documentSymbol", json!({"textDocument": doc})),
            ("textDocument/foldingRange", json!({"textDocument": doc})),
            (
                "textDocument/semanticTokens/full",
                json!({"textDocument": doc}),
            ),
            (
                "textDocument/hover",
                json!({"textDocument": doc, "position": pos(1, 1)}),
            ),
            (
                "textDocument/completion",
                json!({"textDocument": doc, "position": pos(2, 2)}),
            ),
            (
                "textDocument/signatureHelp",
                json!({"textDocument": doc, "position": pos(6, 3)}),
            ),
            (
                "textDocument/definition",
                json!({"textDocument": doc, "position": pos(6, 5)}),
            ),
            ("partscope/dryRun", json!({"textDocument": doc})),
        ] {
            let r = c.request_full(method, params);
            assert!(r.get("error").is_none(), "{name} {method}: {r}");
        }
    }
    assert!(c.shutdown().success());
}

#[test]
fn tool_table_named_by_the_config_reaches_the_interpreter() {
    let root = workspace("tools");
    std::fs::create_dir_all(root.join("mill")).unwrap();
    std::fs::write(
        root.join("mill/partscope.toml"),
        "dialect = \"rs274ngc\"\ntool_table = \"tools.tbl\"\n",
    )
    .unwrap();
    std::fs::write(root.join("mill/tools.tbl"), "T1 P1 D6 Z0\n").unwrap();
    std::fs::write(root.join("mill/job.ngc"), "T1 M6\nT2 M6\nM2\n").unwrap();
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    let (uri, _) = open(&mut c, &root.join("mill/job.ngc"), "ngc");
    assert_eq!(c.diagnostics(&uri, 1), vec![("T001".to_string(), 1)]);
    assert!(c.shutdown().success());
}

/// A LinuxCNC `.ini` named by `partscope.toml` (`ini = …`) reaches the
/// interpreter as in `partscope check`: its TOOL_TABLE (relative to the `.ini`)
/// makes an unknown tool an error, and its axis limits are the travel.
#[test]
fn linuxcnc_ini_named_by_the_config_reaches_the_interpreter() {
    let root = workspace("ini");
    std::fs::create_dir_all(root.join("lathe/machine")).unwrap();
    std::fs::write(
        root.join("lathe/partscope.toml"),
        "dialect = \"rs274ngc\"\nini = \"machine/mill.ini\"\n",
    )
    .unwrap();
    std::fs::write(
        root.join("lathe/machine/mill.ini"),
        "[EMCIO]\nTOOL_TABLE = t.tbl\n[TRAJ]\nLINEAR_UNITS = mm\nCOORDINATES = XYZ\nMAX_LINEAR_VELOCITY = 60\n[AXIS_X]\nMIN_LIMIT = -10\nMAX_LIMIT = 100\nMAX_VELOCITY = 200\nMAX_ACCELERATION = 800\n",
    )
    .unwrap();
    std::fs::write(root.join("lathe/machine/t.tbl"), "T1 P1 Z0.5 D0.25\n").unwrap();
    std::fs::write(
        root.join("lathe/job.ngc"),
        "G21 G90\nT1 M6\nG0 X150\nT5 M6\nM2\n",
    )
    .unwrap();
    let (code, diags) = {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_partscope"))
            .args(["check", "--format", "json"])
            .arg(root.join("lathe/job.ngc"))
            .output()
            .unwrap();
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();
        let mut d: Vec<(String, u64)> = v
            .as_array()
            .unwrap()
            .iter()
            .map(|d| {
                (
                    d["code"].as_str().unwrap().to_string(),
                    d["line"].as_u64().unwrap() - 1,
                )
            })
            .collect();
        d.sort();
        (out.status.code(), d)
    };
    assert_eq!(code, Some(1));
    assert!(diags.contains(&("T001".to_string(), 3)), "check: {diags:?}");
    // X150 is beyond the .ini's MAX_LIMIT of 100.
    assert!(diags.iter().any(|d| d.1 == 2), "check: {diags:?}");
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    let (uri, _) = open(&mut c, &root.join("lathe/job.ngc"), "ngc");
    let mut got = c.diagnostics(&uri, 1);
    got.sort();
    assert_eq!(got, diags, "the language server and check agree");
    // The cycle time is the same machine's too: the ini's limits (60 mm/s, not
    // the default 100) with the config's own times over them, as `partscope run`.
    std::fs::write(
        root.join("lathe/partscope.toml"),
        "dialect = \"rs274ngc\"\nini = \"machine/mill.ini\"\n[machine]\ntool_change_time = 7.0\n",
    )
    .unwrap();
    std::fs::write(
        root.join("lathe/fast.ngc"),
        "G21 G90\nT1 M6\nG0 X90\nG1 X0 F6000\nM2\n",
    )
    .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_partscope"))
        .args(["run", "--format", "json"])
        .arg(root.join("lathe/fast.ngc"))
        .output()
        .unwrap();
    let cli: Value = serde_json::from_slice(&out.stdout).unwrap();
    let cli_cycle = cli["cycle_time_s"].as_f64().unwrap();
    // 7 s of tool change, and 180 mm at no more than 60 mm/s.
    assert!(cli_cycle > 7.0 + 3.0, "{cli_cycle}");
    let (fast, _) = open(&mut c, &root.join("lathe/fast.ngc"), "ngc");
    let r = c.request("partscope/dryRun", json!({"textDocument": {"uri": fast}}));
    assert_eq!(r["cycle_time_s"].as_f64(), Some(cli_cycle), "{r}");
    assert!(c.shutdown().success());
}

/// Above 256 KB a version's static diagnostics are published at once and the
/// interpreter's follow in a second publish, once edits have paused.
#[test]
fn large_files_publish_static_diagnostics_first_then_the_run() {
    // Line 1 moves without a feed rate (F001, found by the interpreter).
    let mut text = String::from("G21 G90\nG1 X1\n");
    while text.len() <= 300 * 1024 {
        text.push_str("G1 X2 Y3 F100\n");
    }
    text.push_str("M2\n");
    let uri = "file:///large/part.ngc";
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {}}),
    );
    c.notify("initialized", json!({}));
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": text}}),
    );
    assert_eq!(c.diagnostics(uri, 1), vec![]);
    assert_eq!(c.diagnostics(uri, 1), vec![("F001".to_string(), 1)]);
    // An `A` without a value on line 5 (L003): static first, then both.
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri, "version": 2}, "contentChanges": [
            {"range": {"start": {"line": 5, "character": 3}, "end": {"line": 5, "character": 3}}, "text": "A "}]}),
    );
    assert_eq!(c.diagnostics(uri, 2), vec![("L003".to_string(), 5)]);
    assert_eq!(
        c.diagnostics(uri, 2),
        vec![("F001".to_string(), 1), ("L003".to_string(), 5)]
    );
    assert!(c.shutdown().success());
}

/// A dry run asked for with the opening of a large file starts on the parse,
/// beside the static rules: the static diagnostics are still published on
/// their own (unless the run is done before they are), and the last publish
/// holds both, as when the run comes after them.
#[test]
fn a_dry_run_asked_at_open_runs_beside_the_static_rules_and_publishes_the_same() {
    // Line 1 moves without a feed rate (F001, the interpreter's); line 5 has an
    // `A` without a value (L003, the parser's).
    let mut text = String::from(
        "G21 G90\nG1 X1\nG1 X2 Y3 F100\nG1 X2 Y3 F100\nG1 X2 Y3 F100\nG1 A X2 Y3 F100\n",
    );
    while text.len() <= 300 * 1024 {
        text.push_str("G1 X2 Y3 F100\n");
    }
    text.push_str("M2\n");
    let uri = "file:///large/part.ngc";
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {}}),
    );
    c.notify("initialized", json!({}));
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": text}}),
    );
    let id = c.send_request("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    let answer = c.response(id);
    let codes: Vec<(&str, u64)> = answer["result"]["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap(),
                d["range"]["start"]["line"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(codes, vec![("F001", 1)], "the run's own diagnostics");
    let statics = vec![("L003".to_string(), 5)];
    let both = vec![("F001".to_string(), 1), ("L003".to_string(), 5)];
    let first = c.diagnostics(uri, 1);
    assert!(first == statics || first == both, "first publish {first:?}");
    assert_eq!(c.diagnostics(uri, 1), both);
    assert!(c.shutdown().success());
}

/// One edit on one line: (line, start character, end character, new text).
type LineEdit = (u64, u64, u64, String);

/// A file name and each edit for it, in order.
fn edits_by_file(ops: &[Value]) -> Vec<(String, Vec<LineEdit>)> {
    ops.iter()
        .filter(|op| op.get("textDocument").is_some())
        .map(|op| {
            let name = op["textDocument"]["uri"].as_str().unwrap();
            let name = name.rsplit('/').next().unwrap().to_string();
            let mut edits: Vec<LineEdit> = op["edits"]
                .as_array()
                .unwrap()
                .iter()
                .map(|e| {
                    let r = &e["range"];
                    (
                        r["start"]["line"].as_u64().unwrap(),
                        r["start"]["character"].as_u64().unwrap(),
                        r["end"]["character"].as_u64().unwrap(),
                        e["newText"].as_str().unwrap().to_string(),
                    )
                })
                .collect();
            edits.sort();
            (name, edits)
        })
        .collect()
}

#[test]
fn rename_a_subroutine_across_two_files_and_its_file() {
    let root = workspace("rename");
    let mut c = Client::spawn();
    let caps = json!({
        "workspace": {"workspaceEdit": {"documentChanges": true, "resourceOperations": ["create", "rename", "delete"]}},
    });
    let init = c.request(
        "initialize",
        json!({"processId": null, "rootUri": uri_of(&root), "capabilities": caps,
               "workspaceFolders": [{"uri": uri_of(&root), "name": "ws"}]}),
    );
    c.notify("initialized", json!({}));
    assert_eq!(
        init["capabilities"]["renameProvider"]["prepareProvider"],
        json!(true)
    );
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    c.diagnostics(&uri, 1);

    // The label under the cursor is what prepareRename offers.
    let r = c.request(
        "textDocument/prepareRename",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 4)}),
    );
    assert_eq!(r, json!({"start": pos(1, 0), "end": pos(1, 8)}));

    let r = c.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 4), "newName": "peck"}),
    );
    let ops = r["documentChanges"].as_array().unwrap();
    let label = |line| (line, 1, 8, "<peck>".to_string());
    assert_eq!(
        edits_by_file(ops),
        vec![
            ("main.ngc".to_string(), vec![label(1)]),
            ("drill.ngc".to_string(), vec![label(0), label(3)]),
        ]
    );
    // The open document's edit names its version; the file on disk's does not.
    assert_eq!(ops[0]["textDocument"]["version"], json!(1));
    assert_eq!(ops[1]["textDocument"]["version"], json!(null));
    // The file is renamed after its text is edited.
    let last = ops.last().unwrap();
    assert_eq!(last["kind"], json!("rename"));
    assert_eq!(last["oldUri"], json!(uri_of(&root.join("drill.ngc"))));
    assert_eq!(last["newUri"], json!(uri_of(&root.join("peck.ngc"))));

    // A named parameter: renamed in this file only, brackets kept.
    let r = c.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": uri}, "position": pos(5, 8), "newName": "cut"}),
    );
    assert_eq!(
        edits_by_file(r["documentChanges"].as_array().unwrap()),
        vec![(
            "main.ngc".to_string(),
            vec![(4, 2, 7, "cut".to_string()), (5, 7, 12, "cut".to_string())]
        )]
    );

    // FANUC-style numbered variables are memory cells: refused with the reason.
    let (drill, _) = open(&mut c, &root.join("drill.ngc"), "ngc");
    let r = c.request_full(
        "textDocument/prepareRename",
        json!({"textDocument": {"uri": drill}, "position": pos(1, 13)}),
    );
    let msg = r["error"]["message"].as_str().unwrap_or_default();
    assert!(msg.contains("memory cells"), "{r}");
    // A name already in use would merge two subroutines.
    std::fs::write(root.join("peck.ngc"), "o<peck> sub\no<peck> endsub\n").unwrap();
    let r = c.request_full(
        "textDocument/rename",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 4), "newName": "peck"}),
    );
    assert!(
        r["error"]["message"]
            .as_str()
            .unwrap_or_default()
            .contains("exists already"),
        "{r}"
    );
    c.shutdown();
}

#[test]
fn rename_without_file_operations_edits_the_calls_only() {
    let root = workspace("rename-plain");
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    let (uri, _) = open(&mut c, &root.join("main.ngc"), "ngc");
    c.diagnostics(&uri, 1);
    let r = c.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": uri}, "position": pos(1, 4), "newName": "o<Peck>"}),
    );
    let changes = r["changes"].as_object().unwrap();
    let mut files: Vec<&str> = changes
        .keys()
        .map(|k| k.rsplit('/').next().unwrap())
        .collect();
    files.sort();
    assert_eq!(files, vec!["drill.ngc", "main.ngc"]);
    assert_eq!(
        changes[&uri_of(&root.join("main.ngc"))][0]["newText"],
        json!("<Peck>")
    );
    c.shutdown();
}

#[test]
fn formatting_renumbers_spaces_and_upper_cases() {
    let root = workspace("format");
    std::fs::write(
        root.join("fanuc/fmt.nc"),
        "%\nO1000;\nN1 g0  x1. (keep  this);\nN2 #1=#1+1;\nIF [#1 LT 3] GOTO 2;\nM30;\n%\n",
    )
    .unwrap();
    let mut c = Client::spawn();
    initialize(
        &mut c,
        &root,
        json!({"format": {"numbers": "renumber", "start": 100}}),
    );
    let (uri, text) = open(&mut c, &root.join("fanuc/fmt.nc"), "fanuc");
    c.diagnostics(&uri, 1);
    let apply = |edits: &Value| -> String {
        // Back to front, each edit on one line.
        let mut lines: Vec<String> = text.split('\n').map(str::to_string).collect();
        let mut es: Vec<&Value> = edits.as_array().unwrap().iter().collect();
        es.sort_by_key(|e| {
            let s = &e["range"]["start"];
            std::cmp::Reverse((
                s["line"].as_u64().unwrap(),
                s["character"].as_u64().unwrap(),
            ))
        });
        for e in es {
            let r = &e["range"];
            let line = r["start"]["line"].as_u64().unwrap() as usize;
            assert_eq!(r["end"]["line"].as_u64().unwrap() as usize, line);
            let (a, b) = (
                r["start"]["character"].as_u64().unwrap() as usize,
                r["end"]["character"].as_u64().unwrap() as usize,
            );
            lines[line].replace_range(a..b, e["newText"].as_str().unwrap());
        }
        lines.join("\n")
    };
    // The client's defaults: renumber from 100 with step 10; the GOTO follows.
    let r = c.request(
        "textDocument/formatting",
        json!({"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    assert_eq!(
        apply(&r),
        "%\nO1000;\nN100 G0 X1. (keep  this);\nN110 #1=#1+1;\nIF [#1 LT 3] GOTO 110;\nM30;\n%\n"
    );
    // The request's properties win: block numbers removed but the GOTO target kept.
    let r = c.request(
        "textDocument/formatting",
        json!({"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": true,
               "partscope.numbers": "remove", "partscope.spacing": "none"}}),
    );
    assert_eq!(
        apply(&r),
        "%\nO1000;\nG0X1. (keep  this);\nN2 #1=#1+1;\nIF [#1 LT 3] GOTO 2;\nM30;\n%\n"
    );
    let r = c.request_full(
        "textDocument/formatting",
        json!({"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": true,
               "partscope.numbers": "sometimes"}}),
    );
    assert!(
        r["error"]["message"]
            .as_str()
            .unwrap_or_default()
            .contains("keep, renumber, add or remove"),
        "{r}"
    );
    c.shutdown();
}

/// A `partscope.toml` with a typo and a bad value: the editor says where each
/// is, in one message.
#[test]
fn config_problems_are_shown_located_and_the_rest_applies() {
    let root = workspace("badconfig");
    std::fs::create_dir_all(root.join("shop")).unwrap();
    let config = root.join("shop/partscope.toml");
    std::fs::write(
        &config,
        "dialect = \"fanuc\"\n[rules]\nignore = [\"W011\"]\n[machine]\nlookahaed = 40\nfeed_override = 20\n",
    )
    .unwrap();
    std::fs::write(root.join("shop/p.nc"), "%\nO1000\nG21 G90\nM30\n%\n").unwrap();
    let mut c = Client::spawn();
    initialize(&mut c, &root, json!({}));
    let (uri, _) = open(&mut c, &root.join("shop/p.nc"), "fanuc");
    c.diagnostics(&uri, 1);
    let want = format!(
        "partscope: {p}:5:1: warning: unknown key `lookahaed`: did you mean `lookahead`? (ignored); \
         {p}:6:17: warning: `machine.feed_override`: 20 must be between 0.001 and 10 (the default is used)",
        p = config.display()
    );
    let shown = c.wait_for("window/showMessage", |m| {
        m["message"]
            .as_str()
            .is_some_and(|s| s.contains("lookahaed"))
    });
    assert_eq!(shown["message"], want.as_str());
    assert_eq!(shown["type"], 2);
    assert!(c.shutdown().success());
}
