//! One analysed version of one document: the text (as a rope, for position
//! conversion), the settings it was analysed with and the analysis.

use analyzer::incremental::{Incremental, Parse, StaticRules};
use analyzer::Severity;
use ropey::Rope;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};
use tower_lsp_server::ls_types::{
    CodeDescription, Diagnostic as LspDiagnostic, DiagnosticRelatedInformation, DiagnosticSeverity,
    Location, NumberOrString, Uri,
};

use super::config::{self, ClientOptions, DocSettings};
use super::dry_run::{CancelFlag, DryRunInput, DryRunner, PreviousRun, RunReport};
use super::position::{rope_bytes, span_to_range};

pub struct Snapshot {
    pub uri: Uri,
    pub version: i32,
    pub rope: Rope,
    pub path: Option<PathBuf>,
    pub doc: DocSettings,
    /// The parse, kept in the form the next version's analysis updates.
    parse: Parse,
    /// The static rules' results: computed on first use (the first publish)
    /// after a whole-text parse, so that a run can start on the tree while
    /// they run; an update computes them at once (an edit re-checks little).
    rules: OnceLock<StaticRules>,
    /// The file is above the size limit: parsed, but no rules ran.
    pub syntax_only: bool,
    pub roots: Vec<PathBuf>,
    runner: Arc<dyn DryRunner>,
    /// Small enough for the interpreter to run with every analysis.
    pub run_eligible: bool,
    /// The interpreter's run of this version, once computed.
    run: OnceLock<Option<Arc<RunReport>>>,
    run_lock: std::sync::Mutex<()>,
    /// Whether the program is for another control (P010), which every caller of
    /// `run_report` asks first: decided once per version.
    mismatch: OnceLock<bool>,
    /// Static and runtime diagnostics together, once the run is done.
    merged: OnceLock<Vec<analyzer::Diagnostic>>,
    /// The latest earlier version's interpreter output, which this version's
    /// run continues from instead of starting over.
    previous_run: Option<Arc<PreviousRun>>,
}

