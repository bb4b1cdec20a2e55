//! A hostile client: malformed framing, bodies that are not JSON-RPC, broken
//! text, oversized messages and random bytes, each sent to `partscope lsp`
//! over stdio, after each of which the server must still answer a hover
//! correctly. Every read has a timeout, so a hung server fails the test.
//!
//! `PARTSCOPE_HOSTILE_SECS` sets the length of the random soak (10 s by
//! default), `PARTSCOPE_HOSTILE_SEED` its seed (printed on failure).

#[path = "../../tests/lsp/harness.rs"]
mod harness;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use harness::Client;
use serde_json::{json, Value};

/// How long one answer may take before the server counts as hung.
const ANSWER: Duration = Duration::from_secs(20);
const DOC: &str = "G1 X1 F100\nG0 Z5\nM2\n";

fn workspace(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "partscope-lsp-hostile-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.canonicalize().unwrap()
}

fn uri_of(p: &std::path::Path) -> String {
    format!("file://{}", p.display())
}

/// A server with one open document (`DOC`), its first diagnostics received.
fn start(name: &str, env: &[(&str, &str)]) -> (Client, String) {
    let root = workspace(name);
    let mut c = Client::spawn_with_env(env);
    c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": uri_of(&root),
            "capabilities": {"textDocument": {"hover": {"contentFormat": ["markdown"]}}},
            "workspaceFolders": [{"uri": uri_of(&root), "name": "ws"}],
        }),
    );
    c.notify("initialized", json!({}));
    let uri = uri_of(&root.join("part.ngc"));
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": DOC}}),
    );
    assert_eq!(c.diagnostics(&uri, 1), vec![]);
    (c, uri)
}

fn hover_params(uri: &str, line: u32, character: u32) -> Value {
    json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}})
}

/// The response to `id`, received already or within [`ANSWER`].
fn take_response(c: &mut Client, id: i64) -> Option<Value> {
    if let Some(i) = c
        .pending
        .iter()
        .position(|m| m["id"] == id && m.get("method").is_none())
    {
        return Some(c.pending.remove(i));
    }
    c.response_within(id, ANSWER)
}

/// The hover on the code at the start of `line`, as `(first words, range)`.
fn hover(c: &mut Client, uri: &str, line: u32, context: &str) -> (String, Value) {
    if let Some(st) = c.exited() {
        panic!("server exited ({st}) after {context}");
    }
    let id = c.send_request("textDocument/hover", hover_params(uri, line, 1));
    hover_answer(c, id, context)
}

fn hover_answer(c: &mut Client, id: i64, context: &str) -> (String, Value) {
    let r = take_response(c, id)
        .unwrap_or_else(|| panic!("no hover answer within {ANSWER:?} after {context}"));
    let md = r["result"]["contents"]["value"]
        .as_str()
        .unwrap_or_else(|| panic!("hover failed after {context}: {r}"));
    let head = md.split(" — ").next().unwrap_or_default().to_string();
    (head, r["result"]["range"].clone())
}

fn range(line: u32, from: u32, to: u32) -> Value {
    json!({"start": {"line": line, "character": from}, "end": {"line": line, "character": to}})
}

/// The hover on the G1 of line 0 is right.
fn hover_ok(c: &mut Client, uri: &str, context: &str) {
    assert_eq!(
        hover(c, uri, 0, context),
        ("**G1**".to_string(), range(0, 0, 2)),
        "after {context}"
    );
}

/// Responses (not notifications) received so far that no test request asked for.
fn stray_responses(c: &mut Client) -> Vec<Value> {
    let (resp, rest): (Vec<Value>, Vec<Value>) = c
        .pending
        .drain(..)
        .partition(|m| m.get("id").is_some() && m.get("method").is_none());
    c.pending = rest;
    resp
}

fn framed(body: &[u8]) -> Vec<u8> {
    let mut v = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    v.extend_from_slice(body);
    v
}

/// One hostile input and the error answer it must get (id, code), if any.
struct Case {
    name: &'static str,
    bytes: Vec<u8>,
    answer: Option<(i64, i64)>,
}

