//! W003: a code without a word it cannot work without.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::diagnostic::Severity;
use crate::dialect::{CodeNum, Dialect};

use super::util::{axis_words, code_name, first_g, has_axis_word, is_emc2, lit, word_item};
use super::{BlockCode, BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags a code written without a word it needs in the same block: an arc without a
    /// radius or centre (`R` or `I`/`J`/`K`); an RS274/NGC dwell `G4` without `P`; `M98` or
    /// `G65` without `P`; `G10` without `L`; ServoWorks `G54.1` without `P` and `G51`
    /// without factors; RS274/NGC `G92`/`G52` without axis words, `G33` without `K` and `G76`
    /// without its required words; FANUC `G73`/`G83` without a peck depth `Q`; ServoWorks
    /// `G02.3`/`G03.3` without the feeds `F` and `Q`. Also: RS274/NGC probes, `G33`/`G33.1`
    /// and canned cycles without axis words, `G96` without `S`, `M61`–`M68` without their
    /// words, `G10 L1`/`L10`/`L11` without a tool, `G5`/`G5.1` spline words, motion without
    /// axis words in `emc2`; ServoWorks `G37` with other than one axis word, `G50.1` without
    /// axes, `G10` P/R forms without P or R, and (info) `G68` without R and reference
    /// returns without axis words; ServoWorks `G43`/`G44`/`G43.2` without `H`, `M29` without
    /// `S`, smoothing `G10 L106`–`L108` not right after a `G04`; FANUC involute
    /// `G02.2`/`G03.2` without end point, base-circle centre or radius.
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
    /// Reported by this rule, not A005, when both see an arc without R or I/J/K on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not X003, when both see a code without a word it needs (G4 without P, …) on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not C003, when both see a canned cycle without a word it needs (G76 without P, …) on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not C002, when both see a peck cycle without Q on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not F002, when both see M98 or G65 without P on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not F011, when both see a probe or motion code without axis words on the same text (one diagnostic per fault).
    ///
    /// Implements: SW020, SW028, SW032, SW046, SW060, SW066, SW068, SW075, SW080, SW095, SW099, SW101, SW105, SW114, SW129, NGC109, NGC115, NGC203, NGC218, NGC219, NGC223, NGC225, NGC300, NGC333, NGC409, NGC424, NGC508, NGC800, NGC801, NGC803, NGC804, NGC807, NGC810, NGC811, NGC812, NGC817, NGC818, FAN030, FAN040, FAN041, FAN042, FAN072
    pub static MISSING_REQUIRED_WORD = {
        code: "W003",
        name: "missing-required-word",
        summary: "Code without a word it needs",
        implements: &["SW020", "SW028", "SW032", "SW046", "SW060", "SW066", "SW068", "SW075", "SW080", "SW095", "SW099", "SW101", "SW105", "SW114", "SW129", "NGC109", "NGC115", "NGC203", "NGC218", "NGC219", "NGC223", "NGC225", "NGC300", "NGC333", "NGC409", "NGC424", "NGC508", "NGC800", "NGC801", "NGC803", "NGC804", "NGC807", "NGC810", "NGC811", "NGC812", "NGC817", "NGC818", "FAN030", "FAN040", "FAN041", "FAN042", "FAN072"],
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
    out.push(MISSING_REQUIRED_WORD.error(c.span, format!("{name} needs {what}: {why}")));
}

fn has_word(cx: &BlockCx<'_>, letter: u8) -> bool {
    word_item(cx, letter).is_some()
}

impl Rule for MissingRequiredWord {
    fn meta(&self) -> &'static RuleMeta {
        &MISSING_REQUIRED_WORD
    }

    /// Words are only required by G and M codes.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"GM")
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
            more_checks(cx, c, num.0, out);
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
                ('G', 920) | ('G', 520) if ngc && !has_axis_word(cx) => {
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
                    Some((q, w)) if lit(w) == Some(0.0) => out.push(MISSING_REQUIRED_WORD.error(
                        q.span,
                        "Q0 in a peck drilling cycle: the depth per peck must not be zero (alarm PS0045).",
                    )),
                    _ => {}
                },
                ('G', 23) | ('G', 33) if sw && !(has_word(cx, b'F') && has_word(cx, b'Q')) => out.push(MISSING_REQUIRED_WORD.warning(
                    c.span,
                    "Exponential interpolation needs F (feed at the start) and Q (feed at the end); the feed varies linearly between them. Give both.",
                )),
                _ => {}
            }
        }
    }
}

fn note(cx: &BlockCx<'_>, c: &BlockCode, sev: Severity, msg: String, out: &mut Vec<Diagnostic>) {
    let _ = cx;
    out.push(MISSING_REQUIRED_WORD.diagnostic(sev, c.span, msg));
}

