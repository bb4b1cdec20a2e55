//! W021: FANUC EQ/NE against a non-integer literal.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use std::collections::HashSet;

use crate::syntax::{BinOp, Block, Expr, ExprId, Func, ItemKind, Program};

use super::macro_loop_structure::literal;
use super::util::{block_exprs, expr_nodes};
use super::{ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags FANUC conditions that compare with `EQ` or `NE` against a number that is not
    /// a whole number when the other side is computed, such as `IF [#1 EQ 0.1] GOTO 10`
    /// after `#1 = #2 / 3`. Values that are not computed hold the number as written and
    /// compare exactly, so they are not flagged: a read of the modal information
    /// (`#4001`–`#4130`, `#4201`–`#4330`: `IF [#4014 EQ 54.1]`), a macro argument
    /// (`B3.2` arrives in `#2` as written), and a variable whose assignments in the
    /// program are only literals, copies of such values, `FIX`, `FUP`, `ROUND` or `ABS`
    /// (`#31 = #4012`).
    ///
    /// ## Why is this bad?
    /// Computed values carry rounding errors, so an exact comparison with a fraction may
    /// never be true. Compare with a tolerance instead.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = #100 / 3;
    /// IF [#1 EQ 0.1] GOTO 10;
    /// N10 M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = #100 / 3;
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

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Fanuc {
            return;
        }
        let blocks: Vec<_> = cx.non_plain_blocks().collect();
        let computed = computed_variables(p, &blocks);
        for block in blocks {
            for root in block_exprs(p, p.items_of(block)) {
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
                    let inexact = |e| may_carry_rounding(p, e, &computed);
                    if (frac(lhs) && inexact(rhs)) || (frac(rhs) && inexact(lhs)) {
                        out.push(EQ_NON_INTEGER.warning(
                            node.span,
                            format!("{} against a fractional number: rounding errors can make an exact comparison fail. Use `ABS[a - b] LT tolerance`.", op.as_str()),
                        ));
                    }
                }
            }
        }
    }
}

/// The variables (by literal number) that some assignment in the program gives a
/// computed value: arithmetic or a function whose result is not a whole number, or
/// a copy of such a variable.
fn computed_variables(p: &Program, blocks: &[&Block]) -> HashSet<u64> {
    let mut computed = HashSet::new();
    let mut copies: Vec<(u64, u64)> = Vec::new();
    for block in blocks {
        for item in p.items_of(block) {
            let ItemKind::Assign { target, value } = item.kind else {
                continue;
            };
            let Expr::Var { index } = p.expr(target).expr else {
                continue;
            };
            let Some(n) = literal(p, index).and_then(var_key) else {
                continue;
            };
            match plain_variable(p, value) {
                Some(src) => copies.push((n, src)),
                None if is_computed(p, value) => {
                    computed.insert(n);
                }
                None => {}
            }
        }
    }
    // Copies of computed values are computed; each round adds at least one variable.
    loop {
        let before = computed.len();
        for &(dst, src) in &copies {
            if computed.contains(&src) {
                computed.insert(dst);
            }
        }
        if computed.len() == before {
            return computed;
        }
    }
}

fn var_key(n: f64) -> Option<u64> {
    (n >= 0.0 && n.fract() == 0.0 && n < 1e9).then_some(n as u64)
}

/// `#n` (through any brackets) with a literal number.
fn plain_variable(p: &Program, e: ExprId) -> Option<u64> {
    p.variable_index(e)
        .and_then(|i| literal(p, i))
        .and_then(var_key)
}

/// Whether evaluating `e` can round: arithmetic, or a function other than the
/// ones that return whole numbers or copy their argument's sign away.
fn is_computed(p: &Program, e: ExprId) -> bool {
    // A variable's number is not its value: `#[#1 + 1]` is not walked into.
    let mut stack = vec![e];
    let mut seen = 0usize;
    while let Some(id) = stack.pop() {
        seen += 1;
        if seen > 100_000 {
            return true;
        }
        match p.expr(id).expr {
            Expr::Binary { op, lhs, rhs } => {
                if matches!(
                    op,
                    BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div | BinOp::Mod | BinOp::Pow
                ) {
                    return true;
                }
                stack.extend([lhs, rhs]);
            }
            Expr::Call { func, arg, arg2 } => {
                if !matches!(func, Func::Fix | Func::Fup | Func::Round | Func::Abs) {
                    return true;
                }
                stack.push(arg);
                stack.extend(arg2);
            }
            Expr::Group { inner } => stack.push(inner),
            Expr::Neg { arg } | Expr::Plus { arg } => stack.push(arg),
            Expr::Num(_) | Expr::Var { .. } | Expr::Named { .. } | Expr::Error => {}
        }
    }
    false
}

/// Whether an operand compared against a fraction can carry a rounding error: a
/// computed expression, or a variable some assignment computes. Modal information
/// (`#4001`–`#4130`, `#4201`–`#4330`) holds the G code as written; a macro argument
/// or a variable given only literals and copies holds the number as written.
fn may_carry_rounding(p: &Program, e: ExprId, computed: &HashSet<u64>) -> bool {
    match plain_variable(p, e) {
        Some(n) => computed.contains(&n),
        // A variable chosen by a computed number is checked when the program runs.
        None => !matches!(p.expr(e).expr, Expr::Var { .. }) && is_computed(p, e),
    }
}
