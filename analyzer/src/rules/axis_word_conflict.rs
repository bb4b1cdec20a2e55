//! W004: axis words claimed by two codes, or by none.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{axis_words, code_name, is_emc2};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags a block where a non-modal code that takes axis words (`G10`, `G28`, `G30`,
    /// `G92`, `G52` …) is written together with an explicit group-1 motion code, and an
    /// RS274/NGC line with axis words and an explicit `G80` but nothing that uses them, and a
    /// LinuxCNC `G43.1` (whose axis words are offsets) with a motion code.
    ///
    /// ## Why is this bad?
    /// Both codes want the same X/Y/Z words. LinuxCNC refuses the line (`Cannot use two G
    /// codes that both use axis values`, `Cannot use axis values with G80`). FANUC gives
    /// the axis words to the group-00 code; the motion code only becomes the new modal
    /// state, so the move you meant does not happen.
    ///
    /// ## Example
    /// ```ngc
    /// G1 G28 Z10 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G28 Z10
    /// G1 Z5 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error (`G80` next to a group-0 axis code is fine). FANUC: warning; `G53`
    /// with `G00`/`G01` is the normal machine-coordinate move and is not flagged, and
    /// `G28`/`G30` with `G00` (`G91 G28 G00 X0 Y0`, which moves at rapid anyway) is
    /// information.
    /// ServoWorks: not checked (the manual is silent).
    ///
    /// Implements: NGC106, NGC108, NGC805, FAN027
    pub static AXIS_WORD_CONFLICT = {
        code: "W004",
        name: "axis-word-conflict",
        summary: "Axis words claimed by two codes, or by none",
        implements: &["NGC106", "NGC108", "NGC805", "FAN027"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct AxisWordConflict;

impl Rule for AxisWordConflict {
    fn meta(&self) -> &'static RuleMeta {
        &AXIS_WORD_CONFLICT
    }

    /// Every report needs a G code that takes the axis words or a motion code.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"G")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let consumers: &[u32] = match d {
            Dialect::Rs274ngc if is_emc2(cx.settings) => &[100, 280, 300, 920],
            Dialect::Rs274ngc => &[100, 280, 300, 920, 520],
            Dialect::Fanuc => &[100, 270, 280, 290, 300, 520, 920],
            Dialect::Servoworks => return,
        };
        let consumer = cx
            .codes
            .iter()
            .find(|c| c.letter == 'G' && c.num.is_some_and(|n| consumers.contains(&n.0)));
        let motion = cx
            .codes
            .iter()
            .find(|c| c.letter == 'G' && c.group() == Some(1) && c.num.is_some_and(|n| n.0 != 800));
        let first_axis = axis_words(cx).next();
        if let (Some(g0), Some(m)) = (consumer, motion) {
            let (Some(gn), Some(mn)) = (g0.num, m.num) else {
                return;
            };
            let (gname, mname) = (code_name(d, 'G', gn), code_name(d, 'G', mn));
            let diag = if d == Dialect::Rs274ngc {
                AXIS_WORD_CONFLICT.error(
                    m.span,
                    format!("Cannot use two G codes that both use axis values: {gname} and {mname} both take the axis words of this line. Put {mname} on its own line."),
                )
            } else {
                if first_axis.is_none() {
                    return;
                }
                let text = format!("{gname} takes the axis words of this block; {mname} only becomes the modal motion and does not move. Put the {mname} move in its own block.");
                // `G91 G28 G00 X0 Y0` is a shop idiom: G28 moves at rapid anyway and
                // the G00 only sets the mode, so nothing the block says is lost.
                if mn.0 == 0 && matches!(gn.0, 280 | 300) {
                    AXIS_WORD_CONFLICT.info(m.span, text)
                } else {
                    AXIS_WORD_CONFLICT.warning(m.span, text)
                }
            };
            out.push(diag.with_related(g0.span, "group-00 code that uses the axis words"));
            return;
        }
        if d == Dialect::Rs274ngc && !is_emc2(cx.settings) {
            if let (Some(tlo), Some(m)) = (cx.codes.iter().find(|c| c.is('G', 431)), motion) {
                out.push(
                    AXIS_WORD_CONFLICT.error(
                        m.span,
                        "G43.1 takes the axis words of this line as tool offsets, so motion on the same line is refused. Put the move on the next line.",
                    )
                    .with_related(tlo.span, "dynamic tool length offset"),
                );
                return;
            }
        }
        if let (Dialect::Rs274ngc, None, Some((axis, _))) = (d, consumer, first_axis) {
            let modern_axis_users =
                !is_emc2(cx.settings) && (cx.has_code('G', 431) || cx.has_code('G', 432));
            if let Some(g80) = cx.codes.iter().find(|c| c.is('G', 800)) {
                if motion.is_none() && !modern_axis_users {
                    out.push(
                        AXIS_WORD_CONFLICT.error(
                            axis.span,
                            "Cannot use axis values with G80: G80 cancels the motion mode, so nothing on this line uses the axis words. Remove them, or add the motion code that should use them.",
                        )
                        .with_related(g80.span, "G80"),
                    );
                }
            }
        }
    }
}
