//! G004: G or M codes the dialect does not know.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::{CodeNum, Dialect};
use crate::syntax::WordValue;

use super::util::{code_name, is_custom, near_integer, table_has_letter};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags G and M codes that are not in the dialect's code table and not listed in
    /// `rules.custom_codes`, and malformed G numbers (negative, or with a second decimal
    /// digit such as `G1.05`).
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops with `Unknown g code used` / `Unknown m code used` / `G code out of
    /// range`; FANUC raises PS0010. ServoWorks silently ignores G codes it does not have, so
    /// the mode you meant is never set (ServoWorks has no `G88`, for instance).
    ///
    /// ## Example
    /// ```ngc
    /// G1.05 X1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC and FANUC: error. ServoWorks: warning for G codes (ignored), info for M
    /// codes outside Table 7-1 (their meaning comes from the PLC ladder or a custom macro);
    /// `G00.1` is flagged as undocumented. FANUC M codes are machine-defined and not
    /// checked. Codes listed in `rules.custom_codes` are accepted.
    ///
    /// Reported by this rule, not X002, when both see a G code that does not exist on the same text (one diagnostic per fault).
    ///
    /// Implements: SW009, SW048, SW133, SW145, NGC104, NGC105, FAN020
    pub static UNKNOWN_CODE = {
        code: "G004",
        name: "unknown-code",
        summary: "G or M code the dialect does not know",
        implements: &["SW009", "SW048", "SW133", "SW145", "NGC104", "NGC105", "FAN020"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct UnknownCode;

impl Rule for UnknownCode {
    fn meta(&self) -> &'static RuleMeta {
        &UNKNOWN_CODE
    }

    /// Only G and M codes are looked up.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"GM")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        for c in cx.codes {
            let item = &cx.items()[c.item];
            let crate::syntax::ItemKind::Word(w) = &item.kind else {
                continue;
            };
            let WordValue::Num(n) = &w.value else {
                continue;
            };
            let text = cx.program.str_of(item.span);
            if n.value < 0.0 {
                if d == Dialect::Rs274ngc {
                    let what = if c.letter == 'G' { "g" } else { "m" };
                    out.push(UNKNOWN_CODE.error(
                        c.span,
                        format!(
                            "Negative {what} code used: `{text}`. Code numbers are never negative."
                        ),
                    ));
                } else if c.letter == 'G' {
                    out.push(unknown(d, c.span, &text));
                }
                continue;
            }
            let Some(num) = c.num else {
                if c.letter == 'G' {
                    let msg = match d {
                        Dialect::Rs274ngc => format!("G code out of range: `{text}` has more than one decimal digit; G numbers are read in tenths (G1, G38.2)."),
                        _ => format!("`{text}` is not a G code: G numbers have at most one decimal digit."),
                    };
                    out.push(UNKNOWN_CODE.error(c.span, msg));
                }
                continue;
            };
            if c.info.is_some()
                || is_custom(cx.settings, c.letter, num)
                || !table_has_letter(d, c.letter)
            {
                if let (Dialect::Servoworks, Some(_)) = (d, c.info) {
                    if c.is('G', 1) {
                        out.push(UNKNOWN_CODE.warning(
                            c.span,
                            "G00.1 is not in the ServoWorks G-code tables; the manual mentions it only in a copied paragraph of the G01 section. Use G00 unless your control is known to have G00.1.",
                        ));
                    }
                }
                continue;
            }
            match (d, c.letter) {
                (Dialect::Rs274ngc, 'G') if num.0 > 999 => out.push(UNKNOWN_CODE.error(
                    c.span,
                    format!("G code out of range: `{text}`; RS274/NGC G codes go up to G99.9."),
                )),
                (Dialect::Rs274ngc, 'M') if !near_integer(n.value) => {}
                (Dialect::Rs274ngc, 'M') => out.push(UNKNOWN_CODE.error(
                    c.span,
                    format!("Unknown m code used: M{} is not an RS274/NGC M code. If your configuration defines it (M100–M199 user commands), list it in `rules.custom_codes`.", num.display()),
                )),
                (Dialect::Servoworks, 'M') => out.push(UNKNOWN_CODE.info(
                    c.span,
                    format!("M{:02} is not in the ServoWorks M-code table: what it does is defined by the PLC ladder or a custom macro. List it in `rules.custom_codes` if it is yours.", num.0 / 10),
                )),
                (Dialect::Fanuc, 'M') => {}
                (Dialect::Servoworks, 'G') if num == CodeNum::whole(88) => out.push(UNKNOWN_CODE.warning(
                    c.span,
                    "ServoWorks has no G88 boring cycle: the code is ignored and no cycle is set. Use G89 (dwell at bottom, feed out) or G86.",
                )),
                (_, 'G') => out.push(unknown(d, c.span, &code_name(d, 'G', num))),
                _ => {}
            }
        }
    }
}

fn unknown(d: Dialect, span: crate::span::Span, name: &str) -> Diagnostic {
    match d {
        Dialect::Rs274ngc => UNKNOWN_CODE.error(
            span,
            format!("Unknown g code used: {name} is not an RS274/NGC G code. If your configuration remaps it, list it in `rules.custom_codes`."),
        ),
        Dialect::Servoworks => UNKNOWN_CODE.warning(
            span,
            format!("{name} is not a ServoWorks G code: the control ignores it as unused data. If a custom macro defines it, list it in `rules.custom_codes`."),
        ),
        Dialect::Fanuc => UNKNOWN_CODE.error(
            span,
            format!("{name} is not a FANUC 30i G code or needs an option (alarm PS0010). If your machine defines it as a macro call, list it in `rules.custom_codes`."),
        ),
    }
}
