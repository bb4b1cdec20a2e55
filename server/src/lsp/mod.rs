//! The language server (`partscope lsp`): LSP over stdio.

/// Runs the language server on stdin/stdout until the client exits.
pub fn run() -> std::process::ExitCode {
    eprintln!("partscope lsp: not built yet");
    std::process::ExitCode::from(2)
}
