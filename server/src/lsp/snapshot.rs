//! One analysed version of one document: the text (as a rope, for position
//! conversion), the settings it was analysed with and the analysis.

use analyzer::syntax::{parse, ParseOptions};
use analyzer::{Analysis, Severity};
use ropey::Rope;
use std::path::PathBuf;
use tower_lsp_server::ls_types::{
    CodeDescription, Diagnostic as LspDiagnostic, DiagnosticRelatedInformation, DiagnosticSeverity,
    Location, NumberOrString, Uri,
};

use super::config::{self, ClientOptions, DocSettings};
use super::position::{rope_bytes, span_to_range};

pub struct Snapshot {
    pub uri: Uri,
    pub version: i32,
    pub rope: Rope,
    pub path: Option<PathBuf>,
    pub doc: DocSettings,
    pub analysis: Analysis,
    /// The file is above the size limit: parsed, but no rules ran.
    pub syntax_only: bool,
}

/// Everything needed to analyse a document, cloned out of the server state.
pub struct Inputs {
    pub uri: Uri,
    pub version: i32,
    pub rope: Rope,
    pub path: Option<PathBuf>,
    pub roots: Vec<PathBuf>,
    pub client: ClientOptions,
}

/// Resolves settings and analyses one document version. Blocking: call it on
/// a blocking thread.
pub fn analyze(inputs: Inputs) -> Snapshot {
    let text = rope_bytes(&inputs.rope);
    let doc = config::resolve(inputs.path.as_deref(), &text, &inputs.roots, &inputs.client);
    let syntax_only = text.len() > doc.max_file_size;
    let analysis = if syntax_only {
        let opts = ParseOptions {
            dialect: doc.settings.dialect,
            variant: doc.settings.variant,
        };
        let program = parse(opts, text);
        let diagnostics = analyzer::finish(&program, &doc.settings, program.diagnostics.clone());
        Analysis {
            program,
            diagnostics,
        }
    } else {
        analyzer::analyze(text, &doc.settings)
    };
    Snapshot {
        uri: inputs.uri,
        version: inputs.version,
        rope: inputs.rope,
        path: inputs.path,
        doc,
        analysis,
        syntax_only,
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
    pub fn program(&self) -> &analyzer::syntax::Program {
        &self.analysis.program
    }

    /// Converts one analyzer diagnostic of this document.
    pub fn to_lsp(&self, d: &analyzer::Diagnostic) -> LspDiagnostic {
        let related: Vec<DiagnosticRelatedInformation> = d
            .related
            .iter()
            .filter(|r| r.file == analyzer::FileId(0))
            .map(|r| DiagnosticRelatedInformation {
                location: Location {
                    uri: self.uri.clone(),
                    range: span_to_range(&self.rope, r.span),
                },
                message: r.message.clone(),
            })
            .collect();
        LspDiagnostic {
            range: span_to_range(&self.rope, d.span),
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

    /// The diagnostics of this document (those located in other files are left
    /// to those files).
    pub fn lsp_diagnostics(&self) -> Vec<LspDiagnostic> {
        self.analysis
            .diagnostics
            .iter()
            .filter(|d| d.file == analyzer::FileId(0))
            .map(|d| self.to_lsp(d))
            .collect()
    }
}
