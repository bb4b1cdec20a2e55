//! Partscope analyzer: text → lossless syntax → blocks; dialect tables; static
//! rules; the [`Diagnostic`] type. Pure: no IO, no LSP, no global state, no `unsafe`.

#![forbid(unsafe_code)]

pub mod config;
pub mod control;
pub mod diagnostic;
pub mod dialect;
pub mod fixes;
pub mod format;
pub mod incremental;
pub mod names;
pub mod rules;
pub mod settings;
pub mod span;
pub mod stream;
pub mod syntax;
pub mod twins;

pub use control::{control_signature, Control, Evidence, Signature};
pub use diagnostic::{Diagnostic, FileId, Fix, Related, Severity, TextEdit};
pub use dialect::{Dialect, Variant};
pub use settings::{Config, Settings, Suppressions};
pub use span::{LineIndex, Span};

use std::sync::Arc;

use rules::syntax_rules::{IO_ERROR, NOT_TEXT};

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
    let parsed = parse_text(text, settings);
    let diagnostics = lint(&parsed, settings);
    Analysis {
        program: parsed.program,
        diagnostics,
    }
}

/// The first half of [`analyze`]: the syntax tree and the diagnostics found while
/// reading. Hosts that interpret the program start the interpreter on `program`
/// while [`lint`] runs the static rules on another thread.
#[derive(Debug, Clone)]
pub struct Parsed {
    pub program: syntax::Program,
    /// Syntax diagnostics (and `L009`), not yet filtered or sorted.
    pub diagnostics: Vec<Diagnostic>,
    /// A binary file: `program` holds the text but no blocks, and only `L009` is reported.
    pub binary: bool,
}

/// Reads one file (see [`Parsed`]).
pub fn parse_text(text: impl Into<Arc<[u8]>>, settings: &Settings) -> Parsed {
    read(text.into(), settings, false)
}

/// [`parse_text`] without tokens ([`syntax::parse_lean`]): for hosts that lint and
/// run but never highlight or print the tree, such as the command line.
pub fn parse_text_lean(text: impl Into<Arc<[u8]>>, settings: &Settings) -> Parsed {
    read(text.into(), settings, true)
}

fn read(text: Arc<[u8]>, settings: &Settings, lean: bool) -> Parsed {
    let opts = settings.parse_options();
    if let Some(d) = binary_check(&text) {
        // A binary file is reported once; parsing it would only produce noise.
        let program = syntax::parse(opts, Arc::<[u8]>::from(&b""[..]));
        let program = syntax::Program { text, ..program };
        return Parsed {
            program,
            diagnostics: vec![d],
            binary: true,
        };
    }
    let utf8 = utf8_check(&text);
    let program = if lean {
        syntax::parse_lean(opts, text)
    } else {
        syntax::parse(opts, text)
    };
    let mut diagnostics = program.diagnostics.clone();
    diagnostics.extend(utf8);
    Parsed {
        program,
        diagnostics,
        binary: false,
    }
}

/// The second half of [`analyze`]: static rules, then [`finish`] (a binary file
/// keeps its single, unfiltered `L009`).
pub fn lint(parsed: &Parsed, settings: &Settings) -> Vec<Diagnostic> {
    let mut diagnostics = parsed.diagnostics.clone();
    if parsed.binary {
        return diagnostics;
    }
    let cx = rules::ProgramCx::new(&parsed.program, settings);
    rules::check(&cx, &mut diagnostics);
    finish(&parsed.program, settings, diagnostics)
}

/// Whether [`analyze`] would report `L009` (binary file, or invalid UTF-8 unless
/// that report is disabled or suppressed), without running the static rules:
/// hosts skip the interpreter on such files.
pub fn reports_l009(parsed: &Parsed, settings: &Settings) -> bool {
    if parsed.binary {
        return true;
    }
    let l009: Vec<Diagnostic> = parsed
        .diagnostics
        .iter()
        .filter(|d| d.code == NOT_TEXT.code)
        .cloned()
        .collect();
    !l009.is_empty() && !finish(&parsed.program, settings, l009).is_empty()
}

/// The code of [`rules::control_mismatch`]: a lathe or Haas program in the `fanuc` dialect.
const MISMATCH: &str = rules::control_mismatch::CONTROL_MISMATCH.code;

