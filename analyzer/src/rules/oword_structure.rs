//! P001: RS274/NGC O-word blocks that do not nest or match.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::{ItemKind, OKeyword, OLabel, OWord, Program};

use super::util::lit;
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks the structure of RS274/NGC O-word flow control: every `sub` has its
    /// `endsub`, `while` its `endwhile`, `do` its closing `while`, `if` its `endif`,
    /// `repeat` its `endrepeat`, with the same label; `else`/`elseif` only inside an
    /// `if`; `break`/`continue` only inside a loop of the same label; `return`/`endsub`
    /// only inside a subroutine; and no subroutine defined inside another.
    ///
    /// ## Why is this bad?
    /// LinuxCNC finds the matching statement by its label when it runs the program. A
    /// missing or mislabelled end makes it search to the end of the file and stop with an
    /// error, sometimes only after part of the program has run.
    ///
    /// ## Example
    /// ```ngc
    /// o101 while [#1 LT 3]
    /// #1 = [#1 + 1]
    /// o102 endwhile
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// o101 while [#1 LT 3]
    /// #1 = [#1 + 1]
    /// o101 endwhile
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, error; a warning for a `while`, `do`, `if` or `repeat` left open with an
    /// M2/M30 after it, which rs274 runs to that end without looking for the closer.
    ///
    /// Reported by this rule, not F007, when both see an O-word statement closing or returning from the wrong block on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC601, NGC602, NGC603, NGC604, NGC605
    pub static OWORD_STRUCTURE = {
        code: "P001",
        name: "oword-structure",
        summary: "O-word blocks that do not nest or match",
        implements: &["NGC601", "NGC602", "NGC603", "NGC604", "NGC605"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct OwordStructure;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Open {
    Sub,
    While,
    Do,
    If { seen_else: bool },
    Repeat,
}

impl Open {
    fn opener(self) -> &'static str {
        match self {
            Open::Sub => "sub",
            Open::While => "while",
            Open::Do => "do",
            Open::If { .. } => "if",
            Open::Repeat => "repeat",
        }
    }

    fn closer(self) -> &'static str {
        match self {
            Open::Sub => "endsub",
            Open::While => "endwhile",
            Open::Do => "while",
            Open::If { .. } => "endif",
            Open::Repeat => "endrepeat",
        }
    }

    fn is_loop(self) -> bool {
        matches!(self, Open::While | Open::Do | Open::Repeat)
    }
}

/// A label as text for comparison (`o100` and `o<name>`, case-insensitive).
fn label_key(p: &Program, ow: &OWord) -> Option<String> {
    match ow.label {
        OLabel::Number(n) => Some(n.to_string()),
        OLabel::Name => Some(p.str_of(ow.name_span()).to_ascii_lowercase()),
        OLabel::Expr(_) | OLabel::Missing => None,
    }
}

fn same(a: &Option<String>, b: &Option<String>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => a == b,
        // A computed label cannot be compared statically; trust it.
        _ => true,
    }
}

struct Frame {
    kind: Open,
    label: Option<String>,
    span: Span,
}

