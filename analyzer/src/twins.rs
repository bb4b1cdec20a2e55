//! One diagnostic per fault. Some faults are seen by two layers (a static rule and
//! the interpreter, or two static rules); [`TWINS`] declares those pairs and which
//! code owns the fault, and [`drop_twins`] removes the other one where both point
//! at the same text. Hosts reach it through [`crate::finish`] and [`crate::merge`].

use crate::diagnostic::{Diagnostic, FileId};
use crate::rules::registry as reg;
use crate::rules::syntax_rules as syn;
use crate::span::Span;

/// The note the interpreter appends to an error after which it cannot go on.
pub const STOP_SUFFIX: &str = " (the dry run stops here)";

/// Two codes that report one fault when their spans overlap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Twin {
    /// The code that stays.
    pub keep: &'static str,
    /// The code dropped where a `keep` diagnostic overlaps it.
    pub drop: &'static str,
    /// The fault both describe.
    pub fault: &'static str,
}

/// The declared twin pairs. A static rule owns each fault it sees: it is reported
/// without a run (subprogram files, the editor before its dry run) and its message
/// says what to do; the interpreter's twin is dropped, and its stop note moves onto
/// the kept one. Between two static rules, or two runtime ones, the more specific
/// one stays.
pub const TWINS: &[Twin] = &[
    Twin {
        keep: reg::MISSING_REQUIRED_WORD.code,
        drop: "A005",
        fault: "an arc without R or I/J/K",
    },
    Twin {
        keep: reg::MISSING_REQUIRED_WORD.code,
        drop: "X003",
        fault: "a code without a word it needs (G4 without P, …)",
    },
    Twin {
        keep: reg::MISSING_REQUIRED_WORD.code,
        drop: "C003",
        fault: "a canned cycle without a word it needs (G76 without P, …)",
    },
    Twin {
        keep: reg::CONSTANT_EXPRESSION.code,
        drop: "X001",
        fault: "a constant expression that cannot be evaluated",
    },
    Twin {
        keep: syn::MISSING_VALUE.code,
        drop: syn::BAD_EXPRESSION.code,
        fault: "a `#` without a parameter",
    },
    Twin {
        keep: reg::UNREACHABLE_AFTER_END.code,
        drop: "F005",
        fault: "code after M2/M30",
    },
    Twin {
        keep: reg::PROGRAM_END.code,
        drop: "F006",
        fault: "a program without an end",
    },
    Twin {
        keep: syn::MISPLACED_PERCENT.code,
        drop: "X003",
        fault: "a `%` that is not a program end",
    },
    Twin {
        keep: syn::MISPLACED_PERCENT.code,
        drop: reg::PROGRAM_END.code,
        fault: "a closing `%` without an opening one, read as the missing end",
    },
    Twin {
        keep: reg::MISSING_REQUIRED_WORD.code,
        drop: "C002",
        fault: "a peck cycle without Q",
    },
    Twin {
        keep: reg::WORD_VALUE_RANGE.code,
        drop: "C002",
        fault: "a negative peck depth Q",
    },
    Twin {
        keep: reg::MISSING_REQUIRED_WORD.code,
        drop: "F002",
        fault: "M98 or G65 without P",
    },
    Twin {
        keep: reg::MISSING_REQUIRED_WORD.code,
        drop: "F011",
        fault: "a probe or motion code without axis words",
    },
    Twin {
        keep: reg::CONFLICTING_WORDS.code,
        drop: "A005",
        fault: "an arc with both R and I/J/K",
    },
    Twin {
        keep: reg::CONFLICTING_WORDS.code,
        drop: "X008",
        fault: "a D peck clearance LinuxCNC 2.9 does not accept",
    },
    Twin {
        keep: reg::UNKNOWN_ADDRESS.code,
        drop: "X003",
        fault: "a word letter the machine or profile does not have",
    },
    Twin {
        keep: reg::WORD_VALUE_RANGE.code,
        drop: "X002",
        fault: "a minus sign on an M or G code",
    },
    Twin {
        keep: reg::WORD_VALUE_RANGE.code,
        drop: "T007",
        fault: "a negative offset number",
    },
    Twin {
        keep: reg::UNKNOWN_CODE.code,
        drop: "X002",
        fault: "a G code that does not exist",
    },
    Twin {
        keep: reg::PARAMETER_NUMBER.code,
        drop: "X001",
        fault: "a write to a read-only parameter",
    },
    Twin {
        keep: reg::EXPRESSION_FORM.code,
        drop: "X001",
        fault: "EXISTS without a parameter",
    },
    Twin {
        keep: reg::CYCLE_WORDS.code,
        drop: "X003",
        fault: "M98 in a block with a canned cycle's axis words",
    },
    Twin {
        keep: reg::OWORD_STRUCTURE.code,
        drop: "F007",
        fault: "an O-word statement closing or returning from the wrong block",
    },
    Twin {
        keep: reg::MACRO_LOOP_STRUCTURE.code,
        drop: "F007",
        fault: "an END without its DO",
    },
    Twin {
        keep: reg::GOTO_TARGET.code,
        drop: "F007",
        fault: "a GOTO to a sequence number that does not exist",
    },
    Twin {
        keep: reg::OWORD_CALLS.code,
        drop: syn::UNKNOWN_CHARACTER.code,
        fault: "an O-word label written with the digit 0",
    },
    Twin {
        keep: reg::OWORD_CALLS.code,
        drop: syn::MISSING_VALUE.code,
        fault: "an O-word label written with the digit 0 (its keyword read as words)",
    },
    Twin {
        keep: "A007",
        drop: "A001",
        fault: "I/J/K in polar coordinate mode (the radius check then fails too)",
    },
    Twin {
        keep: "C009",
        drop: "F001",
        fault: "rigid tapping with F0",
    },
];