/// Word requirements of the less common codes.
fn more_checks(cx: &BlockCx<'_>, c: &BlockCode, t: u32, out: &mut Vec<Diagnostic>) {
    let d = cx.program.dialect;
    // Only a diagnostic needs the code's name.
    let name = || code_name(d, c.letter, CodeNum(t));
    let emc2 = is_emc2(cx.settings);
    // LinuxCNC's polar distance `@` and angle `^` (G17) give the end point too.
    let polar = d == Dialect::Rs274ngc && !emc2 && (has_word(cx, b'@') || has_word(cx, b'^'));
    let axes = polar || has_axis_word(cx);
    let lval = word_item(cx, b'L').and_then(|(_, w)| lit(w));
    match (d, c.letter, t) {
        (Dialect::Rs274ngc, 'G', 330) | (Dialect::Rs274ngc, 'G', 331) if !axes => {
            missing(cx, c, "an axis word", "the end point of the spindle-synchronised move.", out)
        }
        (Dialect::Rs274ngc, 'G', 331) if !has_word(cx, b'K') => missing(cx, c, "K", "the distance per spindle revolution.", out),
        (Dialect::Rs274ngc, 'G', 382..=385) if !axes => {
            missing(cx, c, "an axis word", "the probe target; the probe move has nowhere to go without one.", out)
        }
        (Dialect::Rs274ngc, 'G', 0) | (Dialect::Rs274ngc, 'G', 10) if emc2 && !axes => note(
            cx,
            c,
            Severity::Error,
            format!("{} without axis words: the 2007 interpreter requires at least one axis word with a motion code.", name()),
            out,
        ),
        (Dialect::Rs274ngc, 'G', 730 | 810 | 820 | 830 | 840 | 850 | 860 | 870 | 880 | 890)
            if ![b'X', b'Y', b'Z'].into_iter().any(|l| has_word(cx, l)) =>
        {
            missing(cx, c, "X, Y or Z", "a canned cycle written without any axis word makes no hole and LinuxCNC refuses it.", out)
        }
        (Dialect::Rs274ngc, 'G', 960) if !emc2 && !has_word(cx, b'S') => {
            missing(cx, c, "S", "the surface speed to keep constant.", out)
        }
        (Dialect::Rs274ngc, 'M', 620..=650) if !has_word(cx, b'P') => missing(cx, c, "P", "the number of the digital output.", out),
        (Dialect::Rs274ngc, 'M', 610) if !emc2 => match word_item(cx, b'Q') {
            None => missing(cx, c, "Q", "the number of the tool now in the spindle.", out),
            Some((_, w)) if lit(w).is_some_and(|v| v < 0.0) => {
                note(cx, c, Severity::Error, "M61 Q must not be negative: it is a tool number.".into(), out)
            }
            _ => {}
        },
        (Dialect::Rs274ngc, 'M', 670) | (Dialect::Rs274ngc, 'M', 680) if !emc2 && (!has_word(cx, b'E') || !has_word(cx, b'Q')) => {
            missing(cx, c, "E and Q", "the analog output number and the value to write.", out)
        }
        (Dialect::Rs274ngc, 'M', 660) if !emc2 => {
            match (has_word(cx, b'P'), has_word(cx, b'E')) {
                (true, true) => note(cx, c, Severity::Error, "M66 with both P (digital input) and E (analog input): wait on one input per line.".into(), out),
                (false, false) => missing(cx, c, "P or E", "the digital (P) or analog (E) input to wait on.", out),
                _ => {}
            }
            if lval.is_some_and(|l| !(0.0..=4.0).contains(&l)) {
                note(cx, c, Severity::Error, "M66 L is the wait mode, 0 to 4.".into(), out);
            }
        }
        (Dialect::Rs274ngc, 'G', 100) if !emc2 => match lval {
            Some(l) if l == 1.0 || l == 10.0 || l == 11.0 => match word_item(cx, b'P').and_then(|(_, w)| w.num().map(|n| n.value)) {
                None if !has_word(cx, b'P') => missing(cx, c, "P", "the tool number whose table entry is written.", out),
                Some(p) if p < 1.0 => note(cx, c, Severity::Error, format!("G10 L{l} P must be a tool number of at least 1."), out),
                _ => {}
            },
            Some(l) if l == 20.0 && has_word(cx, b'R') => {
                note(cx, c, Severity::Error, "G10 L20 takes no R: the rotation of a coordinate system is set with G10 L2.".into(), out)
            }
            Some(l) if l == 2.0 && (has_word(cx, b'I') || has_word(cx, b'J')) => {
                note(cx, c, Severity::Error, "G10 L2 takes no I or J: they belong to the tool-table forms L1/L10/L11.".into(), out)
            }
            _ => {}
        },
        (Dialect::Rs274ngc, 'G', 50) if !emc2 => {
            let (i, j) = (has_word(cx, b'I'), has_word(cx, b'J'));
            if !(has_word(cx, b'P') && has_word(cx, b'Q')) {
                missing(cx, c, "P and Q", "the offsets of the end control point of the cubic spline.", out);
            }
            if i != j {
                note(cx, c, Severity::Error, "G5 takes I and J together (the start control point), or neither.".into(), out);
            }
        }
        (Dialect::Rs274ngc, 'G', 51) if !emc2 && !has_word(cx, b'I') && !has_word(cx, b'J') => {
            missing(cx, c, "I or J", "the control point of the quadratic spline.", out)
        }
        (Dialect::Rs274ngc, 'G', 410 | 420) if emc2 && !has_word(cx, b'D') => note(
            cx,
            c,
            Severity::Warning,
            format!("{} without D: the 2007 interpreter's manual requires a D number on every G41/G42 line.", name()),
            out,
        ),
        (Dialect::Servoworks, 'G', 370) if axis_words(cx).count() != 1 => note(
            cx,
            c,
            Severity::Error,
            format!("G37 needs exactly one axis word, the theoretical surface position; this block has {}.", axis_words(cx).count()),
            out,
        ),
        (Dialect::Servoworks, 'G', 501) if !axes => note(
            cx,
            c,
            Severity::Warning,
            "G50.1 cancels mirroring only for the axes it names; without axis words it cancels nothing. Name the axes, e.g. `G50.1 X0 Y0`.".into(),
            out,
        ),
        (Dialect::Servoworks, 'G', 680) if !has_word(cx, b'R') => {
            note(cx, c, Severity::Info, "G68 without R rotates by 0°. Give the angle with R.".into(), out)
        }
        (Dialect::Servoworks, 'G', 280 | 290 | 300 | 530) if !axes => {
            note(cx, c, Severity::Info, format!("{} without axis words moves nothing.", name()), out)
        }
        (Dialect::Servoworks, 'G', 100) => {
            // L106/L107 set one smoothing mode for all axes: `G10 L106 R2` has no P.
            let pr = lval.is_some_and(|l| [10.0, 11.0, 20.0, 30.0, 108.0, 10909.0].contains(&l));
            // With axis words this is the X/Y/Z form (W002 checks where that form exists).
            if pr && !axes && !(has_word(cx, b'P') && has_word(cx, b'R')) {
                missing(cx, c, "P and R", "this data category is written as `G10 L… P… R…`.", out);
            }
            if lval.is_some_and(|l| l == 106.0 || l == 107.0) && !axes && !has_word(cx, b'R') {
                missing(cx, c, "R", "the smoothing mode to set (`G10 L106 R2`).", out);
            }
            if lval.is_some_and(|l| [106.0, 107.0, 108.0].contains(&l)) && !previous_block_dwells(cx) {
                note(
                    cx,
                    c,
                    Severity::Warning,
                    "Smoothing changes are ignored while the axes accelerate or decelerate: put a G04 block right before this G10.".into(),
                    out,
                );
            }
        }
        (Dialect::Servoworks, 'G', 430 | 440 | 432) if !has_word(cx, b'H') => note(
            cx,
            c,
            Severity::Warning,
            format!("{} without H: no tool length offset is selected. Add H with the offset number.", name()),
            out,
        ),
        (Dialect::Servoworks, 'M', 290) if !has_word(cx, b'S') => {
            note(cx, c, Severity::Warning, "M29 (rigid tapping) without S: give the spindle speed in the same block.".into(), out)
        }
        (Dialect::Fanuc, 'G', 22 | 32) => {
            let (i, j, k) = (word_item(cx, b'I'), word_item(cx, b'J'), word_item(cx, b'K'));
            let zero = |w: Option<(&crate::syntax::Item, &crate::syntax::Word)>| w.and_then(|(_, w)| lit(w)).is_none_or(|v| v == 0.0);
            if !axes {
                missing(cx, c, "an end point", "involute interpolation needs the end point (alarm PS0241).", out);
            }
            if i.is_none() && j.is_none() && k.is_none() {
                missing(cx, c, "I/J/K", "the centre of the base circle (alarm PS0241).", out);
            } else if zero(i) && zero(j) && zero(k) && [i, j, k].iter().all(|w| w.is_none_or(|(_, w)| lit(w).is_some())) {
                note(cx, c, Severity::Error, "The base-circle centre I/J/K is zero: the involute is undefined (alarm PS0242).".into(), out);
            }
            match word_item(cx, b'R') {
                None => missing(cx, c, "R", "the base-circle radius (alarm PS0241).", out),
                Some((_, w)) if lit(w) == Some(0.0) => {
                    note(cx, c, Severity::Error, "R0: the base-circle radius must not be zero (alarm PS0242).".into(), out)
                }
                _ => {}
            }
        }
        _ => {}
    }
}

/// Whether the last motion before this block was followed by a G04 dwell:
/// walking back, other G10 blocks and blocks without motion are passed over, a
/// G04 answers yes and a block with axis words answers no. The program start
/// counts as standing still.
fn previous_block_dwells(cx: &BlockCx<'_>) -> bool {
    let p = cx.program;
    for b in p.blocks[..cx.index.min(p.blocks.len())].iter().rev() {
        let g = super::util::block_g_codes(p, b);
        if g.contains(&40) {
            return true;
        }
        if g.contains(&100) {
            continue;
        }
        if super::util::block_has_axis(p, b, cx.settings) {
            return false;
        }
    }
    true
}
