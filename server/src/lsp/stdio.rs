//! The transport: LSP base-protocol framing and JSON-RPC decoding over stdio,
//! in front of `tower-lsp-server`'s service.
//!
//! The library's own `Server` ends the session at the first body it cannot
//! decode, and it trusts `Content-Length`. This loop instead:
//! - finds each header by its `Content-Length` line, skipping whatever bytes
//!   come before it, so a wrong length costs one message, not the session
//!   (a valid JSON body never holds a raw `Content-Length: N` line, since raw
//!   line breaks cannot occur in JSON strings, so a body that does is cut
//!   there and the rest read as the next header);
//! - caps the header block ([`Limits::max_header`]) and the body
//!   ([`Limits::max_body`]): a larger body is skipped as it streams in,
//!   never buffered;
//! - decodes the body into a request, notification or response itself,
//!   repairing invalid UTF-8 and lone UTF-16 surrogate escapes to U+FFFD
//!   (an editor deleting half an emoji sends `"\ud83d"`), and answers what it
//!   cannot use with a JSON-RPC error when it can name the request's id
//!   (-32700 parse error, -32600 invalid request), dropping it otherwise;
//! - answers `$/…` requests with -32601 (the library answers them with
//!   nothing, leaving the client waiting);
//! - writes every outgoing message from one task, header and body in one
//!   buffer, so error answers never interleave with the library's output;
//! - stops at `exit` (status 0 after `shutdown`, 1 without) or when stdin
//!   closes, without waiting for analyses still running.

use std::borrow::Cow;
use std::process::ExitCode;
use std::task::Poll;
use std::time::Duration;

use futures::{SinkExt, StreamExt};
use serde_json::{Map, Value};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};
use tokio::sync::mpsc;
use tower::Service;
use tower_lsp_server::jsonrpc::{Error, ErrorCode, Id, Request, Response};
use tower_lsp_server::{ClientSocket, Loopback};

/// Size limits of incoming messages.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Bytes from `Content-Length` to the blank line ending the header block.
    pub max_header: usize,
    /// Bytes of one message body; larger bodies are skipped.
    pub max_body: u64,
}

/// The default body limit, 256 MiB: a document well above the syntax-only
/// limit (`maxFileSize`, 64 MB) fits with room for JSON escaping, so it is
/// still opened and parsed.
pub const DEFAULT_MAX_BODY: u64 = 256 << 20;

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_header: 8 << 10,
            max_body: DEFAULT_MAX_BODY,
        }
    }
}

impl Limits {
    /// The defaults, with the body limit from `PARTSCOPE_LSP_MAX_MESSAGE_BYTES`
    /// when it is set (the limit applies before any client option arrives).
    pub fn from_env() -> Limits {
        let mut l = Limits::default();
        if let Some(v) = std::env::var_os("PARTSCOPE_LSP_MAX_MESSAGE_BYTES") {
            match v.to_str().and_then(|s| s.trim().parse::<u64>().ok()) {
                Some(n) if n > 0 => l.max_body = n,
                _ => eprintln!(
                    "partscope lsp: PARTSCOPE_LSP_MAX_MESSAGE_BYTES is not a positive number; using {DEFAULT_MAX_BODY}"
                ),
            }
        }
        l
    }
}

/// How much of a broken or skipped body is kept to look for its id.
const PREFIX_KEPT: usize = 4096;
/// `content-length` as it is matched, case-insensitively.
const CONTENT_LENGTH: &[u8] = b"content-length";
/// The longest header line [`header_line_at`] accepts (name, blanks, 20 digits).
const MAX_LENGTH_LINE: usize = 64;
const READ_CHUNK: usize = 1 << 16;
/// Capacity the input buffer keeps between messages; a larger one (a
/// multi-megabyte `didOpen`) is given back once its message is read.
const KEPT_CAPACITY: usize = 4 * READ_CHUNK;

/// One unit of input.
#[derive(Debug, PartialEq)]
pub enum Frame {
    Body(Vec<u8>),
    /// A body cut short: by the next header inside it, or by end of input.
    Broken {
        prefix: Vec<u8>,
    },
    /// A body above [`Limits::max_body`], skipped.
    TooLarge {
        prefix: Vec<u8>,
        len: u64,
    },
    Eof,
}