fn case(name: &'static str, bytes: Vec<u8>, answer: Option<(i64, i64)>) -> Case {
    Case {
        name,
        bytes,
        answer,
    }
}

fn body_case(name: &'static str, body: &[u8], answer: Option<(i64, i64)>) -> Case {
    case(name, framed(body), answer)
}

fn cases(uri: &str) -> Vec<Case> {
    let hover_req = |id: i64| {
        json!({"jsonrpc": "2.0", "id": id, "method": "textDocument/hover",
               "params": hover_params(uri, 0, 1)})
        .to_string()
    };
    let mut invalid_utf8_string =
        br#"{"jsonrpc":"2.0","method":"$/x","params":{"t":"a_b"}}"#.to_vec();
    let at = invalid_utf8_string.iter().position(|&b| b == b'_').unwrap();
    invalid_utf8_string[at] = 0xff;
    let mut invalid_utf8_outside = br#"{"jsonrpc":"2.0","id":908,"method":"x",_}"#.to_vec();
    let at = invalid_utf8_outside
        .iter()
        .position(|&b| b == b'_')
        .unwrap();
    invalid_utf8_outside[at] = 0xc3;
    let good = hover_req(920);
    vec![
        body_case("an empty object", b"{}", None),
        body_case("null", b"null", None),
        body_case("a number", b"42", None),
        body_case("a string", br#""x""#, None),
        body_case("an empty batch", b"[]", None),
        body_case(
            "a batch holding shutdown",
            br#"[{"jsonrpc":"2.0","id":900,"method":"shutdown"}]"#,
            None,
        ),
        body_case(
            "a wrong jsonrpc version",
            format!(
                r#"{{"jsonrpc":"1.0","id":901,"method":"textDocument/hover","params":{}}}"#,
                hover_params(uri, 0, 1)
            )
            .as_bytes(),
            Some((901, -32600)),
        ),
        body_case(
            "no jsonrpc member",
            br#"{"id":902,"method":"textDocument/hover"}"#,
            Some((902, -32600)),
        ),
        body_case(
            "a method that is not a string",
            br#"{"jsonrpc":"2.0","id":903,"method":[1]}"#,
            Some((903, -32600)),
        ),
        body_case(
            "an id that is an object",
            br#"{"jsonrpc":"2.0","id":{"a":1},"method":"textDocument/hover"}"#,
            None,
        ),
        body_case(
            "neither method nor result",
            br#"{"jsonrpc":"2.0","id":904}"#,
            Some((904, -32600)),
        ),
        body_case(
            "a response to nothing",
            br#"{"jsonrpc":"2.0","id":12345,"result":{"x":1}}"#,
            None,
        ),
        body_case(
            "a notification with wrong params",
            br#"{"jsonrpc":"2.0","method":"textDocument/didChange","params":5}"#,
            None,
        ),
        body_case(
            "a $/ request",
            br#"{"jsonrpc":"2.0","id":905,"method":"$/partscope/unknown","params":{}}"#,
            Some((905, -32601)),
        ),
        body_case(
            "an unknown request",
            br#"{"jsonrpc":"2.0","id":906,"method":"partscope/nothing"}"#,
            Some((906, -32601)),
        ),
        body_case(
            "a cancel of nothing",
            br#"{"jsonrpc":"2.0","method":"$/cancelRequest","params":{"id":77777}}"#,
            None,
        ),
        body_case("invalid UTF-8 in a string", &invalid_utf8_string, None),
        body_case(
            "invalid UTF-8 outside a string",
            &invalid_utf8_outside,
            Some((908, -32700)),
        ),
        body_case(
            "a lone surrogate in a request",
            br#"{"jsonrpc":"2.0","id":909,"method":"partscope/\ud83d"}"#,
            Some((909, -32601)),
        ),
        body_case(
            "truncated JSON",
            br#"{"jsonrpc":"2.0","id":910,"method":"textDocument/hover","params":{"#,
            Some((910, -32700)),
        ),
        body_case("deep nesting", "[".repeat(200_000).as_bytes(), None),
        case("an empty body", b"Content-Length: 0\r\n\r\n".to_vec(), None),
        case(
            "a Content-Length that is not a number",
            b"Content-Length: abc\r\n\r\n{}".to_vec(),
            None,
        ),
        case(
            "a header without Content-Length",
            b"Content-Type: application/json\r\n\r\n{}".to_vec(),
            None,
        ),
        case(
            "a header that never ends",
            format!("Content-Length: 10\r\nX-Junk: {}", "y".repeat(100_000)).into_bytes(),
            None,
        ),
        case("bytes that are no header", vec![0xAB; 70_000], None),
        case(
            "a Content-Length 3 bytes short",
            format!("Content-Length: {}\r\n\r\n{good}", good.len() - 3).into_bytes(),
            Some((920, -32700)),
        ),
        case(
            "a Content-Length 5 bytes long",
            format!(
                "Content-Length: {}\r\n\r\n{}",
                good.len() + 5,
                hover_req(921)
            )
            .into_bytes(),
            Some((921, -32700)),
        ),
        case(
            "a Content-Length of 100 TB",
            format!("Content-Length: 100000000000000\r\n\r\n{}", hover_req(922)).into_bytes(),
            Some((922, -32700)),
        ),
        case(
            "a Content-Length beyond u64",
            format!(
                "Content-Length: 99999999999999999999999\r\n\r\n{}",
                hover_req(923)
            )
            .into_bytes(),
            Some((923, -32700)),
        ),
        case("a header cut in the middle", b"Content-Len".to_vec(), None),
    ]
}

#[test]
fn every_hostile_message_leaves_a_working_server() {
    let (mut c, uri) = start("cases", &[]);
    hover_ok(&mut c, &uri, "start");
    for Case {
        name,
        bytes,
        answer,
    } in cases(&uri)
    {
        c.send_bytes(&bytes);
        // The hover goes out before the error answer is awaited: a body
        // longer than its Content-Length is only known to be one when the
        // next message comes.
        let hover = c.send_request("textDocument/hover", hover_params(&uri, 0, 1));
        if let Some((id, code)) = answer {
            let r =
                take_response(&mut c, id).unwrap_or_else(|| panic!("no error answer to {name}"));
            assert_eq!(r["error"]["code"], code, "{name}: {r}");
        }
        assert_eq!(
            hover_answer(&mut c, hover, name),
            ("**G1**".to_string(), range(0, 0, 2)),
            "after {name}"
        );
        assert!(c.exited().is_none(), "server exited after {name}");
        assert_eq!(stray_responses(&mut c), Vec::<Value>::new(), "{name}");
    }
    assert!(c.shutdown().success());
}

#[test]
fn a_change_with_half_an_emoji_still_applies() {
    let (mut c, uri) = start("surrogate", &[]);
    // What `JSON.stringify` sends once half of "😀" is deleted: the text is
    // applied with U+FFFD in its place, so the next hover sees the new code.
    let body = format!(
        r#"{{"jsonrpc":"2.0","method":"textDocument/didChange","params":{{"textDocument":{{"uri":"{uri}","version":2}},"contentChanges":[{{"text":"G0 X1 (\ud83d)\nM2\n"}}]}}}}"#
    );
    c.send_bytes(&framed(body.as_bytes()));
    let p = c.wait_for("textDocument/publishDiagnostics", |p| p["version"] == 2);
    assert_eq!(p["diagnostics"], json!([]));
    assert_eq!(
        hover(&mut c, &uri, 0, "the change"),
        ("**G0**".to_string(), range(0, 0, 2))
    );
    // The comment `(\u{fffd})` is three UTF-16 units long (the escape kept
    // as text would be eight).
    let r = c.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": uri}}),
    );
    let comment = r["data"]
        .as_array()
        .and_then(|d| d.get(20..25).map(<[Value]>::to_vec));
    assert_eq!(
        comment,
        Some(vec![json!(0), json!(2), json!(3), json!(0), json!(0)]),
        "{r}"
    );
    assert!(c.shutdown().success());
}

