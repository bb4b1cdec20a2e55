//! Arbitrary JSON-RPC messages and edit sequences through the language
//! server's own handlers, in process.
//!
//! The server's `lsp` module (from the `partscope` library) is driven through
//! `lsp::service()`, the service `partscope lsp` serves over stdio, on a
//! current-thread tokio runtime whose clock is paused: debounce and wait timers
//! then fire as soon as nothing else can run, so one execution takes
//! microseconds of timers instead of hundreds of milliseconds.
//!
//! The input is a script. Byte 0 picks the document's dialect (by extension)
//! and the client capabilities; then each step is an opcode byte followed by
//! operands and a length-prefixed payload: incremental and full edits with
//! arbitrary (also out-of-range) positions and text, every request the server
//! implements at arbitrary positions, close/reopen with arbitrary versions,
//! configuration changes with the payload as JSON, and raw messages whose
//! method and params come from the payload. libFuzzer's panic hook aborts on
//! any panic, also one the server would catch with `catch_unwind`, so a
//! handler that panics is reported even though the session would survive it.
#![no_main]

use partscope::lsp;

use std::sync::OnceLock;
use std::time::Duration;

use futures::{SinkExt, StreamExt};
use libfuzzer_sys::fuzz_target;
use serde_json::{json, Value};
use tower::{Service, ServiceExt};
use tower_lsp_server::jsonrpc::{Request, Response};

/// Methods a raw message may name; the params come from the fuzzer.
const METHODS: &[&str] = &[
    "textDocument/hover",
    "textDocument/completion",
    "textDocument/signatureHelp",
    "textDocument/definition",
    "textDocument/references",
    "textDocument/documentSymbol",
    "textDocument/foldingRange",
    "textDocument/semanticTokens/full",
    "textDocument/semanticTokens/range",
    "textDocument/codeAction",
    "textDocument/inlayHint",
    "textDocument/codeLens",
    "workspace/executeCommand",
    "partscope/dryRun",
    "textDocument/didOpen",
    "textDocument/didChange",
    "textDocument/didClose",
    "workspace/didChangeConfiguration",
    "workspace/didChangeWorkspaceFolders",
    "workspace/didChangeWatchedFiles",
    "initialized",
    "$/cancelRequest",
    "$/unknown",
    "shutdown",
];

/// Requests taken at a position in the open document.
const POSITION_REQUESTS: &[&str] = &[
    "textDocument/hover",
    "textDocument/completion",
    "textDocument/signatureHelp",
    "textDocument/definition",
    "textDocument/references",
];

/// Requests taken over a range of the open document.
const RANGE_REQUESTS: &[&str] = &[
    "textDocument/semanticTokens/range",
    "textDocument/codeAction",
    "textDocument/inlayHint",
];

/// Requests on the whole document.
const DOC_REQUESTS: &[&str] = &[
    "textDocument/documentSymbol",
    "textDocument/foldingRange",
    "textDocument/semanticTokens/full",
    "textDocument/codeLens",
    "partscope/dryRun",
];

/// A cursor over the fuzz input; reads past the end yield zeros / empty.
struct Script<'a> {
    data: &'a [u8],
}

impl<'a> Script<'a> {
    fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    /// A line or character: mostly small, sometimes far out of range, so
    /// clamping of positions past the end of a line or document is exercised.
    fn coord(&mut self) -> u32 {
        match self.byte() {
            255 => u32::MAX,
            254 => 1 << 20,
            b => u32::from(b % 64),
        }
    }

    /// A payload of up to 255 bytes.
    fn payload(&mut self) -> &'a [u8] {
        let n = (self.byte() as usize).min(self.data.len());
        let (p, rest) = self.data.split_at(n);
        self.data = rest;
        p
    }

    fn text(&mut self) -> String {
        String::from_utf8_lossy(self.payload()).into_owned()
    }

    fn position(&mut self) -> Value {
        json!({"line": self.coord(), "character": self.coord()})
    }

    fn range(&mut self) -> Value {
        json!({"start": self.position(), "end": self.position()})
    }
}

fn runtime() -> &'static tokio::runtime::Runtime {
    static RT: OnceLock<tokio::runtime::Runtime> = OnceLock::new();
    RT.get_or_init(|| {
        tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .start_paused(true)
            .build()
            .expect("a current-thread runtime")
    })
}

fn workspace_dir() -> &'static std::path::Path {
    static DIR: OnceLock<std::path::PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        // An empty folder of our own: whatever paths the fuzzer names, the
        // server reads other files only inside its workspace folders.
        let dir = std::env::temp_dir().join(format!("partscope-lsp-fuzz-{}", std::process::id()));
        let _ = std::fs::create_dir_all(&dir);
        dir
    })
}

fn file_uri(name: &str) -> String {
    format!("file://{}/{}", workspace_dir().display(), name)
}

fuzz_target!(|data: &[u8]| {
    runtime().block_on(drive(data));
});