/// Whether [`analyze`] would report `P010` (the program looks written for a lathe or a
/// Haas mill, and the report is neither disabled nor suppressed): hosts then skip the
/// interpreter, whose findings and cycle time would mean nothing.
pub fn reports_mismatch(parsed: &Parsed, settings: &Settings) -> bool {
    !parsed.binary && program_reports_mismatch(&parsed.program, settings)
}

/// [`reports_mismatch`] of a parsed program (a binary file's has no blocks, so
/// no mismatch).
pub fn program_reports_mismatch(program: &syntax::Program, settings: &Settings) -> bool {
    program_mismatch(program, settings).is_some()
}

/// The `P010` finding [`program_reports_mismatch`] decides on, when it is reported.
pub fn program_mismatch(program: &syntax::Program, settings: &Settings) -> Option<Diagnostic> {
    let d = rules::control_mismatch::mismatch_diagnostic(program)?;
    finish(program, settings, vec![d]).pop()
}

/// Applies rule selection and suppression comments, and sorts. Hosts call this
/// on the runtime's diagnostics too.
pub fn finish(
    program: &syntax::Program,
    settings: &Settings,
    diagnostics: Vec<Diagnostic>,
) -> Vec<Diagnostic> {
    finish_in(program, None, settings, diagnostics, true)
}

/// [`finish`] for a file read in windows: `program` is the window the
/// diagnostics were found in (or any window, for findings elsewhere), and
/// `file` says what only the whole file knows (its suppressions, the text the
/// control never reads).
pub fn finish_window(
    program: &syntax::Program,
    file: &stream::FileFacts,
    settings: &Settings,
    diagnostics: Vec<Diagnostic>,
) -> Vec<Diagnostic> {
    finish_in(program, Some(file), settings, diagnostics, true)
}

/// `limit`: whether to bound the list ([`limit_diagnostics`]); a host that
/// bounds a whole file's parts with one [`Limiter`] finishes them without.
pub(crate) fn finish_in(
    program: &syntax::Program,
    file: Option<&stream::FileFacts>,
    settings: &Settings,
    mut diagnostics: Vec<Diagnostic>,
    limit: bool,
) -> Vec<Diagnostic> {
    let collected;
    let sup = match file {
        Some(f) => &f.suppressions,
        None => {
            collected = Suppressions::collect(program);
            &collected
        }
    };
    // LinuxCNC stops reading at a top-level M2/M30: syntax errors in the text after it
    // can never stop the program (spec NGC026; P006 reports the dead text as info).
    let dead_syntax = |d: &Diagnostic| {
        d.file == FileId(0)
            && d.code.starts_with('L')
            && d.code != NOT_TEXT.code
            && d.code != IO_ERROR.code
    };
    if program.dialect == Dialect::Rs274ngc && diagnostics.iter().any(dead_syntax) {
        match file {
            Some(f) => diagnostics.retain(|d| !(dead_syntax(d) && f.never_read(d.span.start))),
            None => {
                let dead = rules::util::dead_blocks(program);
                if dead.iter().any(|&x| x) {
                    diagnostics.retain(|d| {
                        !(dead_syntax(d)
                            && program
                                .block_at(d.span.start)
                                .is_some_and(|b| dead.get(b).copied().unwrap_or(false)))
                    });
                }
            }
        }
    }
    // FANUC reads no text that an unconditional GOTO, M99 or M30 jumps over (up to
    // the next sequence number): a syntax error there is never raised.
    if program.dialect == Dialect::Fanuc
        && diagnostics
            .iter()
            .any(|d| dead_syntax(d) && d.severity == diagnostic::Severity::Error)
    {
        let over = match file {
            Some(_) => Vec::new(),
            None => rules::util::jumped_over_blocks(program),
        };
        for d in diagnostics.iter_mut() {
            let jumped = dead_syntax(d)
                && d.severity == diagnostic::Severity::Error
                && match file {
                    Some(f) => f.never_read(d.span.start),
                    None => program
                        .block_at(d.span.start)
                        .is_some_and(|b| over.get(b).copied().unwrap_or(false)),
                };
            if jumped {
                // Text nobody reads needs no repair: a fix there could only uncover
                // findings its error hid.
                d.fixes.clear();
                d.severity = diagnostic::Severity::Info;
                d.message = format!(
                    "{}; never read: an unconditional GOTO, M99 or M30 before it skips the text up to the next sequence number, so the control raises no alarm here",
                    d.message
                );
            }
        }
    }
    for d in diagnostics.iter_mut().filter(|d| d.file == FileId(0)) {
        d.fixes
            .retain(|f| rules::block_too_long::edits_keep_line_length(program, settings, &f.edits));
    }
    diagnostics.retain(|d| {
        let enabled = match rules::registry::lookup(d.code) {
            Some(meta) => settings.rule_enabled(meta),
            None => settings.code_enabled(d.code),
        };
        enabled && (d.file != FileId(0) || !sup.is_suppressed(d))
    });
    // A program for another control (P010) gets that one finding: the others would
    // only describe the mismatch, many times over.
    if diagnostics
        .iter()
        .any(|d| d.code == MISMATCH && d.file == FileId(0))
    {
        diagnostics.retain(|d| d.code == MISMATCH && d.file == FileId(0));
    }
    if limit {
        return join_finished(diagnostics, settings);
    }
    join_unbounded(&mut diagnostics);
    diagnostics
}

