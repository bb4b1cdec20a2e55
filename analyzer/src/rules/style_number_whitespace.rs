//! S004: whitespace inside RS274/NGC numbers.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity, TextEdit};
use crate::dialect::Dialect;

use super::{BlockCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out blanks inside a number, such as `X1 .5` or `X0. 12`.
    ///
    /// ## Why is this bad?
    /// RS274/NGC removes all blanks before reading a line, so `X1 .5` is `X1.5`; a reader
    /// sees two things. The seed asks for a space before each word and none inside numbers.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X1 .5
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X1.5
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default; a fix removes the blanks.
    ///
    /// Implements: NGC701
    pub static NUMBER_WHITESPACE = {
        code: "S004",
        name: "whitespace-in-number",
        summary: "Blanks inside a number",
        implements: &["NGC701"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct NumberWhitespace;

impl Rule for NumberWhitespace {
    fn meta(&self) -> &'static RuleMeta {
        &NUMBER_WHITESPACE
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Rs274ngc {
            return;
        }
        for (_, w) in cx.words() {
            let Some(n) = w.num() else { continue };
            // Decoding the text is only worth it when the number holds a blank at all.
            if !cx
                .program
                .slice(n.span)
                .iter()
                .any(|b| matches!(b, b' ' | b'\t'))
            {
                continue;
            }
            let text = cx.program.str_of(n.span);
            let trimmed = text.trim_end_matches([' ', '\t']);
            if trimmed.contains([' ', '\t']) {
                let compact: String = trimmed
                    .chars()
                    .filter(|c| !matches!(c, ' ' | '\t'))
                    .collect();
                let span =
                    crate::span::Span::new(n.span.start, n.span.start + trimmed.len() as u32);
                out.push(
                    NUMBER_WHITESPACE.diagnostic(
                        Severity::Hint,
                        span,
                        format!("Blanks inside the number `{trimmed}`: it is read as `{compact}`. Write it without blanks."),
                    )
                    .with_fix("Remove the blanks", vec![TextEdit { span, new_text: compact }]),
                );
            }
        }
    }
}
