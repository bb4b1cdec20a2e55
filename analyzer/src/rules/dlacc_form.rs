//! W008: ServoWorks G05/G08 forms that the control ignores.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;
use crate::span::Span;

use super::util::{lit, word_item};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks ServoWorks 3D Dynamic Look-Ahead Contour Control commands: only `G05 P10000`
    /// (on), `G05 P0` (off), `G08 P1` (on) and `G08 P0` (off) are valid.
    ///
    /// ## Why is this bad?
    /// Every other form — `G05 P1`, `G08 P10000`, `G05` without P — is silently ignored, so
    /// look-ahead stays in whatever state it was, and the path and cycle time differ from
    /// what you planned.
    ///
    /// ## Example
    /// ```servoworks
    /// G08 P10000
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G08 P1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, warning.
    ///
    /// Implements: SW055
    pub static DLACC_FORM = {
        code: "W008",
        name: "dlacc-form",
        summary: "G05/G08 form that ServoWorks ignores",
        implements: &["SW055"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct DlaccForm;

impl Rule for DlaccForm {
    fn meta(&self) -> &'static RuleMeta {
        &DLACC_FORM
    }

    /// A report needs G05 or G08.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"G")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Servoworks {
            return;
        }
        for c in cx.codes {
            let on = if c.is('G', 50) {
                10000.0
            } else if c.is('G', 80) {
                1.0
            } else {
                continue;
            };
            let p = word_item(cx, b'P');
            // A P given by a variable is checked when the program runs.
            if p.is_some_and(|(_, w)| w.num().is_none()) {
                continue;
            }
            let v = p.and_then(|(_, w)| lit(w));
            if v == Some(0.0) || v == Some(on) {
                continue;
            }
            let name = if on == 1.0 { "G08" } else { "G05" };
            let got = p
                .map(|(i, _)| format!("`{}`", cx.program.str_of(i.span)))
                .unwrap_or_else(|| "no P".into());
            // The fix switches look-ahead on, which is what a program writing
            // `G05 P1` (the FANUC AI contour form) means.
            let edit = match p {
                Some((i, _)) => TextEdit {
                    span: i.span,
                    new_text: format!("P{on}"),
                },
                None => TextEdit {
                    span: Span::new(c.span.end, c.span.end),
                    new_text: format!(" P{on}"),
                },
            };
            let d = DLACC_FORM.warning(
                c.span,
                format!("{name} with {got} is ignored: look-ahead is switched only by `{name} P{on}` (on) or `{name} P0` (off)."),
            );
            // Other codes in the block may read the same P (G08, G54.1 P1); the
            // fix is certain only when this code is alone.
            let both = cx.codes.len() > 1;
            out.push(if both {
                d
            } else {
                d.with_fix(format!("Write `{name} P{on}` (look-ahead on)"), vec![edit])
            });
        }
    }
}
