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
    cli::main()
}
