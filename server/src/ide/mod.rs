//! The editor features over one analysed document, in byte offsets.
//!
//! Each module is one feature (hover, go-to and references, symbols and
//! folding, completion, signature help, the cycle-time lens and inlay
//! hints): a function of an [`Analysis`] and a byte offset that returns plain
//! data with [`analyzer::Span`]s and strings; highlighting ([`highlight`])
//! reads the program alone and answers byte ranges with a class, and
//! [`rename`] answers byte-offset edits for this program and any other one. Nothing here knows the protocol: no LSP
//! types, no tokio, no positions in UTF-16 and no files read. The language
//! server converts a position to an offset, calls a function here and
//! converts the answer back; `ide/tests.rs` calls the same functions in
//! process on cursor fixtures (`$0`), over documents analysed by
//! [`crate::document`] as the server analyses them.

pub mod completion;
pub mod goto;
pub mod highlight;
pub mod hover;
pub mod keywords;
pub mod lens;
pub mod rename;
pub mod signature;
pub mod symbols;
pub mod values;

use std::sync::Arc;

use analyzer::syntax::Program;
use analyzer::{Diagnostic, Settings};

pub use crate::document::run::RunReport;

/// Line look-ups the features need (the line of a definition a hover names,
/// the end of a line an inlay hint sits at). Lines end at CR, LF or CRLF.
pub trait Lines {
    /// The 0-based line of a byte offset (offsets past the end: the last line).
    fn line_of(&self, offset: usize) -> usize;
    /// The byte offset where a 0-based line starts; `None` past the last line.
    fn line_start(&self, line: usize) -> Option<usize>;
}

/// The features find lines in the document's rope.
impl Lines for ropey::Rope {
    fn line_of(&self, offset: usize) -> usize {
        self.byte_to_line(offset.min(self.len_bytes()))
    }

    fn line_start(&self, line: usize) -> Option<usize> {
        (line < self.len_lines()).then(|| self.line_to_byte(line))
    }
}

/// One analysed version of a document, as the features read it.
pub struct Analysis<'a> {
    pub program: &'a Program,
    pub lines: &'a dyn Lines,
    /// The settings it was analysed with (dialect, variant, axes).
    pub settings: &'a Settings,
    /// Why the document is read in its dialect.
    pub dialect_reason: &'a str,
    /// Static diagnostics, joined by the run's when the run is done.
    pub diagnostics: &'a [Diagnostic],
    /// The dry run, when one was made.
    pub run: Option<Arc<RunReport>>,
}

impl<'a> Analysis<'a> {
    /// The features' view of an analysed document: the interpreter's run only
    /// if it is already made (hover does not wait for one).
    pub fn of(doc: &'a crate::document::Document) -> Analysis<'a> {
        Analysis {
            program: doc.program(),
            lines: &doc.rope,
            settings: &doc.doc.settings,
            dialect_reason: &doc.doc.dialect_reason,
            diagnostics: doc.diagnostics(),
            run: doc.cached_run(),
        }
    }

    /// The byte offset where a line's content ends (before its line break).
    pub fn line_content_end(&self, line: usize) -> Option<usize> {
        let start = self.lines.line_start(line)?;
        let text = &self.program.text;
        let rest = text.get(start..).unwrap_or_default();
        Some(start + memchr::memchr2(b'\r', b'\n', rest).unwrap_or(rest.len()))
    }

    /// The text of the line holding `offset` from its start up to `offset`.
    pub fn line_before(&self, offset: usize) -> (usize, String) {
        let offset = offset.min(self.program.text.len());
        let line = self.lines.line_of(offset);
        let start = self.lines.line_start(line).unwrap_or(0).min(offset);
        let bytes = self.program.text.get(start..offset).unwrap_or_default();
        (start, String::from_utf8_lossy(bytes).into_owned())
    }

    /// Whether `offset` is on the document's first line (no `\n` before it).
    pub fn on_first_line(&self, offset: usize) -> bool {
        let text = &self.program.text;
        memchr::memchr(b'\n', text.get(..offset).unwrap_or(text)).is_none()
    }
}

#[cfg(test)]
mod tests;
