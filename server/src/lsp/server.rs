//! The protocol layer: document store, scheduling of analyses, and one small
//! handler per request (convert → analyse off-thread → convert back).
//!
//! Rules this file keeps:
//! - `didChange` edits are applied synchronously, before the handler's first
//!   `.await`, so they are applied in the order the client sent them.
//! - The state lock is a `std::sync::Mutex` held only for short, non-async
//!   sections; analyses run on blocking threads, tagged with the document
//!   version, and a result for an older version is dropped.
//! - Every handler body runs under `catch_unwind`, and analysis work runs in
//!   `spawn_blocking` (whose panics come back as errors), so a bug in one
//!   request cannot take the server down.

use std::collections::HashMap;
use std::future::Future;
use std::panic::AssertUnwindSafe;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use futures::FutureExt;
use ropey::Rope;
use serde_json::Value;
use tower_lsp_server::jsonrpc::{Error, ErrorCode, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer};

use super::config::{BlockTimes, ClientOptions};
use super::dry_run::{self, CancelFlag, DryRunResult, DryRunner};
use super::goto::OtherDoc;
use super::position::{apply_change, offset_to_position, position_to_offset, span_to_range};
use super::snapshot::{self, Inputs, Snapshot};
use super::{
    actions, completion, formatting, goto, rename, semantic, signature, symbols, workspace,
};
use crate::cli::workspace::FileCache;
use crate::ide;

/// How long edits must pause before diagnostics are recomputed: not at all.
/// An edit costs an incremental update (milliseconds), analyses of one
/// document run one at a time, and one whose version was superseded while
/// it waited for its turn is skipped, so a burst of typing coalesces anyway.
const DEBOUNCE: Duration = Duration::ZERO;
/// How long a request waits for the scheduled analysis before doing its own.
const WAIT_FOR_ANALYSIS: Duration = Duration::from_secs(30);
/// How long edits of a large file must pause before the interpreter runs.
const RUN_IDLE: Duration = Duration::from_millis(300);
/// Files up to this size wait [`SMALL_RUN_WAIT`] for the run; larger ones
/// publish their static diagnostics first ([`Backend::publish_then_run`]).
const SMALL_FILE: usize = 256 * 1024;
const SMALL_RUN_WAIT: Duration = Duration::from_secs(5);
/// Above this many tokens a full semantic-tokens response is refused (the
/// client then asks for the visible range).
const MAX_FULL_SEMANTIC_TOKENS: usize = 500_000;
pub const DRY_RUN_COMMAND: &str = "partscope.dryRun";
/// The cycle-time lens's command: the breakdown as text and figures, also
/// shown with `window/showMessage` unless the client asks to show it itself.
pub const BREAKDOWN_COMMAND: &str = "partscope.showBreakdown";

struct Doc {
    rope: Rope,
    version: i32,
    path: Option<PathBuf>,
    /// Bumped by every change; a debounced analysis runs only if it is still current.
    generation: u64,
    /// The newest analysis (possibly of an older version than `version`:
    /// the next analysis updates it).
    snapshot: Option<Arc<Snapshot>>,
    /// Held while the document is analysed: one analysis at a time, so each
    /// starts from the result of the one before.
    analysing: Arc<tokio::sync::Mutex<()>>,
    /// Set when the document is closed: its background runs stop.
    closed: CancelFlag,
    /// The newest `partscope/dryRun` of the document, which the next one
    /// supersedes.
    dry_run: Option<DryRunTicket>,
}

/// One `partscope/dryRun` request as the next one of its document sees it.
struct DryRunTicket {
    /// The document version when it arrived.
    version: i32,
    /// Stops its run: set when a newer request comes for a newer version.
    run: CancelFlag,
    /// Set when any newer request comes: it answers with an error instead of
    /// a toolpath (the run itself, shared by a request for the same version,
    /// goes on).
    superseded: CancelFlag,
}

/// The answer of a superseded `partscope/dryRun` (LSP's ServerCancelled).
pub const SUPERSEDED: i64 = -32802;

#[derive(Default)]
struct State {
    docs: HashMap<Uri, Doc>,
    roots: Vec<PathBuf>,
    init_options: ClientOptions,
    client_options: ClientOptions,
    supports_configuration: bool,
    /// The client applies `RenameFile` operations in workspace edits.
    supports_rename_file: bool,
    supports_watch_registration: bool,
    /// Config errors already shown, so each is shown once.
    shown_errors: Vec<String>,
    /// The document last opened or edited: the breakdown command's target
    /// when it comes without one (Helix's `:lsp-workspace-command`).
    last_uri: Option<Uri>,
}

#[derive(Clone)]
pub struct Backend {
    client: Client,
    state: Arc<Mutex<State>>,
    runner: Arc<dyn DryRunner>,
    /// The configuration and `ini` files documents' settings come from.
    files: Arc<FileCache>,
    run_gate: Arc<tokio::sync::Semaphore>,
    /// Signalled whenever a snapshot is stored.
    stored: Arc<tokio::sync::Notify>,
}

