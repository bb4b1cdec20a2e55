//! W002: words that exclude each other in one block.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{first_g, has, word_item};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags words that exclude each other in one block: an arc (`G02`/`G03`) with both a
    /// radius `R` and centre offsets `I`/`J`/`K`; ServoWorks scaling `G51` with both an
    /// overall factor `P` and per-axis factors `I`/`J`/`K`; ServoWorks dwell `G04` with
    /// both `P` (milliseconds) and `X` (seconds); LinuxCNC `G4` on a line with `G2`/`G3`
    /// (both read `P`); `F` with `G33`/`G33.1`; `G43.2` with both or neither of `H` and axis
    /// words; words in a ServoWorks `G41.1`/`G42.1` block, which takes none; ServoWorks
    /// `G10` mixing its P/R and X/Y/Z forms; a LinuxCNC 2.9 `G73`/`G83` with `D`; FANUC
    /// `G40`/`G41`/`G42` in an arc block.
    ///
    /// ## Why is this bad?
    /// The two forms describe the same thing twice and can disagree. LinuxCNC and
    /// ServoWorks stop with an error; FANUC uses `R` and ignores `I`/`J`/`K`, so the arc may
    /// not be the one the centre offsets describe.
    ///
    /// ## Example
    /// ```ngc
    /// G17 G2 X10 Y0 R5 I5 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G17 G2 X10 Y0 I5 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// Arcs: error in RS274/NGC and ServoWorks, warning in FANUC. `G51 P`+`I/J/K`: ServoWorks
    /// error. `G04 P`+`X`: ServoWorks warning. `G4` with `G2`/`G3`: `linuxcnc` error.
    ///
    /// Reported by this rule, not A005, when both see an arc with both R and I/J/K on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not X008, when both see a D peck clearance LinuxCNC 2.9 does not accept on the same text (one diagnostic per fault).
    ///
    /// Implements: SW031, SW053, SW067, SW089, SW100, NGC114, NGC204, NGC222, NGC806, NGC823, FAN032, FAN152
    pub static CONFLICTING_WORDS = {
        code: "W002",
        name: "conflicting-words",
        summary: "Words that exclude each other in one block",
        implements: &["SW031", "SW053", "SW067", "SW089", "SW100", "NGC114", "NGC204", "NGC222", "NGC806", "NGC823", "FAN032", "FAN152"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ConflictingWords;

fn ijk<'a>(cx: &BlockCx<'a>) -> Option<&'a crate::syntax::Item> {
    [b'I', b'J', b'K']
        .into_iter()
        .find_map(|l| word_item(cx, l))
        .map(|(i, _)| i)
}

