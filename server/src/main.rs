//! `partscope`: lint, dry-run and language server for CNC part programs.

mod cli;
mod lsp;
mod page;
mod picture;
mod resolve;
mod rules;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
