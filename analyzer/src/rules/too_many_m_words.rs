//! G003: more M words in a block than the control accepts.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Counts the M words of a block: more than four on an RS274/NGC line, or more than
    /// one on a FANUC block.
    ///
    /// ## Why is this bad?
    /// LinuxCNC accepts at most four M words per line (`Too many m codes on line`). A FANUC
    /// control accepts one M code per block unless the multiple-M option (parameter 3404#7
    /// M3B) is set, and then at most three; otherwise it raises an alarm.
    ///
    /// ## Example
    /// ```ngc
    /// M3 M8 M48 M62 P1 M66 P0 L0
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// M3 M8 M48
    /// M62 P1
    /// M66 P0 L0
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error above four. FANUC: error above three; warning for two or three (needs
    /// the multiple-M option). ServoWorks does not state a limit.
    ///
    /// Implements: NGC101, FAN016
    pub static TOO_MANY_M_WORDS = {
        code: "G003",
        name: "too-many-m-words",
        summary: "More M words in a block than the control accepts",
        implements: &["NGC101", "FAN016"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct TooManyMWords;

impl Rule for TooManyMWords {
    fn meta(&self) -> &'static RuleMeta {
        &TOO_MANY_M_WORDS
    }

    /// Only two or more M words are reported.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::repeated(b"M")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let m: Vec<_> = cx
            .words()
            .filter(|(_, w)| w.letter == b'M' && !w.comma)
            .collect();
        let n = m.len();
        match cx.program.dialect {
            Dialect::Rs274ngc if n > 4 => out.push(TOO_MANY_M_WORDS.error(
                m[4].0.span,
                format!("Too many m codes on line: {n} M words, LinuxCNC accepts at most 4. Move the extra M codes to another line."),
            )),
            Dialect::Fanuc if n > 3 => out.push(TOO_MANY_M_WORDS.error(
                m[3].0.span,
                format!("{n} M codes in one block: even with the multiple-M option (parameter 3404#7) a FANUC block takes at most 3. Move the extra M codes to another block."),
            )),
            Dialect::Fanuc if n > 1 => out.push(TOO_MANY_M_WORDS.warning(
                m[1].0.span,
                format!("{n} M codes in one block need the multiple-M option (parameter 3404#7 M3B); without it the control raises an alarm. Put each M code in its own block if the option is not set."),
            )),
            _ => {}
        }
    }
}
