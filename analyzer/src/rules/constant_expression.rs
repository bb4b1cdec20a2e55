//! W015: expressions whose constant parts fail to evaluate.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::syntax::{BinOp, Expr, ExprId, Func, Program};

use super::util::{block_exprs, is_emc2};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Evaluates the constant parts of expressions (those without parameters) and flags
    /// the ones that cannot be computed: division or `MOD` by zero, a negative number to a
    /// fractional power, `SQRT` of a negative number, `LN` of zero or less, `ASIN`/`ACOS`
    /// outside -1 to 1.
    ///
    /// ## Why is this bad?
    /// The control stops when it evaluates the block (LinuxCNC `Attempt to divide by zero`,
    /// `Negative argument to sqrt`; FANUC PS0112, PS0119).
    ///
    /// ## Example
    /// ```ngc
    /// #1 = [10 / [2 - 2]]
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #1 = [10 / [2 + 2]]
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error. Expressions that read parameters are checked when the program runs.
    ///
    /// Reported by this rule, not X001, when both see a constant expression that cannot be evaluated on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC014, NGC015, NGC016, NGC017, FAN128, FAN129
    pub static CONSTANT_EXPRESSION = {
        code: "W015",
        name: "constant-expression-error",
        summary: "Constant expression that cannot be evaluated",
        implements: &["NGC014", "NGC015", "NGC016", "NGC017", "FAN128", "FAN129"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ConstantExpression;

struct Eval<'a> {
    p: &'a Program,
    emc2: bool,
    out: &'a mut Vec<Diagnostic>,
}

impl Eval<'_> {
    fn fail(&mut self, id: ExprId, msg: &str) -> Option<f64> {
        self.out
            .push(CONSTANT_EXPRESSION.error(self.p.expr(id).span, msg.to_string()));
        None
    }

    /// The value of a constant expression; `None` when it reads a parameter or fails
    /// (failures are reported at the innermost node).
    fn eval(&mut self, id: ExprId, depth: u32) -> Option<f64> {
        if depth > crate::syntax::MAX_EXPR_HEIGHT {
            return None;
        }
        let v = match self.p.expr(id).expr {
            Expr::Num(n) => n.value,
            Expr::Var { index } => {
                // The index is evaluated for its own errors; the value is unknown.
                self.eval(index, depth + 1);
                return None;
            }
            Expr::Named { .. } | Expr::Error => return None,
            Expr::Group { inner } => self.eval(inner, depth + 1)?,
            Expr::Plus { arg } => self.eval(arg, depth + 1)?,
            Expr::Neg { arg } => -self.eval(arg, depth + 1)?,
            Expr::Binary { op, lhs, rhs } => {
                let a = self.eval(lhs, depth + 1);
                let b = self.eval(rhs, depth + 1);
                let (a, b) = (a?, b?);
                match op {
                    BinOp::Add => a + b,
                    BinOp::Sub => a - b,
                    BinOp::Mul => a * b,
                    BinOp::Div if b == 0.0 => {
                        return self
                            .fail(id, "Division by zero: the divisor of this expression is 0.")
                    }
                    BinOp::Div => a / b,
                    BinOp::Mod if b == 0.0 => {
                        return self.fail(
                            id,
                            "MOD by zero: the result is not a number and the control stops.",
                        );
                    }
                    BinOp::Mod => a.rem_euclid(b.abs()),
                    BinOp::Pow if a < 0.0 && b.fract() != 0.0 => {
                        return self.fail(
                            id,
                            "A negative number raised to a fractional power has no real value.",
                        );
                    }
                    BinOp::Pow => a.powf(b),
                    _ => return None,
                }
            }
            Expr::Call { func, arg, arg2 } => {
                let x = self.eval(arg, depth + 1);
                let y = arg2.and_then(|a| self.eval(a, depth + 1));
                let x = x?;
                match func {
                    Func::Sqrt if x < 0.0 => return self.fail(id, "SQRT of a negative number."),
                    Func::Ln if x <= 0.0 => {
                        return self.fail(id, "LN of zero or a negative number.")
                    }
                    Func::Asin | Func::Acos if !(-1.0..=1.0).contains(&x) => {
                        return self.fail(id, "ASIN and ACOS take values from -1 to 1.");
                    }
                    Func::Sqrt => x.sqrt(),
                    Func::Ln => x.ln(),
                    Func::Abs => x.abs(),
                    Func::Asin => x.asin().to_degrees(),
                    Func::Acos => x.acos().to_degrees(),
                    Func::Sin => x.to_radians().sin(),
                    Func::Cos => x.to_radians().cos(),
                    Func::Tan => x.to_radians().tan(),
                    Func::Exp => x.exp(),
                    Func::Atan => y.map(|y| x.atan2(y).to_degrees())?,
                    _ => return None,
                }
            }
        };
        if !v.is_finite() && !self.emc2 {
            return self.fail(
                id,
                "The result of this expression is infinite or not a number.",
            );
        }
        Some(v)
    }
}

impl Rule for ConstantExpression {
    fn meta(&self) -> &'static RuleMeta {
        &CONSTANT_EXPRESSION
    }

    /// Only expressions are evaluated.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let mut e = Eval {
            p: cx.program,
            emc2: is_emc2(cx.settings),
            out,
        };
        for root in block_exprs(cx.program, cx.items()) {
            e.eval(root, 0);
        }
    }
}
