//! Applying the analyzer's quick fixes to a text: each diagnostic's first
//! (preferred) fix, non-overlapping fixes together, repeated until no fix is
//! left. Hosts use it for "fix all"; the property test in
//! `tests/rules.rs` holds every rule's fix to ruff's rule: fixes converge, and
//! they never add a diagnostic that was not there before.

use crate::diagnostic::{Diagnostic, FileId, TextEdit};
use crate::Settings;

/// How many rounds [`fix_all`] runs at most. Fixes that touch each other are
/// applied one per round; a well-behaved set of fixes settles in two or three.
pub const MAX_ROUNDS: usize = 8;

/// The edits of the preferred fix of each diagnostic of `FileId(0)`, leaving
/// out every fix that overlaps or touches one taken before (in the order of
/// the diagnostics), so that the result does not depend on how two edits at
/// one place would interleave. Sorted by position.
pub fn compatible_edits(diagnostics: &[Diagnostic]) -> Vec<TextEdit> {
    let mut taken: Vec<TextEdit> = Vec::new();
    for d in diagnostics.iter().filter(|d| d.file == FileId(0)) {
        let Some(fix) = d.fixes.first() else { continue };
        let clashes = fix.edits.iter().any(|e| {
            taken
                .iter()
                .any(|t| e.span.start <= t.span.end && t.span.start <= e.span.end)
        });
        // A fix's own edits must not overlap either, or applying them is ambiguous.
        let own_clash = fix.edits.iter().enumerate().any(|(i, a)| {
            fix.edits[i + 1..]
                .iter()
                .any(|b| a.span.start < b.span.end && b.span.start < a.span.end)
        });
        if clashes || own_clash || fix.edits.is_empty() {
            continue;
        }
        taken.extend(fix.edits.iter().cloned());
    }
    taken.sort_by_key(|e| (e.span.start, e.span.end));
    taken
}

/// Applies non-overlapping edits (as [`compatible_edits`] returns them) to a
/// text. Edits past the end of the text are clamped to it.
pub fn apply_edits(text: &[u8], edits: &[TextEdit]) -> Vec<u8> {
    let mut out = Vec::with_capacity(text.len() + 16);
    let mut at = 0usize;
    for e in edits {
        let start = (e.span.start as usize).clamp(at, text.len());
        let end = (e.span.end as usize).clamp(start, text.len());
        out.extend_from_slice(&text[at..start]);
        out.extend_from_slice(e.new_text.as_bytes());
        at = end;
    }
    out.extend_from_slice(&text[at..]);
    out
}

/// The outcome of [`fix_all`].
#[derive(Debug, Clone)]
pub struct Fixed {
    pub text: Vec<u8>,
    /// Rounds that changed the text.
    pub rounds: usize,
    /// Whether a last round found nothing left to fix (false when
    /// [`MAX_ROUNDS`] ran out first).
    pub settled: bool,
}

/// Applies every fix the analysis offers, round after round, until a round
/// finds nothing to fix or [`MAX_ROUNDS`] have run.
pub fn fix_all(text: &[u8], settings: &Settings) -> Fixed {
    let mut text = text.to_vec();
    for round in 0..MAX_ROUNDS {
        let diagnostics = crate::analyze(text.clone(), settings).diagnostics;
        let edits = compatible_edits(&diagnostics);
        let next = apply_edits(&text, &edits);
        if edits.is_empty() || next == text {
            return Fixed {
                text,
                rounds: round,
                settled: true,
            };
        }
        text = next;
    }
    Fixed {
        text,
        rounds: MAX_ROUNDS,
        settled: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Dialect;

    fn fixed(dialect: Dialect, text: &str) -> String {
        let mut settings = Settings::new(dialect);
        settings.select = vec!["ALL".into()];
        let f = fix_all(text.as_bytes(), &settings);
        assert!(
            f.settled,
            "did not settle: {:?}",
            String::from_utf8_lossy(&f.text)
        );
        String::from_utf8(f.text).expect("fixes write UTF-8")
    }

    #[test]
    fn the_fixes_the_messages_name() {
        assert_eq!(
            fixed(Dialect::Fanuc, "%\nO1000;\nG04 P1.5;\nM30;\n%\n"),
            "%\nO1000;\nG04 P1500;\nM30;\n%\n"
        );
        assert_eq!(
            fixed(Dialect::Servoworks, "G05 P1\nG1 X1. F100.\nM30\n"),
            "G05 P10000\nG1 X1. F100.\nM30\n"
        );
        assert_eq!(
            fixed(Dialect::Fanuc, "%\nO1000;\ng01 x1. F100.;\nM30;\n%\n"),
            "%\nO1000;\nG01 X1. F100.;\nM30;\n%\n"
        );
        // The end code goes before the closing `%`, with the file's `;`.
        assert_eq!(
            fixed(Dialect::Fanuc, "%\nO1000;\nG01 X1. F100.;\n%\n"),
            "%\nO1000;\nG01 X1. F100.;\nM30;\n%\n"
        );
        assert_eq!(fixed(Dialect::Rs274ngc, "G1 X1 F100"), "G1 X1 F100\nM2\n");
        assert_eq!(
            fixed(Dialect::Servoworks, "G1 X1. F100.\r\nG1 X2. X3.\r\n"),
            "G1 X1. F100.\r\nG1 X2.\r\nM30\r\n"
        );
    }
}