/// A `Content-Length: N` line at `i`: (N saturated to `u64::MAX`, the
/// offset after its line break). `Err(true)` when `data` ends before the line
/// could be told apart, `Err(false)` when there is no such line at `i`.
fn header_line_at(data: &[u8], i: usize) -> Result<(u64, usize), bool> {
    let incomplete = |j: usize| j >= data.len() && data.len() - i < MAX_LENGTH_LINE;
    let name = data.get(i..i + CONTENT_LENGTH.len());
    match name {
        Some(n) if n.eq_ignore_ascii_case(CONTENT_LENGTH) => {}
        Some(_) => return Err(false),
        None => {
            let rest = &data[i..];
            return Err(CONTENT_LENGTH[..rest.len()].eq_ignore_ascii_case(rest));
        }
    }
    let mut j = i + CONTENT_LENGTH.len();
    let blanks = |j: &mut usize| {
        while data.get(*j).is_some_and(|b| *b == b' ' || *b == b'\t') {
            *j += 1;
        }
    };
    blanks(&mut j);
    match data.get(j) {
        Some(b':') => j += 1,
        Some(_) => return Err(false),
        None => return Err(incomplete(j)),
    }
    blanks(&mut j);
    let digits = j;
    let mut n: u64 = 0;
    while let Some(d) = data.get(j).filter(|b| b.is_ascii_digit()) {
        n = n.saturating_mul(10).saturating_add(u64::from(d - b'0'));
        j += 1;
    }
    if j >= data.len() {
        return Err(incomplete(j));
    }
    if j == digits {
        return Err(false);
    }
    blanks(&mut j);
    if data.get(j) == Some(&b'\r') {
        j += 1;
    }
    match data.get(j) {
        Some(b'\n') => Ok((n, j + 1)),
        Some(_) => Err(false),
        None => Err(incomplete(j)),
    }
}

/// Where a header block starts in `data`.
#[derive(Debug, PartialEq)]
enum Scan {
    /// Bytes before `start` are not a header; the body starts at `body`.
    Found { start: usize, len: u64, body: usize },
    /// No complete header yet: bytes before `keep` can be dropped.
    NeedMore { keep: usize },
}

fn is_candidate(b: u8) -> bool {
    b == b'c' || b == b'C'
}

/// Finds the first complete header block (a `Content-Length` line, maybe
/// other lines, then an empty line) of at most `max_header` bytes.
fn scan_header(data: &[u8], max_header: usize) -> Scan {
    let mut i = 0;
    'candidates: while i < data.len() {
        if !is_candidate(data[i]) {
            i += 1;
            continue;
        }
        let (len, mut k) = match header_line_at(data, i) {
            Err(true) => return Scan::NeedMore { keep: i },
            Err(false) => {
                i += 1;
                continue;
            }
            Ok(found) => found,
        };
        loop {
            let Some(nl) = data[k..].iter().position(|&b| b == b'\n') else {
                if data.len() - i > max_header {
                    i += 1;
                    continue 'candidates;
                }
                return Scan::NeedMore { keep: i };
            };
            // A second `Content-Length` line, also one after junk on its
            // line, starts a new header: the block before it never ended.
            if let Some(q) = embedded_header(&data[k..=k + nl]) {
                i = k + q;
                continue 'candidates;
            }
            let line = &data[k..k + nl];
            k += nl + 1;
            if k - i > max_header {
                i += 1;
                continue 'candidates;
            }
            if line.is_empty() || line == b"\r" {
                return Scan::Found {
                    start: i,
                    len,
                    body: k,
                };
            }
        }
    }
    Scan::NeedMore {
        keep: data.len().saturating_sub(CONTENT_LENGTH.len()),
    }
}

/// The first complete `Content-Length: N` line in `data`, which cannot be
/// part of a valid JSON body.
fn embedded_header(data: &[u8]) -> Option<usize> {
    (0..data.len()).find(|&i| is_candidate(data[i]) && header_line_at(data, i).is_ok())
}

/// Whether a `Content-Length` line that starts before `end` may still be
/// completed by bytes yet to come (it runs to the end of `data`).
fn header_may_start_before(data: &[u8], end: usize) -> bool {
    let from = data.len().saturating_sub(MAX_LENGTH_LINE);
    (from..end.min(data.len()))
        .any(|i| is_candidate(data[i]) && header_line_at(data, i) == Err(true))
}

