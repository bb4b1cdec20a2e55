//! Partscope analyzer: text → lossless syntax → blocks; dialect tables; static
//! rules; the [`Diagnostic`] type. Pure: no IO, no LSP, no global state.

pub mod diagnostic;
pub mod dialect;
pub mod rules;
pub mod settings;
pub mod span;
pub mod syntax;

pub use diagnostic::{Diagnostic, FileId, Fix, Related, Severity, TextEdit};
pub use dialect::{Dialect, Variant};
pub use settings::{Config, Settings, Suppressions};
pub use span::{LineIndex, Span};

use std::sync::Arc;

/// The result of the static analysis of one file.
#[derive(Debug, Clone)]
pub struct Analysis {
    pub program: syntax::Program,
    /// Syntax and static-rule diagnostics, filtered by the settings and the
    /// file's suppression comments, sorted by position.
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses and checks one file.
pub fn analyze(text: impl Into<Arc<[u8]>>, settings: &Settings) -> Analysis {
    let opts = syntax::ParseOptions { dialect: settings.dialect, variant: settings.variant };
    let program = syntax::parse(opts, text);
    let mut diagnostics = program.diagnostics.clone();
    let cx = rules::ProgramCx { program: &program, settings };
    rules::check(&cx, &mut diagnostics);
    let diagnostics = finish(&program, settings, diagnostics);
    Analysis { program, diagnostics }
}

/// Applies rule selection and suppression comments, and sorts. Hosts call this
/// on the runtime's diagnostics too.
pub fn finish(program: &syntax::Program, settings: &Settings, mut diagnostics: Vec<Diagnostic>) -> Vec<Diagnostic> {
    let sup = Suppressions::collect(program);
    diagnostics.retain(|d| {
        let enabled = match rules::registry::lookup(d.code) {
            Some(meta) => settings.rule_enabled(meta),
            None => settings.code_enabled(d.code),
        };
        enabled && (d.file != FileId(0) || !sup.is_suppressed(program, d))
    });
    diagnostics.sort_by(|a, b| (a.file, a.span.start, a.code).cmp(&(b.file, b.span.start, b.code)));
    diagnostics.dedup_by(|a, b| a.file == b.file && a.span == b.span && a.code == b.code && a.message == b.message);
    diagnostics
}