/// Everything needed to analyse a document, cloned out of the server state.
pub struct Inputs {
    pub uri: Uri,
    pub version: i32,
    pub rope: Rope,
    pub path: Option<PathBuf>,
    pub roots: Vec<PathBuf>,
    pub client: ClientOptions,
    pub runner: Arc<dyn DryRunner>,
    pub files: Arc<crate::cli::workspace::FileCache>,
    /// The previous analysis of the document, which an edit updates instead
    /// of analysing the whole text again.
    pub previous: Option<Arc<Snapshot>>,
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

/// Resolves settings and analyses one document version. Blocking: call it on
/// a blocking thread.
pub fn analyze(inputs: Inputs) -> Snapshot {
    let timing = std::env::var_os("PARTSCOPE_LSP_TIMING").is_some();
    let t0 = std::time::Instant::now();
    let text = rope_bytes(&inputs.rope);
    let doc = config::resolve(
        inputs.path.as_deref(),
        &text,
        &inputs.roots,
        &inputs.client,
        &inputs.files,
    );
    let t1 = std::time::Instant::now();
    let syntax_only = text.len() > doc.max_file_size;
    let previous = inputs.previous;
    // The newest run among earlier versions (a version whose run never
    // happened passes its own predecessor's on).
    let previous_run = previous.as_ref().and_then(|p| {
        p.run
            .get()
            .and_then(|r| r.as_ref())
            .map(|r| r.run.clone())
            .or_else(|| p.previous_run.clone())
    });
    // The previous analysis is edited in place when this is its only holder
    // (the server hands it over once a newer version exists); otherwise,
    // while a run or a request still reads it, it is copied first.
    let mut in_place = false;
    let (parse, rules) = match previous.map(Arc::try_unwrap) {
        Some(Ok(prev)) => {
            in_place = true;
            let rules = prev
                .rules
                .into_inner()
                .unwrap_or_else(|| prev.parse.rules(&prev.doc.settings));
            let inc =
                prev.parse
                    .with_rules(rules)
                    .update_owned(text.clone(), &doc.settings, syntax_only);
            let (parse, rules) = inc.into_parts();
            (parse, OnceLock::from(rules))
        }
        Some(Err(shared)) => {
            let inc = shared.parse.update(
                shared.static_rules(),
                text.clone(),
                &doc.settings,
                syntax_only,
            );
            let (parse, rules) = inc.into_parts();
            (parse, OnceLock::from(rules))
        }
        None => (
            Incremental::parse(text.clone(), &doc.settings, syntax_only),
            OnceLock::new(),
        ),
    };
    if timing {
        eprintln!(
            "partscope lsp: v{} {} bytes: copy+config {:?}, {} {:?}{}",
            inputs.version,
            text.len(),
            t1 - t0,
            if rules.get().is_some() {
                "analyze"
            } else {
                "parse"
            },
            t1.elapsed(),
            if in_place { " (in place)" } else { "" }
        );
    }
    let program = parse.program();
    let run_eligible = !syntax_only
        && text.len() <= doc.max_run_file_size
        && !runtime::interp::files::is_subprogram_file(program, doc.settings.file_stem.as_deref());
    Snapshot {
        uri: inputs.uri,
        version: inputs.version,
        rope: inputs.rope,
        path: inputs.path,
        doc,
        parse,
        rules,
        syntax_only,
        run_eligible,
        roots: inputs.roots,
        runner: inputs.runner,
        run: OnceLock::new(),
        run_lock: std::sync::Mutex::new(()),
        mismatch: OnceLock::new(),
        merged: OnceLock::new(),
        previous_run,
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
        self.parse.program()
    }

    /// The static rules' results, computed here on first use.
    fn static_rules(&self) -> &StaticRules {
        let timing = std::env::var_os("PARTSCOPE_LSP_TIMING").is_some();
        self.rules.get_or_init(|| {
            let t0 = std::time::Instant::now();
            let rules = self.parse.rules(&self.doc.settings);
            if timing {
                eprintln!(
                    "partscope lsp: v{} static rules {:?}",
                    self.version,
                    t0.elapsed()
                );
            }
            rules
        })
    }

    /// The interpreter's run of this version (computed on first use; `None`
    /// above the size limit, when cancelled, or without a runtime).
    pub fn run_report(&self, cancel: &CancelFlag) -> Option<Arc<RunReport>> {
        if let Some(r) = self.run.get() {
            return r.clone();
        }
        // A program for another control (P010, which is then the only static
        // finding) is not interpreted: its findings and cycle time would mean nothing.
        // Decided without the other rules, so the run need not wait for them.
        if self.syntax_only
            || *self.mismatch.get_or_init(|| {
                analyzer::program_reports_mismatch(self.program(), &self.doc.settings)
            })
        {
            return None;
        }
        // One run per version: a second caller waits for the first run
        // instead of repeating it.
        let _running = self.run_lock.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(r) = self.run.get() {
            return r.clone();
        }
        if cancel.is_cancelled() {
            return None;
        }
        let input = DryRunInput {
            program: self.program(),
            settings: &self.doc.settings,
            machine: &self.doc.machine,
            profile: &self.doc.profile,
            doc_path: self.path.clone(),
            config_path: self.doc.config_path.clone(),
            tool_table: self.doc.tool_table.clone(),
            var_file: self.doc.var_file.clone(),
            roots: &self.roots,
            cancel,
            previous: self.previous_run.as_deref(),
            max_file_size: self.doc.max_run_file_size,
        };
        let report = self.runner.run(&input).map(Arc::new);
        if cancel.is_cancelled() {
            // A cancelled run is not an answer for this version: do not keep it.
            return None;
        }
        self.run.get_or_init(|| report).clone()
    }

    /// The diagnostics of this version: static ones, joined by the
    /// interpreter's once its run is done (same selection and suppressions).
    pub fn diagnostics(&self) -> &[analyzer::Diagnostic] {
        if let Some(m) = self.merged.get() {
            return m;
        }
        let Some(report) = self.cached_run() else {
            return &self.static_rules().diagnostics;
        };
        self.merged.get_or_init(|| {
            let runtime = analyzer::finish(
                self.program(),
                &self.doc.settings,
                report.diagnostics.to_vec(),
            );
            analyzer::merge(
                self.static_rules().diagnostics.clone(),
                runtime,
                &self.doc.settings,
            )
        })
    }

    /// Why no dry run (or no analysis at all) is made for this document, when
    /// that is its size: the editor then says so, in a diagnostic and the
    /// lens, instead of showing no runtime findings and no time.
    pub fn run_skipped_reason(&self) -> Option<String> {
        let len = self.program().text.len();
        if self.syntax_only {
            return Some(format!(
                "No analysis: the file ({} KB) is above the size limit ({} KB, partscope.maxFileSize); only syntax errors are shown, no rules, runtime diagnostics or cycle time",
                len / 1024,
                self.doc.max_file_size / 1024
            ));
        }
        if len <= self.doc.max_run_file_size {
            return None;
        }
        Some(format!(
            "No dry run: the file ({} KB) is above the dry-run size limit ({} KB, partscope.maxRunFileSize); runtime diagnostics and the cycle time are not shown",
            len / 1024,
            self.doc.max_run_file_size / 1024
        ))
    }

    /// The run only if it was already computed.
    pub fn cached_run(&self) -> Option<Arc<RunReport>> {
        self.run.get().cloned().flatten()
    }

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

#[cfg(test)]
mod tests {
    use analyzer::syntax::{parse, ParseOptions};
    use analyzer::Dialect;
    use runtime::interp::files::is_subprogram_file as is_subroutine_file;

    fn sub(dialect: Dialect, text: &str) -> bool {
        is_subroutine_file(
            &parse(
                ParseOptions {
                    dialect,
                    variant: dialect.default_variant(),
                },
                text.as_bytes().to_vec(),
            ),
            None,
        )
    }

    #[test]
    fn a_library_is_named_after_one_of_its_subroutines() {
        // LinuxCNC finds `o<z_touch> call` in z_touch.ngc: in z_probe.ngc nobody can
        // call it, and run as a program the file ends without M2.
        let p = parse(
            ParseOptions::new(Dialect::Rs274ngc),
            b"o<z_touch> sub
G38.2 Z-10 F25
o<z_touch> endsub
"
            .to_vec(),
        );
        assert!(is_subroutine_file(&p, Some("z_touch")));
        assert!(is_subroutine_file(&p, Some("Z_Touch")));
        assert!(!is_subroutine_file(&p, Some("z_probe")));
        assert!(is_subroutine_file(&p, None));
    }

    #[test]
    fn subprogram_files_are_recognised() {
        assert!(sub(
            Dialect::Rs274ngc,
            "(library)\no<drill> sub\nG81 Z-1 R1\no<drill> endsub\n"
        ));
        assert!(!sub(
            Dialect::Rs274ngc,
            "G0 X1\no<drill> sub\no<drill> endsub\nM2\n"
        ));
        // Definitions first, then the main program that calls them.
        assert!(!sub(
            Dialect::Rs274ngc,
            "o<drill> sub\nG81 Z-1 R1\no<drill> endsub\no<drill> call\nM2\n"
        ));
        assert!(sub(
            Dialect::Rs274ngc,
            "%\no<a> sub\nG0 X1\no<a> endsub\n(two in one file)\no<b> sub\no<b> endsub\n%\n"
        ));
        assert!(sub(Dialect::Fanuc, "%\nO1234;\nG01 X1. F100.;\nM99;\n%\n"));
        assert!(!sub(
            Dialect::Fanuc,
            "%\nO0001;\nM98 P1234;\nM30;\nO1234;\nM99;\n%\n"
        ));
        assert!(sub(Dialect::Servoworks, "G1 X1 F100\nM99\n"));
        assert!(!sub(Dialect::Servoworks, "G1 X1 F100\nM30\n"));
    }
}
