//! Document formatting as CAM editors offer it: block numbers renumbered with
//! a start and step, removed or added; one blank or none between words; upper
//! case address letters. Pure: the result is a list of edits.
//!
//! It never changes what the control executes: comments and everything
//! inside an item (expressions, names, numbers) stay byte for byte; only the
//! blanks between items, address letters and `N` words change. Where the
//! control reads a block number (a FANUC `GOTO n` / `IF … GOTO n`), the
//! targets are renumbered with their blocks, or kept when block numbers are
//! removed; a computed `GOTO #1` or an `M99 P` return (to a caller's block
//! number) makes renumbering refuse. ServoWorks ignores lower-case words, so
//! upper case is never applied there.

use std::collections::HashMap;

use crate::diagnostic::TextEdit;
use crate::dialect::Dialect;
use crate::names::{block_occurrences, Occ, Sym};
use crate::span::Span;
use crate::syntax::{BlockKind, ItemKind, MacroStmt, Program, WordValue};

/// What happens to block numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Numbers {
    #[default]
    Keep,
    /// Blocks that have an `N` word get `start`, `start + step`, …
    Renumber { start: u32, step: u32 },
    /// Every code block gets a number (`start`, `start + step`, …).
    Add { start: u32, step: u32 },
    /// `N` words go, except those a `GOTO` jumps to.
    Remove,
}

/// Blanks between the items of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Spacing {
    #[default]
    Keep,
    /// One blank between items, none at the end of the block.
    One,
    /// No blank between words (`G1X1Y2`), one before a comment.
    None,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FormatOptions {
    pub numbers: Numbers,
    pub spacing: Spacing,
    pub uppercase: bool,
}

/// The largest block number each dialect reads without a setting.
fn max_number(d: Dialect) -> u64 {
    match d {
        Dialect::Rs274ngc => 99_999,
        // Five digits (P007); N1–N99999999 only with parameter No. 3204.
        Dialect::Fanuc => 99_999,
        Dialect::Servoworks => 99_999,
    }
}

fn blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// Whether a block holds a syntax error: how it reads depends on the
/// exact text, so formatting leaves it alone.
fn broken(program: &Program, b: &crate::syntax::Block) -> bool {
    let full = b.span;
    program
        .diagnostics
        .iter()
        .filter(|d| d.severity == crate::Severity::Error)
        .any(|d| d.span.start < full.end.max(full.start + 1) && full.start <= d.span.start)
}

/// Whether a block carries code a block number can precede. An RS274/NGC
/// line of parameter assignments stays unnumbered: outside a subroutine it is
/// what a library file may hold (`Program::is_ngc_library`).
fn numberable(program: &Program, b: &crate::syntax::Block) -> bool {
    let items = program.items_of(b);
    let assignments_only = items
        .iter()
        .all(|i| matches!(i.kind, ItemKind::Assign { .. } | ItemKind::Comment(_)));
    if program.dialect == Dialect::Rs274ngc && assignments_only {
        return false;
    }
    b.kind == BlockKind::Normal
        && !broken(program, b)
        && items
            .iter()
            .any(|i| !matches!(i.kind, ItemKind::Comment(_)))
        && !items.iter().any(|i| {
            matches!(
                i.kind,
                ItemKind::ProgramHead { .. } | ItemKind::OWord(_) | ItemKind::Error
            )
        })
}

/// The longest line the control reads, in characters (W011), if it has a limit.
fn line_limit(program: &Program) -> Option<usize> {
    match program.dialect {
        Dialect::Servoworks => Some(85),
        // 252, or 251 with CR LF; the 2007 seed reads 256.
        Dialect::Rs274ngc => Some(251),
        Dialect::Fanuc => None,
    }
}

