//! Hover over stdio: the values variables and word expressions took in the
//! dry run, system variables, G65 arguments and macro keywords, as an editor
//! shows them.

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::{Path, PathBuf};

use harness::Client;
use serde_json::{json, Value};

fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "partscope-lsp-values-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.canonicalize().unwrap()
}

fn uri_of(p: &Path) -> String {
    format!("file://{}", p.display())
}

fn start(root: &Path) -> Client {
    let mut c = Client::spawn();
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(root),
            "capabilities": {"textDocument": {"hover": {"contentFormat": ["markdown"]}}},
            "workspaceFolders": [{"uri": uri_of(root), "name": "ws"}],
        }),
    );
    c.notify("initialized", json!({}));
    c
}

/// Opens `name` with `text` and waits for its diagnostics (the dry run is done then).
fn open(c: &mut Client, root: &Path, name: &str, text: &str) -> String {
    let path = root.join(name);
    std::fs::write(&path, text).unwrap();
    let uri = uri_of(&path);
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": text}}),
    );
    c.diagnostics(&uri, 1);
    uri
}

fn hover(c: &mut Client, uri: &str, line: u32, character: u32) -> (String, Value) {
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}),
    );
    let md = h["contents"]["value"]
        .as_str()
        .unwrap_or_default()
        .to_string();
    (md, h["range"].clone())
}

fn range(l0: u32, c0: u32, l1: u32, c1: u32) -> Value {
    json!({"start": {"line": l0, "character": c0}, "end": {"line": l1, "character": c1}})
}

const FANUC: &str = "%
O1000 (VALUES);
#1 = 0;
#2 = 2.5;
WHILE [#1 LT 10] DO1;
#1 = #1 + 1;
G01 X[#1 + #2] F100.;
END1;
#3 = #4119;
G65 P9010 X5. Y#2;
M08;
M30;
O9010;
#30 = #24 + #25;
M99;
%
";

#[test]
fn fanuc_values_keywords_and_arguments() {
    let root = folder("fanuc");
    let mut c = start(&root);
    let uri = open(&mut c, &root, "O1000.fnc", FANUC);

    // `#1` on the left of `#1 = #1 + 1` (line 5): the value each pass gave it.
    let (md, r) = hover(&mut c, &uri, 5, 1);
    assert_eq!(r, range(5, 0, 5, 2), "{md}");
    assert!(md.contains("**#1** — variable"), "{md}");
    assert!(
        md.contains("Value in the dry run: `10` (last of 10 executions)"),
        "{md}"
    );
    assert!(
        md.contains("Each execution: `1`, `2`, `3`, `4`, `5`, `6`, `7`, `8`, …"),
        "{md}"
    );
    assert!(md.contains("G65/G66 argument A"), "{md}");
    // `#1` on the right: the value read, one less each time.
    let (md, _) = hover(&mut c, &uri, 5, 6);
    assert!(md.contains("`9` (last of 10 executions)"), "{md}");
    assert!(md.contains("Each execution: `0`, `1`, `2`"), "{md}");
    // The loop condition ran 11 times: 10 true and the last false.
    let (md, _) = hover(&mut c, &uri, 4, 10);
    assert!(md.starts_with("**LT** — operator"), "{md}");
    assert!(md.contains("`0` (last of 11 executions)"), "{md}");
    assert!(md.contains("Each execution: `1`, `1`, `1`"), "{md}");

    // The word `X[#1 + #2]`: its expression's value on each pass.
    let (md, r) = hover(&mut c, &uri, 6, 4);
    assert!(md.starts_with("**X** — "), "{md}");
    assert_eq!(r, range(6, 4, 6, 14), "{md}");
    assert!(
        md.contains("Value in the dry run: `12.5` (last of 10 executions)"),
        "{md}"
    );
    assert!(md.contains("Each execution: `3.5`, `4.5`"), "{md}");

    // A system variable: its meaning and the value read.
    let (md, _) = hover(&mut c, &uri, 8, 6);
    assert!(md.contains("**#4119**"), "{md}");
    assert!(
        md.contains("*S code (spindle speed) in force in the preceding block (read only)*"),
        "{md}"
    );
    assert!(md.contains("Value in the dry run: `0`"), "{md}");

    // A G65 argument letter: the local variable it sets.
    let (md, _) = hover(&mut c, &uri, 9, 10);
    assert!(md.starts_with("**X** — "), "{md}");
    assert!(
        md.contains("Argument of **G65**: sets local variable **#24** of the macro (Argument Specification I)."),
        "{md}"
    );

    // Macro B keywords.
    let (md, r) = hover(&mut c, &uri, 4, 2);
    assert!(md.starts_with("**WHILE** — macro statement"), "{md}");
    assert_eq!(r, range(4, 0, 4, 5));
    // The arguments arrive in the macro's locals.
    let (md, _) = hover(&mut c, &uri, 13, 7);
    assert!(md.contains("Value in the dry run: `5`"), "{md}");
    let (md, _) = hover(&mut c, &uri, 7, 1);
    assert!(md.starts_with("**END** — macro statement"), "{md}");

    // M08 is the machine's, not an unknown code.
    let (md, _) = hover(&mut c, &uri, 10, 1);
    assert!(md.starts_with("**M08** — machine M code"), "{md}");
    assert!(md.contains("flood coolant on"), "{md}");

    // Completion offers the keywords of the dialect.
    let r = c.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": uri}, "position": {"line": 4, "character": 2}}),
    );
    let labels: Vec<&str> = r
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, vec!["WHILE"]);
    assert!(c.shutdown().success());
}