fn internal(msg: impl Into<String>) -> Error {
    Error {
        code: ErrorCode::InternalError,
        message: msg.into().into(),
        data: None,
    }
}

/// Runs a request handler body, turning a panic into an internal error.
async fn guarded<T>(name: &str, fut: impl Future<Output = Result<T>>) -> Result<T> {
    match AssertUnwindSafe(fut).catch_unwind().await {
        Ok(r) => r,
        Err(_) => {
            eprintln!("partscope lsp: handler `{name}` panicked");
            Err(internal(format!("internal error in {name}")))
        }
    }
}

/// Runs a notification handler body, swallowing a panic.
async fn guarded_notify(name: &str, fut: impl Future<Output = ()>) {
    if AssertUnwindSafe(fut).catch_unwind().await.is_err() {
        eprintln!("partscope lsp: notification `{name}` panicked");
    }
}

/// Runs `f` on a blocking thread; a panic there becomes an internal error.
async fn blocking<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> Result<T> {
    tokio::task::spawn_blocking(f)
        .await
        .map_err(|e| internal(format!("analysis failed: {e}")))
}

/// The document's run for lenses and hints: the cached one, or a new one when
/// the file is small enough to run with every analysis.
fn planned_run(snap: &Snapshot) -> Option<Arc<dry_run::RunReport>> {
    snap.cached_run().or_else(|| {
        if snap.run_eligible {
            snap.run_report(&CancelFlag::default())
        } else {
            None
        }
    })
}

pub(crate) use crate::ide::lens::format_duration;

/// A document named by a command argument: a URI string, `{uri}` or
/// `{textDocument: {uri}}`.
fn uri_argument(v: &Value) -> Option<Uri> {
    let u = match v {
        Value::String(_) => v,
        Value::Object(o) => o
            .get("uri")
            .or_else(|| o.get("textDocument").and_then(|t| t.get("uri")))?,
        _ => return None,
    };
    serde_json::from_value(u.clone()).ok()
}

fn uri_path(uri: &Uri) -> Option<PathBuf> {
    uri.to_file_path().map(|p| p.into_owned())
}

