//! One analysed version of one document as the server keeps it: the
//! protocol-free [`Document`] with the document's URI, and the conversion of
//! its diagnostics.

use analyzer::Severity;
use ropey::Rope;
use std::sync::Arc;
use tower_lsp_server::ls_types::{
    CodeDescription, Diagnostic as LspDiagnostic, DiagnosticRelatedInformation, DiagnosticSeverity,
    Location, NumberOrString, Uri,
};

use super::position::span_to_range;
use crate::document::{self, Document, Previous};

pub struct Snapshot {
    pub uri: Uri,
    analysed: Document,
}

impl std::ops::Deref for Snapshot {
    type Target = Document;

    fn deref(&self) -> &Document {
        &self.analysed
    }
}

/// Everything needed to analyse a document, cloned out of the server state.
pub struct Inputs {
    pub uri: Uri,
    /// The document's inputs, with the previous snapshot.
    pub doc: document::Inputs<Arc<Snapshot>>,
}

/// Converts one analyzer diagnostic of the document `uri` holding `rope`.
pub fn lsp_diagnostic(uri: &Uri, rope: &Rope, d: &analyzer::Diagnostic) -> LspDiagnostic {
    let related: Vec<DiagnosticRelatedInformation> = d
        .related
        .iter()
        .filter(|r| r.file == analyzer::FileId(0))
        .map(|r| DiagnosticRelatedInformation {
            location: Location {
                uri: uri.clone(),
                range: span_to_range(rope, r.span),
            },
            message: r.message.clone(),
        })
        .collect();
    LspDiagnostic {
        range: span_to_range(rope, d.span),
        severity: Some(severity(d.severity)),
        code: Some(NumberOrString::String(d.code.to_string())),
        code_description: rule_href(d.code).map(|href| CodeDescription { href }),
        source: Some("partscope".to_string()),
        message: d.message.clone(),
        related_information: (!related.is_empty()).then_some(related),
        tags: None,
        data: None,
    }
}

/// Resolves settings and analyses one document version ([`document::analyze`]).
/// Blocking: call it on a blocking thread.
pub fn analyze(inputs: Inputs) -> Snapshot {
    // The previous snapshot is handed over owned when this is its only holder
    // (so `document::analyze` edits it in place), borrowed while a run or a
    // request still reads it.
    let (doc, previous) = inputs.doc.replace_previous(None);
    let shared;
    let previous = match previous.map(Arc::try_unwrap) {
        Some(Ok(prev)) => Some(Previous::Owned(Box::new(prev.analysed))),
        Some(Err(arc)) => {
            shared = arc;
            Some(Previous::Shared(&shared.analysed))
        }
        None => None,
    };
    Snapshot {
        uri: inputs.uri,
        analysed: document::analyze(document::Inputs { previous, ..doc }),
    }
}

pub fn rule_href(code: &str) -> Option<Uri> {
    format!("https://partscope.dev/rules/{code}").parse().ok()
}

fn severity(s: Severity) -> DiagnosticSeverity {
    match s {
        Severity::Error => DiagnosticSeverity::ERROR,
        Severity::Warning => DiagnosticSeverity::WARNING,
        Severity::Info => DiagnosticSeverity::INFORMATION,
        Severity::Hint => DiagnosticSeverity::HINT,
    }
}

impl Snapshot {
    /// Converts one analyzer diagnostic of this document.
    pub fn to_lsp(&self, d: &analyzer::Diagnostic) -> LspDiagnostic {
        lsp_diagnostic(&self.uri, &self.rope, d)
    }

    /// The diagnostics of this document (those located in other files are left
    /// to those files).
    pub fn lsp_diagnostics(&self) -> Vec<LspDiagnostic> {
        let mut out: Vec<LspDiagnostic> = self
            .diagnostics()
            .iter()
            .filter(|d| d.file == analyzer::FileId(0))
            .map(|d| self.to_lsp(d))
            .collect();
        if let Some(reason) = self.run_skipped_reason() {
            let d = runtime::rules::STEP_BUDGET.diagnostic(
                Severity::Info,
                analyzer::Span::new(0, 0),
                reason,
            );
            out.insert(0, self.to_lsp(&d));
        }
        out
    }
}
