//! G001: two G codes of one modal group in a block.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::ItemKind;

use super::util::{code_name, is_drilling_cycle, removal_span};
use super::{BlockCode, BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags a block that holds two G codes of the same modal group, such as `G00` and
    /// `G01`, or `G90` and `G91`. On FANUC and ServoWorks it also flags a group-01 motion
    /// code written in the same block as a canned cycle.
    ///
    /// ## Why is this bad?
    /// A group can only be in one state. RS274/NGC refuses the line (`Two G codes used
    /// from same modal group`); it silently drops a `G80` written next to another motion
    /// code. ServoWorks and FANUC keep the last code of the group and ignore the others,
    /// so `G01 X10 G00 Y20` moves both axes at rapid. A group-01 code in a canned-cycle
    /// block cancels the cycle: the block runs as plain motion and no hole is drilled.
    ///
    /// ## Example
    /// ```ngc
    /// G0 G1 X10 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X0
    /// G1 X10 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error, except for `G80` beside another motion code, which is dropped:
    /// a warning when that code is a canned cycle (the block drills instead of
    /// cancelling), information otherwise (`G0 G80` ends the cycle either way); when
    /// only G codes precede the second code, a quick fix splits the line before it.
    /// ServoWorks and FANUC: warning; a quick fix removes the code that has no effect.
    /// Groups come from each dialect's code table; ServoWorks and FANUC group 00 codes are
    /// one-shot and may share a block.
    ///
    /// Implements: SW006, SW116, NGC100, NGC113, FAN021, FAN022, FAN109
    pub static MODAL_GROUP_CONFLICT = {
        code: "G001",
        name: "modal-group-conflict",
        summary: "Two G codes of one modal group in a block",
        implements: &["SW006", "SW116", "NGC100", "NGC113", "FAN021", "FAN022", "FAN109"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ModalGroupConflict;

impl Rule for ModalGroupConflict {
    fn meta(&self) -> &'static RuleMeta {
        &MODAL_GROUP_CONFLICT
    }

    /// A report needs two G codes.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::repeated(b"G")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let known_g = |c: &&BlockCode| c.letter == 'G' && c.info.is_some();
        for (j, later) in cx.codes.iter().enumerate().filter(|(_, c)| known_g(c)) {
            let Some(group) = later.group() else { continue };
            if group == 0 && d != Dialect::Rs274ngc {
                continue;
            }
            let Some(earlier) = cx.codes[..j]
                .iter()
                .filter(known_g)
                .find(|e| e.group() == Some(group))
            else {
                continue;
            };
            let (Some(en), Some(ln)) = (earlier.num, later.num) else {
                continue;
            };
            let e_name = code_name(d, 'G', en);
            let l_name = code_name(d, 'G', ln);
            let diag = match d {
                Dialect::Rs274ngc if group == 1 && (en.0 == 800 || ln.0 == 800) => {
                    let (g80, other, on) = if en.0 == 800 { (*earlier, &l_name, ln) } else { (*later, &e_name, en) };
                    if is_drilling_cycle(d, on.0) || on.0 == 760 {
                        MODAL_GROUP_CONFLICT.warning(
                            g80.span,
                            format!("G80 is dropped: {other} on the same line starts the cycle, so the block drills instead of cancelling. Put the G80 on its own line if the cycle must be cancelled first."),
                        )
                    } else {
                        // `G0 G80` is a common CAM idiom: the motion code ends the cycle anyway.
                        MODAL_GROUP_CONFLICT.info(
                            g80.span,
                            format!("G80 has no effect: {other} on the same line sets the motion mode, which ends any canned cycle as well."),
                        )
                    }
                }
                Dialect::Rs274ngc => {
                    let d = MODAL_GROUP_CONFLICT.error(
                        later.span,
                        format!("Two G codes used from same modal group: {e_name} and {l_name} are both in group {group}, and the interpreter refuses the line. Keep one, or put them on separate lines."),
                    );
                    match split_fix(cx, later.item) {
                        Some(edit) => d.with_fix(format!("Put {l_name} and the rest of the line on a new line"), vec![edit]),
                        None => d,
                    }
                }
                _ if en == ln => MODAL_GROUP_CONFLICT.warning(
                    later.span,
                    format!("{l_name} is written twice in this block; the second one changes nothing. Remove one (if this is a second block, put it on its own line)."),
                )
                .with_fix(
                    format!("Remove the repeated {e_name}"),
                    vec![TextEdit { span: removal_span(cx.program, earlier.span), new_text: String::new() }],
                ),
                _ => MODAL_GROUP_CONFLICT.warning(
                    later.span,
                    format!("{e_name} and {l_name} are both in modal group {group:02}; only the last one ({l_name}) takes effect and {e_name} is ignored. Remove {e_name}, or put it on its own line."),
                )
                .with_fix(
                    format!("Remove the ineffective {e_name}"),
                    vec![TextEdit { span: removal_span(cx.program, earlier.span), new_text: String::new() }],
                ),
            };
            let other = if diag.span == earlier.span {
                later.span
            } else {
                earlier.span
            };
            out.push(diag.with_related(other, "the other code of the group"));
        }
        if d != Dialect::Rs274ngc {
            // By number, so the check does not depend on how complete a table is.
            let motion = cx
                .codes
                .iter()
                .find(|c| c.letter == 'G' && c.num.is_some_and(|n| [0, 10, 20, 30].contains(&n.0)));
            let cycle = cx
                .codes
                .iter()
                .find(|c| c.letter == 'G' && c.num.is_some_and(|n| is_drilling_cycle(d, n.0)));
            if let (Some(m), Some(c)) = (motion, cycle) {
                let (Some(mn), Some(cn)) = (m.num, c.num) else {
                    return;
                };
                out.push(
                    MODAL_GROUP_CONFLICT.warning(
                        m.span,
                        format!(
                            "{} cancels the canned cycle {} written in the same block: the block runs as {} motion and no hole is made. Put the positioning move on its own block before the cycle.",
                            code_name(d, 'G', mn),
                            code_name(d, 'G', cn),
                            code_name(d, 'G', mn)
                        ),
                    )
                    .with_related(c.span, "the canned cycle"),
                );
            }
        }
    }
}

/// Splitting a line before its `item`-th item is certain only when every item
/// before it is a G word or a comment: then the first line keeps exactly the
/// codes written before, and the rest of the line runs next, as written.
fn split_fix(cx: &BlockCx<'_>, item: usize) -> Option<TextEdit> {
    let items = cx.items();
    let before = items.get(..item)?;
    let clean = before.iter().all(|i| match i.kind {
        ItemKind::Word(w) => w.letter == b'G',
        ItemKind::Comment(_) => true,
        _ => false,
    });
    // An O-word in the block (`O100` as a program head) decides what the line is:
    // moving codes off it onto a line of their own changes the program's structure.
    let o_word = items
        .iter()
        .any(|i| matches!(i.kind, ItemKind::OWord(_) | ItemKind::ProgramHead { .. }));
    if !clean || o_word || cx.block.skip().is_some() {
        return None;
    }
    // The codes left behind stand alone on their line: the split is only
    // certain for G0/G1 and mode settings that take no words (a G92, G04, arc
    // or canned cycle alone would lack them, W003).
    // The 2007 seed wants axis words with a lone G0/G1 too.
    let lone_motion_ok = !super::util::is_emc2(cx.settings);
    let alone_is_complete = before.iter().all(|i| match i.kind {
        ItemKind::Word(w) => w.num().is_some_and(|n| {
            let v = (n.value * 10.0).round() as i64;
            (lone_motion_ok && matches!(v, 0 | 10))
                || matches!(
                    v,
                    150 | 160 | 170 | 180 | 190 | 200 | 210 | 400 | 490 | 500 | 540
                        ..=599
                            | 610
                            | 640
                            | 670
                            | 690
                            | 800
                            | 900
                            | 910
                            | 930
                            | 940
                            | 950
                            | 980
                            | 990
                )
        }),
        _ => true,
    });
    if !alone_is_complete {
        return None;
    }
    let at = items.get(item)?.span.start;
    let mut start = at as usize;
    while start > cx.program.base as usize
        && matches!(cx.program.byte_at(start - 1), Some(b' ') | Some(b'\t'))
    {
        start -= 1;
    }
    Some(TextEdit {
        span: Span::new(start as u32, at),
        new_text: "\n".into(),
    })
}