impl Backend {
    pub fn new(client: Client) -> Backend {
        Backend {
            client,
            state: Arc::new(Mutex::new(State::default())),
            runner: dry_run::default_runner(),
            files: Arc::default(),
            run_gate: Arc::new(tokio::sync::Semaphore::new(1)),
            stored: Arc::new(tokio::sync::Notify::new()),
        }
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        // A panic while holding the lock poisons it; the state is still usable
        // (every critical section leaves it consistent), so keep going.
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn client_options(state: &State) -> ClientOptions {
        let mut o = state.init_options.clone();
        let c = &state.client_options;
        o.dialect = c.dialect.or(o.dialect);
        if c.machine.is_some() {
            o.machine = c.machine.clone();
        }
        o.select.extend(c.select.iter().cloned());
        o.ignore.extend(c.ignore.iter().cloned());
        o.max_file_size = c.max_file_size.or(o.max_file_size);
        o.max_run_file_size = c.max_run_file_size.or(o.max_run_file_size);
        o.max_toolpath_points = c.max_toolpath_points.or(o.max_toolpath_points);
        o.format = c.format.clone().or(o.format);
        o.block_times = c.block_times.or(o.block_times);
        o
    }

    fn inputs(&self, state: &State, uri: &Uri) -> Option<Inputs> {
        let doc = state.docs.get(uri)?;
        Some(Inputs {
            uri: uri.clone(),
            doc: crate::document::Inputs {
                version: doc.version,
                rope: doc.rope.clone(),
                path: doc.path.clone(),
                roots: state.roots.clone(),
                client: Self::client_options(state),
                runner: self.runner.clone(),
                files: self.files.clone(),
                previous: doc.snapshot.clone(),
            },
        })
    }

    /// Schedules a debounced analysis of `uri` followed by publishing its diagnostics.
    fn schedule(&self, uri: Uri, delay: Duration) {
        let generation = {
            let mut st = self.lock();
            let Some(doc) = st.docs.get_mut(&uri) else {
                return;
            };
            doc.generation += 1;
            doc.generation
        };
        let this = self.clone();
        tokio::spawn(async move {
            tokio::time::sleep(delay).await;
            let (gate, closed) = match this.lock().docs.get(&uri) {
                Some(doc) if doc.generation == generation => {
                    (doc.analysing.clone(), doc.closed.clone())
                }
                _ => return,
            };
            let analysing = gate.lock_owned().await;
            let inputs = {
                let mut st = this.lock();
                match st.docs.get(&uri) {
                    Some(doc) if doc.generation == generation => this.take_inputs(&mut st, &uri),
                    _ => None,
                }
            };
            let Some(inputs) = inputs else { return };
            let Ok(snap) = blocking(move || snapshot::analyze(inputs)).await else {
                return;
            };
            let snap = Arc::new(snap);
            let current = this.store(&snap);
            drop(analysing);
            if !current {
                return;
            }
            // A newer analysis of the same version is scheduled (a re-analysis
            // without an edit): it publishes, with the interpreter's results;
            // publishing the static ones here would make those flicker.
            if !this.is_current(&snap.uri, generation) {
                return;
            }
            if !snap.run_eligible {
                this.publish(&snap).await;
                return;
            }
            if snap.rope.len_bytes() > SMALL_FILE {
                this.publish_then_run(snap, generation).await;
                return;
            }
            // The interpreter adds flow-sensitive diagnostics. When it is quick,
            // publish once with everything; when not, publish the static ones
            // first so syntax errors show at once, then again when it is done.
            // One interpreter run at a time (a run cannot be interrupted, so
            // runs for superseded versions must not pile up on the cores); a
            // run whose version is stale by the time it gets the gate is skipped.
            let gate = this.run_gate.clone();
            let (s, me) = (snap.clone(), this.clone());
            let mut run = tokio::spawn(async move {
                let permit = gate.acquire_owned().await.ok()?;
                if !me.is_current(&s.uri, generation) {
                    return None;
                }
                tokio::task::spawn_blocking(move || {
                    let _permit = permit;
                    s.run_report(&closed);
                })
                .await
                .ok()
            });
            // A small file waits for its run, so it normally gets one publish per version.
            let (done, published) = match tokio::time::timeout(SMALL_RUN_WAIT, &mut run).await {
                Ok(r) => (r.ok().flatten().is_some(), false),
                Err(_) => {
                    this.publish(&snap).await;
                    (run.await.ok().flatten().is_some(), true)
                }
            };
            let current = this.is_current(&snap.uri, generation);
            // A failed run still leaves the static diagnostics to publish.
            if !current || (!done && published) {
                return;
            }
            this.publish(&snap).await;
        });
    }

    /// A large file: its static diagnostics go out at once; the interpreter
    /// (not incremental, hundreds of milliseconds) runs only once edits have
    /// paused for [`RUN_IDLE`], and its diagnostics follow in a second
    /// publish. Until the run starts only the document holds the snapshot, so
    /// the next edit's analysis can take it over and update it in place.
    async fn publish_then_run(&self, snap: Arc<Snapshot>, generation: u64) {
        self.publish(&snap).await;
        let uri = snap.uri.clone();
        let weak = Arc::downgrade(&snap);
        drop(snap);
        tokio::time::sleep(RUN_IDLE).await;
        if !self.is_current(&uri, generation) {
            return;
        }
        let Ok(permit) = self.run_gate.clone().acquire_owned().await else {
            return;
        };
        if !self.is_current(&uri, generation) {
            return;
        }
        let Some(snap) = weak.upgrade() else { return };
        let Some(closed) = self.lock().docs.get(&uri).map(|d| d.closed.clone()) else {
            return;
        };
        let s = snap.clone();
        let done = blocking(move || {
            let _permit = permit;
            s.run_report(&closed).is_some()
        })
        .await
        .unwrap_or(false);
        if done && self.is_current(&uri, generation) {
            self.publish(&snap).await;
        }
    }

    /// Whether no change arrived since the analysis of `generation` was scheduled.
    fn is_current(&self, uri: &Uri, generation: u64) -> bool {
        self.lock()
            .docs
            .get(uri)
            .is_some_and(|d| d.generation == generation)
    }

    /// Keeps a snapshot as the document's newest analysis; whether it is
    /// for the document's current version. A superseded one is kept too (when
    /// no newer one is stored): the next analysis updates it instead of
    /// starting over.
    fn store(&self, snap: &Arc<Snapshot>) -> bool {
        let mut st = self.lock();
        let Some(doc) = st.docs.get_mut(&snap.uri) else {
            return false;
        };
        if doc
            .snapshot
            .as_ref()
            .is_none_or(|s| s.version <= snap.version)
        {
            doc.snapshot = Some(snap.clone());
        }
        self.stored.notify_waiters();
        doc.version == snap.version
    }

    /// Like [`Backend::inputs`] for the scheduled analysis, which takes the
    /// stored analysis over when it is of an older version (no request can
    /// use it any more): if nothing else holds it either, the update edits
    /// it in place instead of copying it.
    fn take_inputs(&self, state: &mut State, uri: &Uri) -> Option<Inputs> {
        let mut inputs = self.inputs(state, uri)?;
        let doc = state.docs.get_mut(uri)?;
        if doc
            .snapshot
            .as_ref()
            .is_some_and(|s| s.version != doc.version)
        {
            inputs.doc.previous = doc.snapshot.take();
        }
        Some(inputs)
    }

    async fn publish(&self, snap: &Arc<Snapshot>) {
        let s = snap.clone();
        let Ok(diags) = blocking(move || s.lsp_diagnostics()).await else {
            return;
        };
        if let Some(err) = &snap.doc.config_error {
            let first = {
                let mut st = self.lock();
                let new = !st.shown_errors.contains(err);
                if new {
                    st.shown_errors.push(err.clone());
                }
                new
            };
            if first {
                self.client
                    .show_message(MessageType::WARNING, format!("partscope: {err}"))
                    .await;
            }
        }
        // Drop the result if the document moved on while it was converted.
        let current = self
            .lock()
            .docs
            .get(&snap.uri)
            .is_some_and(|d| d.version == snap.version);
        if !current {
            return;
        }
        if std::env::var_os("PARTSCOPE_LSP_TIMING").is_some() {
            eprintln!(
                "partscope lsp: publish {} v{}: {} diagnostics, run {}",
                snap.uri.as_str(),
                snap.version,
                diags.len(),
                if snap.cached_run().is_some() {
                    "included"
                } else {
                    "not included"
                }
            );
        }
        self.client
            .publish_diagnostics(snap.uri.clone(), diags, Some(snap.version))
            .await;
    }

    /// The analysis of the document's current version, computing it if the
    /// stored one is stale.
    async fn snapshot(&self, uri: &Uri) -> Option<Arc<Snapshot>> {
        // Every change schedules an analysis; a request waits for it rather
        // than starting its own (editors send several requests per keystroke,
        // and on a large file each analysis takes a while).
        let deadline = tokio::time::Instant::now() + WAIT_FOR_ANALYSIS;
        loop {
            let notified = self.stored.notified();
            tokio::pin!(notified);
            notified.as_mut().enable();
            {
                let st = self.lock();
                let doc = st.docs.get(uri)?;
                if let Some(s) = doc.snapshot.as_ref().filter(|s| s.version == doc.version) {
                    return Some(s.clone());
                }
            }
            if tokio::time::timeout_at(deadline, notified).await.is_err() {
                break;
            }
        }
        // The scheduled analysis did not come (it failed): analyse here.
        let inputs = {
            let st = self.lock();
            self.inputs(&st, uri)?
        };
        let snap = Arc::new(blocking(move || snapshot::analyze(inputs)).await.ok()?);
        self.store(&snap);
        Some(snap)
    }

    fn reanalyze_all(&self) {
        let uris: Vec<Uri> = self.lock().docs.keys().cloned().collect();
        for uri in uris {
            self.schedule(uri, Duration::ZERO);
        }
    }

    async fn fetch_configuration(&self) {
        if !self.lock().supports_configuration {
            return;
        }
        let item = ConfigurationItem {
            scope_uri: None,
            section: Some("partscope".into()),
        };
        if let Ok(values) = self.client.configuration(vec![item]).await {
            if let Some(v) = values.into_iter().next().filter(|v| v.is_object()) {
                self.lock().client_options = ClientOptions::from_json(&v);
            }
        }
    }

    fn roots(&self) -> Vec<PathBuf> {
        self.lock().roots.clone()
    }

    fn other_docs(&self) -> Vec<OtherDoc> {
        self.lock()
            .docs
            .iter()
            .map(|(uri, d)| OtherDoc {
                uri: uri.clone(),
                version: Some(d.version),
                rope: d.rope.clone(),
            })
            .collect()
    }

    fn open_rope(&self, uri: &Uri) -> Option<Rope> {
        self.lock().docs.get(uri).map(|d| d.rope.clone())
    }

    /// The dry run of a document (the `partscope/dryRun` request). Params:
    /// `textDocument`, and optionally `tolerance` (mm) or `viewSize` (the
    /// view's size in pixels: the tolerance is the part's extent over it) and
    /// `maxPoints` (else the `maxToolpathPoints` setting). A newer request for
    /// the same document supersedes this one: it then answers error -32802
    /// ([`SUPERSEDED`]), and its run stops if the newer one is for a newer
    /// version.
    pub async fn dry_run(&self, params: Value) -> Result<Value> {
        guarded("partscope/dryRun", async {
            let uri: Uri = params
                .get("textDocument")
                .and_then(|t| t.get("uri"))
                .and_then(|u| serde_json::from_value(u.clone()).ok())
                .ok_or_else(|| Error::invalid_params("expected {textDocument: {uri}}"))?;
            let positive = |key: &str| {
                params
                    .get(key)
                    .and_then(Value::as_f64)
                    .filter(|v| v.is_finite() && *v >= 0.0)
            };
            let (tolerance, view_size) = (positive("tolerance"), positive("viewSize"));
            let max_points = params
                .get("maxPoints")
                .and_then(Value::as_u64)
                .map(|n| n as usize);
            // Registered before the first await, so in the order requests came.
            let (cancel, superseded, max_points) = {
                let mut st = self.lock();
                let max_points = max_points
                    .or(Self::client_options(&st).max_toolpath_points)
                    .unwrap_or(super::decimate::DEFAULT_MAX_POINTS);
                let doc = st
                    .docs
                    .get_mut(&uri)
                    .ok_or_else(|| Error::invalid_params("document is not open"))?;
                if let Some(old) = doc.dry_run.take() {
                    old.superseded.cancel();
                    if old.version != doc.version {
                        old.run.cancel();
                    }
                }
                let ticket = DryRunTicket {
                    version: doc.version,
                    run: CancelFlag::default(),
                    superseded: CancelFlag::default(),
                };
                let flags = (ticket.run.clone(), ticket.superseded.clone());
                doc.dry_run = Some(ticket);
                (flags.0, flags.1, max_points)
            };
            let superseded_error = || Error {
                code: ErrorCode::ServerError(SUPERSEDED),
                message: "superseded by a newer partscope/dryRun of this document".into(),
                data: None,
            };
            let _guard = cancel.guard();
            let snap = self
                .snapshot(&uri)
                .await
                .ok_or_else(|| Error::invalid_params("document is not open"))?;
            if superseded.is_cancelled() {
                return Err(superseded_error());
            }
            if snap.syntax_only {
                return Err(internal(format!(
                    "no dry run: the file is above the size limit ({} KB, partscope.maxFileSize): syntax-only mode",
                    snap.doc.max_file_size / 1024
                )));
            }
            // The JSON value is built on the blocking thread too: a long
            // toolpath is a large conversion.
            let stale = superseded.clone();
            let result: Option<Result<Value>> = blocking(move || {
                let report = snap.run_report(&cancel)?;
                if stale.is_cancelled() {
                    return None;
                }
                let diags = report
                    .diagnostics
                    .iter()
                    .filter(|d| d.file == analyzer::FileId(0))
                    .filter_map(|d| serde_json::to_value(snap.to_lsp(d)).ok())
                    .collect();
                let tolerance = tolerance.or_else(|| {
                    view_size
                        .filter(|v| *v >= 1.0)
                        .map(|v| report.path.extent() / v)
                });
                let request = dry_run::Request {
                    tolerance,
                    max_points,
                };
                let r: DryRunResult = dry_run::summarize(snap.version, &report, diags, request);
                Some(serde_json::to_value(r).map_err(|e| internal(e.to_string())))
            })
            .await?;
            match result {
                Some(r) => r,
                None if superseded.is_cancelled() => Err(superseded_error()),
                None => Err(Error {
                    code: ErrorCode::ServerError(-32001),
                    message: "no dry run for this document (cancelled, or above the size limit)"
                        .into(),
                    data: None,
                }),
            }
        })
        .await
    }

    /// The `partscope.showBreakdown` command: arguments `[uri, {show}]`, the
    /// URI as a string, `{uri}` or `{textDocument: {uri}}`, by default the
    /// document last opened or edited; `show: false` when the client shows
    /// the answer itself.
    async fn show_breakdown(&self, arguments: Vec<Value>) -> Result<Value> {
        guarded(BREAKDOWN_COMMAND, async {
            let mut args = arguments.into_iter();
            let target = args.next().unwrap_or(Value::Null);
            let show = args
                .next()
                .and_then(|o| o.get("show").and_then(Value::as_bool))
                .unwrap_or(true);
            let uri = match uri_argument(&target) {
                Some(u) => u,
                None if target.is_null() => self.lock().last_uri.clone().ok_or_else(|| {
                    Error::invalid_params("no document given and none is open")
                })?,
                None => {
                    return Err(Error::invalid_params(
                        "expected a document URI, {uri} or {textDocument: {uri}}",
                    ))
                }
            };
            let snap = self
                .snapshot(&uri)
                .await
                .ok_or_else(|| Error::invalid_params("document is not open"))?;
            let skipped = if snap.syntax_only {
                Some("file is above the size limit: syntax-only mode, no dry run".to_string())
            } else {
                snap.run_skipped_reason()
            };
            let cancel = CancelFlag::default();
            let _guard = cancel.guard();
            let name = uri_path(&uri)
                .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                .unwrap_or_else(|| uri.as_str().to_string());
            let key = uri.as_str().to_string();
            let result = if skipped.is_some() {
                None
            } else {
                blocking(move || {
                    let report = snap.run_report(&cancel)?;
                    Some(dry_run::breakdown_of(key, &name, snap.version, &report))
                })
                .await?
            };
            let Some(r) = result else {
                return Err(Error {
                    code: ErrorCode::ServerError(-32001),
                    message: skipped
                        .unwrap_or_else(|| {
                            "no dry run for this document (cancelled, or a program for another control)"
                                .into()
                        })
                        .into(),
                    data: None,
                });
            };
            if show {
                self.client
                    .show_message(MessageType::INFO, r.text.clone())
                    .await;
            }
            serde_json::to_value(r).map_err(|e| internal(e.to_string()))
        })
        .await
    }

    fn offset(snap: &Snapshot, pos: Position) -> u32 {
        position_to_offset(&snap.rope, pos) as u32
    }
}

fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        position_encoding: Some(PositionEncodingKind::UTF16),
        text_document_sync: Some(TextDocumentSyncCapability::Options(
            TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(TextDocumentSyncKind::INCREMENTAL),
                save: Some(TextDocumentSyncSaveOptions::Supported(false)),
                ..Default::default()
            },
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec!["#".into(), "<".into()]),
            ..Default::default()
        }),
        signature_help_provider: Some(SignatureHelpOptions {
            trigger_characters: Some(vec![" ".into()]),
            retrigger_characters: None,
            work_done_progress_options: Default::default(),
        }),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Right(RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: Default::default(),
        })),
        document_symbol_provider: Some(OneOf::Left(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        folding_range_provider: Some(FoldingRangeProviderCapability::Simple(true)),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: semantic::legend(),
                range: Some(true),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                work_done_progress_options: Default::default(),
            },
        )),
        code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
            code_action_kinds: Some(vec![
                CodeActionKind::QUICKFIX,
                CodeActionKind::SOURCE_FIX_ALL,
            ]),
            ..Default::default()
        })),
        inlay_hint_provider: Some(OneOf::Left(true)),
        code_lens_provider: Some(CodeLensOptions {
            resolve_provider: Some(false),
        }),
        workspace: Some(WorkspaceServerCapabilities {
            workspace_folders: Some(WorkspaceFoldersServerCapabilities {
                supported: Some(true),
                change_notifications: Some(OneOf::Left(true)),
            }),
            file_operations: None,
        }),
        execute_command_provider: Some(ExecuteCommandOptions {
            commands: vec![DRY_RUN_COMMAND.into(), BREAKDOWN_COMMAND.into()],
            work_done_progress_options: Default::default(),
        }),
        ..Default::default()
    }
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        guarded("initialize", async {
            let mut folders: Vec<PathBuf> = params
                .workspace_folders
                .iter()
                .flatten()
                .filter_map(|f| uri_path(&f.uri))
                .collect();
            #[allow(deprecated)]
            if folders.is_empty() {
                if let Some(root) = params.root_uri.as_ref().and_then(uri_path) {
                    folders.push(root);
                }
            }
            let ws = params.capabilities.workspace.as_ref();
            let mut st = self.lock();
            st.roots = workspace::canonical_roots(folders);
            st.init_options = params
                .initialization_options
                .as_ref()
                .map(ClientOptions::from_json)
                .unwrap_or_default();
            st.supports_configuration = ws.and_then(|w| w.configuration).unwrap_or(false);
            let edit_caps = ws.and_then(|w| w.workspace_edit.as_ref());
            st.supports_rename_file = edit_caps.is_some_and(|e| {
                e.document_changes == Some(true)
                    && e.resource_operations
                        .as_ref()
                        .is_some_and(|ops| ops.contains(&ResourceOperationKind::Rename))
            });
            st.supports_watch_registration = ws
                .and_then(|w| w.did_change_watched_files.as_ref())
                .and_then(|d| d.dynamic_registration)
                .unwrap_or(false);
            Ok(InitializeResult {
                capabilities: capabilities(),
                server_info: Some(ServerInfo {
                    name: "partscope".into(),
                    version: Some(env!("CARGO_PKG_VERSION").into()),
                }),
                offset_encoding: None,
            })
        })
        .await
    }

    async fn initialized(&self, _: InitializedParams) {
        guarded_notify("initialized", async {
            if self.lock().supports_watch_registration {
                let opts = DidChangeWatchedFilesRegistrationOptions {
                    watchers: vec![FileSystemWatcher {
                        glob_pattern: GlobPattern::String("**/partscope.toml".into()),
                        kind: None,
                    }],
                };
                let reg = Registration {
                    id: "partscope-config-watcher".into(),
                    method: "workspace/didChangeWatchedFiles".into(),
                    register_options: serde_json::to_value(opts).ok(),
                };
                let _ = self.client.register_capability(vec![reg]).await;
            }
            if self.lock().supports_configuration {
                self.fetch_configuration().await;
                self.reanalyze_all();
            }
        })
        .await
    }

    async fn shutdown(&self) -> Result<()> {
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        guarded_notify("didOpen", async {
            let doc = params.text_document;
            {
                let mut st = self.lock();
                st.docs.insert(
                    doc.uri.clone(),
                    Doc {
                        rope: Rope::from_str(&doc.text),
                        version: doc.version,
                        path: uri_path(&doc.uri),
                        generation: 0,
                        snapshot: None,
                        analysing: Arc::default(),
                        closed: CancelFlag::default(),
                        dry_run: None,
                    },
                );
                st.last_uri = Some(doc.uri.clone());
            }
            self.schedule(doc.uri, Duration::ZERO);
        })
        .await
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        guarded_notify("didChange", async {
            let uri = params.text_document.uri;
            // Applied here, before any await: edits keep the client's order.
            {
                let mut st = self.lock();
                let Some(doc) = st.docs.get_mut(&uri) else {
                    return;
                };
                for change in &params.content_changes {
                    apply_change(&mut doc.rope, change.range, &change.text);
                }
                doc.version = params.text_document.version;
                st.last_uri = Some(uri.clone());
            }
            self.schedule(uri, DEBOUNCE);
        })
        .await
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        guarded_notify("didClose", async {
            let uri = params.text_document.uri;
            if let Some(doc) = self.lock().docs.remove(&uri) {
                doc.closed.cancel();
            }
            self.client.publish_diagnostics(uri, Vec::new(), None).await;
        })
        .await
    }

    async fn did_change_configuration(&self, params: DidChangeConfigurationParams) {
        guarded_notify("didChangeConfiguration", async {
            if params.settings.get("partscope").is_some() {
                self.lock().client_options = ClientOptions::from_json(&params.settings);
            } else {
                self.fetch_configuration().await;
            }
            self.reanalyze_all();
        })
        .await
    }

    async fn did_change_workspace_folders(&self, params: DidChangeWorkspaceFoldersParams) {
        guarded_notify("didChangeWorkspaceFolders", async {
            let removed = workspace::canonical_roots(
                params.event.removed.iter().filter_map(|f| uri_path(&f.uri)),
            );
            let added = workspace::canonical_roots(
                params.event.added.iter().filter_map(|f| uri_path(&f.uri)),
            );
            {
                let mut st = self.lock();
                let mut roots: Vec<PathBuf> = st
                    .roots
                    .iter()
                    .filter(|r| !removed.contains(r))
                    .cloned()
                    .collect();
                roots.extend(added);
                st.roots = workspace::canonical_roots(roots);
            }
            self.reanalyze_all();
        })
        .await
    }

    async fn did_change_watched_files(&self, params: DidChangeWatchedFilesParams) {
        guarded_notify("didChangeWatchedFiles", async {
            let config_changed = params
                .changes
                .iter()
                .any(|c| c.uri.path().as_str().ends_with("partscope.toml"));
            if config_changed {
                self.lock().shown_errors.clear();
                self.reanalyze_all();
            }
        })
        .await
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        guarded("hover", async {
            let p = params.text_document_position_params;
            let Some(snap) = self.snapshot(&p.text_document.uri).await else {
                return Ok(None);
            };
            let offset = Self::offset(&snap, p.position);
            blocking(move || {
                ide::hover::hover(&super::analysis(&snap), offset).map(|h| Hover {
                    contents: HoverContents::Markup(MarkupContent {
                        kind: MarkupKind::Markdown,
                        value: h.markdown,
                    }),
                    range: Some(span_to_range(&snap.rope, h.span)),
                })
            })
            .await
        })
        .await
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        guarded("completion", async {
            let p = params.text_document_position;
            let Some(snap) = self.snapshot(&p.text_document.uri).await else {
                return Ok(None);
            };
            let offset = position_to_offset(&snap.rope, p.position);
            let items = blocking(move || completion::complete(&snap, offset)).await?;
            Ok(Some(CompletionResponse::Array(items)))
        })
        .await
    }

    async fn signature_help(&self, params: SignatureHelpParams) -> Result<Option<SignatureHelp>> {
        guarded("signatureHelp", async {
            let p = params.text_document_position_params;
            let Some(snap) = self.snapshot(&p.text_document.uri).await else {
                return Ok(None);
            };
            let offset = Self::offset(&snap, p.position);
            blocking(move || signature::signature_help(&snap, offset)).await
        })
        .await
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        guarded("definition", async {
            let p = params.text_document_position_params;
            let Some(snap) = self.snapshot(&p.text_document.uri).await else {
                return Ok(None);
            };
            let offset = Self::offset(&snap, p.position);
            let roots = self.roots();
            let this = self.clone();
            let loc =
                blocking(move || goto::definition(&snap, offset, &roots, &|u| this.open_rope(u)))
                    .await?;
            Ok(loc.map(GotoDefinitionResponse::Scalar))
        })
        .await
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        guarded("references", async {
            let p = params.text_document_position;
            let Some(snap) = self.snapshot(&p.text_document.uri).await else {
                return Ok(None);
            };
            let offset = Self::offset(&snap, p.position);
            let roots = self.roots();
            let others = self.other_docs();
            let include = params.context.include_declaration;
            let cancel = CancelFlag::default();
            let _guard = cancel.guard();
            let locs = blocking(move || {
                goto::references(&snap, offset, include, &others, &roots, &cancel)
            })
            .await?;
            Ok(Some(locs))
        })
        .await
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        guarded("formatting", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let defaults = Self::client_options(&self.lock()).format;
            let props = params.options.properties;
            blocking(move || formatting::format(&snap, defaults.as_ref(), &props))
                .await?
                .map(Some)
                .map_err(Error::invalid_params)
        })
        .await
    }

    async fn prepare_rename(
        &self,
        params: TextDocumentPositionParams,
    ) -> Result<Option<PrepareRenameResponse>> {
        guarded("prepareRename", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let offset = Self::offset(&snap, params.position);
            match blocking(move || rename::prepare(&snap, offset)).await? {
                None => Ok(None),
                Some(Ok(range)) => Ok(Some(PrepareRenameResponse::Range(range))),
                Some(Err(why)) => Err(Error::invalid_params(why)),
            }
        })
        .await
    }

    async fn rename(&self, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
        guarded("rename", async {
            let p = params.text_document_position;
            let Some(snap) = self.snapshot(&p.text_document.uri).await else {
                return Ok(None);
            };
            let offset = Self::offset(&snap, p.position);
            let roots = self.roots();
            let others = self.other_docs();
            let files = self.lock().supports_rename_file;
            let new_name = params.new_name;
            let cancel = CancelFlag::default();
            let _guard = cancel.guard();
            blocking(move || {
                rename::rename(&snap, offset, &new_name, &others, &roots, files, &cancel)
            })
            .await?
            .map_err(Error::invalid_params)
        })
        .await
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        guarded("documentSymbol", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let syms = blocking(move || symbols::document_symbols(&snap)).await?;
            Ok(Some(DocumentSymbolResponse::Nested(syms)))
        })
        .await
    }

    async fn folding_range(&self, params: FoldingRangeParams) -> Result<Option<Vec<FoldingRange>>> {
        guarded("foldingRange", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            Ok(Some(
                blocking(move || symbols::folding_ranges(&snap)).await?,
            ))
        })
        .await
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        guarded("semanticTokens/full", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let data = blocking(move || {
                semantic::encode(snap.program(), 0, u32::MAX, MAX_FULL_SEMANTIC_TOKENS)
            })
            .await?;
            Ok(data.map(|data| {
                SemanticTokensResult::Tokens(SemanticTokens {
                    result_id: None,
                    data,
                })
            }))
        })
        .await
    }

    async fn semantic_tokens_range(
        &self,
        params: SemanticTokensRangeParams,
    ) -> Result<Option<SemanticTokensRangeResult>> {
        guarded("semanticTokens/range", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let (a, b) = super::position::range_to_offsets(&snap.rope, params.range);
            let data =
                blocking(move || semantic::encode(snap.program(), a as u32, b as u32, usize::MAX))
                    .await?;
            Ok(data.map(|data| {
                SemanticTokensRangeResult::Tokens(SemanticTokens {
                    result_id: None,
                    data,
                })
            }))
        })
        .await
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        guarded("codeAction", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let range = params.range;
            // Source actions only when asked for, as clients do on save.
            let fix_all = params.context.only.as_ref().is_some_and(|only| {
                only.iter()
                    .any(|k| *k == CodeActionKind::SOURCE_FIX_ALL || *k == CodeActionKind::SOURCE)
            });
            Ok(Some(
                blocking(move || {
                    if fix_all {
                        return actions::fix_all(&snap).into_iter().collect();
                    }
                    actions::code_actions(&snap, range)
                })
                .await?,
            ))
        })
        .await
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        // Each block's time (or the program time when it ends) and the program
        // time at each tool change, from the planned run.
        guarded("inlayHint", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            let mode = Self::client_options(&self.lock())
                .block_times
                .unwrap_or_default();
            let mode = match mode {
                BlockTimes::Block => ide::lens::BlockTimes::Block,
                BlockTimes::Cumulative => ide::lens::BlockTimes::Cumulative,
                BlockTimes::Off => ide::lens::BlockTimes::Off,
            };
            let range = params.range;
            blocking(move || {
                let run = planned_run(&snap);
                let analysis = ide::Analysis {
                    run,
                    ..super::analysis(&snap)
                };
                let hints =
                    ide::lens::inlay_hints(&analysis, range.start.line, range.end.line, mode);
                Some(
                    hints
                        .into_iter()
                        .map(|h| InlayHint {
                            position: offset_to_position(&snap.rope, h.offset),
                            label: InlayHintLabel::String(h.label),
                            kind: None,
                            text_edits: None,
                            tooltip: h.tooltip.map(InlayHintTooltip::String),
                            padding_left: Some(true),
                            padding_right: None,
                            data: None,
                        })
                        .collect(),
                )
            })
            .await
        })
        .await
    }

    async fn code_lens(&self, params: CodeLensParams) -> Result<Option<Vec<CodeLens>>> {
        // The cycle time above the first line; clicking it shows the breakdown.
        guarded("codeLens", async {
            let Some(snap) = self.snapshot(&params.text_document.uri).await else {
                return Ok(None);
            };
            blocking(move || {
                let title = ide::lens::cycle_time_title(
                    planned_run(&snap).as_deref(),
                    snap.run_skipped_reason(),
                )?;
                Some(vec![CodeLens {
                    range: Range::new(Position::new(0, 0), Position::new(0, 0)),
                    command: Some(Command {
                        title,
                        command: BREAKDOWN_COMMAND.into(),
                        arguments: Some(vec![
                            serde_json::to_value(&snap.uri).unwrap_or(Value::Null)
                        ]),
                    }),
                    data: None,
                }])
            })
            .await
            .map(|l| Some(l.unwrap_or_default()))
        })
        .await
    }

    async fn execute_command(&self, params: ExecuteCommandParams) -> Result<Option<LSPAny>> {
        if params.command == BREAKDOWN_COMMAND {
            return self.show_breakdown(params.arguments).await.map(Some);
        }
        if params.command != DRY_RUN_COMMAND {
            return Err(Error::invalid_params(format!(
                "unknown command `{}`",
                params.command
            )));
        }
        let arg = params.arguments.into_iter().next().unwrap_or(Value::Null);
        // Accept `{textDocument:{uri}}`, `{uri}` or a bare URI string.
        let arg = match arg {
            Value::String(s) => serde_json::json!({"textDocument": {"uri": s}}),
            Value::Object(ref o) if o.contains_key("uri") => {
                serde_json::json!({"textDocument": {"uri": o["uri"]}})
            }
            other => other,
        };
        self.dry_run(arg).await.map(Some)
    }
}