/// Reads frames from a byte stream, holding at most one body (within the
/// limit) and a header's worth of other bytes.
pub struct FrameReader<R> {
    inner: R,
    buf: Vec<u8>,
    /// Start of the unread bytes in `buf`.
    pos: usize,
    eof: bool,
    limits: Limits,
}

impl<R: AsyncRead + Unpin> FrameReader<R> {
    pub fn new(inner: R, limits: Limits) -> Self {
        FrameReader {
            inner,
            buf: Vec::new(),
            pos: 0,
            eof: false,
            limits,
        }
    }

    fn data(&self) -> &[u8] {
        &self.buf[self.pos..]
    }

    /// Reads more input after the unread bytes; `false` at end of input.
    async fn fill(&mut self) -> std::io::Result<bool> {
        if self.eof {
            return Ok(false);
        }
        if self.pos > 0 {
            self.buf.drain(..self.pos);
            self.pos = 0;
        }
        let old = self.buf.len();
        self.buf.resize(old + READ_CHUNK, 0);
        let n = self.inner.read(&mut self.buf[old..]).await;
        self.buf.truncate(old + *n.as_ref().unwrap_or(&0));
        if n? == 0 {
            self.eof = true;
            return Ok(false);
        }
        Ok(true)
    }

    pub async fn next(&mut self) -> std::io::Result<Frame> {
        let frame = self.next_frame().await;
        self.compact();
        frame
    }

    /// Drops the read bytes and, after a large message, the capacity it grew
    /// to: the server would otherwise hold the largest message's size for its
    /// whole life, beside the document it became.
    fn compact(&mut self) {
        if self.buf.capacity() > KEPT_CAPACITY {
            let rest = self.buf.get(self.pos..).unwrap_or_default();
            let mut kept = Vec::with_capacity(rest.len().max(READ_CHUNK));
            kept.extend_from_slice(rest);
            self.buf = kept;
            self.pos = 0;
        }
    }

    async fn next_frame(&mut self) -> std::io::Result<Frame> {
        let len = loop {
            match scan_header(self.data(), self.limits.max_header) {
                Scan::Found { start, len, body } => {
                    let skipped = &self.data()[..start];
                    // Other header lines before `Content-Length` are not news.
                    if !skipped.iter().all(|b| b.is_ascii_whitespace())
                        && !skipped.to_ascii_lowercase().starts_with(b"content-type")
                    {
                        eprintln!(
                            "partscope lsp: skipped {start} bytes before the next Content-Length header"
                        );
                    }
                    self.pos += body;
                    break len;
                }
                Scan::NeedMore { keep } => {
                    self.pos += keep;
                    if !self.fill().await? {
                        return Ok(Frame::Eof);
                    }
                }
            }
        };
        if len > self.limits.max_body {
            return self.skip_body(len).await;
        }
        let len = len as usize;
        let mut scanned: usize = 0;
        loop {
            // Look for the next header inside the body as it arrives, a little
            // past the body's end for one that begins inside it.
            let avail = self.data().len();
            let upto = avail.min(len + MAX_LENGTH_LINE);
            let from = scanned.saturating_sub(MAX_LENGTH_LINE);
            if let Some(p) = embedded_header(&self.data()[from..upto]).map(|p| p + from) {
                if p < len {
                    let prefix = self.data()[..p.min(PREFIX_KEPT)].to_vec();
                    self.pos += p;
                    eprintln!(
                        "partscope lsp: a message ended {} bytes before its Content-Length of {len}",
                        len - p
                    );
                    return Ok(Frame::Broken { prefix });
                }
            }
            scanned = upto;
            // A valid body never ends inside a header line; a broken one
            // may, and then the rest of that header is awaited.
            if avail >= len && (self.eof || !header_may_start_before(&self.data()[..upto], len)) {
                let body = self.data()[..len].to_vec();
                self.pos += len;
                return Ok(Frame::Body(body));
            }
            self.buf.reserve(len.saturating_sub(avail));
            if !self.fill().await? && avail < len {
                let prefix = self.data()[..avail.min(PREFIX_KEPT)].to_vec();
                self.pos = self.buf.len();
                return Ok(Frame::Broken { prefix });
            }
        }
    }