#[test]
fn a_body_above_the_limit_is_refused_without_losing_the_session() {
    let (mut c, uri) = start("limit", &[("PARTSCOPE_LSP_MAX_MESSAGE_BYTES", "65536")]);
    let text = "G1 X2\n".repeat(200_000);
    let body = json!({"jsonrpc": "2.0", "id": 950, "method": "textDocument/hover",
                      "params": {"textDocument": {"uri": uri}, "position": {"line": 0, "character": 0}},
                      "pad": text});
    c.send_bytes(&framed(body.to_string().as_bytes()));
    let r = c
        .response_within(950, ANSWER)
        .expect("no answer to the large message");
    assert_eq!(r["error"]["code"], -32600, "{r}");
    assert_eq!(
        r["error"]["message"],
        format!(
            "the message of {} bytes is above the limit of 65536 bytes",
            body.to_string().len()
        )
    );
    hover_ok(&mut c, &uri, "the large message");
    assert!(c.shutdown().success());
}

#[test]
fn exit_status_follows_the_protocol() {
    // `exit` without `shutdown`: status 1.
    let (mut c, _) = start("exit1", &[]);
    c.notify("exit", Value::Null);
    let st = c.close_and_wait(ANSWER).expect("server did not exit");
    assert_eq!(st.code(), Some(1));
    // After `shutdown`: status 0.
    let (c, _) = start("exit0", &[]);
    assert_eq!(c.shutdown().code(), Some(0));
    // End of input without either: status 1.
    let (c, _) = start("eof", &[]);
    let st = c.close_and_wait(ANSWER).expect("server did not exit");
    assert_eq!(st.code(), Some(1));
}

