//! `partscope`: lint, dry-run and language server for CNC part programs. The
//! binary (`main.rs`) is only `cli::main`; the library lets the fuzz targets and
//! benchmarks drive the CLI and the language server in process.

pub mod cli;
pub mod document;
pub mod ide;
pub mod lsp;
pub mod page;
pub mod picture;
pub mod resolve;
pub mod rules;