    /// Drops a body above the limit as it arrives (keeping its start for the
    /// id), unless a header inside it shows the length was wrong.
    async fn skip_body(&mut self, len: u64) -> std::io::Result<Frame> {
        eprintln!(
            "partscope lsp: skipping a message of {len} bytes (limit {}; PARTSCOPE_LSP_MAX_MESSAGE_BYTES raises it)",
            self.limits.max_body
        );
        let mut prefix = Vec::new();
        let mut left = len;
        loop {
            let avail = self.data().len();
            let here = (avail as u64).min(left) as usize;
            if let Some(p) = embedded_header(&self.data()[..avail.min(here + MAX_LENGTH_LINE)])
                .filter(|&p| p < here)
            {
                let take = p.min(PREFIX_KEPT.saturating_sub(prefix.len()));
                prefix.extend_from_slice(&self.data()[..take]);
                self.pos += p;
                return Ok(Frame::Broken { prefix });
            }
            // Keep a header's worth unread: a header may start in it.
            let end = avail.min(here + MAX_LENGTH_LINE);
            let drop = if (here as u64) == left
                && (self.eof || !header_may_start_before(&self.data()[..end], here))
            {
                here
            } else {
                here.saturating_sub(MAX_LENGTH_LINE)
            };
            let take = drop.min(PREFIX_KEPT.saturating_sub(prefix.len()));
            prefix.extend_from_slice(&self.data()[..take]);
            self.pos += drop;
            left -= drop as u64;
            if left == 0 {
                return Ok(Frame::TooLarge { prefix, len });
            }
            if !self.fill().await? && (self.data().len() as u64) < left {
                return Ok(Frame::Broken { prefix });
            }
        }
    }
}

/// What a body holds.
#[derive(Debug, PartialEq)]
pub enum Decoded {
    Request(Request),
    Response(Response),
    /// Not a usable message: answered when `id` is known, dropped otherwise.
    Invalid {
        id: Option<Id>,
        code: ErrorCode,
        message: String,
    },
}

/// Replaces `\u` escapes of unpaired UTF-16 surrogates with `\uFFFD`.
/// `None` when there are none.
fn repair_surrogates(text: &str) -> Option<String> {
    let b = text.as_bytes();
    let hex = |at: usize| -> Option<u32> {
        let s = b.get(at..at + 4)?;
        u32::from_str_radix(std::str::from_utf8(s).ok()?, 16).ok()
    };
    let escape_at = |at: usize| -> Option<u32> {
        if b.get(at) == Some(&b'\\') && b.get(at + 1) == Some(&b'u') {
            hex(at + 2)
        } else {
            None
        }
    };
    let mut out: Option<String> = None;
    let mut copied = 0;
    let mut i = 0;
    while i < b.len() {
        if b[i] != b'\\' {
            i += 1;
            continue;
        }
        let Some(u) = escape_at(i) else {
            // Any other escape, `\\` included, is two bytes.
            i += 2;
            continue;
        };
        let paired = (0xD800..0xDC00).contains(&u)
            && escape_at(i + 6).is_some_and(|l| (0xDC00..0xE000).contains(&l));
        if paired {
            i += 12;
        } else if (0xD800..0xE000).contains(&u) {
            let o = out.get_or_insert_with(String::new);
            o.push_str(&text[copied..i]);
            o.push_str("\\uFFFD");
            i += 6;
            copied = i;
        } else {
            i += 6;
        }
    }
    let mut o = out?;
    o.push_str(&text[copied..]);
    Some(o)
}

