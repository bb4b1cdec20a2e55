//! P005: a program that does not end properly.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::{BlockKind, ItemKind, Program};

use super::macro_loop_structure::literal;
use super::util::{append_block_edit, fanuc_call_start, has_code_items, lit};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks that a main program ends: with `M2`/`M30` (RS274/NGC, unless the file is
    /// wrapped in `%` lines), with `M02`/`M30` (ServoWorks main programs), or with
    /// `M02`/`M30`/`M99` (FANUC). An RS274/NGC file that opens with `%` needs its closing
    /// `%` unless it reaches `M2`/`M30` first, a ServoWorks file must end with a `%` line or a line break, and a FANUC file
    /// starts with `%` and an `O` number.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops with `File ended with no percent sign or program end` (or `File ended
    /// with no percent sign` when the opening `%` has no partner). A ServoWorks or FANUC
    /// program without an end code does not reset the modal state, and the last line of a
    /// ServoWorks file without a line break may not be read at all.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X1
    /// G1 X2 F100
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X1
    /// G1 X2 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error (files that only define subroutines are exempt). ServoWorks and
    /// FANUC: warning; files that contain `M99` are subprograms and need no `M30`.
    ///
    /// Reported by this rule, not F006, when both see a program without an end on the same text (one diagnostic per fault).
    ///
    /// Reported by L011, not this rule, when both see a closing `%` without an opening one, read as the missing end on the same text (one diagnostic per fault).
    ///
    /// Implements: SW011, SW019, NGC024, NGC025, FAN010, FAN012
    pub static PROGRAM_END = {
        code: "P005",
        name: "missing-program-end",
        summary: "Program without an end code",
        implements: &["SW011", "SW019", "NGC024", "NGC025", "FAN010", "FAN012"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ProgramEnd;

/// Whether the block holds one of the M codes (whole numbers).
/// ServoWorks runs only the first M word of a block (W001), so only that one counts there.
fn has_m(p: &Program, b: &crate::syntax::Block, ms: &[f64]) -> bool {
    let mut m_words = p.words(b).filter(|(_, w)| w.letter == b'M' && !w.comma);
    let is_end = |(_, w): (&crate::syntax::Item, &crate::syntax::Word)| {
        lit(w).is_some_and(|v| ms.contains(&v))
    };
    if p.dialect == Dialect::Servoworks {
        return m_words.next().is_some_and(is_end);
    }
    m_words.any(is_end)
}

/// Whether a FANUC program's last code block hands the end to something else:
/// a macro alarm (`#3000 = n` stops the program) or a call (`M98 P…`, `G65 P…`),
/// whose program may well end with M30 itself; the file alone cannot tell.
fn ends_elsewhere(p: &Program) -> bool {
    use crate::syntax::Expr;
    let Some(last) = p.blocks.iter().rev().find(|b| has_code_items(p, b)) else {
        return false;
    };
    let items = p.items_of(last);
    let alarm = items.iter().any(|i| match i.kind {
        ItemKind::Assign { target, .. } => {
            matches!(p.expr(target).expr, Expr::Var { index } if literal(p, index) == Some(3000.0))
        }
        _ => false,
    });
    alarm || has_m(p, last, &[98.0]) || fanuc_call_start(p, last).is_some()
}

/// The file's own line break.
fn line_break(p: &Program) -> &'static str {
    if p.text.windows(2).any(|w| w == b"\r\n") {
        "\r\n"
    } else {
        "\n"
    }
}

/// A line `text` added at the end of the file.
fn eof_line(p: &Program, text: &str) -> TextEdit {
    let n = p.text.len() as u32;
    let nl = line_break(p);
    let lead = if matches!(p.text.last(), None | Some(b'\n')) {
        ""
    } else {
        nl
    };
    TextEdit {
        span: Span::new(n, n),
        new_text: format!("{lead}{text}{nl}"),
    }
}

fn end_span(p: &Program) -> Span {
    let n = p.text.len() as u32;
    let start = p
        .blocks
        .iter()
        .rev()
        .find(|b| has_code_items(p, b))
        .map(|b| b.span.start)
        .unwrap_or(0);
    Span::new(start, n.max(start))
}

impl Rule for ProgramEnd {
    fn meta(&self) -> &'static RuleMeta {
        &PROGRAM_END
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        // A run of plain blocks counts once: they are all code blocks at the
        // same O-word depth, and none holds an M code or is a `%` line.
        let firsts = || cx.segments().iter().filter_map(|s| p.blocks.get(s.first));
        let code_blocks: Vec<_> = firsts()
            .filter(|b| b.kind == BlockKind::Normal && has_code_items(p, b))
            .collect();
        if code_blocks.is_empty() {
            return;
        }
        let ends = |ms: &[f64]| cx.non_plain_blocks().any(|b| has_m(p, b, ms));
        match p.dialect {
            Dialect::Rs274ngc => {
                let first = firsts().find(|b| {
                    b.kind != BlockKind::Normal || has_code_items(p, b) || !p.items_of(b).is_empty()
                });
                let opens_with_percent = first.is_some_and(|b| b.kind == BlockKind::Percent);
                if opens_with_percent {
                    let percents = cx
                        .non_plain_blocks()
                        .filter(|b| b.kind == BlockKind::Percent)
                        .count();
                    // Reading stops at M2/M30 too, so the closing `%` is not needed after one.
                    if percents < 2 && !ends(&[2.0, 30.0]) {
                        out.push(PROGRAM_END.error(
                            end_span(p),
                            "File ended with no percent sign: the file opens with `%`, so it must end with a second `%` line. Add it after the last line.",
                        ).with_fix("Add the closing `%` line", vec![eof_line(p, "%")]));
                    }
                    return;
                }
                // A file that only defines subroutines is a library called by others.
                let top_level_code = !p.is_ngc_library_named(cx.settings.file_stem.as_deref());
                if top_level_code && !ends(&[2.0, 30.0]) {
                    out.push(PROGRAM_END.error(
                        end_span(p),
                        "File ended with no percent sign or program end: add M2 (or M30) after the last line, or wrap the program in `%` lines.",
                    ).with_fix("Add M2 after the last line", vec![append_block_edit(p, "M2")]));
                }
            }
            Dialect::Servoworks => {
                let last_byte = p.text.last().copied();
                let last_is_percent = p
                    .blocks
                    .iter()
                    .rev()
                    .find(|b| b.kind != BlockKind::Normal || !p.items_of(b).is_empty())
                    .is_some_and(|b| b.kind == BlockKind::Percent);
                if !matches!(last_byte, Some(b'\n') | Some(b'\r')) && !last_is_percent {
                    let n = p.text.len() as u32;
                    out.push(PROGRAM_END.warning(
                        Span::new(n.saturating_sub(1), n),
                        "The file must end with a `%` line or a line break; the last block may not be read. Add a line break at the end.",
                    ).with_fix("Add a line break at the end", vec![TextEdit { span: Span::new(n, n), new_text: line_break(p).into() }]));
                }
                if !ends(&[2.0, 30.0, 99.0]) {
                    out.push(PROGRAM_END.warning(
                        end_span(p),
                        "The main program does not end with M02 or M30, so the control does not reset at the end. Add M30 (or M02) as the last block; subprograms end with M99.",
                    )
                    .with_fix("Add M30 as the last block", vec![append_block_edit(p, "M30")])
                    .with_fix("Add M99 as the last block (a subprogram)", vec![append_block_edit(p, "M99")]));
                }
            }
            Dialect::Fanuc => {
                // Comment lines before the first `%` are tape leader, which the
                // control skips (a `(partscope: dialect=fanuc)` line, a title).
                let opens_with_percent = p
                    .blocks
                    .iter()
                    .find(|b| b.kind != BlockKind::Normal || has_code_items(p, b))
                    .is_some_and(|b| b.kind == BlockKind::Percent);
                let has_head = p
                    .items
                    .iter()
                    .any(|i| matches!(i.kind, ItemKind::ProgramHead { .. }));
                if !opens_with_percent || !has_head {
                    let what = match (opens_with_percent, has_head) {
                        (false, false) => "does not start with a `%` line and has no O number",
                        (false, true) => "does not start with a `%` line",
                        _ => "has no O program number",
                    };
                    let start = code_blocks.first().map(|b| b.span).unwrap_or_default();
                    out.push(PROGRAM_END.warning(
                        start,
                        format!("The file {what}: a FANUC program is stored as `%`, `O1234;`, blocks, end code, `%`. Text between the first `%` and the first end of block is skipped as the leader."),
                    ));
                }
                if !ends(&[2.0, 30.0, 99.0]) && !ends_elsewhere(p) {
                    out.push(PROGRAM_END.warning(
                        end_span(p),
                        "The program does not end with M02, M30 or M99 before the closing `%`. Add M30 (main program) or M99 (subprogram) as the last block.",
                    )
                    .with_fix("Add M30 as the last block", vec![append_block_edit(p, "M30")])
                    .with_fix("Add M99 as the last block (a subprogram)", vec![append_block_edit(p, "M99")]));
                }
            }
        }
    }
}
