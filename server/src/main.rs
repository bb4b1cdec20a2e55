//! `partscope`: lint, dry-run and language server for CNC part programs.

mod cli;
mod lsp;
mod picture;
mod resolve;
mod rules;

use std::process::ExitCode;

// Large files parse into a few large vectors; huge pages spare the kernel most of
// their page faults (analyzer::memory).
#[global_allocator]
static ALLOC: analyzer::memory::LargePages = analyzer::memory::LargePages;

fn main() -> ExitCode {
    // The language server allocates and frees large blocks on every edit of a big
    // file; the system allocator keeps that memory for reuse (BENCHMARKS.md, session 6).
    // This runs before anything large is allocated, so the switch takes effect.
    if std::env::args_os().nth(1).is_some_and(|a| a == "lsp") {
        analyzer::memory::LargePages::disable();
    }
    cli::main()
}
