//! W016: parameter (variable) numbers out of range, fractional, or read-only.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{Expr, ExprId, Func, ItemKind};

use super::util::{block_exprs, expr_nodes, is_emc2, near_integer};
use super::{BlockCx, Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks parameter numbers written as literals (`#5400`, `#[12]`): RS274/NGC indices
    /// must be whole numbers (within 0.0001) from 1 to 5399 (`emc2`) or 5601 (`linuxcnc`);
    /// FANUC variable numbers 34 to 99 and 200 to 499 do not exist. Assignments to
    /// read-only parameters are flagged too: LinuxCNC #5021–#5029 and #5400–#5413,
    /// `#<_ini[…]>`, `#<_hal[…]>`; FANUC #0, the input signals #1000–#1035, the date and
    /// time #3011/#3012, modal information #4001–#4999 and positions #5001–#5199.
    ///
    /// ## Why is this bad?
    /// The control stops: LinuxCNC `Parameter number out of range`, FANUC PS0115 (number
    /// out of range) and PS0116 (write-protected variable).
    ///
    /// ## Example
    /// ```ngc
    /// #6000 = 1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #3000 = 1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC and FANUC, error. Computed indices are checked when the program runs.
    ///
    /// Reported by this rule, not X001, when both see a write to a read-only parameter on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC018, NGC019, NGC029, FAN126, FAN127
    pub static PARAMETER_NUMBER = {
        code: "W016",
        name: "parameter-number",
        summary: "Parameter number out of range or read-only",
        implements: &["NGC018", "NGC019", "NGC029", "FAN126", "FAN127"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ParameterNumber;

fn fanuc_read_only(n: f64) -> bool {
    n == 0.0
        || (1000.0..=1035.0).contains(&n)
        || n == 3011.0
        || n == 3012.0
        || (4001.0..=4999.0).contains(&n)
        || (5001.0..=5199.0).contains(&n)
}

fn ngc_read_only(n: f64) -> bool {
    (5021.0..=5029.0).contains(&n) || (5400.0..=5413.0).contains(&n)
}

impl Rule for ParameterNumber {
    fn meta(&self) -> &'static RuleMeta {
        &PARAMETER_NUMBER
    }

    /// FANUC #200–#499 exist with the additional common variables option: without
    /// a `machine.common_variables` setting the program's use of them is the
    /// evidence, said once per file at the first use.
    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Fanuc || cx.settings.common_variables_end.is_some() {
            return;
        }
        let first = p.exprs.iter().find(|node| {
            matches!(node.expr, Expr::Var { index } if matches!(p.expr(index).expr,
                Expr::Num(n) if (200.0..=499.0).contains(&n.value) && n.value.fract() == 0.0))
        });
        if let Some(node) = first {
            let text = p.str_of(node.span).into_owned();
            out.push(PARAMETER_NUMBER.info(node.span, format!(
                "`{text}` is a common variable of the additional common variables option (#100–#499; the standard control has #100–#199): checked as if the control has it. Set machine.common_variables = 199 or 499 to say which."
            )));
        }
    }

    /// Only parameter references and assignments are read.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        let d = p.dialect;
        if d == Dialect::Servoworks {
            return;
        }
        let max = if is_emc2(cx.settings) { 5399.0 } else { 5601.0 };
        for root in block_exprs(p, cx.items()) {
            let nodes = expr_nodes(p, root);
            // `EXISTS[#n]` asks whether #n exists, so its own number is not range-checked.
            let exists_args: Vec<ExprId> = nodes
                .iter()
                .filter_map(|id| match p.expr(*id).expr {
                    Expr::Call {
                        func: Func::Exists,
                        arg,
                        ..
                    } => {
                        let mut a = arg;
                        while let Expr::Group { inner } = p.expr(a).expr {
                            a = inner;
                        }
                        Some(a)
                    }
                    _ => None,
                })
                .collect();
            for id in nodes {
                if exists_args.contains(&id) {
                    continue;
                }
                let node = p.expr(id);
                let Expr::Var { index } = node.expr else {
                    continue;
                };
                let Expr::Num(n) = p.expr(index).expr else {
                    continue;
                };
                let v = n.value;
                let text = p.str_of(node.span).into_owned();
                let msg = match d {
                    Dialect::Rs274ngc if !near_integer(v) => Some(format!("`{text}`: a parameter number must be a whole number.")),
                    Dialect::Rs274ngc if v.round() < 1.0 || v.round() > max => {
                        Some(format!("Parameter number out of range: `{text}`; this profile has parameters 1 to {max}."))
                    }
                    Dialect::Fanuc if v < 0.0 || v.fract() != 0.0 || (34.0..=99.0).contains(&v) => Some(format!(
                        "`{text}` is not a variable of the control (alarm PS0115): locals are #1–#33, commons #100–#199 and #500–#999, system variables from #1000."
                    )),
                    Dialect::Fanuc if (200.0..=499.0).contains(&v) && cx.settings.common_variables_end == Some(199) => Some(format!(
                        "`{text}` is not a variable of this control (alarm PS0115): machine.common_variables = 199 says it has commons #100–#199 only (499 with the additional common variables option)."
                    )),
                    _ => None,
                };
                if let Some(msg) = msg {
                    out.push(PARAMETER_NUMBER.error(node.span, msg));
                }
            }
        }
        for item in cx.items() {
            let ItemKind::Assign { target, .. } = item.kind else {
                continue;
            };
            let node = p.expr(target);
            let text = p.str_of(node.span).into_owned();
            let ro = match node.expr {
                Expr::Var { index } => match p.expr(index).expr {
                    Expr::Num(n) if d == Dialect::Fanuc => fanuc_read_only(n.value),
                    Expr::Num(n) => !is_emc2(cx.settings) && ngc_read_only(n.value.round()),
                    _ => false,
                },
                Expr::Named { name } if d == Dialect::Rs274ngc && !is_emc2(cx.settings) => {
                    let s = p.str_of(name).to_ascii_lowercase().replace(' ', "");
                    s.contains("_ini[") || s.contains("_hal[")
                }
                _ => false,
            };
            if ro {
                let msg = match d {
                    Dialect::Fanuc => {
                        format!("`{text}` is read-only: writing it raises alarm PS0116.")
                    }
                    _ => format!(
                        "`{text}` is a read-only parameter; LinuxCNC refuses the assignment."
                    ),
                };
                out.push(PARAMETER_NUMBER.error(node.span, msg));
            }
        }
    }
}
