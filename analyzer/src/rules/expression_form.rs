//! W017: expression forms a profile does not accept.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{Expr, Func};

use super::util::{block_exprs, expr_nodes, is_emc2};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags expression forms the selected RS274/NGC profile rejects: in the 2007 `emc2`
    /// profile a sign in front of anything but a number (`-#1`, `-[…]`, `-SIN[…]`); in
    /// `linuxcnc`, `EXISTS[…]` applied to something other than a parameter.
    ///
    /// ## Why is this bad?
    /// The 2007 interpreter reads a sign only as part of a literal number and reports a
    /// bad number format; `EXISTS` tests whether a parameter exists, so a number or an
    /// expression as its argument is an error in LinuxCNC.
    ///
    /// ## Example
    /// ```ngc
    /// #2 = EXISTS[1]
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #2 = EXISTS[#<depth>]
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, error. Write `[0 - #1]` instead of `-#1` for `emc2`.
    ///
    /// Reported by this rule, not X001, when both see EXISTS without a parameter on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC033, NGC616
    pub static EXPRESSION_FORM = {
        code: "W017",
        name: "expression-form",
        summary: "Expression form the profile rejects",
        implements: &["NGC033", "NGC616"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ExpressionForm;

impl Rule for ExpressionForm {
    fn meta(&self) -> &'static RuleMeta {
        &EXPRESSION_FORM
    }

    /// Only expressions are read.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let emc2 = is_emc2(cx.settings);
        for root in block_exprs(p, cx.items()) {
            for id in expr_nodes(p, root) {
                let node = p.expr(id);
                match node.expr {
                    Expr::Neg { arg } | Expr::Plus { arg }
                        if emc2 && !matches!(p.expr(arg).expr, Expr::Num(_)) =>
                    {
                        out.push(EXPRESSION_FORM.error(
                            node.span,
                            format!("`{}`: the 2007 interpreter accepts a sign only on a number. Write `[0 - …]` instead.", p.str_of(node.span)),
                        ));
                    }
                    Expr::Call {
                        func: Func::Exists,
                        arg,
                        ..
                    } if !emc2 => {
                        let mut a = arg;
                        while let Expr::Group { inner } = p.expr(a).expr {
                            a = inner;
                        }
                        if !matches!(p.expr(a).expr, Expr::Named { .. } | Expr::Var { .. }) {
                            out.push(EXPRESSION_FORM.error(
                                node.span,
                                "EXISTS takes a parameter, `EXISTS[#<name>]` or `EXISTS[#n]`, not a number or an expression.",
                            ));
                        }
                    }
                    _ => {}
                }
            }
        }
    }
}
