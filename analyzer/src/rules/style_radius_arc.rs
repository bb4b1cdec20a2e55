//! S003: radius-format arcs in RS274/NGC.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::{first_g, word_item};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out arcs programmed with a radius `R` instead of centre offsets `I`/`J`/`K`.
    ///
    /// ## Why is this bad?
    /// From a radius the interpreter must compute the centre, and near 180° or 360° a
    /// tiny change of the end point moves that centre a lot. Centre format is exact and is
    /// what the seed's style chapter recommends.
    ///
    /// ## Example
    /// ```ngc
    /// G17 G2 X10 Y0 R5 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G17 G2 X10 Y0 I5 J0 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default.
    ///
    /// Implements: NGC702
    pub static RADIUS_ARC = {
        code: "S003",
        name: "prefer-centre-format-arc",
        summary: "Arc programmed with R instead of I/J/K",
        implements: &["NGC702"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct RadiusArc;

impl Rule for RadiusArc {
    fn meta(&self) -> &'static RuleMeta {
        &RADIUS_ARC
    }

    /// A report needs an arc code.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"G")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Rs274ngc || first_g(cx, &[20, 30]).is_none() {
            return;
        }
        if let Some((r, _)) = word_item(cx, b'R') {
            out.push(RADIUS_ARC.diagnostic(
                Severity::Hint,
                r.span,
                "Prefer centre format (I/J/K) to a radius: the centre computed from R is poorly conditioned near 180° and 360°.",
            ));
        }
    }
}