async fn drive(data: &[u8]) {
    let (mut service, socket) = lsp::service();
    // Answer the server's own requests (configuration, registrations) so its
    // handlers never wait on a client that does not reply; notifications such
    // as published diagnostics are dropped.
    let (mut requests, mut responses) = socket.split();
    let client = tokio::spawn(async move {
        while let Some(req) = requests.next().await {
            if let Some(id) = req.id().cloned() {
                let result = match req.method() {
                    "workspace/configuration" => json!([{"dialect": "fanuc"}]),
                    _ => Value::Null,
                };
                if responses
                    .send(Response::from_parts(id, Ok(result)))
                    .await
                    .is_err()
                {
                    break;
                }
            }
        }
    });

    let mut s = Script { data };
    let head = s.byte();
    let ext = ["nc", "ngc", "fnc", "txt"][usize::from(head & 3)];
    let uri = file_uri(&format!("doc.{ext}"));
    let mut next_id: i64 = 1;
    let mut version: i32 = 1;

    let init = json!({
        "processId": null,
        "rootUri": file_uri(""),
        "capabilities": {"workspace": {
            "configuration": head & 4 != 0,
            "didChangeWatchedFiles": {"dynamicRegistration": head & 8 != 0},
        }},
        "initializationOptions": if head & 16 != 0 { json!({"maxFileSize": 64, "maxRunFileSize": 32}) } else { Value::Null },
    });
    send(&mut service, &mut next_id, "initialize", init, true).await;
    send(&mut service, &mut next_id, "initialized", json!({}), false).await;
    let first_text = s.text();
    send(
        &mut service,
        &mut next_id,
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": version, "text": first_text}}),
        false,
    )
    .await;

    // A bounded number of steps keeps one execution cheap whatever the input.
    for _ in 0..32 {
        if s.data.is_empty() {
            break;
        }
        let op = s.byte();
        match op % 10 {
            0 | 1 | 2 => {
                version = version.wrapping_add(1);
                let range = s.range();
                let text = s.text();
                send(
                    &mut service,
                    &mut next_id,
                    "textDocument/didChange",
                    json!({"textDocument": {"uri": uri, "version": version},
                           "contentChanges": [{"range": range, "text": text}]}),
                    false,
                )
                .await;
            }
            3 => {
                version = version.wrapping_add(1);
                let text = s.text();
                send(
                    &mut service,
                    &mut next_id,
                    "textDocument/didChange",
                    json!({"textDocument": {"uri": uri, "version": version},
                           "contentChanges": [{"text": text}]}),
                    false,
                )
                .await;
            }
            4 => {
                let m = POSITION_REQUESTS[usize::from(s.byte()) % POSITION_REQUESTS.len()];
                let p = s.position();
                send(
                    &mut service,
                    &mut next_id,
                    m,
                    json!({"textDocument": {"uri": uri}, "position": p,
                           "context": {"includeDeclaration": true, "triggerKind": 1}}),
                    true,
                )
                .await;
            }
            5 => {
                let m = RANGE_REQUESTS[usize::from(s.byte()) % RANGE_REQUESTS.len()];
                let r = s.range();
                send(
                    &mut service,
                    &mut next_id,
                    m,
                    json!({"textDocument": {"uri": uri}, "range": r,
                           "context": {"diagnostics": []}}),
                    true,
                )
                .await;
            }
            6 => {
                let m = DOC_REQUESTS[usize::from(s.byte()) % DOC_REQUESTS.len()];
                send(
                    &mut service,
                    &mut next_id,
                    m,
                    json!({"textDocument": {"uri": uri}}),
                    true,
                )
                .await;
            }
            7 => {
                // Close and reopen under an arbitrary version (also older).
                send(
                    &mut service,
                    &mut next_id,
                    "textDocument/didClose",
                    json!({"textDocument": {"uri": uri}}),
                    false,
                )
                .await;
                version = i32::from(s.byte() as i8);
                let text = s.text();
                send(&mut service, &mut next_id, "textDocument/didOpen",
                    json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": version, "text": text}}), false).await;
            }
            8 => {
                // A raw message: the payload as JSON params for a chosen
                // method, or as a whole request when it parses as one.
                let m = METHODS[usize::from(s.byte()) % METHODS.len()];
                let is_request = s.byte() & 1 == 1;
                let payload = s.payload();
                if let Ok(req) = serde_json::from_slice::<Request>(payload) {
                    let _ = call(&mut service, req).await;
                } else {
                    let params = serde_json::from_slice::<Value>(payload).unwrap_or_else(|_| {
                        Value::String(String::from_utf8_lossy(payload).into_owned())
                    });
                    send(&mut service, &mut next_id, m, params, is_request).await;
                }
            }
            _ => {
                // Let the debounced analysis and the run finish (virtual time).
                tokio::time::sleep(Duration::from_millis(u64::from(s.byte()) * 4)).await;
            }
        }
    }

    tokio::time::sleep(Duration::from_secs(1)).await;
    send(&mut service, &mut next_id, "shutdown", Value::Null, true).await;
    send(&mut service, &mut next_id, "exit", Value::Null, false).await;
    drop(service);
    let _ = client.await;
}

async fn send(
    service: &mut tower_lsp_server::LspService<lsp::Backend>,
    next_id: &mut i64,
    method: &'static str,
    params: Value,
    is_request: bool,
) {
    let mut b = Request::build(method).params(params);
    if is_request {
        b = b.id(*next_id);
        *next_id += 1;
    }
    let _ = call(service, b.finish()).await;
}

async fn call(
    service: &mut tower_lsp_server::LspService<lsp::Backend>,
    req: Request,
) -> Option<Response> {
    let ready = service.ready().await.ok()?;
    ready.call(req).await.ok().flatten()
}
