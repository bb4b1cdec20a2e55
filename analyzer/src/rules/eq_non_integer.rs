//! W021: FANUC EQ/NE against a non-integer literal.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{BinOp, Expr};

use super::macro_loop_structure::literal;
use super::util::{block_exprs, expr_nodes};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags FANUC conditions that compare with `EQ` or `NE` against a number that is not
    /// a whole number, such as `IF [#1 EQ 0.1] GOTO 10`. A read of the modal information
    /// (`#4001`–`#4130`, `#4201`–`#4330`) holds the G code as written, so
    /// `IF [#4014 EQ 54.1]` is exact and not flagged.
    ///
    /// ## Why is this bad?
    /// Computed values carry rounding errors, so an exact comparison with a fraction may
    /// never be true. Compare with a tolerance instead.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// IF [#1 EQ 0.1] GOTO 10;
    /// N10 M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// IF [ABS[#1 - 0.1] LT 0.0001] GOTO 10;
    /// N10 M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// FANUC, warning. Comparisons of two variables are checked when the program runs.
    ///
    /// Implements: FAN142
    pub static EQ_NON_INTEGER = {
        code: "W021",
        name: "eq-non-integer",
        summary: "EQ/NE against a fractional number",
        implements: &["FAN142"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct EqNonInteger;

impl Rule for EqNonInteger {
    fn meta(&self) -> &'static RuleMeta {
        &EQ_NON_INTEGER
    }

    /// Only comparisons inside expressions are read.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Fanuc {
            return;
        }
        for root in block_exprs(p, cx.items()) {
            for id in expr_nodes(p, root) {
                let node = p.expr(id);
                let Expr::Binary {
                    op: op @ (BinOp::Eq | BinOp::Ne),
                    lhs,
                    rhs,
                } = node.expr
                else {
                    continue;
                };
                let frac = |e| matches!(p.expr(e).expr, Expr::Num(n) if n.value.fract() != 0.0);
                // Modal information (#4001–#4130, and #4201–#4330 for the block
                // before) holds the G code as written, 54.1 exactly: no rounding.
                let modal = |e| {
                    matches!(p.expr(e).expr, Expr::Var { index } if literal(p, index)
                        .is_some_and(|n| (4001.0..=4130.0).contains(&n) || (4201.0..=4330.0).contains(&n)))
                };
                if (frac(lhs) && !modal(rhs)) || (frac(rhs) && !modal(lhs)) {
                    out.push(Diagnostic::warning(
                        "W021",
                        node.span,
                        format!("{} against a fractional number: rounding errors can make an exact comparison fail. Use `ABS[a - b] LT tolerance`.", op.as_str()),
                    ));
                }
            }
        }
    }
}
