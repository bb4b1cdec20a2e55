//! Flow-sensitive rule: its metadata and its check, which the interpreter runs on
//! the expressions of each block before it executes (`Interp::spec_items`).

use analyzer::declare_rule;
use analyzer::syntax::{BinOp, Expr, ExprId, Program};
use analyzer::{Dialect, Severity};

use super::check::Sink;

declare_rule! {
    /// ## What it does
    /// Flags a read of a vacant variable in an assignment or a word value: FANUC local variables #1–#33 of the current level (warning), and ServoWorks variables (info). Comparisons with EQ/NE are exempt, as that is how a macro tests whether an argument was given.
    ///
    /// ## Why is this bad?
    /// A vacant value reads as 0 in arithmetic (and drops the word it is in), so the program computes with a value nobody set.
    ///
    /// ## Example
    /// ```gcode
    /// #101 = #1 + 1
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// #1 = 2
    /// #101 = #1 + 1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC (warning, locals; information inside a G65/G66 macro, where a local is an
    /// argument the caller may leave out and reads as 0 in arithmetic; nothing for a
    /// local set from a machine value the dry run does not know, `#24 = #516`),
    /// ServoWorks (info).
    ///
    /// Implements: SW017, FAN144
    pub static VACANT_READ = {
        code: "X010",
        name: "vacant-read",
        summary: "Variable read before it is assigned",
        implements: &["SW017", "FAN144"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the read check sees: the parameters before the block and how the
/// machine and the call stack answer for a variable.
pub(crate) struct Reads<'c> {
    pub(crate) dialect: Dialect,
    pub(crate) params: &'c [Option<f64>],
    /// The variable was set from a machine value the dry run does not know
    /// (`#24 = #516`): not read before it is assigned.
    pub(crate) machine_value: &'c dyn Fn(usize) -> bool,
    /// The current level is a macro (G65/G66, or a main program returning with M99).
    pub(crate) macro_level: &'c dyn Fn() -> bool,
    pub(crate) out: Sink<'c>,
}

impl Reads<'_> {
    /// Reports reads of vacant variables in `e` (FANUC locals #1–#33 and, in
    /// ServoWorks, any variable). Operands of EQ/NE are exempt: comparing with
    /// a vacant value is how macros test whether an argument was given.
    #[inline]
    pub(crate) fn check(&mut self, prog: &Program, e: ExprId, in_compare: bool) {
        let node = *prog.expr(e);
        match node.expr {
            Expr::Var { index } => {
                if let Expr::Num(n) = prog.expr(index).expr {
                    let k = n.value;
                    let fanuc_local = self.dialect == Dialect::Fanuc && (1.0..=33.0).contains(&k);
                    let sw = self.dialect == Dialect::Servoworks && (1.0..1000.0).contains(&k);
                    let vacant = self.params.get(k as usize).copied().flatten().is_none();
                    // Set from a machine value the dry run does not know (`#24 = #516`):
                    // not read before it is assigned.
                    let machine_value = (self.machine_value)(k as usize);
                    if !in_compare && (fanuc_local || sw) && vacant && !machine_value {
                        let (sev, why) = if fanuc_local && (self.macro_level)() {
                            (Severity::Info, "an argument the caller did not pass is vacant and reads as 0 in arithmetic")
                        } else if fanuc_local {
                            (Severity::Warning, "a local variable that was not assigned at this level (nor passed as an argument) is vacant")
                        } else {
                            (
                                Severity::Info,
                                "the variable has not been assigned yet, so its value is vacant",
                            )
                        };
                        self.out.diag(
                            &VACANT_READ,
                            sev,
                            node.span,
                            format!(
                                "#{} is read before it is assigned: {why}; assign it first",
                                k as i64
                            ),
                        );
                    }
                } else {
                    self.check(prog, index, in_compare);
                }
            }
            Expr::Neg { arg } | Expr::Plus { arg } => self.check(prog, arg, in_compare),
            Expr::Group { inner } => self.check(prog, inner, in_compare),
            Expr::Binary { op, lhs, rhs } => {
                let cmp = in_compare || matches!(op, BinOp::Eq | BinOp::Ne);
                self.check(prog, lhs, cmp);
                self.check(prog, rhs, cmp);
            }
            Expr::Call { arg, arg2, .. } => {
                self.check(prog, arg, in_compare);
                if let Some(a) = arg2 {
                    self.check(prog, a, in_compare);
                }
            }
            _ => {}
        }
    }
}
