//! The language server (`partscope lsp`): LSP over stdio.
//!
//! A thin protocol layer ([`server`]) over pure analysis: each request is
//! converted (UTF-16 positions ↔ byte offsets in [`position`] only), answered
//! by the feature's function in [`crate::ide`] over the analysed
//! [`snapshot`] ([`analysis`]), and converted back (the feature's module
//! here, or the handler itself when the conversion is a few lines).
//!
//! Shape:
//! - Documents are ropes. `didChange` edits are applied before the handler's
//!   first `.await`; each change schedules an analysis on a blocking thread
//!   (no debounce), tagged with the document version; analyses of one
//!   document run one at a time, one superseded while waiting is skipped,
//!   and a result for an older version is not published (but kept as the
//!   base of the next update). Requests wait for that analysis instead of
//!   starting their own. The analysis is incremental
//!   (`analyzer::incremental`): it updates the previous version's parse and
//!   static-rule results where the text changed (found by comparing the two
//!   texts). The scheduled analysis takes the previous one over and, when
//!   nothing else holds it (no run, no request), edits it in place
//!   (`Incremental::update_owned`); otherwise it updates a copy.
//! - The interpreter and planner ([`crate::document::runner`], behind the
//!   [`dry_run::DryRunner`] trait, through `runtime::dryrun`, the glue
//!   `partscope run` uses too) run with the analysis for files up to
//!   `maxRunFileSize` (32 MB): the interpreter's diagnostics join the static
//!   ones (a diagnostic inside a subprogram file is shown on the document's
//!   call of that file), its per-block state shows on hover, the cycle time is
//!   a code lens (its command `partscope.showBreakdown` answers with the
//!   breakdown, [`dry_run::BreakdownResult`], and shows its text with
//!   `window/showMessage` unless the arguments say `{show: false}`), tool changes get their program time as inlay hints, and
//!   `partscope/dryRun` returns toolpath and times. The config's
//!   `tool_table`/`var_file` are passed to the interpreter. One run at a
//!   time; a run for a superseded version is skipped. Files above 256 KB
//!   publish the static diagnostics at once; the interpreter (not
//!   incremental) runs once edits have paused for 300 ms, and the full set
//!   is published again when it ends. Subprogram
//!   files (NGC `o<name> sub` libraries, FANUC/ServoWorks files ending in M99)
//!   are not run on their own.
//! - Above `maxFileSize` (64 MB) a document is only parsed: syntax
//!   diagnostics, navigation, symbols and tokens, no rules and no run. Above
//!   either limit a diagnostic at the top of the file and the lens say so.
//! - Every handler runs under `catch_unwind` and its work in `spawn_blocking`;
//!   the transport is [`stdio`] (framing, JSON-RPC decoding, limits, exit
//!   status), so no message can end the session. A cancelled request's
//!   [`dry_run::CancelFlag`] reaches the interpreter and the planner, which
//!   poll it.
//! - Other files are read only inside the workspace folders (canonicalized,
//!   so symlinks cannot escape): [`workspace`].
//! - The environment holds no behaviour switches: `PARTSCOPE_LSP_MAX_MESSAGE_BYTES`
//!   is a user setting (the transport's limit, [`stdio`]) and
//!   `PARTSCOPE_LSP_TIMING` a diagnostic aid that only writes timings and
//!   memory to stderr (docs/configuration.md).
//!
//! Settings ([`config`]): the nearest `partscope.toml` (up to the workspace
//! folder), then a first-line `(partscope: dialect=…)` comment, then the
//! client's options (`initializationOptions` or the `partscope` section of
//! `workspace/configuration`: `dialect`, `machine` (table or path), `select`,
//! `ignore`, `maxFileSize`, `maxRunFileSize`, `maxToolpathPoints`), then sniffing. Changes of
//! `partscope.toml` (watched through `didChangeWatchedFiles`) and of the
//! client configuration re-analyse the open documents.
//!
//! Custom request `partscope/dryRun` (and command `partscope.dryRun`, whose
//! argument is the URI or `{uri}`): params `{textDocument: {uri}, tolerance?,
//! viewSize?, maxPoints?}` (the toolpath is decimated and capped,
//! [`decimate`]; a newer request of the document supersedes it), result
//! [`dry_run::DryRunResult`]: `{version, cycle_time_s, motion_s, rapid_s,
//! cutting_s, dwell_s, tool_change_s, distance_mm, toolpath: {segments:
//! [{kind: "rapid"|"feed"|"arc", line, feed, tool, points: [[x,y,z]…]}],
//! bounds: {min, max}}, diagnostics, decimation}`. Times are `null` when the `[machine]`
//! table is not a valid planner profile; error -32001 when no run is possible
//! (cancelled), -32603 in syntax-only mode. `partscope run --html` embeds the
//! same result, made by the same conversion ([`dry_run_result`]), in its page.

mod actions;
mod completion;
pub(crate) use crate::document::{config, decimate, workspace};
pub(crate) mod dry_run;
mod formatting;
mod goto;
pub(crate) use analyzer::names as nav;
pub(crate) mod position;
mod rename;
mod semantic;
mod server;
mod signature;
pub(crate) mod snapshot;
mod stdio;
mod symbols;

use std::process::ExitCode;

use tower_lsp_server::{ClientSocket, LspService};

pub use crate::resolve::Loaded;
pub use dry_run::dry_run_result;
pub use server::Backend;

/// The features' view of one analysed version ([`crate::ide::Analysis::of`]).
pub(crate) fn analysis(snap: &snapshot::Snapshot) -> crate::ide::Analysis<'_> {
    crate::ide::Analysis::of(snap)
}

/// Builds the protocol service `run` serves over stdio. It is public so an
/// in-process driver (the `lsp_messages` fuzz target, which compiles this
/// module from its source) exercises the same handlers without a process
/// and pipes around them.
pub fn service() -> (LspService<Backend>, ClientSocket) {
    LspService::build(Backend::new)
        .custom_method("partscope/dryRun", Backend::dry_run)
        .finish()
}

/// Runs the language server on stdin/stdout until the client exits: status 0
/// after `shutdown` and `exit`, 1 when `exit` or the end of input comes
/// without `shutdown` (as the protocol asks).
pub fn run() -> ExitCode {
    let rt = match tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("partscope lsp: cannot start the async runtime: {e}");
            return ExitCode::from(2);
        }
    };
    let code = rt.block_on(async {
        let (service, socket) = service();
        let limits = stdio::Limits::from_env();
        stdio::serve(
            tokio::io::stdin(),
            tokio::io::stdout(),
            service,
            socket,
            limits,
        )
        .await
    });
    // Blocking analyses still running are abandoned rather than awaited: the
    // process ends with them (the writer has flushed what was queued).
    rt.shutdown_background();
    code
}