/// Drops the edits of every line they would make longer than the control
/// reads: a block number or blank added to a full line would cut it.
fn within_line_limit(program: &Program, edits: Vec<TextEdit>) -> Vec<TextEdit> {
    let Some(limit) = line_limit(program) else {
        return edits;
    };
    let text = &program.text;
    let line_of = |at: usize| -> (usize, usize) {
        let start = text[..at.min(text.len())]
            .iter()
            .rposition(|c| *c == b'\n' || *c == b'\r')
            .map_or(0, |i| i + 1);
        let end = text[at.min(text.len())..]
            .iter()
            .position(|c| *c == b'\n' || *c == b'\r')
            .map_or(text.len(), |i| at + i);
        (start, end)
    };
    let mut out = Vec::with_capacity(edits.len());
    let mut i = 0;
    while i < edits.len() {
        let (start, end) = line_of(edits[i].span.start as usize);
        let mut j = i;
        let mut growth: i64 = 0;
        while j < edits.len() && (edits[j].span.start as usize) <= end {
            growth += edits[j].new_text.len() as i64 - edits[j].span.len() as i64;
            j += 1;
        }
        let chars = text[start..end]
            .iter()
            .filter(|b| (**b & 0xC0) != 0x80)
            .count() as i64;
        if growth <= 0 || chars + growth <= limit as i64 {
            out.extend(edits[i..j].iter().cloned());
        }
        i = j;
    }
    out
}