const NGC: &str = "G21 G90
#<step> = 1.5
#1 = 0
o100 while [#1 LT 3]
#1 = [#1 + 1]
G1 X[#1 * #<step>] F100
o100 endwhile
#2 = #<_x>
#3 = ATAN[1]/[1]
o200 if [#1 GT 5]
#5 = 1
o200 endif
M2
";

#[test]
fn ngc_values_and_oword_keywords() {
    let root = folder("ngc");
    let mut c = start(&root);
    let uri = open(&mut c, &root, "values.ngc", NGC);

    let (md, _) = hover(&mut c, &uri, 4, 8);
    assert!(md.contains("**#1** — variable"), "{md}");
    assert!(
        md.contains(
            "Value in the dry run: `2` (last of 3 executions)  \nEach execution: `0`, `1`, `2`"
        ),
        "{md}"
    );
    assert!(md.contains("subroutine argument / local parameter"), "{md}");
    let (md, _) = hover(&mut c, &uri, 5, 4);
    assert!(md.contains("`4.5` (last of 3 executions)"), "{md}");
    assert!(md.contains("Each execution: `1.5`, `3`, `4.5`"), "{md}");
    // A named predefined parameter.
    let (md, _) = hover(&mut c, &uri, 7, 7);
    assert!(
        md.contains("*current position X in the work frame*"),
        "{md}"
    );
    assert!(md.contains("Value in the dry run: `4.5`"), "{md}");
    // The O-word keyword and a function.
    let (md, r) = hover(&mut c, &uri, 3, 7);
    assert!(md.starts_with("**while** — O-word keyword"), "{md}");
    assert_eq!(r, range(3, 5, 3, 10));
    let (md, _) = hover(&mut c, &uri, 8, 6);
    assert!(
        md.starts_with("**ATAN** — function\n\n`ATAN[y]/[x]`"),
        "{md}"
    );

    // A condition's value on its operator; a block the run skipped.
    let (md, _) = hover(&mut c, &uri, 9, 12);
    assert!(md.starts_with("**GT** — operator"), "{md}");
    assert!(md.contains("Value in the dry run: `0`"), "{md}");
    let (md, _) = hover(&mut c, &uri, 10, 1);
    assert!(md.contains("Not evaluated in the dry run."), "{md}");

    // Completion: `o100 endw` → endwhile; `GO` has no GOTO in RS274/NGC.
    let items = |c: &mut Client, line: u32, ch: u32| -> Vec<String> {
        let r = c.request(
            "textDocument/completion",
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": ch}}),
        );
        r.as_array()
            .unwrap()
            .iter()
            .map(|i| i["label"].as_str().unwrap().to_string())
            .collect()
    };
    assert_eq!(items(&mut c, 6, 9), vec!["endwhile"]);
    assert!(c.shutdown().success());
}

/// Hover on the first line says which dialect the file is read in and why:
/// a FANUC program in a `.nc` file is visible as such in the editor.
#[test]
fn first_line_hover_names_the_dialect_and_why() {
    let root = folder("dialect");
    let mut c = start(&root);
    let uri = open(
        &mut c,
        &root,
        "part.nc",
        "%\nO1234 (PART)\nG90 G00 X0 Y0\nM30\n%\n",
    );
    let (md, _) = hover(&mut c, &uri, 0, 0);
    assert!(
        md.contains("*Checked as fanuc: the `%` line 1 and program number O1234 on line 2*"),
        "{md}"
    );
    // Other lines do not repeat it.
    let (md, _) = hover(&mut c, &uri, 2, 1);
    assert!(!md.contains("Checked as"), "{md}");
}
