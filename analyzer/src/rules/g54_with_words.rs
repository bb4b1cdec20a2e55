//! W009: words in a ServoWorks G54–G59 block.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags words other than a sequence number written in the same ServoWorks block as a
    /// workpiece coordinate system selection `G54`–`G59`.
    ///
    /// ## Why is this bad?
    /// ServoWorks `G54`–`G59` take no parameters and the words in their block are ignored,
    /// so a move written there (`G54 G00 X0 Y0`) does not happen.
    ///
    /// ## Example
    /// ```servoworks
    /// G54 G00 X0 Y0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G54
    /// G00 X0 Y0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, warning. In RS274/NGC and FANUC the words of the block are executed.
    ///
    /// Implements: SW109
    pub static G54_WITH_WORDS = {
        code: "W009",
        name: "g54-with-words",
        summary: "Words in a ServoWorks G54–G59 block are ignored",
        implements: &["SW109"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct G54WithWords;

impl Rule for G54WithWords {
    fn meta(&self) -> &'static RuleMeta {
        &G54_WITH_WORDS
    }

    /// A report needs a G54-G59 code.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"G")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Servoworks {
            return;
        }
        let Some(wcs) = cx.codes.iter().find(|c| {
            c.letter == 'G'
                && c.num
                    .is_some_and(|n| (540..=590).contains(&n.0) && n.0 % 10 == 0)
        }) else {
            return;
        };
        let others: Vec<_> = cx
            .words()
            .filter(|(i, w)| w.letter != b'N' && i.span != wcs.span)
            .collect();
        if let Some((first, _)) = others.first() {
            let span = others.iter().fold(first.span, |s, (i, _)| s.cover(i.span));
            out.push(
                G54_WITH_WORDS.warning(
                    span,
                    "Words in a G54–G59 block are ignored by ServoWorks; put the coordinate system selection alone on its line and the other words on the next one.",
                )
                .with_related(wcs.span, "coordinate system selection"),
            );
        }
    }
}