/// The top-level `"id"` of a (possibly cut) JSON object, read without
/// parsing the rest: a number or a string.
fn sniff_id(b: &[u8]) -> Option<Id> {
    let ws = |i: &mut usize| {
        while b.get(*i).is_some_and(|c| c.is_ascii_whitespace()) {
            *i += 1;
        }
    };
    // The end of the string starting at `i` (after its closing quote).
    let string_end = |i: usize| -> Option<usize> {
        let mut j = i + 1;
        loop {
            match b.get(j)? {
                b'\\' => j += 2,
                b'"' => return Some(j + 1),
                _ => j += 1,
            }
        }
    };
    let mut depth = 0usize;
    let mut key_next = false;
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'{' => {
                depth += 1;
                key_next = depth == 1;
            }
            b'[' => depth += 1,
            b'}' | b']' => depth = depth.saturating_sub(1),
            b',' => key_next = depth == 1,
            b'"' => {
                let end = string_end(i)?;
                let is_id = depth == 1 && key_next && &b[i..end] == b"\"id\"";
                key_next = false;
                i = end;
                if !is_id {
                    continue;
                }
                ws(&mut i);
                if b.get(i) != Some(&b':') {
                    return None;
                }
                i += 1;
                ws(&mut i);
                let start = i;
                return match b.get(i)? {
                    b'"' => {
                        let end = string_end(i)?;
                        serde_json::from_slice::<String>(&b[start..end])
                            .ok()
                            .map(Id::String)
                    }
                    _ => {
                        if b.get(i) == Some(&b'-') {
                            i += 1;
                        }
                        while b.get(i).is_some_and(u8::is_ascii_digit) {
                            i += 1;
                        }
                        // A fraction or exponent is not an id, nor a cut number.
                        match b.get(i) {
                            Some(c) if !matches!(c, b'.' | b'e' | b'E') => {
                                std::str::from_utf8(&b[start..i])
                                    .ok()?
                                    .parse()
                                    .ok()
                                    .map(Id::Number)
                            }
                            _ => None,
                        }
                    }
                };
            }
            _ => {}
        }
        i += 1;
    }
    None
}

fn invalid(id: Option<Id>, code: ErrorCode, message: impl Into<String>) -> Decoded {
    Decoded::Invalid {
        id,
        code,
        message: message.into(),
    }
}

/// Decodes one body.
pub fn decode(body: &[u8]) -> Decoded {
    let value = match serde_json::from_slice::<Value>(body) {
        Ok(v) => v,
        Err(first) => {
            let text = String::from_utf8_lossy(body);
            let repaired = repair_surrogates(&text);
            let changed = repaired.is_some() || matches!(text, Cow::Owned(_));
            let text = repaired.map_or(text, Cow::Owned);
            match serde_json::from_str::<Value>(&text) {
                Ok(v) if changed => {
                    eprintln!(
                        "partscope lsp: replaced invalid UTF-8 or unpaired surrogates in a message with U+FFFD"
                    );
                    v
                }
                _ => {
                    return invalid(
                        sniff_id(body),
                        ErrorCode::ParseError,
                        format!("the message is not JSON: {first}"),
                    )
                }
            }
        }
    };
    let Value::Object(map) = value else {
        return invalid(
            None,
            ErrorCode::InvalidRequest,
            "a message must be a JSON object (batches are not supported)",
        );
    };
    classify(map)
}

fn classify(map: Map<String, Value>) -> Decoded {
    let id = match map.get("id") {
        None => None,
        Some(v) => match serde_json::from_value::<Id>(v.clone()) {
            Ok(id) => Some(id),
            Err(_) => {
                return invalid(
                    None,
                    ErrorCode::InvalidRequest,
                    "the id must be an integer or a string",
                )
            }
        },
    };
    if map.get("jsonrpc").and_then(Value::as_str) != Some("2.0") {
        return invalid(id, ErrorCode::InvalidRequest, "\"jsonrpc\" must be \"2.0\"");
    }
    match map.get("method") {
        Some(Value::String(_)) => match serde_json::from_value::<Request>(Value::Object(map)) {
            Ok(r) => Decoded::Request(r),
            Err(e) => invalid(id, ErrorCode::InvalidRequest, e.to_string()),
        },
        Some(_) => invalid(id, ErrorCode::InvalidRequest, "\"method\" must be a string"),
        None if id.is_some() && (map.contains_key("result") || map.contains_key("error")) => {
            match serde_json::from_value::<Response>(Value::Object(map)) {
                Ok(r) => Decoded::Response(r),
                // A broken answer to one of our requests is not answered.
                Err(e) => invalid(None, ErrorCode::InvalidRequest, e.to_string()),
            }
        }
        None => invalid(
            id,
            ErrorCode::InvalidRequest,
            "a message needs a \"method\", or a \"result\" or \"error\"",
        ),
    }
}