/// An RS274/NGC program that runs until the step budget stops it.
/// A loop that never ends, each pass made costly (500 sine evaluations) so that its
/// step budget takes far longer than any of these tests waits, however fast the
/// machine: a run that ended by itself would answer instead of being cancelled.
fn endless() -> String {
    let sines = vec!["SIN[#1]"; 100].join("+");
    let mut text = String::from("#1=0\no100 while [1 GT 0]\n#1=[#1+1]\n");
    for n in 2..7 {
        text.push_str(&format!("#{n}=[{sines}]\n"));
    }
    text.push_str("G1 X[#1 MOD 100] F1000\no100 endwhile\nM2\n");
    text
}

fn open(c: &mut Client, uri: &str, text: &str) {
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "ngc", "version": 1, "text": text}}),
    );
}

#[test]
fn a_running_dry_run_neither_blocks_other_documents_nor_outlives_its_cancel() {
    let (mut c, uri) = start("busy", &[]);
    let busy = uri.replace("part.ngc", "busy.ngc");
    open(&mut c, &busy, &endless());
    let run = c.send_request("partscope/dryRun", json!({"textDocument": {"uri": busy}}));
    // The other document answers while the run goes on.
    std::thread::sleep(Duration::from_millis(300));
    let t = Instant::now();
    hover_ok(&mut c, &uri, "a dry run of another document");
    let r = c.request("partscope/dryRun", json!({"textDocument": {"uri": uri}}));
    assert_eq!(r["toolpath"]["segments"].as_array().map(Vec::len), Some(2));
    let other = t.elapsed();
    assert!(
        other < Duration::from_secs(5),
        "other document took {other:?}"
    );
    c.notify("$/cancelRequest", json!({"id": run}));
    let t = Instant::now();
    let r = c
        .response_within(run, ANSWER)
        .expect("no answer to the cancelled run");
    let cancel = t.elapsed();
    assert_eq!(r["error"]["code"], -32800, "{r}");
    eprintln!("hover and dry run of another document: {other:?}; cancel answered in {cancel:?}");
    assert!(
        cancel < Duration::from_millis(250),
        "cancel took {cancel:?}"
    );
    hover_ok(&mut c, &uri, "the cancel");
    assert!(c.shutdown().success());
}

