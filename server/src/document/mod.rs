//! One analysed version of one document, without the protocol: the text (a
//! rope), the settings it was analysed with ([`config`]), the parse and the
//! static rules' results (updated incrementally from the previous version),
//! and the dry run ([`run`], made by [`runner`] on first use). The editor
//! features read it through [`crate::ide::Analysis::of`]; the language server
//! wraps it with the document's URI and converts its diagnostics.

pub mod config;
pub mod decimate;
pub mod run;
pub mod runner;
pub mod workspace;

use analyzer::incremental::{Incremental, Parse, StaticRules};
use ropey::Rope;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use config::{ClientOptions, DocSettings};
use run::{CancelFlag, DryRunInput, DryRunner, PreviousRun, RunReport};

pub struct Document {
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

/// The document's bytes, copied out of the rope for the analyzer.
pub fn rope_bytes(rope: &Rope) -> std::sync::Arc<[u8]> {
    // Filled where it lies: collecting a `Vec` and converting it would copy
    // the whole text twice (tens of megabytes per edit of a large file).
    let mut out: std::sync::Arc<[u8]> = std::iter::repeat_n(0u8, rope.len_bytes()).collect();
    if let Some(buf) = std::sync::Arc::get_mut(&mut out) {
        let mut at = 0;
        for chunk in rope.chunks() {
            let b = chunk.as_bytes();
            if let Some(dst) = buf.get_mut(at..at + b.len()) {
                dst.copy_from_slice(b);
            }
            at += b.len();
        }
        return out;
    }
    let mut v = Vec::with_capacity(rope.len_bytes());
    for chunk in rope.chunks() {
        v.extend_from_slice(chunk.as_bytes());
    }
    v.into()
}

/// Everything needed to analyse a document version; `P` is how the previous
/// analysis is held ([`analyze`] takes a [`Previous`], the language server
/// keeps its snapshots).
pub struct Inputs<P> {
    pub version: i32,
    pub rope: Rope,
    pub path: Option<PathBuf>,
    pub roots: Vec<PathBuf>,
    pub client: ClientOptions,
    pub runner: Arc<dyn DryRunner>,
    pub files: Arc<crate::cli::workspace::FileCache>,
    /// The previous analysis of the document, which an edit updates instead
    /// of analysing the whole text again.
    pub previous: Option<P>,
}

impl<P> Inputs<P> {
    /// The same inputs with `previous` instead, and the previous analysis they held.
    pub fn replace_previous<Q>(self, previous: Option<Q>) -> (Inputs<Q>, Option<P>) {
        let inputs = Inputs {
            version: self.version,
            rope: self.rope,
            path: self.path,
            roots: self.roots,
            client: self.client,
            runner: self.runner,
            files: self.files,
            previous,
        };
        (inputs, self.previous)
    }
}

/// The previous analysis of a document: edited in place when nothing else
/// holds it, otherwise updated into a copy.
pub enum Previous<'a> {
    Owned(Box<Document>),
    Shared(&'a Document),
}

impl Previous<'_> {
    fn document(&self) -> &Document {
        match self {
            Previous::Owned(d) => d,
            Previous::Shared(d) => d,
        }
    }
}

/// Resolves settings and analyses one document version. Blocking: call it on
/// a blocking thread.
pub fn analyze(inputs: Inputs<Previous<'_>>) -> Document {
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
        let p = p.document();
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
    let (parse, rules) = match previous {
        Some(Previous::Owned(prev)) => {
            let prev = *prev;
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
        Some(Previous::Shared(shared)) => {
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
    Document {
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

impl Document {
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
