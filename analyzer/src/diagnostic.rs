//! The one diagnostic type shared by syntax checks, static rules and the interpreter.

use crate::span::Span;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Hint,
    Info,
    Warning,
    Error,
}

impl Severity {
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Hint => "hint",
            Severity::Info => "info",
            Severity::Warning => "warning",
            Severity::Error => "error",
        }
    }

    pub fn parse(s: &str) -> Option<Severity> {
        Some(match s.to_ascii_lowercase().as_str() {
            "hint" => Severity::Hint,
            "info" | "information" => Severity::Info,
            "warning" | "warn" => Severity::Warning,
            "error" => Severity::Error,
            _ => return None,
        })
    }
}

/// Identifies a source file within one analysis. `FileId(0)` is the file being
/// checked; the interpreter numbers the subprogram files it resolves from 1 on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct FileId(pub u32);

/// A secondary location that explains a diagnostic (the earlier conflicting
/// code, the call site of a subprogram, …).
#[derive(Debug, Clone, PartialEq)]
pub struct Related {
    pub file: FileId,
    pub span: Span,
    pub message: String,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextEdit {
    pub span: Span,
    pub new_text: String,
}

/// A fix the user can apply. Only offered when the fix is certain.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fix {
    pub title: String,
    pub edits: Vec<TextEdit>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Stable rule code, e.g. `"G001"`; see [`crate::rules::registry`].
    pub code: &'static str,
    pub severity: Severity,
    /// What is wrong, why, and what to do.
    pub message: String,
    pub file: FileId,
    pub span: Span,
    pub related: Vec<Related>,
    pub fixes: Vec<Fix>,
}

impl Diagnostic {
    /// Moves the diagnostic's spans (its own, its related locations' in the
    /// same file, its fixes' edits) `bytes` further into the file.
    pub fn shift(&mut self, bytes: u32) {
        let sp = |s: &mut Span| {
            s.start = s.start.saturating_add(bytes);
            s.end = s.end.saturating_add(bytes);
        };
        sp(&mut self.span);
        for r in self.related.iter_mut().filter(|r| r.file == self.file) {
            sp(&mut r.span);
        }
        for f in &mut self.fixes {
            for e in &mut f.edits {
                sp(&mut e.span);
            }
        }
    }

    pub fn new(
        code: &'static str,
        severity: Severity,
        span: Span,
        message: impl Into<String>,
    ) -> Self {
        Diagnostic {
            code,
            severity,
            message: message.into(),
            file: FileId(0),
            span,
            related: Vec::new(),
            fixes: Vec::new(),
        }
    }

    pub fn error(code: &'static str, span: Span, message: impl Into<String>) -> Self {
        Self::new(code, Severity::Error, span, message)
    }

    pub fn warning(code: &'static str, span: Span, message: impl Into<String>) -> Self {
        Self::new(code, Severity::Warning, span, message)
    }

    pub fn info(code: &'static str, span: Span, message: impl Into<String>) -> Self {
        Self::new(code, Severity::Info, span, message)
    }

    pub fn with_related(mut self, span: Span, message: impl Into<String>) -> Self {
        self.related.push(Related {
            file: self.file,
            span,
            message: message.into(),
        });
        self
    }

    pub fn with_fix(mut self, title: impl Into<String>, edits: Vec<TextEdit>) -> Self {
        self.fixes.push(Fix {
            title: title.into(),
            edits,
        });
        self
    }

    pub fn in_file(mut self, file: FileId) -> Self {
        self.file = file;
        for r in &mut self.related {
            if r.file == FileId(0) {
                r.file = file;
            }
        }
        self
    }
}
