//! Partscope analyzer: text → lossless syntax → blocks; dialect tables; static
//! rules; the [`Diagnostic`] type. Pure: no IO, no LSP, no global state, no `unsafe`.

#![forbid(unsafe_code)]

pub mod diagnostic;
pub mod dialect;
pub mod incremental;
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
    let opts = syntax::ParseOptions {
        dialect: settings.dialect,
        variant: settings.variant,
    };
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
        .filter(|d| d.code == "L009")
        .cloned()
        .collect();
    !l009.is_empty() && !finish(&parsed.program, settings, l009).is_empty()
}

/// Applies rule selection and suppression comments, and sorts. Hosts call this
/// on the runtime's diagnostics too.
pub fn finish(
    program: &syntax::Program,
    settings: &Settings,
    mut diagnostics: Vec<Diagnostic>,
) -> Vec<Diagnostic> {
    let sup = Suppressions::collect(program);
    // LinuxCNC stops reading at a top-level M2/M30: syntax errors in the text after it
    // can never stop the program (spec NGC026; P006 reports the dead text as info).
    let dead_syntax = |d: &Diagnostic| {
        d.file == FileId(0) && d.code.starts_with('L') && d.code != "L009" && d.code != "L000"
    };
    if program.dialect == Dialect::Rs274ngc && diagnostics.iter().any(dead_syntax) {
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
    diagnostics.retain(|d| {
        let enabled = match rules::registry::lookup(d.code) {
            Some(meta) => settings.rule_enabled(meta),
            None => settings.code_enabled(d.code),
        };
        enabled && (d.file != FileId(0) || !sup.is_suppressed(program, d))
    });
    diagnostics.sort_by(|a, b| (a.file, a.span.start, a.code).cmp(&(b.file, b.span.start, b.code)));
    diagnostics.dedup_by(|a, b| {
        a.file == b.file && a.span == b.span && a.code == b.code && a.message == b.message
    });
    diagnostics
}

/// The warning for text that is not valid UTF-8, at its first bad byte.
pub(crate) fn utf8_check(text: &[u8]) -> Option<Diagnostic> {
    let e = std::str::from_utf8(text).err()?;
    let at = e.valid_up_to() as u32;
    Some(Diagnostic::warning(
        "L009",
        Span::new(at, at + e.error_len().unwrap_or(1) as u32),
        "the file is not valid UTF-8 (saved in a legacy code page?); text around here may show garbled",
    ))
}

/// A file is binary when its first 8 KiB hold a NUL byte or mostly non-text bytes.
pub(crate) fn binary_check(text: &[u8]) -> Option<Diagnostic> {
    let head = &text[..text.len().min(8192)];
    if head.is_empty() {
        return None;
    }
    let nul = head.iter().position(|b| *b == 0);
    let odd = head
        .iter()
        .filter(|b| **b < 0x20 && !matches!(**b, b'\n' | b'\r' | b'\t' | 0x0c))
        .count();
    if nul.is_some() || odd * 10 > head.len() {
        let at = nul.unwrap_or(0) as u32;
        return Some(Diagnostic::error(
            "L009",
            Span::new(at, at + 1),
            "this is a binary file, not a part program; it was not analysed",
        ));
    }
    None
}
