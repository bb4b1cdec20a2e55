//! W023: notes on codes whose effect is easy to misread (off by default).

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{axis_words, has, has_axis_word, lit, word_item};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Adds notes where the manuals describe an effect that is easy to misread.
    /// ServoWorks: `L` in a `G10`/`G65` block is not a direct output; an M code in a motion
    /// block runs after the motion; `G10 L2` has no documented format; `G10 L10909`
    /// changes a position-loop gain; mirroring one axis reverses arcs; `G51` with some of
    /// I/J/K keeps the others. FANUC: `G04 P` is milliseconds; `G60`'s group depends on
    /// parameter MDL; `G25`/`G26` next to `G40.1`–`G42.1` (both listed as group 19); `G88`
    /// waits for the operator; an M code in a repeated cycle block runs once.
    ///
    /// ## Why is this bad?
    /// Nothing is wrong in itself; the notes explain what the control will do, which is
    /// not always what the block seems to say.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// G04 P500;
    /// M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// G04 X0.5;
    /// M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks and FANUC, info, off by default (select `W023`).
    ///
    /// Implements: SW069, SW104, SW106, SW142, SW144, SW150, FAN026, FAN028, FAN086, FAN089, FAN151
    pub static CONTROL_NOTES = {
        code: "W023",
        name: "control-notes",
        summary: "Notes on codes whose effect is easy to misread",
        implements: &["SW069", "SW104", "SW106", "SW142", "SW144", "SW150", "FAN026", "FAN028", "FAN086", "FAN089", "FAN151"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct ControlNotes;

impl Rule for ControlNotes {
    fn meta(&self) -> &'static RuleMeta {
        &CONTROL_NOTES
    }

    /// Every note is about a G or M code.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NOT_AXIS_FEED
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let note = |out: &mut Vec<Diagnostic>, span, msg: &str| {
            out.push(CONTROL_NOTES.info(span, msg.to_string()))
        };
        match cx.program.dialect {
            Dialect::Servoworks => {
                let g10 = has(cx, 'G', 100);
                if let Some((l, w)) = word_item(cx, b'L') {
                    if g10 || has(cx, 'G', 650) {
                        note(out, l.span, "L in a G10 or G65 block is the data category or repeat count, not a direct digital output.");
                    }
                    if g10 && lit(w) == Some(2.0) {
                        note(out, l.span, "G10 L2 (workpiece zero offsets) is only mentioned in the manual; its word format is not documented, so check the result on the control.");
                    }
                    if g10 && lit(w) == Some(10909.0) {
                        note(out, l.span, "This changes a position-loop gain from the program; too high a gain can make the axis vibrate or become unstable.");
                    }
                }
                if let Some(m) = cx.codes.iter().find(|c| c.is('G', 511)) {
                    if axis_words(cx).count() == 1 {
                        note(out, m.span, "Mirroring a single axis reverses the direction of G02/G03 arcs and of cutter compensation.");
                    }
                }
                if let Some(g51) = cx.codes.iter().find(|c| c.is('G', 510)) {
                    let n = [b'I', b'J', b'K']
                        .into_iter()
                        .filter(|l| word_item(cx, *l).is_some())
                        .count();
                    if n == 1 || n == 2 {
                        note(out, g51.span, "G51 with only some of I/J/K: the missing factors keep the values of the previous G51.");
                    }
                }
                if has_axis_word(cx) {
                    if let Some(m) = cx
                        .codes
                        .iter()
                        .find(|c| c.letter == 'M' && !c.is('M', 980) && !c.is('M', 990))
                    {
                        note(out, m.span, "An M code in a motion block runs after the motion has finished. Put it on the line before if it must act first.");
                    }
                }
            }
            Dialect::Fanuc => {
                if has(cx, 'G', 40) {
                    if let Some((p, w)) = word_item(cx, b'P') {
                        if w.num().is_some_and(|n| !n.has_point) {
                            note(
                                out,
                                p.span,
                                "G04 P is in milliseconds: P1000 dwells one second.",
                            );
                        }
                    }
                }
                let cycle = cx.codes.iter().find(|c| {
                    c.letter == 'G'
                        && c.num
                            .is_some_and(|n| super::util::is_drilling_cycle(Dialect::Fanuc, n.0))
                });
                if let Some(cyc) = cycle {
                    if cyc.is('G', 880) {
                        note(out, cyc.span, "G88 stops at the hole bottom for a manual operation; the cycle time includes the operator's time.");
                    }
                    let repeats = word_item(cx, b'K')
                        .and_then(|(_, w)| lit(w))
                        .is_some_and(|k| k >= 2.0);
                    if let (true, Some(m)) = (repeats, cx.codes.iter().find(|c| c.letter == 'M')) {
                        note(out, m.span, "An M code in a cycle block with K repeats runs for the first hole only.");
                    }
                }
                if let Some(g60) = cx.codes.iter().find(|c| c.is('G', 600)) {
                    note(out, g60.span, "G60 is one-shot (group 00) or modal (group 01) depending on parameter MDL (No. 5431#0).");
                }
                let spindle = cx.codes.iter().find(|c| c.is('G', 250) || c.is('G', 260));
                let ndc = cx
                    .codes
                    .iter()
                    .find(|c| c.is('G', 401) || c.is('G', 411) || c.is('G', 421));
                if let (Some(s), Some(_)) = (spindle, ndc) {
                    note(out, s.span, "The manual lists G25/G26 and G40.1–G42.1 both as group 19; they are treated as independent here, so both take effect.");
                }
            }
            Dialect::Rs274ngc => {}
        }
    }
}