impl Rule for OwordStructure {
    fn meta(&self) -> &'static RuleMeta {
        &OWORD_STRUCTURE
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let mut stack: Vec<Frame> = Vec::new();
        // Plain blocks hold no O-word.
        for block in cx.non_plain_blocks() {
            let items = p.items_of(block);
            let Some(pos) = items
                .iter()
                .position(|i| matches!(i.kind, ItemKind::OWord(_)))
            else {
                continue;
            };
            let ItemKind::OWord(ow) = items[pos].kind else {
                continue;
            };
            let span = items[pos].span;
            let Some(kw) = ow.keyword else { continue };
            let label = label_key(p, &ow);
            let name = format!("o{}", p.str_of(ow.label_span));
            match kw {
                OKeyword::Sub => {
                    if let Some(outer) = stack.iter().find(|f| f.kind == Open::Sub) {
                        out.push(
                            OWORD_STRUCTURE.error(
                                span,
                                "Subroutine defined inside another subroutine: RS274/NGC does not nest definitions. Move this `sub` … `endsub` outside.",
                            )
                            .with_related(outer.span, "enclosing subroutine"),
                        );
                    }
                    stack.push(Frame {
                        kind: Open::Sub,
                        label,
                        span,
                    });
                }
                OKeyword::Endsub => close(
                    &mut stack,
                    |k| k == Open::Sub,
                    "endsub",
                    (&label, &name, span),
                    out,
                ),
                OKeyword::Return => {
                    // LinuxCNC accepts `return` with the label of any block inside the
                    // subroutine (its own examples use the label of an enclosing `if`).
                    if !stack.iter().any(|f| f.kind == Open::Sub) {
                        out.push(OWORD_STRUCTURE.error(
                            span,
                            format!("`{name} return` is not inside a subroutine: return leaves the subroutine that is running."),
                        ));
                    }
                }
                OKeyword::Do => stack.push(Frame {
                    kind: Open::Do,
                    label,
                    span,
                }),
                OKeyword::While => {
                    if matches!(stack.last(), Some(top) if top.kind == Open::Do && same(&top.label, &label))
                    {
                        stack.pop();
                    } else {
                        stack.push(Frame {
                            kind: Open::While,
                            label,
                            span,
                        });
                    }
                }
                OKeyword::Endwhile => close(
                    &mut stack,
                    |k| k == Open::While,
                    "endwhile",
                    (&label, &name, span),
                    out,
                ),
                OKeyword::Repeat => stack.push(Frame {
                    kind: Open::Repeat,
                    label,
                    span,
                }),
                OKeyword::Endrepeat => close(
                    &mut stack,
                    |k| k == Open::Repeat,
                    "endrepeat",
                    (&label, &name, span),
                    out,
                ),
                OKeyword::If => stack.push(Frame {
                    kind: Open::If { seen_else: false },
                    label,
                    span,
                }),
                OKeyword::Elseif | OKeyword::Else => match stack.last_mut() {
                    Some(top)
                        if matches!(top.kind, Open::If { .. }) && same(&top.label, &label) =>
                    {
                        if top.kind == (Open::If { seen_else: true }) {
                            // rs274 accepts a second `else` and runs the first one: the
                            // later branch is dead code, not an error.
                            let d = if kw == OKeyword::Else {
                                OWORD_STRUCTURE.warning(
                                    span,
                                    format!("`{name} else` after `else` never runs: LinuxCNC takes the first `else` branch. Remove the second one or merge the branches."),
                                )
                            } else {
                                OWORD_STRUCTURE.error(
                                    span,
                                    format!("`{name} {}` after `else`: the `else` branch must be the last one of the `if`.", kw.as_str()),
                                )
                            };
                            out.push(d.with_related(top.span, "the if"));
                        }
                        if kw == OKeyword::Else {
                            top.kind = Open::If { seen_else: true };
                        }
                    }
                    _ => out.push(OWORD_STRUCTURE.error(
                        span,
                        format!(
                            "`{name} {}` is not inside an `{name} if` … `endif` block.",
                            kw.as_str()
                        ),
                    )),
                },
                OKeyword::Endif => close(
                    &mut stack,
                    |k| matches!(k, Open::If { .. }),
                    "endif",
                    (&label, &name, span),
                    out,
                ),
                OKeyword::Break | OKeyword::Continue => {
                    if !stack
                        .iter()
                        .any(|f| f.kind.is_loop() && same(&f.label, &label))
                    {
                        out.push(OWORD_STRUCTURE.error(
                            span,
                            format!(
                                "`{name} {}` is not inside a loop labelled {name}: break and continue act on the enclosing while, do or repeat of the same label.",
                                kw.as_str()
                            ),
                        ));
                    }
                }
                OKeyword::Call => {}
            }
        }
        for f in stack {
            let text = format!(
                "`{}` is never closed: add the matching `{}` with the same label. LinuxCNC would search to the end of the file and stop.",
                p.str_of(f.span).trim(),
                f.kind.closer()
            );
            // LinuxCNC only looks for the closer when it has to jump to it (a false
            // condition, a break). With M2/M30 after the opener the
            // program may end first and run cleanly, as rs274 does; the interpreter
            // reports the failed search when it happens, so this stays a warning.
            let end_follows = f.kind != Open::Sub
                && p.blocks
                    .iter()
                    .filter(|b| b.span.start > f.span.start)
                    .any(|b| {
                        p.words(b).any(|(_, w)| {
                            w.letter == b'M' && matches!(lit(w), Some(v) if v == 2.0 || v == 30.0)
                        })
                    });
            out.push(if end_follows {
                OWORD_STRUCTURE.warning(
                    f.span,
                    format!(
                        "`{}` is never closed: add the matching `{}` with the same label. LinuxCNC stops only when it has to jump to it; until then the program runs on to the M2/M30 after it (a loop body runs once).",
                        p.str_of(f.span).trim(),
                        f.kind.closer()
                    ),
                )
            } else {
                OWORD_STRUCTURE.error(f.span, text)
            });
        }
    }
}

/// Closes the innermost block if it is of the wanted kind and label, and
/// reports what does not match.
fn close(
    stack: &mut Vec<Frame>,
    want: fn(Open) -> bool,
    closer: &str,
    (label, name, span): (&Option<String>, &str, Span),
    out: &mut Vec<Diagnostic>,
) {
    match stack.last() {
        Some(top) if want(top.kind) && same(&top.label, label) => {
            stack.pop();
        }
        Some(top) if want(top.kind) => {
            let msg = format!(
                "`{name} {closer}` closes the `{}` opened with another label: the statement pairs are found by label, so both must use the same one.",
                top.kind.opener()
            );
            out.push(OWORD_STRUCTURE.error(span, msg).with_related(top.span, "opened here"));
            stack.pop();
        }
        Some(top) => {
            let msg = format!(
                "`{name} {closer}` does not match the innermost open block, a `{}` that still needs its `{}`. Close blocks in the reverse order of opening.",
                top.kind.opener(),
                top.kind.closer()
            );
            out.push(OWORD_STRUCTURE.error(span, msg).with_related(top.span, "innermost open block"));
            if let Some(i) = stack.iter().rposition(|f| want(f.kind)) {
                stack.truncate(i);
            }
        }
        None => out.push(OWORD_STRUCTURE.error(
            span,
            format!("`{name} {closer}` has no matching opening statement. Remove it, or add the statement that opens the block."),
        )),
    }
}