#[test]
fn closing_stdin_ends_the_server_while_it_runs() {
    let (mut c, uri) = start("eof-busy", &[]);
    let busy = uri.replace("part.ngc", "busy.ngc");
    open(&mut c, &busy, &endless());
    c.send_request("partscope/dryRun", json!({"textDocument": {"uri": busy}}));
    std::thread::sleep(Duration::from_millis(300));
    let t = Instant::now();
    let st = c.close_and_wait(ANSWER).expect("server did not exit");
    let took = t.elapsed();
    eprintln!("exit after stdin closed: {took:?}");
    assert_eq!(st.code(), Some(1));
    assert!(took < Duration::from_secs(2), "exit took {took:?}");
}

/// CPU time the server spends over `window`.
fn cpu_over(c: &Client, window: Duration) -> Duration {
    let before = c.cpu_time().expect("server CPU time");
    std::thread::sleep(window);
    c.cpu_time()
        .expect("server CPU time")
        .saturating_sub(before)
}

#[test]
fn runs_stop_when_their_request_is_cancelled_or_their_document_closes() {
    let (mut c, uri) = start("stop", &[]);
    let window = Duration::from_secs(1);
    // Below a few ticks of CPU the server is idle; a run takes at least a
    // tenth of a core even on a machine loaded by other builds (measured over
    // twice the window, so the verdict does not hang on one scheduler slice).
    let idle = Duration::from_millis(60);
    let busy = Duration::from_millis(200);
    let busy_window = 2 * window;
    // What a stopped run does after its answer (dropping its tables, the
    // cancelled request's error reply) is not a run going on: measured after it.
    let settle = Duration::from_millis(300);
    // A small document runs with its analysis, for its diagnostics: closing
    // the document stops that run.
    let small = uri.replace("part.ngc", "small.ngc");
    open(&mut c, &small, &endless());
    let running = cpu_over(&c, busy_window);
    c.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": small}}),
    );
    hover_ok(&mut c, &uri, "the close");
    std::thread::sleep(settle);
    let after_close = cpu_over(&c, window);
    // Above 256 KB the document's own run waits for edits to pause, so the
    // dry run is the request's: its cancel stops it (the close stops the
    // document's run that would follow).
    let large = uri.replace("part.ngc", "large.ngc");
    let text = endless() + &"(padding to make the file large)\n".repeat(10_000);
    open(&mut c, &large, &text);
    let run = c.send_request("partscope/dryRun", json!({"textDocument": {"uri": large}}));
    let running_request = cpu_over(&c, busy_window);
    c.notify("$/cancelRequest", json!({"id": run}));
    c.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": large}}),
    );
    assert_eq!(take_response(&mut c, run).unwrap()["error"]["code"], -32800);
    std::thread::sleep(settle);
    let after_cancel = cpu_over(&c, window);
    eprintln!(
        "server CPU: document run {running:?} per {busy_window:?}, after its close {after_close:?} per {window:?}; \
         request run {running_request:?}, after its cancel {after_cancel:?}"
    );
    assert!(
        running >= busy && running_request >= busy,
        "no run was running"
    );
    assert!(
        after_close <= idle,
        "the run went on after the close: {after_close:?}"
    );
    assert!(
        after_cancel <= idle,
        "the run went on after the cancel: {after_cancel:?}"
    );
    hover_ok(&mut c, &uri, "the cancel");
    assert!(c.shutdown().success());
}

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }

    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len() as u64) as usize]
    }
}

