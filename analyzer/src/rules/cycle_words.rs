//! W020: words and codes a canned-cycle block should not carry.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{code_name, is_drilling_cycle, is_emc2, word_item};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks blocks that command a canned cycle: words the cycle does not use (ServoWorks:
    /// `Q` in G81/G82/G84/G85/G86/G89, `P` in G73/G81/G83/G85/G86); rotary axis words, and
    /// X/Y/Z mixed with U/V/W (RS274/NGC); cycles whose behaviour LinuxCNC leaves
    /// undefined (`G87`, `G88`; `G84` in `emc2`); and a FANUC `M98` in the cycle block.
    ///
    /// ## Why is this bad?
    /// An unused word is ignored but kept as modal data, which surprises the next cycle.
    /// LinuxCNC refuses rotary and mixed axis words in cycles. FANUC requires `M98` in a
    /// block of its own while a cycle is active.
    ///
    /// ## Example
    /// ```ngc
    /// G17 G81 X1 Y1 Z-1 R1 A10 F100
    /// G80
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 A10
    /// G17 G81 X1 Y1 Z-1 R1 F100
    /// G80
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error for rotary or mixed axis words, warning for undefined cycles.
    /// ServoWorks: warning for unused words. FANUC: error for `M98`. Lines that continue a
    /// modal cycle without its code are checked by the runtime.
    ///
    /// Reported by this rule, not X003, when both see M98 in a block with a canned cycle's axis words on the same text (one diagnostic per fault).
    ///
    /// Implements: SW132, NGC309, NGC314, NGC317, FAN083
    pub static CYCLE_WORDS = {
        code: "W020",
        name: "cycle-words",
        summary: "Words and codes a canned-cycle block should not carry",
        implements: &["SW132", "NGC309", "NGC314", "NGC317", "FAN083"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct CycleWords;

impl Rule for CycleWords {
    fn meta(&self) -> &'static RuleMeta {
        &CYCLE_WORDS
    }

    /// A report needs a canned-cycle G code.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"G")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let Some(cycle) = cx
            .codes
            .iter()
            .find(|c| c.letter == 'G' && c.num.is_some_and(|n| is_drilling_cycle(d, n.0)))
        else {
            return;
        };
        let Some(num) = cycle.num else { return };
        let name = code_name(d, 'G', num);
        match d {
            Dialect::Servoworks => {
                let unused: &[u8] = match num.0 {
                    810 | 850 | 860 => b"QP",
                    820 | 840 | 890 => b"Q",
                    730 | 830 => b"P",
                    _ => b"",
                };
                for l in unused {
                    if let Some((i, _)) = word_item(cx, *l) {
                        out.push(
                            CYCLE_WORDS.warning(i.span, format!("{name} does not use {}: the word is ignored here but stays as modal data for later cycles.", *l as char))
                                .with_related(cycle.span, "canned cycle"),
                        );
                    }
                }
            }
            Dialect::Rs274ngc => {
                let emc2 = is_emc2(cx.settings);
                if let Some((i, w)) = cx
                    .words()
                    .find(|(_, w)| matches!(w.letter, b'A' | b'B' | b'C'))
                {
                    out.push(
                        CYCLE_WORDS.error(i.span, format!("{} axis word in a canned-cycle line: LinuxCNC does not move rotary axes in cycles. Move it to its own line.", w.letter_char()))
                            .with_related(cycle.span, "canned cycle"),
                    );
                }
                let xyz = cx
                    .words()
                    .find(|(_, w)| matches!(w.letter, b'X' | b'Y' | b'Z'));
                let uvw = cx
                    .words()
                    .find(|(_, w)| matches!(w.letter, b'U' | b'V' | b'W'));
                if let (false, Some(_), Some((i, _))) = (emc2, xyz, uvw) {
                    out.push(CYCLE_WORDS.error(i.span, "X/Y/Z and U/V/W words mixed in a canned cycle: a cycle works on one set of axes."));
                }
                let undefined = matches!(num.0, 870 | 880) || (emc2 && num.0 == 840);
                if undefined {
                    out.push(CYCLE_WORDS.warning(
                        cycle.span,
                        format!("The behaviour of {name} is not fully defined by RS274/NGC (it depends on manual spindle and operator steps); check it on the machine before relying on it."),
                    ));
                }
            }
            Dialect::Fanuc => {
                if let Some(m98) = cx.codes.iter().find(|c| c.is('M', 980)) {
                    out.push(
                        CYCLE_WORDS.error(m98.span, "M98 in a canned-cycle block: while a cycle is active the subprogram call must be a block of its own.")
                            .with_related(cycle.span, "canned cycle"),
                    );
                }
            }
        }
    }
}
