//! W013: a ServoWorks M98 name glued to the next word.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::WordValue;

use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags a ServoWorks `M98 P` subprogram name that starts with digits and runs on into
    /// an address letter, such as `M98 P100R5`.
    ///
    /// ## Why is this bad?
    /// A subprogram name runs up to the next blank, so `P100R5` calls a program named
    /// `100R5` instead of calling `100` five times. Separate the repeat count with a space.
    ///
    /// ## Example
    /// ```servoworks
    /// M98 P100R5
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// M98 P100 R5
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, warning; a fix inserts the space.
    ///
    /// Implements: SW151
    pub static SUBPROGRAM_NAME_GLUED = {
        code: "W013",
        name: "subprogram-name-glued",
        summary: "M98 name glued to the next word",
        implements: &["SW151"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct SubprogramNameGlued;

impl Rule for SubprogramNameGlued {
    fn meta(&self) -> &'static RuleMeta {
        &SUBPROGRAM_NAME_GLUED
    }

    /// A report needs a P word whose value is a name.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Servoworks || !cx.has_code('M', 980) {
            return;
        }
        for (item, w) in cx.words() {
            let (b'P', WordValue::Name(name)) = (w.letter, w.value) else {
                continue;
            };
            let bytes = cx.program.slice(name);
            let digits = bytes.iter().take_while(|b| b.is_ascii_digit()).count();
            if digits == 0 || digits == bytes.len() || !bytes[digits].is_ascii_uppercase() {
                continue;
            }
            let at = name.start + digits as u32;
            let head = String::from_utf8_lossy(&bytes[..digits]).into_owned();
            let tail = String::from_utf8_lossy(&bytes[digits..]).into_owned();
            out.push(
                SUBPROGRAM_NAME_GLUED.warning(
                    item.span,
                    format!("The subprogram name runs on into `{tail}`: this calls a program named `{head}{tail}`. If `{tail}` is a separate word, put a space before it."),
                )
                .with_fix(format!("Insert a space before `{tail}`"), vec![TextEdit { span: Span::new(at, at), new_text: " ".into() }]),
            );
        }
    }
}
