//! S009: upper-case O-word letters.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity, TextEdit};
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::ItemKind;

use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out O-word statements written with a capital `O`.
    ///
    /// ## Why is this bad?
    /// The LinuxCNC documentation writes O-codes with a lower-case `o`, which keeps them
    /// apart from the digit `0` when read.
    ///
    /// ## Example
    /// ```ngc
    /// O100 sub
    /// O100 endsub
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// o100 sub
    /// o100 endsub
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default; a fix lower-cases the letter.
    ///
    /// Implements: NGC709
    pub static LOWERCASE_O = {
        code: "S009",
        name: "lowercase-o-word",
        summary: "Write O-codes with a lower-case o",
        implements: &["NGC709"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct LowercaseO;

impl Rule for LowercaseO {
    fn meta(&self) -> &'static RuleMeta {
        &LOWERCASE_O
    }

    /// A report needs an O-word.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Rs274ngc {
            return;
        }
        for item in cx.items() {
            if !matches!(item.kind, ItemKind::OWord(_))
                || cx.program.byte_at(item.span.start as usize) != Some(b'O')
            {
                continue;
            }
            let at = Span::new(item.span.start, item.span.start + 1);
            out.push(
                LOWERCASE_O.diagnostic(
                    Severity::Hint,
                    at,
                    "Write O-codes with a lower-case `o`; it is easier to tell from the digit 0.",
                )
                .with_fix(
                    "Use a lower-case o",
                    vec![TextEdit {
                        span: at,
                        new_text: "o".into(),
                    }],
                ),
            );
        }
    }
}
