//! W024: RS274/NGC words that no code on the line uses.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{has, is_emc2, word_item};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags LinuxCNC words that only some codes accept, written where none of them is:
    /// an `E` word without `G76`, `G70` or `M66`–`M68`; polar words `@`/`^` together with
    /// `X`/`Y` or `G53`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses a word that nothing on the line uses. Polar coordinates replace X
    /// and Y, so they cannot be combined with them, nor with machine coordinates.
    ///
    /// ## Example
    /// ```ngc
    /// G1 X1 E2 F100
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
    /// RS274/NGC `linuxcnc` profile, error (the 2007 profile has no E, @ or ^ at all). The
    /// plane and the incremental-from-origin rules of polar words are checked at run time.
    ///
    /// Implements: NGC815, NGC816
    pub static WORD_WITHOUT_USER = {
        code: "W024",
        name: "word-without-user",
        summary: "Word that no code on the line uses",
        implements: &["NGC815", "NGC816"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct WordWithoutUser;

impl Rule for WordWithoutUser {
    fn meta(&self) -> &'static RuleMeta {
        &WORD_WITHOUT_USER
    }

    /// Only E and the polar words @ and ^ are checked.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"E@^")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Rs274ngc || is_emc2(cx.settings) {
            return;
        }
        if let Some((e, _)) = word_item(cx, b'E') {
            let users = [('G', 760), ('G', 700), ('M', 660), ('M', 670), ('M', 680)];
            if !users.iter().any(|(l, t)| has(cx, *l, *t)) {
                out.push(WORD_WITHOUT_USER.error(e.span, "E word with no code that uses it: only G76, G70 and M66–M68 take E. Remove it."));
            }
        }
        let polar = word_item(cx, b'@').or_else(|| word_item(cx, b'^'));
        if let Some((pw, _)) = polar {
            if word_item(cx, b'X').is_some() || word_item(cx, b'Y').is_some() {
                out.push(WORD_WITHOUT_USER.error(pw.span, "Polar words @ and ^ replace X and Y; they cannot be used with X or Y on the same line."));
            } else if has(cx, 'G', 530) {
                out.push(WORD_WITHOUT_USER.error(
                    pw.span,
                    "Polar words cannot be combined with G53 machine coordinates.",
                ));
            }
        }
    }
}
