//! P002: FANUC Custom Macro B `WHILE … DO m` / `END m` pairing.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::{Expr, ExprId, ItemKind, MacroStmt, Program};

use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks Custom Macro B loops: each `WHILE […] DO m` (or bare `DO m`) needs an
    /// `END m` with the same identifier, `m` is 1, 2 or 3, loops nest at most three deep,
    /// an identifier is not reused by a loop nested in a loop that already uses it, and
    /// loop ranges do not cross (`DO 1 … DO 2 … END 1 … END 2`).
    ///
    /// ## Why is this bad?
    /// The control pairs `DO m` with `END m` by the identifier: a missing `END` raises
    /// PS0124, a wrong identifier, crossing ranges or a fourth level raise PS0126.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = 0;
    /// WHILE [#1 LT 3] DO 1;
    /// #1 = #1 + 1;
    /// END 2;
    /// M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = 0;
    /// WHILE [#1 LT 3] DO 1;
    /// #1 = #1 + 1;
    /// END 1;
    /// M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// FANUC, error. Each `O` program of a file is checked separately.
    ///
    /// Reported by this rule, not F007, when both see an END without its DO on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN121, FAN122, FAN123
    pub static MACRO_LOOP_STRUCTURE = {
        code: "P002",
        name: "macro-loop-structure",
        summary: "WHILE/DO and END that do not pair",
        implements: &["FAN121", "FAN122", "FAN123"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct MacroLoopStructure;

/// The literal value of an expression, looking through brackets.
pub(super) fn literal(p: &Program, id: ExprId) -> Option<f64> {
    match p.expr(id).expr {
        Expr::Num(n) => Some(n.value),
        Expr::Group { inner } => literal(p, inner),
        Expr::Neg { arg } => literal(p, arg).map(|v| -v),
        _ => None,
    }
}

struct Frame {
    m: Option<f64>,
    span: Span,
    block: usize,
}

/// Walks the loops of a FANUC program. Returns the closed loop ranges (block
/// indices of the `DO` and the `END`) and, when `out` is given, reports errors.
pub(super) fn loops(
    p: &Program,
    segs: &[super::Seg],
    mut out: Option<&mut Vec<Diagnostic>>,
) -> Vec<(usize, usize)> {
    let mut ranges = Vec::new();
    let mut stack: Vec<Frame> = Vec::new();
    let mut report = |d: Diagnostic| {
        if let Some(o) = out.as_deref_mut() {
            o.push(d);
        }
    };
    let unclosed = |stack: &mut Vec<Frame>, report: &mut dyn FnMut(Diagnostic)| {
        for f in stack.drain(..) {
            let m = f.m.map(|m| format!("{m}")).unwrap_or_else(|| "m".into());
            report(MACRO_LOOP_STRUCTURE.error(
                f.span,
                format!("DO {m} has no matching END {m} in this program (alarm PS0124). Add `END {m}` after the loop body."),
            ));
        }
    };
    // Plain blocks hold words only, which no arm below matches: their runs are skipped.
    for seg in segs.iter().filter(|s| !s.plain) {
        let bi = seg.first;
        let Some(block) = p.blocks.get(bi) else {
            break;
        };
        for item in p.items_of(block) {
            match item.kind {
                ItemKind::ProgramHead { .. } => unclosed(&mut stack, &mut report),
                ItemKind::Macro(MacroStmt::While { m, .. })
                | ItemKind::Macro(MacroStmt::Do { m }) => {
                    // A malformed statement was reported by the parser; do not pair it.
                    if matches!(p.expr(m).expr, Expr::Error) {
                        continue;
                    }
                    let mv = literal(p, m);
                    if let Some(v) = mv {
                        if !(v == 1.0 || v == 2.0 || v == 3.0) {
                            report(MACRO_LOOP_STRUCTURE.error(
                                item.span,
                                format!(
                                    "DO {v}: the loop identifier must be 1, 2 or 3 (alarm PS0126)."
                                ),
                            ));
                        }
                        if let Some(outer) = stack.iter().find(|f| f.m == Some(v)) {
                            report(
                                MACRO_LOOP_STRUCTURE.error(
                                    item.span,
                                    format!("DO {v} inside a loop that already uses identifier {v}: the END would close the wrong loop (alarm PS0126). Use another identifier for the inner loop."),
                                )
                                .with_related(outer.span, "outer loop"),
                            );
                        }
                    }
                    if stack.len() >= 3 {
                        report(MACRO_LOOP_STRUCTURE.error(
                            item.span,
                            "Fourth nested DO loop: Custom Macro B nests loops at most three deep (alarm PS0126). Move the inner loop into a macro called with G65.",
                        ));
                    }
                    stack.push(Frame {
                        m: mv,
                        span: item.span,
                        block: bi,
                    });
                }
                ItemKind::Macro(MacroStmt::End { m }) => {
                    let mv = literal(p, m);
                    let top_matches = stack
                        .last()
                        .is_some_and(|t| t.m.is_none() || mv.is_none() || t.m == mv);
                    if top_matches {
                        if let Some(f) = stack.pop() {
                            ranges.push((f.block, bi));
                        }
                    } else if let Some(i) = stack.iter().rposition(|f| f.m == mv) {
                        let crossed = &stack[i + 1..];
                        if let Some(inner) = crossed.last() {
                            report(
                                MACRO_LOOP_STRUCTURE.error(
                                    item.span,
                                    format!(
                                        "END {} closes its loop while DO {} inside it is still open: loop ranges must not cross (alarm PS0126). Close the inner loop first.",
                                        mv.unwrap_or(0.0),
                                        inner.m.unwrap_or(0.0)
                                    ),
                                )
                                .with_related(inner.span, "inner loop"),
                            );
                        }
                        let f = stack.remove(i);
                        ranges.push((f.block, bi));
                    } else {
                        let m = mv.map(|v| format!("{v}")).unwrap_or_else(|| "m".into());
                        report(MACRO_LOOP_STRUCTURE.error(
                            item.span,
                            format!("END {m} without an open DO {m} (alarm PS0126). Remove it, or fix the identifier."),
                        ));
                    }
                }
                _ => {}
            }
        }
    }
    unclosed(&mut stack, &mut report);
    ranges
}

impl Rule for MacroLoopStructure {
    fn meta(&self) -> &'static RuleMeta {
        &MACRO_LOOP_STRUCTURE
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect == Dialect::Fanuc {
            loops(cx.program, cx.segments(), Some(out));
        }
    }
}