/// The edits that format `program`, or why the options cannot be applied
/// without changing what it does.
pub fn format_edits(program: &Program, opts: &FormatOptions) -> Result<Vec<TextEdit>, String> {
    let d = program.dialect;
    let mut edits: Vec<TextEdit> = Vec::new();
    // Jump targets: literal `GOTO n`, and whether any jump is computed.
    let mut targets: HashMap<u32, Vec<Span>> = HashMap::new();
    let mut computed = false;
    let mut m99_return = false;
    for b in &program.blocks {
        let mut occ: Vec<Occ> = Vec::new();
        block_occurrences(program, b, &mut occ);
        for o in occ {
            if let (Sym::Seq(n), false) = (&o.sym, o.def) {
                targets.entry(*n).or_default().push(o.span);
            }
        }
        for i in program.items_of(b) {
            if let ItemKind::Macro(MacroStmt::Goto { .. } | MacroStmt::IfGoto { .. }) = i.kind {
                computed = true;
            }
        }
        let m99 = program
            .words(b)
            .any(|(_, w)| w.letter == b'M' && w.num().is_some_and(|n| n.value == 99.0));
        m99_return |= m99 && program.words(b).any(|(_, w)| w.letter == b'P');
    }
    let literal_jumps: usize = targets.values().map(Vec::len).sum();
    let jumps = program.items.iter().filter(|i| {
        matches!(
            i.kind,
            ItemKind::Macro(MacroStmt::Goto { .. } | MacroStmt::IfGoto { .. })
        )
    });
    computed = computed && jumps.count() > literal_jumps;
    if opts.numbers != Numbers::Keep && d != Dialect::Rs274ngc {
        if computed {
            return Err("a GOTO with a computed target jumps to block numbers this formatting would change; block numbers are left as they are".into());
        }
        if m99_return && !matches!(opts.numbers, Numbers::Remove) {
            return Err("an M99 P returns to a block number of the calling program; block numbers are left as they are".into());
        }
    }
    // Block numbers first; `renumbered` maps old target numbers to new ones.
    let mut renumbered: HashMap<u32, u32> = HashMap::new();
    let mut next = match opts.numbers {
        Numbers::Renumber { start, .. } | Numbers::Add { start, .. } => u64::from(start),
        _ => 0,
    };
    let step = match opts.numbers {
        Numbers::Renumber { step, .. } | Numbers::Add { step, .. } => u64::from(step.max(1)),
        _ => 1,
    };
    // RS274/NGC reads block numbers as labels only; the others jump to them.
    let jumps_read_numbers = d != Dialect::Rs274ngc;
    let mut seen_targets: HashMap<u32, usize> = HashMap::new();
    for b in program.blocks.iter().filter(|b| numberable(program, b)) {
        let items = program.items_of(b);
        let first = items
            .iter()
            .find(|i| !matches!(i.kind, ItemKind::Comment(_)));
        let n_word = first.and_then(|i| match i.kind {
            ItemKind::Word(w) if w.letter == b'N' && !w.comma => Some((i, w)),
            _ => None,
        });
        let old = n_word.and_then(|(_, w)| match w.value {
            WordValue::Num(n) if n.value >= 0.0 && n.value.fract() == 0.0 && n.value < 1e9 => {
                Some(n.value as u32)
            }
            _ => None,
        });
        if n_word.is_some() && old.is_none() && opts.numbers != Numbers::Keep {
            return Err("a block number that is not a whole number cannot be renumbered".into());
        }
        if let Some(o) = old.filter(|o| u64::from(*o) > max_number(d)) {
            if opts.numbers != Numbers::Keep {
                return Err(format!(
                    "N{o} is longer than this control reads (P007); fix it before renumbering"
                ));
            }
        }
        let is_target = old.is_some_and(|n| jumps_read_numbers && targets.contains_key(&n));
        match opts.numbers {
            Numbers::Keep => {}
            Numbers::Remove => {
                if let (Some((i, _)), false) = (n_word, is_target) {
                    let mut end = i.span.end as usize;
                    while program.text.get(end).copied().is_some_and(blank) {
                        end += 1;
                    }
                    edits.push(TextEdit {
                        span: Span::new(i.span.start, end as u32),
                        new_text: String::new(),
                    });
                }
            }
            Numbers::Renumber { .. } | Numbers::Add { .. } => {
                let add = matches!(opts.numbers, Numbers::Add { .. });
                if n_word.is_none() && !add {
                    continue;
                }
                if next > max_number(d) {
                    return Err(format!(
                        "block numbers would pass N{}, the largest this control reads",
                        max_number(d)
                    ));
                }
                let new = next as u32;
                next += step;
                if let Some(o) = old.filter(|_| is_target) {
                    // The same number twice: a jump's destination is ambiguous.
                    if seen_targets.insert(o, 1).is_some() {
                        return Err(format!("N{o} is a GOTO target on more than one block; block numbers are left as they are"));
                    }
                    renumbered.insert(o, new);
                }
                match n_word {
                    Some((i, _)) => edits.push(TextEdit {
                        span: i.span,
                        new_text: format!("N{new}"),
                    }),
                    None => {
                        let at = first.map_or(b.span.start, |i| i.span.start);
                        edits.push(TextEdit {
                            span: Span::new(at, at),
                            new_text: format!("N{new} "),
                        });
                    }
                }
            }
        }
    }
    if matches!(opts.numbers, Numbers::Renumber { .. } | Numbers::Add { .. }) {
        for (old, spans) in &targets {
            if !jumps_read_numbers {
                break;
            }
            // A jump to a number no block has: the control alarms; keep it so.
            let Some(new) = renumbered.get(old) else {
                continue;
            };
            for s in spans {
                edits.push(TextEdit {
                    span: *s,
                    new_text: new.to_string(),
                });
            }
        }
    }
    // Spacing and case, item by item.
    for b in program
        .blocks
        .iter()
        .filter(|b| b.kind == BlockKind::Normal && !broken(program, b))
    {
        let items = program.items_of(b);
        for (k, item) in items.iter().enumerate() {
            if opts.uppercase && d != Dialect::Servoworks {
                if let ItemKind::Word(w) = item.kind {
                    let at = w.letter_span(item.span);
                    let byte = program.text.get(at.start as usize).copied();
                    // An upper-case FANUC `O` may start a program head.
                    let safe = !(d == Dialect::Fanuc && w.letter == b'O');
                    if let Some(c) = byte.filter(|c| c.is_ascii_lowercase() && safe) {
                        edits.push(TextEdit {
                            span: Span::new(at.start, at.start + 1),
                            new_text: (c.to_ascii_uppercase() as char).to_string(),
                        });
                    }
                }
            }
            if opts.spacing == Spacing::Keep {
                continue;
            }
            let gap_start = item.span.end;
            let gap_end = items.get(k + 1).map_or(b.span.end, |n| n.span.start);
            if gap_end < gap_start {
                continue;
            }
            let gap = program.slice(Span::new(gap_start, gap_end));
            if !gap.iter().all(|c| blank(*c)) {
                continue;
            }
            let next = items.get(k + 1);
            let want = match (next, opts.spacing) {
                // No blank at the end of the block.
                (None, _) => "",
                (Some(_), Spacing::One) => " ",
                (Some(n), _) => {
                    let words = matches!(item.kind, ItemKind::Word(_))
                        && matches!(n.kind, ItemKind::Word(_));
                    // A name runs on into the next letter (`M98 PMoveXY X1`).
                    let named = matches!(item.kind, ItemKind::Word(w) if matches!(w.value, WordValue::Name(_)));
                    if words && !named {
                        ""
                    } else {
                        " "
                    }
                }
            };
            // A block without its last blanks keeps its terminator: nothing to
            // do when the line ends in a comment or has no blanks.
            if gap != want.as_bytes() && !(next.is_none() && gap.is_empty()) {
                edits.push(TextEdit {
                    span: Span::new(gap_start, gap_end),
                    new_text: want.into(),
                });
            }
        }
    }
    edits.sort_by_key(|e| (e.span.start, e.span.end));
    let edits = within_line_limit(program, edits);
    // A block number's edit and the blank after it may meet; keep the first.
    let mut out: Vec<TextEdit> = Vec::with_capacity(edits.len());
    for e in edits {
        if out
            .last()
            .is_some_and(|l: &TextEdit| e.span.start < l.span.end)
        {
            continue;
        }
        out.push(e);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::{parse, ParseOptions};

    fn fmt(d: Dialect, text: &str, opts: FormatOptions) -> Result<String, String> {
        let p = parse(
            ParseOptions {
                dialect: d,
                variant: d.default_variant(),
            },
            text.as_bytes().to_vec(),
        );
        let edits = format_edits(&p, &opts)?;
        Ok(String::from_utf8(crate::fixes::apply_edits(text.as_bytes(), &edits)).unwrap())
    }

    #[test]
    fn renumbers_spaces_and_upper_cases() {
        let opts = FormatOptions {
            numbers: Numbers::Add {
                start: 10,
                step: 10,
            },
            spacing: Spacing::One,
            uppercase: true,
        };
        assert_eq!(
            fmt(
                Dialect::Rs274ngc,
                "g0   x1 (keep  this)\nN5 g1x2  f100  \n(only a comment)\nM2\n",
                opts
            ),
            Ok("N10 G0 X1 (keep  this)\nN20 G1 X2 F100\n(only a comment)\nN30 M2\n".into())
        );
        let none = FormatOptions {
            spacing: Spacing::None,
            ..Default::default()
        };
        assert_eq!(
            fmt(Dialect::Servoworks, "M98 PMoveXY X1\nG1 X1 Y2 (c)\n", none),
            Ok("M98PMoveXY X1\nG1X1Y2 (c)\n".into())
        );
    }

    #[test]
    fn goto_targets_follow_their_blocks() {
        let text = "O1000;\nN1 #1=0;\nN2 #1=#1+1;\nIF [#1 LT 3] GOTO 2;\nN3 GOTO 1;\nM30;\n";
        let renumber = FormatOptions {
            numbers: Numbers::Renumber {
                start: 100,
                step: 5,
            },
            ..Default::default()
        };
        assert_eq!(
            fmt(Dialect::Fanuc, text, renumber),
            Ok(
                "O1000;\nN100 #1=0;\nN105 #1=#1+1;\nIF [#1 LT 3] GOTO 105;\nN110 GOTO 100;\nM30;\n"
                    .into()
            )
        );
        let remove = FormatOptions {
            numbers: Numbers::Remove,
            ..Default::default()
        };
        assert_eq!(
            fmt(Dialect::Fanuc, text, remove),
            Ok("O1000;\nN1 #1=0;\nN2 #1=#1+1;\nIF [#1 LT 3] GOTO 2;\nGOTO 1;\nM30;\n".into())
        );
        assert!(fmt(Dialect::Fanuc, "N1 GOTO #5;\nM30;\n", renumber).is_err());
    }
}
