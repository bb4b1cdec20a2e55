//! W005: address letters the dialect or the machine does not have.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{has, is_emc2, is_machine_axis};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags words whose letter the dialect does not define (for example `E`, `U`, `V`, `W`
    /// in the 2007 RS274/NGC profile), and axis words for axes the configured machine does
    /// not have (`machine.axes` in `partscope.toml`; default X Y Z A B C).
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops with `Unknown word starting with …` or an unconfigured-axis error;
    /// FANUC raises PS0009. ServoWorks treats an axis it does not have as an error, and the
    /// manual names its axes X, Y, Z, A, B, C only: `E`, `U`, `V`, `W` as axis names work
    /// only when the machine is set up that way.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X1 U2
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X1 Y2
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error; ServoWorks `E`/`U`/`V`/`W` axes that are configured get a warning.
    /// Words of a `G65`/`G66` macro call are arguments, not axes, and are not checked.
    ///
    /// Reported by this rule, not X003, when both see a word letter the machine or profile does not have on the same text (one diagnostic per fault).
    ///
    /// Implements: SW015, SW016, NGC007, NGC231, FAN001
    pub static UNKNOWN_ADDRESS = {
        code: "W005",
        name: "unknown-address",
        summary: "Address letter the dialect or machine does not have",
        implements: &["SW015", "SW016", "NGC007", "NGC231", "FAN001"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct UnknownAddress;

/// The letters the dialect reads as words other than axes, and its axis letters,
/// as bit masks: one test per word instead of two byte scans.
fn letter_sets(d: Dialect, emc2: bool) -> (u128, u128) {
    match d {
        Dialect::Rs274ngc if emc2 => (
            const { letters(b"DFGHIJKLMNPQRST") },
            const { letters(b"XYZABC") },
        ),
        Dialect::Rs274ngc => (
            const { letters(b"DEFGHIJKLMNPQRST$@^") },
            const { letters(b"XYZABCUVW") },
        ),
        Dialect::Servoworks => (
            const { letters(b"DFGHIJKLMNOPQRST") },
            const { letters(b"XYZABCEUVW") },
        ),
        Dialect::Fanuc => (
            const { letters(b"DEFGHIJKLMNOPQRST") },
            const { letters(b"XYZABCUVW") },
        ),
    }
}

/// The set of ASCII letters in `s`, one bit per byte value.
const fn letters(s: &[u8]) -> u128 {
    let mut m = 0u128;
    let mut i = 0;
    while i < s.len() {
        m |= 1u128 << (s[i] & 127);
        i += 1;
    }
    m
}

impl Rule for UnknownAddress {
    fn meta(&self) -> &'static RuleMeta {
        &UNKNOWN_ADDRESS
    }

    /// A word's verdict depends on its letter alone (a G65/G66 call only
    /// silences some): the rule may report on a letter the dialect does not read
    /// as a non-axis word unless it is a configured axis (and, for ServoWorks, not
    /// one of the E/U/V/W axes it warns about).
    fn interest(&self, settings: &crate::Settings) -> Interest {
        let (other, axes) = letter_sets(settings.dialect, is_emc2(settings));
        let configured = settings
            .axes
            .iter()
            .filter(|a| a.is_ascii())
            .fold(0u128, |m, a| m | 1u128 << (*a as u8 & 127));
        let warned = if settings.dialect == Dialect::Servoworks {
            const { letters(b"EUVW") }
        } else {
            0
        };
        Interest {
            letters: !other & !(axes & configured & !warned),
            ..Interest::NONE
        }
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let emc2 = is_emc2(cx.settings);
        let (other, axes) = letter_sets(d, emc2);
        let in_set = |set: u128, l: u8| l < 128 && set & (1u128 << l) != 0;
        let macro_call =
            d != Dialect::Rs274ngc && (has(cx, 'G', 650) || has(cx, 'G', 660) || has(cx, 'G', 661));
        for (item, w) in cx.words() {
            if w.comma || in_set(other, w.letter) {
                continue;
            }
            let l = w.letter_char();
            if !in_set(axes, w.letter) {
                let msg = match d {
                    Dialect::Rs274ngc => format!(
                        "Unknown word starting with {l}: {l} is not a word letter in the `{}` profile.",
                        cx.settings.variant.as_str()
                    ),
                    _ => format!("{l} is not an address of this control (FANUC alarm PS0009)."),
                };
                out.push(UNKNOWN_ADDRESS.error(item.span, msg));
                continue;
            }
            if macro_call {
                continue;
            }
            let configured = is_machine_axis(cx.settings, w.letter);
            if d == Dialect::Servoworks
                && matches!(w.letter, b'E' | b'U' | b'V' | b'W')
                && configured
            {
                out.push(UNKNOWN_ADDRESS.warning(
                    item.span,
                    format!("{l} as an axis name: the ServoWorks manual names axes X, Y, Z, A, B, C only. Make sure the control is configured with a {l} axis."),
                ));
                continue;
            }
            // LinuxCNC reads the profile of a G70-G72 cycle with U and W as relative
            // X and Z, whatever the machine's axes; a program with such a cycle may
            // use them in its profile subroutines.
            if !configured
                && d == Dialect::Rs274ngc
                && matches!(w.letter, b'U' | b'W')
                && cx
                    .file
                    .map_or_else(|| has_lathe_cycle(cx.program), |f| f.lathe_cycle)
            {
                continue;
            }
            if !configured {
                let have: String = cx.settings.axes.iter().collect();
                out.push(UNKNOWN_ADDRESS.error(
                    item.span,
                    format!("The machine has no {l} axis (configured axes: {have}); the control rejects the word. Fix the letter, or add the axis to `machine.axes` in partscope.toml."),
                ));
            }
        }
    }
}

/// Whether the program has a G70, G71 or G72 cycle (any form) with a literal code.
pub(crate) fn has_lathe_cycle(p: &crate::syntax::Program) -> bool {
    p.blocks.iter().any(|b| {
        p.items_of(b).iter().any(|it| match &it.kind {
            crate::syntax::ItemKind::Word(w) => {
                w.letter == b'G' && w.num().is_some_and(|n| (70.0..73.0).contains(&n.value))
            }
            _ => false,
        })
    })
}
