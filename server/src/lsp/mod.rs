//! The language server (`partscope lsp`): LSP over stdio.
//!
//! A thin protocol layer ([`server`]) over pure analysis: each request is
//! converted (UTF-16 positions ↔ byte offsets in [`position`] only), answered
//! by a small module working on an analysed [`snapshot`], and converted back.

mod actions;
mod completion;
mod config;
mod dry_run;
mod goto;
mod hover;
mod nav;
mod position;
mod semantic;
mod server;
mod signature;
mod snapshot;
mod stdio;
mod symbols;
mod workspace;

use std::process::ExitCode;

use tower_lsp_server::{LspService, Server};

/// Runs the language server on stdin/stdout until the client exits.
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
    rt.block_on(async {
        let (service, socket) = LspService::build(server::Backend::new)
            .custom_method("partscope/dryRun", server::Backend::dry_run)
            .finish();
        Server::new(stdio::filtered_stdin(), tokio::io::stdout(), socket)
            .serve(service)
            .await;
    });
    // Blocking analyses still running are abandoned rather than awaited.
    rt.shutdown_timeout(std::time::Duration::from_millis(100));
    ExitCode::SUCCESS
}
