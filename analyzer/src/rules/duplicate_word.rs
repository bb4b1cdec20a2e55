//! W001: the same address twice in a block.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;

use super::util::{has, removal_span};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags an address letter written twice in one block, such as `X13.0 … X2.0`.
    ///
    /// ## Why is this bad?
    /// RS274/NGC refuses the line (`Multiple X words on one line`). ServoWorks keeps the
    /// first occurrence and silently ignores the others, which is what happens when two
    /// blocks are joined on one line: the second block's words are lost. FANUC accepts one
    /// word per address too.
    ///
    /// ## Example
    /// ```servoworks
    /// N100 G00 X13.0 Z3.0 X2.0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// N100 G00 X13.0 Z3.0
    /// N110 X2.0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error (G and M words are checked by G001/G002/G003 instead).
    /// ServoWorks: warning, M words included; a fix removes the ignored word. FANUC: warning;
    /// repeated I/J/K in a `G65` block are argument specification II and are not flagged.
    ///
    /// Implements: SW005, NGC103
    pub static DUPLICATE_WORD = {
        code: "W001",
        name: "duplicate-word",
        summary: "Same address twice in a block",
        implements: &["SW005", "NGC103"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct DuplicateWord;

impl Rule for DuplicateWord {
    fn meta(&self) -> &'static RuleMeta {
        &DUPLICATE_WORD
    }

    /// Without a repeated letter there is no duplicate to report (comma words
    /// count as other contents).
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest {
            repeated: !0,
            ..Interest::OTHER
        }
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let macro_call =
            d == Dialect::Fanuc && (has(cx, 'G', 650) || has(cx, 'G', 660) || has(cx, 'G', 661));
        // Most blocks repeat no letter: one pass over bit sets proves it without allocating.
        let (mut seen, mut seen_comma, mut repeat) = (0u128, 0u128, false);
        for (_, w) in cx.words() {
            let bit = 1u128 << (w.letter & 127);
            let set = if w.comma { &mut seen_comma } else { &mut seen };
            repeat |= *set & bit != 0;
            *set |= bit;
        }
        if !repeat {
            return;
        }
        let words: Vec<_> = cx.words().collect();
        for (j, (item, w)) in words.iter().enumerate() {
            if w.letter == b'G' || (w.letter == b'M' && d != Dialect::Servoworks) {
                continue;
            }
            if macro_call && matches!(w.letter, b'I' | b'J' | b'K') {
                continue;
            }
            let Some((first, _)) = words[..j]
                .iter()
                .find(|(_, e)| e.letter == w.letter && e.comma == w.comma)
            else {
                continue;
            };
            let l = if w.comma {
                format!(",{}", w.letter_char())
            } else {
                w.letter_char().to_string()
            };
            let text = cx.program.str_of(item.span).into_owned();
            let diag = match d {
                Dialect::Rs274ngc => DUPLICATE_WORD.error(
                    item.span,
                    format!("Multiple {l} words on one line: each letter may appear once. Remove one, or split the line."),
                ),
                Dialect::Servoworks => {
                    let d = DUPLICATE_WORD.warning(
                        item.span,
                        format!("{l} appears twice in this block; ServoWorks uses only the first one and ignores `{text}`. If this is a second block, put it on its own line."),
                    );
                    // The text of the block decides how P is read (a name after
                    // M98), so removing an ignored M98 would change another word.
                    if text.to_ascii_uppercase().contains("98") && w.letter == b'M' {
                        d
                    } else {
                        d.with_fix(format!("Remove the ignored `{text}`"), vec![TextEdit { span: removal_span(cx.program, item.span), new_text: String::new() }])
                    }
                }
                Dialect::Fanuc => DUPLICATE_WORD.warning(
                    item.span,
                    format!("{l} appears twice in this block; a FANUC block takes one word per address (depending on parameters the control raises an alarm or keeps only one). Remove one, or split the block."),
                ),
            };
            out.push(diag.with_related(first.span, "first occurrence"));
        }
    }
}
