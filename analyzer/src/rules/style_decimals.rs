//! S005: too few decimal places for the units in use.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::block_g_codes;
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out coordinates (X Y Z A B C U V W I J K R) written with a decimal point but
    /// fewer than 3 decimals in millimetre programs (`G21`) or fewer than 4 in inch programs
    /// (`G20`). The units are taken from the last `G20`/`G21` above the line; lines before
    /// any units code are not checked. Whole numbers without a point (`X10`) are fine.
    ///
    /// ## Why is this bad?
    /// LinuxCNC checks arcs to 0.001 mm or 0.0001 in; values rounded more coarsely, for
    /// example by a post-processor, make arcs fail those checks and parts come out off.
    ///
    /// ## Example
    /// ```ngc
    /// G21
    /// G0 X1.5
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G21
    /// G0 X1.500
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default. Reported once per line.
    ///
    /// Implements: NGC700
    pub static TOO_FEW_DECIMALS = {
        code: "S005",
        name: "too-few-decimals",
        summary: "Too few decimal places for the units",
        implements: &["NGC700"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct TooFewDecimals;

impl Rule for TooFewDecimals {
    fn meta(&self) -> &'static RuleMeta {
        &TOO_FEW_DECIMALS
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let mut need: Option<usize> = None;
        for b in &p.blocks {
            let g = block_g_codes(p, b);
            if g.contains(&200) {
                need = Some(4);
            }
            if g.contains(&210) {
                need = Some(3);
            }
            let Some(need) = need else { continue };
            for (item, w) in p.words(b) {
                if !b"XYZABCUVWIJKR".contains(&w.letter) || w.comma {
                    continue;
                }
                let Some(n) = w.num().filter(|n| n.has_point) else {
                    continue;
                };
                let text = p.str_of(n.span);
                let decimals = text
                    .split('.')
                    .nth(1)
                    .map(|f| f.chars().filter(|c| c.is_ascii_digit()).count())
                    .unwrap_or(0);
                if decimals < need {
                    let units = if need == 4 {
                        "inch (G20)"
                    } else {
                        "millimetre (G21)"
                    };
                    out.push(TOO_FEW_DECIMALS.diagnostic(
                        Severity::Hint,
                        item.span,
                        format!("`{}` has {decimals} decimal place{}; {units} programs should give at least {need}, the precision LinuxCNC checks arcs to.", p.str_of(item.span), if decimals == 1 { "" } else { "s" }),
                    ));
                    break;
                }
            }
        }
    }
}