/// The last step of [`finish`]: sorts by position and code, joins repeats
/// of one code on one span, drops twins and bounds the list. A host that
/// finished the parts of one file's static findings separately (the windows
/// and the skeleton of `stream`) joins them with it.
pub fn join_finished(mut diagnostics: Vec<Diagnostic>, settings: &Settings) -> Vec<Diagnostic> {
    join_unbounded(&mut diagnostics);
    limit_diagnostics(diagnostics, settings)
}

fn join_unbounded(diagnostics: &mut Vec<Diagnostic>) {
    diagnostics.sort_by(|a, b| (a.file, a.span.start, a.code).cmp(&(b.file, b.span.start, b.code)));
    twins::join_same_code(diagnostics);
    twins::drop_twins(diagnostics);
}

/// Joins the static diagnostics of a file with its interpreter's, each already
/// through [`finish`]: sorted by position (static first where they start
/// together), one diagnostic per fault ([`twins::drop_twins`]) and bounded again.
/// The one way every host (`check`, `run`, the language server) combines the two.
pub fn merge(
    mut diagnostics: Vec<Diagnostic>,
    runtime: Vec<Diagnostic>,
    settings: &Settings,
) -> Vec<Diagnostic> {
    diagnostics.extend(runtime);
    diagnostics.sort_by_key(|d| (d.file, d.span.start));
    twins::drop_twins(&mut diagnostics);
    limit_diagnostics(diagnostics, settings)
}

/// How the "… and N more" diagnostics of [`limit_diagnostics`] begin.
pub(crate) const MORE_PREFIX: &str = "… and ";

/// Keeps the first `settings.max_per_code` diagnostics of each code in each file
/// and the first `settings.max_per_file` of each file, in the order given (sorted
/// by position), and reports what it drops as one "… and N more" diagnostic per
/// code (or per file) at the first one dropped. Hostile files produce millions of
/// diagnostics; this bounds the memory and output they take. Idempotent.
pub fn limit_diagnostics(diagnostics: Vec<Diagnostic>, settings: &Settings) -> Vec<Diagnostic> {
    if diagnostics.len()
        <= settings
            .max_per_code
            .max(1)
            .min(settings.max_per_file.max(1))
    {
        return diagnostics;
    }
    let mut limit = Limiter::new(settings);
    for d in diagnostics {
        limit.push(d);
    }
    limit.finish()
}