/// Raw JSON text: random values whose keys and strings lean towards
/// JSON-RPC members and LSP methods, with escapes and surrogates.
fn random_json(rng: &mut Rng, depth: u32, out: &mut String) {
    const KEYS: &[&str] = &[
        "jsonrpc",
        "id",
        "method",
        "params",
        "result",
        "error",
        "textDocument",
        "uri",
        "position",
        "contentChanges",
        "text",
        "version",
        "x",
    ];
    const STRINGS: &[&str] = &[
        "2.0",
        "1.0",
        "textDocument/hover",
        "textDocument/didChange",
        "textDocument/didOpen",
        "partscope/dryRun",
        "$/cancelRequest",
        "$/x",
        // Not `shutdown` or `exit`: those end the session by right.
        "initialize",
        "initialized",
        "file:///nowhere.ngc",
        "\\ud83d",
        "\\ude00x",
        "\\u0000",
        "G1 X[1+",
        "\\\\",
        "",
    ];
    match rng.below(if depth > 3 { 5 } else { 8 }) {
        0 => out.push_str("null"),
        1 => out.push_str(if rng.below(2) == 0 { "true" } else { "false" }),
        2 => out.push_str(&(rng.next() as i64 >> rng.below(64)).to_string()),
        3 => out.push_str(&format!("{}.5e{}", rng.below(1000), rng.below(400))),
        4 => {
            out.push('"');
            out.push_str(rng.pick::<&str>(STRINGS));
            out.push('"');
        }
        5 | 6 => {
            out.push('{');
            if rng.below(2) == 0 {
                out.push_str(r#""jsonrpc":"2.0","#);
            }
            for i in 0..rng.below(5) {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&format!(r#""{}":"#, *rng.pick(KEYS)));
                random_json(rng, depth + 1, out);
            }
            out.push('}');
        }
        _ => {
            out.push('[');
            for i in 0..rng.below(4) {
                if i > 0 {
                    out.push(',');
                }
                random_json(rng, depth + 1, out);
            }
            out.push(']');
        }
    }
}

/// One random hostile input: framed random JSON, framed with a wrong length,
/// or raw random bytes (now and then with header fragments).
fn random_input(rng: &mut Rng) -> Vec<u8> {
    let mut json = String::new();
    random_json(rng, 0, &mut json);
    match rng.below(5) {
        0 | 1 => framed(json.as_bytes()),
        2 => {
            let len = (json.len() as i64 + rng.below(21) as i64 - 10).max(0);
            let mut v = format!("Content-Length: {len}\r\n\r\n").into_bytes();
            v.extend_from_slice(json.as_bytes());
            v
        }
        3 => {
            let mut body = json.into_bytes();
            for _ in 0..rng.below(4) {
                if !body.is_empty() {
                    let at = rng.below(body.len() as u64) as usize;
                    body[at] = rng.next() as u8;
                }
            }
            framed(&body)
        }
        _ => {
            let mut v: Vec<u8> = (0..rng.below(3000)).map(|_| rng.next() as u8).collect();
            for _ in 0..rng.below(3) {
                let at = rng.below(v.len() as u64 + 1) as usize;
                let frag = rng.pick(&[
                    "Content-Length: ",
                    "Content-Length: 12\r\n",
                    "\r\n\r\n",
                    "Content-Length: 4000000000\r\n\r\n",
                    "content-length:3\r\n\r\n{}",
                ]);
                v.splice(at..at, frag.bytes());
            }
            v
        }
    }
}

#[test]
fn random_json_and_bytes_for_a_bounded_time() {
    let secs: u64 = std::env::var("PARTSCOPE_HOSTILE_SECS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let seed: u64 = std::env::var("PARTSCOPE_HOSTILE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(1, |d| d.as_nanos() as u64)
        })
        | 1;
    let (mut c, uri) = start("soak", &[]);
    let mut rng = Rng(seed);
    let end = Instant::now() + Duration::from_secs(secs);
    let mut n = 0u64;
    while Instant::now() < end {
        let input = random_input(&mut rng);
        c.send_bytes(&input);
        let context = format!(
            "random input {n} (seed {seed}): {:?}",
            String::from_utf8_lossy(&input[..input.len().min(300)])
        );
        hover_ok(&mut c, &uri, &context);
        // Error answers to random ids are allowed; nothing else may come.
        for r in stray_responses(&mut c) {
            assert!(r["error"]["code"].is_i64(), "{context}: {r}");
        }
        n += 1;
    }
    eprintln!("random soak: {n} hostile inputs in {secs} s (seed {seed}), a hover after each");
    assert!(n > 0);
    assert!(c.shutdown().success());
}
