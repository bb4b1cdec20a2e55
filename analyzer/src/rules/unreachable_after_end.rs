//! P006: blocks after the program end that never run.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;
use crate::syntax::{BlockKind, ItemKind, MacroStmt, OKeyword};

use super::macro_loop_structure::literal;
use super::util::{fanuc_call_start, has_code_items, lit};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags blocks after `M2`/`M30` that can never run: the rest of the main program
    /// up to the end of the file, the next `O` program head (ServoWorks, FANUC) or the next
    /// subroutine definition (RS274/NGC).
    ///
    /// ## Why is this bad?
    /// The control stops reading at the program end, so the code after it is dead. It
    /// usually means a misplaced `M30`, or blocks that were meant to be a subprogram.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X0
    /// M2
    /// G0 X10
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X0
    /// G0 X10
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks: warning; FANUC: info (shops start blocks after M30 from the cursor or by a sequence-number search, one entry point per tool); RS274/NGC: info (LinuxCNC never reads past M2, harmlessly). FANUC blocks whose sequence number is a `GOTO` target are reachable.
    ///
    /// Reported by this rule, not F005, when both see code after M2/M30 on the same text (one diagnostic per fault).
    ///
    /// Implements: SW018, NGC026, FAN013
    pub static UNREACHABLE_AFTER_END = {
        code: "P006",
        name: "unreachable-after-end",
        summary: "Blocks after M2/M30 that never run",
        implements: &["SW018", "NGC026", "FAN013"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct UnreachableAfterEnd;

impl Rule for UnreachableAfterEnd {
    fn meta(&self) -> &'static RuleMeta {
        &UNREACHABLE_AFTER_END
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        let d = p.dialect;
        let mut targets: Vec<f64> = Vec::new();
        if d == Dialect::Fanuc {
            let mut goto_targets = |items: &[crate::syntax::Item]| {
                for item in items {
                    if let ItemKind::Macro(
                        MacroStmt::Goto { target } | MacroStmt::IfGoto { target, .. },
                    ) = item.kind
                    {
                        targets.extend(literal(p, target));
                    }
                }
            };
            // Plain blocks hold words only, so the items of their runs are skipped;
            // every other item, inside a block or not, is read in order.
            let mut next = 0usize;
            for seg in cx.segments() {
                let (Some(b), Some(last)) = (p.blocks.get(seg.first), p.blocks.get(seg.last()))
                else {
                    break;
                };
                let (start, end) = (b.items.0 as usize, last.items.1 as usize);
                goto_targets(p.items.get(next..start).unwrap_or(&[]));
                if !seg.plain {
                    goto_targets(p.items.get(start..end).unwrap_or(&[]));
                }
                next = next.max(end);
            }
            goto_targets(p.items.get(next..).unwrap_or(&[]));
        }
        if d == Dialect::Rs274ngc {
            // LinuxCNC stops reading at an unconditional top-level end; `dead_blocks`
            // knows which lines that leaves out (the same set the block rules skip).
            let dead = super::util::dead_blocks_in(p, cx.segments());
            let mut run: Option<(crate::span::Span, usize)> = None;
            let mut end = "M2";
            for seg in cx.segments() {
                let i = seg.first;
                let (Some(b), Some(last)) = (p.blocks.get(i), p.blocks.get(seg.last())) else {
                    break;
                };
                if seg.plain {
                    // A run of plain blocks is all dead or all live, holds
                    // code and no M word.
                    if !dead.get(i).copied().unwrap_or(false) {
                        if let Some((span, n)) = run.take() {
                            out.push(unreachable(span, n, end, Severity::Info));
                        }
                        continue;
                    }
                    let span = b.span.cover(last.span);
                    let k = cx.blocks_in(seg);
                    run = Some(match run {
                        Some((s, n)) => (s.cover(span), n + k),
                        None => (span, k),
                    });
                    continue;
                }
                if !dead.get(i).copied().unwrap_or(false) {
                    if let Some(e) = p.words(b).find_map(|(_, w)| match lit(w) {
                        Some(v) if w.letter == b'M' && v == 30.0 => Some("M30"),
                        Some(v) if w.letter == b'M' && v == 2.0 => Some("M2"),
                        _ => None,
                    }) {
                        end = e;
                    }
                    if let Some((span, n)) = run.take() {
                        out.push(unreachable(span, n, end, Severity::Info));
                    }
                    continue;
                }
                if b.kind == BlockKind::Normal && has_code_items(p, b) {
                    let k = cx.blocks_in(seg);
                    run = Some(match run {
                        Some((s, n)) => (s.cover(b.span), n + k),
                        None => (b.span, k),
                    });
                }
            }
            if let Some((span, n)) = run {
                out.push(unreachable(span, n, end, Severity::Info));
            }
            return;
        }
        let mut ended: Option<&'static str> = None;
        let mut sub_depth = 0i32;
        let mut run: Option<(crate::span::Span, usize)> = None;
        // FANUC shops start blocks after M30 from the cursor or by a sequence-number
        // search (one entry point per tool): information there.
        let sev = if d == Dialect::Fanuc {
            Severity::Info
        } else {
            Severity::Warning
        };
        let flush =
            |run: &mut Option<(crate::span::Span, usize)>, end: &str, out: &mut Vec<Diagnostic>| {
                if let Some((span, n)) = run.take() {
                    out.push(unreachable(span, n, end, sev));
                }
            };
        for seg in cx.segments() {
            let (Some(b), Some(last)) = (p.blocks.get(seg.first), p.blocks.get(seg.last())) else {
                break;
            };
            if seg.plain {
                // A run of plain blocks (words only: no program head, N, O or M
                // word) starts no scope and ends no program; after an end it is
                // dead as a whole.
                if ended.is_some() {
                    let span = b.span.cover(last.span);
                    let n = cx.blocks_in(seg);
                    run = Some(match run {
                        Some((s, k)) => (s.cover(span), k + n),
                        None => (span, n),
                    });
                }
                continue;
            }
            if b.kind != BlockKind::Normal || !has_code_items(p, b) {
                continue;
            }
            let items = p.items_of(b);
            let head = items
                .iter()
                .any(|i| matches!(i.kind, ItemKind::ProgramHead { .. }));
            let okw = items.iter().find_map(|i| match i.kind {
                ItemKind::OWord(o) => o.keyword,
                _ => None,
            });
            let fanuc_head = items
                .iter()
                .any(|i| matches!(i.kind, ItemKind::OWord(o) if o.keyword.is_none()));
            let target = p
                .words(b)
                .any(|(_, w)| w.letter == b'N' && lit(w).is_some_and(|v| targets.contains(&v)));
            let starts_scope = match d {
                // A Fanuc-style `O…` program head (no keyword) starts an M98 subprogram.
                Dialect::Rs274ngc => okw == Some(OKeyword::Sub) || sub_depth > 0 || fanuc_head,
                _ => head || target,
            };
            match okw {
                Some(OKeyword::Sub) => sub_depth += 1,
                Some(OKeyword::Endsub) => sub_depth -= 1,
                _ => {}
            }
            if let Some(end) = ended {
                if starts_scope {
                    flush(&mut run, end, out);
                    ended = None;
                } else {
                    let k = cx.blocks_in(seg);
                    run = Some(match run {
                        Some((s, n)) => (s.cover(b.span), n + k),
                        None => (b.span, k),
                    });
                    continue;
                }
            }
            if d == Dialect::Rs274ngc && sub_depth > 0 {
                continue;
            }
            let call = fanuc_call_start(p, b);
            let mut m_words = 0;
            for (i, w) in p.words(b) {
                // A FANUC macro call's `M2.0` is argument #13, not an end code.
                if call.is_some_and(|c| i.span.start > c) {
                    continue;
                }
                if w.letter == b'M' && !w.comma {
                    m_words += 1;
                    // ServoWorks runs only the first M word of a block (W001).
                    if d == Dialect::Servoworks && m_words > 1 {
                        continue;
                    }
                    let v = lit(w);
                    if v == Some(2.0) {
                        ended = Some(if d == Dialect::Rs274ngc { "M2" } else { "M02" });
                    } else if v == Some(30.0) {
                        ended = Some("M30");
                    }
                }
            }
        }
        if let Some(end) = ended {
            flush(&mut run, end, out);
        }
    }
}

/// The P006 report for `n` dead blocks after `end`. RS274/NGC gives it as info
/// (spec NGC026: LinuxCNC never reads past M2, so nothing there can go wrong);
/// ServoWorks and FANUC as a warning (SW018, FAN013).
fn unreachable(span: crate::span::Span, n: usize, end: &str, severity: Severity) -> Diagnostic {
    let what = if n == 1 {
        "This block is never executed: it follows".to_string()
    } else {
        format!("These {n} blocks are never executed: they follow")
    };
    UNREACHABLE_AFTER_END.diagnostic(
        severity,
        span,
        format!("{what} {end}, and the control stops reading at the program end. Move the end code, or remove the dead code."),
    )
}

#[cfg(test)]
mod tests {
    use crate::{analyze, Dialect, Settings};

    /// The P006 reports of `text`: (covered text, message start).
    fn p006(dialect: Dialect, text: &str) -> Vec<(String, String)> {
        let a = analyze(text.as_bytes().to_vec(), &Settings::new(dialect));
        a.diagnostics
            .iter()
            .filter(|d| d.code == "P006")
            .map(|d| {
                let covered = text[d.span.start as usize..d.span.end as usize].to_string();
                let head = d.message.split(':').next().unwrap_or("").to_string();
                (covered, head)
            })
            .collect()
    }

    /// Runs of plain blocks after the end are counted block by block, as one
    /// report over all of them.
    #[test]
    fn plain_runs_after_the_end_count_every_block() {
        assert_eq!(
            p006(
                Dialect::Servoworks,
                "G00 X0\nM30\nG01 X1 F100\nX2\nX3 Y4\n(note)\nG00 X10.0\n"
            ),
            vec![(
                "G01 X1 F100\nX2\nX3 Y4\n(note)\nG00 X10.0".to_string(),
                "These 4 blocks are never executed".to_string()
            )]
        );
    }

    /// A GOTO target after the end starts a live scope, and the plain run
    /// before it is reported up to its last block.
    #[test]
    fn a_goto_target_ends_the_dead_run() {
        assert_eq!(
            p006(
                Dialect::Fanuc,
                "O1000\n#1=1\nGOTO 20\nM30\nX1.\nX2.\nX3. Z1.\nN20 X3.\nM30\n"
            ),
            vec![(
                "X1.\nX2.\nX3. Z1.".to_string(),
                "These 3 blocks are never executed".to_string()
            )]
        );
    }
}
