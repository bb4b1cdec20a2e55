//! `partscope`: lint, dry-run and language server for CNC part programs.

use std::process::ExitCode;

fn main() -> ExitCode {
    partscope::cli::main()
}