/// Whether the twin list pairs `a` and `b`, either way round.
pub fn are_twins(a: &str, b: &str) -> bool {
    TWINS
        .iter()
        .any(|t| (t.keep == a && t.drop == b) || (t.keep == b && t.drop == a))
}

/// Whether two spans point at the same text: they share a byte, or an empty one
/// (the end of the file) lies inside or at an end of the other.
pub fn spans_meet(a: Span, b: Span) -> bool {
    if a.start == a.end || b.start == b.end {
        return a.start <= b.end && b.start <= a.end;
    }
    a.start < b.end && b.start < a.end
}

/// One diagnostic per code and place: diagnostics of one code that start at the same
/// place with the same message are one (the first stays); two of one code on the
/// same span with different messages become one whose message says both. Expects
/// the list sorted by file and start.
pub fn join_same_code(diagnostics: &mut Vec<Diagnostic>) {
    let mut out: Vec<Diagnostic> = Vec::with_capacity(diagnostics.len());
    for d in diagnostics.drain(..) {
        let same = out
            .iter_mut()
            .rev()
            .take_while(|o| o.file == d.file && o.span.start == d.span.start)
            .take(64)
            .find(|o| o.code == d.code && (o.message == d.message || o.span == d.span));
        match same {
            Some(o) if o.message == d.message || o.message.contains(d.message.as_str()) => {
                o.severity = o.severity.max(d.severity);
            }
            Some(o) => {
                // A stop note belongs at the end of the joined message.
                let stops = o.message.ends_with(STOP_SUFFIX) || d.message.ends_with(STOP_SUFFIX);
                let first = o.message.trim_end_matches(STOP_SUFFIX).to_string();
                let second = d.message.trim_end_matches(STOP_SUFFIX);
                // Sentences follow each other; fragments are joined with a semicolon.
                let sep = if first.ends_with('.') { " " } else { "; " };
                o.message = format!("{first}{sep}{second}");
                if stops {
                    o.message.push_str(STOP_SUFFIX);
                }
                o.severity = o.severity.max(d.severity);
                o.fixes.extend(d.fixes);
                o.related.extend(d.related);
            }
            None => out.push(d),
        }
    }
    *diagnostics = out;
}

/// The diagnostics of one kept code in one file.
struct Keepers {
    code: &'static str,
    file: FileId,
    /// (span, index in the list), sorted by start.
    spans: Vec<(Span, usize)>,
    /// The largest end among `spans[..=j]`.
    max_end: Vec<u32>,
}