impl Rule for ConflictingWords {
    fn meta(&self) -> &'static RuleMeta {
        &CONFLICTING_WORDS
    }

    /// Every conflict it knows involves a G code.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NOT_AXIS_FEED
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        if let Some(arc) = first_g(cx, &[20, 30]) {
            if let (Some((r, _)), Some(c)) = (word_item(cx, b'R'), ijk(cx)) {
                let diag = match d {
                    Dialect::Fanuc => CONFLICTING_WORDS.warning(
                        r.span,
                        "Arc with both R and I/J/K: FANUC uses R and ignores the centre offsets, so the arc may differ from the one I/J/K describe. Keep one form.",
                    ),
                    _ => CONFLICTING_WORDS.error(
                        r.span,
                        "Arc with both a radius R and centre offsets I/J/K: the control refuses the block. Keep one form (I/J/K is more accurate near 180°).",
                    ),
                };
                out.push(
                    diag.with_related(c.span, "centre offset")
                        .with_related(arc.span, "arc code"),
                );
            }
            if d == Dialect::Rs274ngc && !super::util::is_emc2(cx.settings) && has(cx, 'G', 40) {
                out.push(CONFLICTING_WORDS.error(
                    arc.span,
                    "G4 and an arc on one line both use P (dwell time / number of turns), so LinuxCNC refuses the line. Put the dwell on its own line.",
                ));
            }
        }
        if d == Dialect::Fanuc {
            if let (Some(arc), Some(comp)) = (first_g(cx, &[20, 30]), first_g(cx, &[400, 410, 420]))
            {
                out.push(
                    CONFLICTING_WORDS.error(
                        comp.span,
                        "Cutter compensation cannot start or end in a G02/G03 block (alarm PS0034). Start and cancel it on a straight G00/G01 move.",
                    )
                    .with_related(arc.span, "arc"),
                );
            }
        }
        if d == Dialect::Rs274ngc {
            if let (Some(g33), Some((f, _))) = (first_g(cx, &[330, 331]), word_item(cx, b'F')) {
                out.push(
                    CONFLICTING_WORDS.error(
                        f.span,
                        "F on a spindle-synchronised line: the feed of G33/G33.1 comes from K and the spindle speed, so F is refused. Remove it.",
                    )
                    .with_related(g33.span, "synchronised motion"),
                );
            }
            if !super::util::is_emc2(cx.settings) {
                if let (Some(peck), Some((dw, _))) = (first_g(cx, &[730, 830]), word_item(cx, b'D'))
                {
                    out.push(
                        CONFLICTING_WORDS.warning(
                            dw.span,
                            "A D peck clearance in G73/G83 exists only in LinuxCNC development versions; 2.9 does not accept it. Remove it.",
                        )
                        .with_related(peck.span, "peck drilling cycle"),
                    );
                }
            }
            if let Some(tcp) = first_g(cx, &[432]).filter(|_| !super::util::is_emc2(cx.settings)) {
                let axes = super::util::has_axis_word(cx);
                let h = word_item(cx, b'H').is_some();
                if axes == h {
                    let msg = if h {
                        "G43.2 takes either H (add a tool's offset) or axis words (add the given offsets), not both."
                    } else {
                        "G43.2 needs H (a tool whose offset is added) or axis words (the offsets to add)."
                    };
                    out.push(CONFLICTING_WORDS.error(tcp.span, msg));
                }
            }
        }
        if d != Dialect::Servoworks {
            return;
        }
        if has(cx, 'G', 100) {
            let l = word_item(cx, b'L').and_then(|(_, w)| super::util::lit(w));
            let pr_only = l.is_some_and(|l| [10.0, 11.0, 106.0, 107.0].contains(&l));
            if let (true, false, Some((a, _))) = (
                pr_only,
                word_item(cx, b'R').is_some(),
                [b'X', b'Y', b'Z']
                    .into_iter()
                    .find_map(|l| word_item(cx, l)),
            ) {
                out.push(CONFLICTING_WORDS.warning(
                    a.span,
                    "This G10 category is documented only in the `G10 L… P… R…` form; the X/Y/Z form may not be supported. Write it in the P/R form.",
                ));
            }
        }
        if has(cx, 'G', 100) && word_item(cx, b'R').is_some() {
            if let Some((a, _)) = [b'X', b'Y', b'Z']
                .into_iter()
                .find_map(|l| word_item(cx, l))
            {
                out.push(CONFLICTING_WORDS.warning(
                    a.span,
                    "G10 with both the P/R form and axis words: the manual documents them as separate formats. Use `G10 L… P… R…` or `G10 L… X… Y… Z…`.",
                ));
            }
        }
        if let Some(ndc) = first_g(cx, &[411, 421]) {
            let extra = cx
                .words()
                .find(|(i, w)| w.letter != b'G' && w.letter != b'N' && i.span != ndc.span);
            if let Some((i, _)) = extra {
                out.push(
                    CONFLICTING_WORDS.warning(
                        i.span,
                        format!(
                            "`{}` in a normal-direction-control block: the manual lists no parameters for G41.1/G42.1, so the word is probably ignored. Put it on another line.",
                            cx.program.str_of(i.span)
                        ),
                    )
                    .with_related(ndc.span, "normal direction control"),
                );
            }
        }
        if has(cx, 'G', 510) {
            if let (Some((p, _)), Some(c)) = (word_item(cx, b'P'), ijk(cx)) {
                out.push(
                    CONFLICTING_WORDS.error(
                        p.span,
                        "G51 with both P (one factor for all axes) and I/J/K (per-axis factors): the control refuses it. Use P alone, or I/J/K alone.",
                    )
                    .with_related(c.span, "per-axis factor"),
                );
            }
        }
        if has(cx, 'G', 40) {
            if let (Some((p, _)), Some((x, _))) = (word_item(cx, b'P'), word_item(cx, b'X')) {
                out.push(
                    CONFLICTING_WORDS.warning(
                        x.span,
                        "G04 with both P (milliseconds) and X (seconds): the manual does not say which one wins. Keep one of them.",
                    )
                    .with_related(p.span, "P dwell"),
                );
            }
        }
    }
}
