//! W010: motion in a ServoWorks M98 block.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::axis_words;
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags axis words in the same ServoWorks block as a subprogram call `M98`.
    ///
    /// ## Why is this bad?
    /// ServoWorks ignores the motion of an `M98` block: the subprogram is called and the
    /// move never happens.
    ///
    /// ## Example
    /// ```servoworks
    /// G01 X10.0 F100.0 M98 PMoveXY
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G01 X10.0 F100.0
    /// M98 PMoveXY
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, warning.
    ///
    /// Implements: SW024
    pub static M98_WITH_MOTION = {
        code: "W010",
        name: "m98-with-motion",
        summary: "Motion in a ServoWorks M98 block is ignored",
        implements: &["SW024"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct M98WithMotion;

impl Rule for M98WithMotion {
    fn meta(&self) -> &'static RuleMeta {
        &M98_WITH_MOTION
    }

    /// A report needs M98.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"M")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Servoworks {
            return;
        }
        let Some(call) = cx.codes.iter().find(|c| c.is('M', 980)) else {
            return;
        };
        let mut axes = axis_words(cx);
        if let Some((first, _)) = axes.next() {
            let span = axes.fold(first.span, |s, (i, _)| s.cover(i.span));
            out.push(
                M98_WITH_MOTION.warning(
                    span,
                    "The motion in an M98 block is ignored: ServoWorks only calls the subprogram. Put the move on its own line before the call.",
                )
                .with_related(call.span, "subprogram call"),
            );
        }
    }
}