/// Removes each diagnostic whose code is a twin's `drop` where a diagnostic of its
/// `keep` code meets it in the same file. The kept one takes the more severe severity
/// and the dropped one's stop note, so exit codes and "the dry run stops here" stay.
/// Order is kept. Idempotent.
pub fn drop_twins(diagnostics: &mut Vec<Diagnostic>) {
    let dropping = |c: &str| TWINS.iter().any(|t| t.drop == c);
    if !diagnostics.iter().any(|d| dropping(d.code)) {
        return;
    }
    // Per kept code and file: its spans sorted by start, with the running maximum
    // end, so the search for a span that meets another stops where none can.
    let mut keepers: Vec<Keepers> = Vec::new();
    for t in TWINS {
        if keepers.iter().any(|k| k.code == t.keep) {
            continue;
        }
        for (i, d) in diagnostics.iter().enumerate() {
            if d.code != t.keep {
                continue;
            }
            match keepers
                .iter_mut()
                .find(|k| k.code == t.keep && k.file == d.file)
            {
                Some(k) => k.spans.push((d.span, i)),
                None => keepers.push(Keepers {
                    code: t.keep,
                    file: d.file,
                    spans: vec![(d.span, i)],
                    max_end: Vec::new(),
                }),
            }
        }
    }
    for k in &mut keepers {
        k.spans.sort_by_key(|(s, _)| (s.start, s.end));
        let mut m = 0;
        k.max_end = k
            .spans
            .iter()
            .map(|(s, _)| {
                m = m.max(s.end);
                m
            })
            .collect();
    }
    let meeting = |keep: &str, file: FileId, span: Span| -> Option<usize> {
        let k = keepers.iter().find(|k| k.code == keep && k.file == file)?;
        let upto = k.spans.partition_point(|(s, _)| s.start <= span.end);
        (0..upto)
            .rev()
            .take_while(|&j| k.max_end[j] >= span.start)
            .find(|&j| spans_meet(k.spans[j].0, span))
            .map(|j| k.spans[j].1)
    };
    let mut merge_into: Vec<(usize, usize)> = Vec::new();
    for (i, d) in diagnostics.iter().enumerate() {
        // A "… and N more" summary stands for many: it stays.
        if d.message.starts_with(crate::MORE_PREFIX) {
            continue;
        }
        let owner = TWINS
            .iter()
            .filter(|t| t.drop == d.code)
            .find_map(|t| meeting(t.keep, d.file, d.span));
        if let Some(o) = owner {
            merge_into.push((i, o));
        }
    }
    if merge_into.is_empty() {
        return;
    }
    let mut owner_of: Vec<Option<usize>> = vec![None; diagnostics.len()];
    for &(i, o) in &merge_into {
        owner_of[i] = Some(o);
    }
    for &(i, o) in &merge_into {
        // A dropped diagnostic's owner may itself be dropped (F006 under P005 under
        // L011): what it carries goes to the first owner that stays.
        let mut o = o;
        for _ in 0..TWINS.len() {
            match owner_of[o] {
                Some(next) if next != i => o = next,
                _ => break,
            }
        }
        let (sev, stops) = {
            let d = &diagnostics[i];
            (d.severity, d.message.ends_with(STOP_SUFFIX))
        };
        let keep = &mut diagnostics[o];
        keep.severity = keep.severity.max(sev);
        if stops && !keep.message.ends_with(STOP_SUFFIX) {
            keep.message.push_str(STOP_SUFFIX);
        }
    }
    let mut n = 0;
    diagnostics.retain(|_| {
        n += 1;
        owner_of[n - 1].is_none()
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostic::Severity;

    fn d(code: &'static str, sev: Severity, a: u32, b: u32, msg: &str) -> Diagnostic {
        Diagnostic::new(code, sev, Span::new(a, b), msg)
    }

    #[test]
    fn the_static_twin_stays_with_the_stop_note() {
        let mut v = vec![
            d("W003", Severity::Error, 10, 12, "G4 needs P"),
            d(
                "X003",
                Severity::Error,
                10,
                12,
                "dwell time P word missing with G4 (the dry run stops here)",
            ),
            d(
                "X003",
                Severity::Error,
                20,
                22,
                "other (the dry run stops here)",
            ),
        ];
        drop_twins(&mut v);
        let got: Vec<(&str, &str)> = v.iter().map(|d| (d.code, d.message.as_str())).collect();
        assert_eq!(
            got,
            [
                ("W003", "G4 needs P (the dry run stops here)"),
                ("X003", "other (the dry run stops here)")
            ]
        );
        let again = v.clone();
        drop_twins(&mut v);
        assert_eq!(v, again);
    }

    #[test]
    fn the_end_of_file_meets_a_span_ending_there() {
        let mut v = vec![
            d("P005", Severity::Warning, 5, 30, "no end"),
            d("F006", Severity::Error, 30, 30, "no end"),
        ];
        drop_twins(&mut v);
        assert_eq!(v.len(), 1);
        assert_eq!((v[0].code, v[0].severity), ("P005", Severity::Error));
        // Adjacent spans are different text.
        let mut w = vec![
            d("W003", Severity::Error, 0, 2, "a"),
            d("A005", Severity::Error, 2, 4, "b"),
        ];
        drop_twins(&mut w);
        assert_eq!(w.len(), 2);
    }

    #[test]
    fn many_neighbours_that_never_meet_stay_and_cost_little() {
        // 20 000 of each, side by side: a quadratic search would take seconds.
        let mut v = Vec::new();
        for i in 0..20_000u32 {
            v.push(d("W003", Severity::Error, 4 * i, 4 * i + 2, "a"));
            v.push(d("A005", Severity::Error, 4 * i + 2, 4 * i + 4, "b"));
        }
        let t = std::time::Instant::now();
        drop_twins(&mut v);
        assert_eq!(v.len(), 40_000);
        assert!(t.elapsed().as_secs_f64() < 1.0, "{:?}", t.elapsed());
    }

    #[test]
    fn every_code_is_kept_or_dropped_one_way() {
        for t in TWINS {
            assert_ne!(t.keep, t.drop);
            assert!(!TWINS.iter().any(|u| u.keep == t.drop && u.drop == t.keep));
        }
    }
}