/// Frames and queues one outgoing message.
fn send<T: serde::Serialize>(out: &mpsc::UnboundedSender<Vec<u8>>, msg: &T) {
    match serde_json::to_vec(msg) {
        Ok(body) => {
            let mut framed = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
            framed.extend_from_slice(&body);
            let _ = out.send(framed);
        }
        Err(e) => eprintln!("partscope lsp: cannot serialise a message: {e}"),
    }
}

fn error_response(id: Id, code: ErrorCode, message: String) -> Response {
    Response::from_error(
        id,
        Error {
            code,
            message: message.into(),
            data: None,
        },
    )
}

/// The only writer of `output`: each message in one `write_all`, until the
/// channel closes or an empty message (the end marker) comes.
async fn write_all<O: AsyncWrite + Unpin>(mut rx: mpsc::UnboundedReceiver<Vec<u8>>, mut output: O) {
    while let Some(msg) = rx.recv().await {
        if msg.is_empty() {
            break;
        }
        if output.write_all(&msg).await.is_err() || output.flush().await.is_err() {
            break;
        }
    }
}

/// Serves `service` on `input`/`output` until `exit` or end of input; the
/// process status to exit with.
pub async fn serve<I, O, S>(
    input: I,
    output: O,
    mut service: S,
    socket: ClientSocket,
    limits: Limits,
) -> ExitCode
where
    I: AsyncRead + Unpin,
    O: AsyncWrite + Unpin + Send + 'static,
    S: Service<Request, Response = Option<Response>>,
    S::Future: Send + 'static,
{
    let (out, rx) = mpsc::unbounded_channel();
    let writer = tokio::spawn(write_all(rx, output));
    let (mut to_client, mut from_client) = Loopback::split(socket);
    let forward = {
        let out = out.clone();
        tokio::spawn(async move {
            while let Some(req) = to_client.next().await {
                send(&out, &req);
            }
        })
    };
    let mut reader = FrameReader::new(input, limits);
    let mut shutdown = false;
    let status = |shutdown: bool| {
        if shutdown {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        }
    };
    let code = loop {
        let frame = match reader.next().await {
            Ok(f) => f,
            Err(e) => {
                eprintln!("partscope lsp: reading stdin failed: {e}");
                break status(shutdown);
            }
        };
        let answer = |id: Option<Id>, code: ErrorCode, message: String| match id {
            Some(id) => send(&out, &error_response(id, code, message)),
            None => eprintln!("partscope lsp: dropped a message: {message}"),
        };
        let req = match frame {
            Frame::Eof => break status(shutdown),
            Frame::Broken { prefix } => {
                answer(
                    sniff_id(&prefix),
                    ErrorCode::ParseError,
                    "the message is shorter or longer than its Content-Length".into(),
                );
                continue;
            }
            Frame::TooLarge { prefix, len } => {
                answer(
                    sniff_id(&prefix),
                    ErrorCode::InvalidRequest,
                    format!(
                        "the message of {len} bytes is above the limit of {} bytes",
                        limits.max_body
                    ),
                );
                continue;
            }
            Frame::Body(body) => match decode(&body) {
                Decoded::Invalid { id, code, message } => {
                    answer(id, code, message);
                    continue;
                }
                Decoded::Response(r) => {
                    let _ = from_client.send(r).await;
                    continue;
                }
                Decoded::Request(r) => r,
            },
        };
        if let (Some(id), true) = (req.id(), req.method().starts_with("$/")) {
            let message = format!("method not found: {}", req.method());
            send(
                &out,
                &error_response(id.clone(), ErrorCode::MethodNotFound, message),
            );
            continue;
        }
        // These two are requests; as notifications they would change the
        // server's state with nobody waiting for the answer.
        if req.id().is_none() && matches!(req.method(), "initialize" | "shutdown") {
            eprintln!(
                "partscope lsp: dropped `{}` sent without an id",
                req.method()
            );
            continue;
        }
        let exit = req.method() == "exit";
        if req.method() == "shutdown" && req.id().is_some() {
            shutdown = true;
        }
        // The service is not ready while `initialize` runs, and does not wake
        // anyone when it becomes ready: poll again shortly.
        let ready = loop {
            match futures::poll!(futures::future::poll_fn(|cx| service.poll_ready(cx))) {
                Poll::Ready(r) => break r.is_ok(),
                Poll::Pending => tokio::time::sleep(Duration::from_millis(1)).await,
            }
        };
        if !ready {
            break status(shutdown);
        }
        // The first poll runs the handler up to its first `.await`, in the
        // order messages arrived (`didChange` edits apply there); the rest
        // runs as its own task, so a slow request never holds up the next.
        let mut fut = Box::pin(service.call(req));
        match futures::poll!(&mut fut) {
            Poll::Ready(r) => {
                if let Ok(Some(resp)) = r {
                    send(&out, &resp);
                }
            }
            Poll::Pending => {
                let out = out.clone();
                tokio::spawn(async move {
                    let Ok(Some(resp)) = fut.await else { return };
                    // A dry run's answer can be large: serialise it off the
                    // async workers.
                    let _ = tokio::task::spawn_blocking(move || send(&out, &resp)).await;
                });
            }
        }
        if exit {
            break status(shutdown);
        }
    };
    forward.abort();
    // Answers already queued (the one to `shutdown`) still go out; answers of
    // requests still running are abandoned with them.
    let _ = out.send(Vec::new());
    let _ = tokio::time::timeout(Duration::from_millis(500), writer).await;
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    async fn frames(input: &[u8], limits: Limits) -> Vec<Frame> {
        let mut r = FrameReader::new(input, limits);
        let mut out = Vec::new();
        loop {
            let f = r.next().await.unwrap();
            if f == Frame::Eof {
                return out;
            }
            out.push(f);
        }
    }

    fn msg(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    #[tokio::test]
    async fn a_large_message_leaves_no_large_buffer_behind() {
        let big = format!(r#"{{"text":"{}"}}"#, "G1 X1\n".repeat(300_000));
        let small = r#"{"jsonrpc":"2.0","method":"a"}"#;
        let input = format!("{}{}", msg(&big), msg(small));
        let mut r = FrameReader::new(input.as_bytes(), Limits::default());
        assert_eq!(r.next().await.unwrap(), Frame::Body(big.into_bytes()));
        assert!(r.buf.capacity() <= KEPT_CAPACITY, "{}", r.buf.capacity());
        assert_eq!(
            r.next().await.unwrap(),
            Frame::Body(small.as_bytes().to_vec())
        );
        assert_eq!(r.next().await.unwrap(), Frame::Eof);
    }

    #[tokio::test]
    async fn frames_resynchronise_on_the_next_header() {
        let good = r#"{"jsonrpc":"2.0","method":"a"}"#;
        // Too short by 3, too long by 5, garbage between, a Content-Type line,
        // a lower-case header with blanks, and a header split across lines.
        let input = format!(
            "Content-Length: {}\r\n\r\n{good}{}junk\r\nContent-Length: {}\r\n\r\n{good}{}Content-Type: x\r\ncontent-length :  {}\r\n\r\n{good}",
            good.len() - 3,
            msg(good),
            good.len() + 5,
            msg(good),
            good.len(),
        );
        let got = frames(input.as_bytes(), Limits::default()).await;
        let body = || Frame::Body(good.as_bytes().to_vec());
        assert_eq!(
            got,
            vec![
                Frame::Body(good.as_bytes()[..good.len() - 3].to_vec()),
                body(),
                Frame::Broken {
                    prefix: good.as_bytes().to_vec()
                },
                body(),
                body(),
            ]
        );
    }

    #[tokio::test]
    async fn a_body_above_the_limit_is_skipped_and_one_that_lies_is_cut() {
        let limits = Limits {
            max_header: 8 << 10,
            max_body: 100,
        };
        let big = format!(r#"{{"id":7,"x":"{}"}}"#, "a".repeat(300_000));
        let good = r#"{"jsonrpc":"2.0","method":"a"}"#;
        let input = format!(
            "{}{}Content-Length: 999999999999\r\n\r\n{{\"id\":\"q\"}}{}",
            msg(&big),
            msg(good),
            msg(good)
        );
        let got = frames(input.as_bytes(), limits).await;
        assert_eq!(got.len(), 4, "{got:?}");
        match &got[0] {
            Frame::TooLarge { prefix, len } => {
                assert_eq!(*len, big.len() as u64);
                assert_eq!(prefix.len(), PREFIX_KEPT);
                assert_eq!(sniff_id(prefix), Some(Id::Number(7)));
            }
            f => panic!("{f:?}"),
        }
        assert_eq!(got[1], Frame::Body(good.as_bytes().to_vec()));
        assert_eq!(
            got[2],
            Frame::Broken {
                prefix: br#"{"id":"q"}"#.to_vec()
            }
        );
        assert_eq!(got[3], Frame::Body(good.as_bytes().to_vec()));
    }

    #[tokio::test]
    async fn header_garbage_is_bounded_and_skipped() {
        let good = r#"{"jsonrpc":"2.0","method":"a"}"#;
        // A header that never ends within the cap, then a good message.
        let input = format!(
            "Content-Length: 5\r\nX: {}\r\n\r\n{}",
            "y".repeat(20_000),
            msg(good)
        );
        let got = frames(input.as_bytes(), Limits::default()).await;
        assert_eq!(got, vec![Frame::Body(good.as_bytes().to_vec())]);
        // A header whose blank line was lost gives way to the next header,
        // also one that follows junk on the same line.
        let input = format!("Content-Length: 50\r\n{}", msg(good));
        let got = frames(input.as_bytes(), Limits::default()).await;
        assert_eq!(got, vec![Frame::Body(good.as_bytes().to_vec())]);
        let input = format!("Content-Length: 50\r\nab\x01{}", msg(good));
        let got = frames(input.as_bytes(), Limits::default()).await;
        assert_eq!(got, vec![Frame::Body(good.as_bytes().to_vec())]);
    }

    #[test]
    fn non_json_rpc_bodies_are_classified() {
        let code = |b: &[u8]| match decode(b) {
            Decoded::Invalid { id, code, .. } => Some((id, code)),
            _ => None,
        };
        assert_eq!(code(b"{}"), Some((None, ErrorCode::InvalidRequest)));
        assert_eq!(code(b"null"), Some((None, ErrorCode::InvalidRequest)));
        assert_eq!(
            code(br#"[{"jsonrpc":"2.0","id":1,"method":"shutdown"}]"#),
            Some((None, ErrorCode::InvalidRequest))
        );
        assert_eq!(
            code(br#"{"jsonrpc":"1.0","id":3,"method":"x"}"#),
            Some((Some(Id::Number(3)), ErrorCode::InvalidRequest))
        );
        assert_eq!(
            code(br#"{"jsonrpc":"2.0","id":"a","method":5}"#),
            Some((Some(Id::String("a".into())), ErrorCode::InvalidRequest))
        );
        assert_eq!(
            code(br#"{"jsonrpc":"2.0","id":4,"method":"x","params":{"#),
            Some((Some(Id::Number(4)), ErrorCode::ParseError))
        );
        assert_eq!(
            code(br#"{"jsonrpc":"2.0","id":1.5,"method":"x"}"#),
            Some((None, ErrorCode::InvalidRequest))
        );
        assert!(matches!(
            decode(br#"{"jsonrpc":"2.0","id":9,"result":null}"#),
            Decoded::Response(_)
        ));
    }

    #[test]
    fn lone_surrogates_and_invalid_utf8_become_replacement_characters() {
        let text = |b: &[u8]| match decode(b) {
            Decoded::Request(r) => r.params().cloned().unwrap_or_default()["t"].clone(),
            d => panic!("{d:?}"),
        };
        let m = |t: &str| format!(r#"{{"jsonrpc":"2.0","method":"m","params":{{"t":"{t}"}}}}"#);
        assert_eq!(text(m(r"a\ud83db").as_bytes()), "a\u{fffd}b");
        assert_eq!(text(m(r"\ude00").as_bytes()), "\u{fffd}");
        // A pair stays, and an escaped backslash is not an escape.
        assert_eq!(text(m(r"\ud83d\ude00\\ud83d").as_bytes()), "😀\\ud83d");
        let mut bad = m("x_y").into_bytes();
        let at = bad.iter().position(|&b| b == b'_').unwrap();
        bad[at] = 0xff;
        assert_eq!(text(&bad), "x\u{fffd}y");
    }
}