/// [`limit_diagnostics`] as a fold: a host that finds a file's diagnostics in
/// parts, in file order (the windows of `stream`), pushes them as they come, so
/// that no more than the kept ones are ever held.
pub struct Limiter {
    per_code: usize,
    per_file: usize,
    counts: std::collections::HashMap<(FileId, &'static str), usize>,
    file_counts: std::collections::HashMap<FileId, usize>,
    /// (first dropped, how many) per code and per file.
    dropped: std::collections::HashMap<(FileId, &'static str), (Diagnostic, usize)>,
    dropped_file: std::collections::HashMap<FileId, (Diagnostic, usize)>,
    kept: Vec<Diagnostic>,
}

impl Limiter {
    pub fn new(settings: &Settings) -> Limiter {
        Limiter {
            per_code: settings.max_per_code.max(1),
            per_file: settings.max_per_file.max(1),
            counts: Default::default(),
            file_counts: Default::default(),
            dropped: Default::default(),
            dropped_file: Default::default(),
            kept: Vec::new(),
        }
    }

    pub fn push(&mut self, d: Diagnostic) {
        if d.message.starts_with(MORE_PREFIX) {
            self.kept.push(d);
            return;
        }
        let n = self.counts.entry((d.file, d.code)).or_insert(0);
        if *n >= self.per_code {
            let e = self
                .dropped
                .entry((d.file, d.code))
                .or_insert_with(|| (d.clone(), 0));
            e.1 += 1;
            return;
        }
        let f = self.file_counts.entry(d.file).or_insert(0);
        if *f >= self.per_file {
            let e = self
                .dropped_file
                .entry(d.file)
                .or_insert_with(|| (d.clone(), 0));
            e.1 += 1;
            return;
        }
        *n += 1;
        *f += 1;
        self.kept.push(d);
    }

    /// The kept diagnostics and one "… and N more" per code (or file) that
    /// dropped some, sorted by position.
    pub fn finish(self) -> Vec<Diagnostic> {
        let (per_code, per_file) = (self.per_code, self.per_file);
        let mut kept = self.kept;
        if self.dropped.is_empty() && self.dropped_file.is_empty() {
            return kept;
        }
        for ((_, code), (first, n)) in self.dropped {
            let mut d = Diagnostic::new(code, first.severity, first.span, format!("{MORE_PREFIX}{n} more {code} diagnostics in this file from here on: at most {per_code} of one code are reported (raise with --max-per-code)"));
            d.file = first.file;
            kept.push(d);
        }
        for (_, (first, n)) in self.dropped_file {
            let mut d = Diagnostic::new(first.code, first.severity, first.span, format!("{MORE_PREFIX}{n} more diagnostics in this file from here on: at most {per_file} are reported per file (raise with --max-per-file)"));
            d.file = first.file;
            kept.push(d);
        }
        kept.sort_by(|a, b| {
            (a.file, a.span.start, a.code, &a.message).cmp(&(
                b.file,
                b.span.start,
                b.code,
                &b.message,
            ))
        });
        kept
    }
}

/// The warning for text that is not valid UTF-8, at its first bad byte.
pub(crate) fn utf8_check(text: &[u8]) -> Option<Diagnostic> {
    let e = std::str::from_utf8(text).err()?;
    let at = e.valid_up_to() as u32;
    Some(NOT_TEXT.warning(
        Span::new(at, at + e.error_len().unwrap_or(1) as u32),
        "the file is not valid UTF-8 (saved in a legacy code page?); text around here may show garbled",
    ))
}

/// The byte order of UTF-16 text: a byte-order mark, or (without one) a NUL in
/// every second byte of mostly ASCII text, as Windows editors save "Unicode".
fn utf16_order(head: &[u8]) -> Option<&'static str> {
    if head.starts_with(&[0xFF, 0xFE]) {
        return Some("little-endian");
    }
    if head.starts_with(&[0xFE, 0xFF]) {
        return Some("big-endian");
    }
    let pairs = head.len() / 2;
    if pairs < 2 {
        return None;
    }
    let nul_at = |odd: usize| {
        head.chunks_exact(2)
            .filter(|p| p[odd] == 0 && p[1 - odd] != 0)
            .count()
    };
    if nul_at(1) * 10 >= pairs * 9 {
        Some("little-endian")
    } else if nul_at(0) * 10 >= pairs * 9 {
        Some("big-endian")
    } else {
        None
    }
}

/// A file is binary when its first 8 KiB hold a NUL byte or mostly non-text bytes.
pub(crate) fn binary_check(text: &[u8]) -> Option<Diagnostic> {
    let head = &text[..text.len().min(8192)];
    if head.is_empty() {
        return None;
    }
    if let Some(order) = utf16_order(head) {
        let bom = head.starts_with(&[0xFF, 0xFE]) || head.starts_with(&[0xFE, 0xFF]);
        return Some(NOT_TEXT.error(
            Span::new(0, if bom { 2 } else { 1 }),
            format!(
                "the file is UTF-16 ({order}) text, which no control reads; save it as ASCII or \
                 UTF-8. It was not analysed"
            ),
        ));
    }
    let nul = head.iter().position(|b| *b == 0);
    let odd = head
        .iter()
        .filter(|b| **b < 0x20 && !matches!(**b, b'\n' | b'\r' | b'\t' | 0x0c))
        .count();
    if nul.is_some() || odd * 10 > head.len() {
        let at = nul.unwrap_or(0) as u32;
        return Some(NOT_TEXT.error(
            Span::new(at, at + 1),
            "this is a binary file, not a part program; it was not analysed",
        ));
    }
    None
}
