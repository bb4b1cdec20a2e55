//! W018: a parameter set twice, or set and read, on one RS274/NGC line.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;
use crate::syntax::{Expr, ExprId, ItemKind, Program};

use super::util::{block_exprs, expr_nodes};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags an RS274/NGC line that sets the same parameter twice, or sets a parameter
    /// and also reads it outside the right-hand side of its own assignment.
    ///
    /// ## Why is this bad?
    /// All reads of a line happen before any of its assignments: with `#3 = 15`, the line
    /// `#3 = 6 G1 X#3` moves to X15. When a parameter is set twice the last setting wins.
    /// Both are legal but rarely what the author meant.
    ///
    /// ## Example
    /// ```ngc
    /// #3 = 6 G1 X#3 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #3 = 6
    /// G1 X#3 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: warning for set-and-read, info for set twice. (FANUC allows one
    /// assignment per block; ServoWorks macro statements stand alone.)
    ///
    /// Implements: NGC021, NGC022
    pub static PARAMETER_SAME_LINE = {
        code: "W018",
        name: "parameter-same-line",
        summary: "Parameter set twice, or set and read, on one line",
        implements: &["NGC021", "NGC022"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ParameterSameLine;

/// A comparable key for a parameter reference with a constant index or a name.
fn key(p: &Program, target: ExprId) -> Option<String> {
    match p.expr(target).expr {
        Expr::Var { index } => match p.expr(index).expr {
            Expr::Num(n) => Some(format!("#{}", n.value.round())),
            _ => None,
        },
        Expr::Named { name } => Some(p.str_of(name).to_ascii_lowercase().replace(' ', "")),
        _ => None,
    }
}

impl Rule for ParameterSameLine {
    fn meta(&self) -> &'static RuleMeta {
        &PARAMETER_SAME_LINE
    }

    /// Only assignments are compared.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let items = cx.items();
        let assigns: Vec<(usize, ExprId, String)> = items
            .iter()
            .enumerate()
            .filter_map(|(i, it)| match it.kind {
                ItemKind::Assign { target, .. } => key(p, target).map(|k| (i, target, k)),
                _ => None,
            })
            .collect();
        if assigns.is_empty() {
            return;
        }
        for (j, (_, target, k)) in assigns.iter().enumerate() {
            if let Some((_, first, _)) = assigns[..j].iter().find(|(_, _, k2)| k2 == k) {
                out.push(
                    PARAMETER_SAME_LINE
                        .diagnostic(
                            Severity::Info,
                            p.expr(*target).span,
                            format!("{k} is set twice on this line; only the last setting counts."),
                        )
                        .with_related(p.expr(*first).span, "first setting"),
                );
            }
        }
        // Reads: every parameter node except assignment targets; reads on the right side
        // of the parameter's own assignment are the allowed update form.
        for (i, item) in items.iter().enumerate() {
            let roots: Vec<ExprId> = match item.kind {
                ItemKind::Assign { target, value } => {
                    let mut r = vec![value];
                    if let Expr::Var { index } = p.expr(target).expr {
                        r.push(index);
                    }
                    r
                }
                _ => block_exprs(p, std::slice::from_ref(item)),
            };
            let own = assigns
                .iter()
                .find(|(ai, _, _)| *ai == i)
                .map(|(_, _, k)| k.clone());
            for root in roots {
                for id in expr_nodes(p, root) {
                    let Some(k) = key(p, id) else { continue };
                    if own.as_ref() == Some(&k) {
                        continue;
                    }
                    if let Some((_, target, _)) = assigns.iter().find(|(_, _, ak)| *ak == k) {
                        out.push(
                            PARAMETER_SAME_LINE.diagnostic(
                                Severity::Warning,
                                p.expr(id).span,
                                format!("{k} is read and set on the same line: the read sees the old value, because a line's assignments happen after all its reads. Set it on the line before."),
                            )
                            .with_related(p.expr(*target).span, "set here"),
                        );
                    }
                }
            }
        }
    }
}
