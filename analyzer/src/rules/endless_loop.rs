//! P009: loops whose condition can never become false.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{Expr, ExprId, ItemKind, MacroStmt, OKeyword, Program};

use super::macro_loop_structure::literal;
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags loops that never end by their condition: a FANUC `DO m` without `WHILE`, or a
    /// `WHILE` whose condition is a non-zero constant; an RS274/NGC `while`/`do … while`
    /// with a constant true condition and no `break` inside.
    ///
    /// ## Why is this bad?
    /// Such a loop only ends through a branch out of it (FANUC `GOTO`, LinuxCNC `break`,
    /// `return`) or an alarm. Without one the program runs forever.
    ///
    /// ## Example
    /// ```ngc
    /// o100 while [1]
    /// G0 X1
    /// o100 endwhile
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #1 = 0
    /// o100 while [#1 LT 3]
    /// #1 = [#1 + 1]
    /// o100 endwhile
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC and FANUC, warning. A FANUC loop with a `GOTO` inside is not flagged.
    ///
    /// Implements: NGC615, FAN145
    pub static ENDLESS_LOOP = {
        code: "P009",
        name: "endless-loop",
        summary: "Loop whose condition never becomes false",
        implements: &["NGC615", "FAN145"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct EndlessLoop;

fn constant_true(p: &Program, cond: ExprId) -> bool {
    let mut e = cond;
    while let Expr::Group { inner } = p.expr(e).expr {
        e = inner;
    }
    literal(p, e).is_some_and(|v| v != 0.0)
}

impl Rule for EndlessLoop {
    fn meta(&self) -> &'static RuleMeta {
        &ENDLESS_LOOP
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        match p.dialect {
            Dialect::Fanuc => {
                let ranges = super::macro_loop_structure::loops(p, cx.segments(), None);
                for (s, e) in ranges {
                    let Some(head) = p.blocks.get(s).and_then(|b| {
                        p.items_of(b).iter().find(|i| {
                            matches!(
                                i.kind,
                                ItemKind::Macro(MacroStmt::While { .. } | MacroStmt::Do { .. })
                            )
                        })
                    }) else {
                        continue;
                    };
                    let endless = match head.kind {
                        ItemKind::Macro(MacroStmt::Do { .. }) => true,
                        ItemKind::Macro(MacroStmt::While { cond, .. }) => constant_true(p, cond),
                        _ => false,
                    };
                    let exits = p.blocks[s..=e.min(p.blocks.len() - 1)].iter().any(|b| {
                        p.items_of(b).iter().any(|i| {
                            matches!(
                                i.kind,
                                ItemKind::Macro(MacroStmt::Goto { .. } | MacroStmt::IfGoto { .. })
                            )
                        })
                    });
                    if endless && !exits {
                        out.push(ENDLESS_LOOP.warning(
                            head.span,
                            "This loop never ends: DO without WHILE (or WHILE with a constant true condition) repeats until a GOTO leaves it, and there is none inside.",
                        ));
                    }
                }
            }
            Dialect::Rs274ngc => {
                // (label, span, constant-true, saw break)
                let mut open: Vec<(u32, crate::span::Span, bool, bool, bool)> = Vec::new();
                // Plain blocks hold no O-word.
                for b in cx.non_plain_blocks() {
                    for item in p.items_of(b) {
                        let ItemKind::OWord(o) = item.kind else {
                            continue;
                        };
                        let crate::syntax::OLabel::Number(l) = o.label else {
                            continue;
                        };
                        let cond = p.expr_list(o.args()).first().copied();
                        match o.keyword {
                            Some(OKeyword::Do) => open.push((l, item.span, false, false, true)),
                            Some(OKeyword::While) => {
                                if let Some(pos) = open.iter().rposition(|f| f.0 == l && f.4) {
                                    let f = open.remove(pos);
                                    if cond.is_some_and(|c| constant_true(p, c)) && !f.3 {
                                        out.push(ENDLESS_LOOP.warning(item.span, "This do … while loop has a constant true condition and no break: it never ends."));
                                    }
                                } else {
                                    open.push((
                                        l,
                                        item.span,
                                        cond.is_some_and(|c| constant_true(p, c)),
                                        false,
                                        false,
                                    ));
                                }
                            }
                            Some(OKeyword::Break) | Some(OKeyword::Return) => {
                                for f in open.iter_mut() {
                                    f.3 = true;
                                }
                            }
                            Some(OKeyword::Endwhile) => {
                                if let Some(pos) = open.iter().rposition(|f| f.0 == l && !f.4) {
                                    let f = open.remove(pos);
                                    if f.2 && !f.3 {
                                        out.push(ENDLESS_LOOP.warning(f.1, "This while loop has a constant true condition and no break: it never ends."));
                                    }
                                }
                            }
                            _ => {}
                        }
                    }
                }
            }
            Dialect::Servoworks => {}
        }
    }
}
