//! W003: a code without a word it cannot work without.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::util::{axis_words, code_name, first_g, is_emc2, lit, word_item};
use super::{BlockCode, BlockCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags a code written without a word it needs in the same block: an arc without a
    /// radius or centre (`R` or `I`/`J`/`K`); an RS274/NGC dwell `G4` without `P`; `M98` or
    /// `G65` without `P`; `G10` without `L`; ServoWorks `G54.1` without `P` and `G51`
    /// without factors; RS274/NGC `G92`/`G52` without axis words, `G33` without `K` and `G76`
    /// without its required words; FANUC `G73`/`G83` without a peck depth `Q`; ServoWorks
    /// `G02.3`/`G03.3` without the feeds `F` and `Q`.
    ///
    /// ## Why is this bad?
    /// The control cannot execute the code and stops with an error (LinuxCNC `Dwell time
    /// missing with G4`, FANUC PS0022/PS0045, ServoWorks "needs either R or I/J/K").
    ///
    /// ## Example
    /// ```ngc
    /// G4
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G4 P0.5
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All; which codes are checked depends on the dialect (above). ServoWorks `G04`
    /// without P or X is a valid exact stop and is not flagged. Errors, except the
    /// ServoWorks exponential-interpolation feeds (warning).
    ///
    /// Implements: SW020, SW028, SW032, SW046, SW060, SW101, NGC115, NGC203, NGC218, NGC223, NGC333, NGC409, NGC818, FAN030, FAN072
    pub static MISSING_REQUIRED_WORD = {
        code: "W003",
        name: "missing-required-word",
        summary: "Code without a word it needs",
        implements: &[
            "SW020", "SW028", "SW032", "SW046", "SW060", "SW101", "NGC115", "NGC203", "NGC218", "NGC223", "NGC333",
            "NGC409", "NGC818", "FAN030", "FAN072",
        ],
        origin: Static,
        default_enabled: true,
    }
}

pub struct MissingRequiredWord;

fn missing(cx: &BlockCx<'_>, c: &BlockCode, what: &str, why: &str, out: &mut Vec<Diagnostic>) {
    let name = c
        .num
        .map(|n| code_name(cx.program.dialect, c.letter, n))
        .unwrap_or_default();
    out.push(Diagnostic::error(
        "W003",
        c.span,
        format!("{name} needs {what}: {why}"),
    ));
}

fn has_word(cx: &BlockCx<'_>, letter: u8) -> bool {
    word_item(cx, letter).is_some()
}

impl Rule for MissingRequiredWord {
    fn meta(&self) -> &'static RuleMeta {
        &MISSING_REQUIRED_WORD
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let ngc = d == Dialect::Rs274ngc;
        let sw = d == Dialect::Servoworks;
        let fanuc = d == Dialect::Fanuc;
        if let Some(arc) = first_g(cx, &[20, 30]) {
            if !has_word(cx, b'R') && ![b'I', b'J', b'K'].into_iter().any(|l| has_word(cx, l)) {
                missing(cx, arc, "a radius R or centre offsets I/J/K", "without them the arc is undefined and the control stops. Add R (radius) or I/J/K (centre relative to the start point).", out);
            }
        }
        for c in cx.codes {
            let Some(num) = c.num else { continue };
            match (c.letter, num.0) {
                ('G', 40) if ngc && !has_word(cx, b'P') => {
                    missing(cx, c, "P", "the dwell time in seconds (`Dwell time missing with G4`). Write for example `G4 P0.5`.", out)
                }
                ('M', 980) if (sw || fanuc) && !has_word(cx, b'P') => {
                    missing(cx, c, "P", "the subprogram to call. Write `M98 P<name or number>`.", out)
                }
                ('G', 650) if (sw || fanuc) && !has_word(cx, b'P') => {
                    missing(cx, c, "P", "the number of the macro program to call. Write `G65 P<number>` before the arguments.", out)
                }
                ('G', 100) if (sw || ngc) && !has_word(cx, b'L') => {
                    missing(cx, c, "L", "the data category to write (for example L2 work offsets). The control refuses G10 without it.", out)
                }
                ('G', 541) if sw && !has_word(cx, b'P') => {
                    missing(cx, c, "P1–P58", "the number of the additional workpiece coordinate system.", out)
                }
                ('G', 510) if sw && !has_word(cx, b'P') && ![b'I', b'J', b'K'].into_iter().any(|l| has_word(cx, l)) => {
                    missing(cx, c, "P or I/J/K", "the magnification (P for all axes, I/J/K per axis).", out)
                }
                ('G', 920) | ('G', 520) if ngc && axis_words(cx).is_empty() => {
                    if num.0 == 520 && is_emc2(cx.settings) {
                        continue;
                    }
                    missing(cx, c, "at least one axis word", "it sets the offset so the current point gets the given coordinates; without axis words there is nothing to set.", out)
                }
                ('G', 330) if ngc && !has_word(cx, b'K') => {
                    missing(cx, c, "K", "the distance the tool travels per spindle revolution (thread pitch).", out)
                }
                ('G', 760) if ngc => {
                    let req: &[u8] = if is_emc2(cx.settings) { b"PZIJRKQH" } else { b"PIJK" };
                    let absent: String = req.iter().filter(|l| !has_word(cx, **l)).map(|l| *l as char).collect();
                    if !absent.is_empty() {
                        let list: Vec<String> = absent.chars().map(|c| c.to_string()).collect();
                        missing(cx, c, &list.join(", "), "G76 threading cannot be computed without these words (P pitch, I/J/K thread peak, first cut and full depth).", out);
                    }
                }
                ('G', 730) | ('G', 830) if fanuc => match word_item(cx, b'Q') {
                    None => missing(cx, c, "Q", "the depth of cut per peck (alarm PS0045). Add a positive Q.", out),
                    Some((q, w)) if lit(w) == Some(0.0) => out.push(Diagnostic::error(
                        "W003",
                        q.span,
                        "Q0 in a peck drilling cycle: the depth per peck must not be zero (alarm PS0045).",
                    )),
                    _ => {}
                },
                ('G', 23) | ('G', 33) if sw && !(has_word(cx, b'F') && has_word(cx, b'Q')) => out.push(Diagnostic::warning(
                    "W003",
                    c.span,
                    "Exponential interpolation needs F (feed at the start) and Q (feed at the end); the feed varies linearly between them. Give both.",
                )),
                _ => {}
            }
        }
    }
}
