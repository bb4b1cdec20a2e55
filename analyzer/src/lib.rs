//! Partscope analyzer: text → lossless syntax → blocks; dialect tables; static
//! rules; the [`Diagnostic`] type. Pure: no IO, no LSP, no global state.

pub mod diagnostic;
pub mod dialect;
pub mod span;

pub use diagnostic::{Diagnostic, FileId, Fix, Related, Severity, TextEdit};
pub use dialect::{Dialect, Variant};
pub use span::{LineIndex, Span};
