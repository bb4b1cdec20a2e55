//! W007: literal word values outside the range the control accepts.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;
use crate::syntax::ItemKind;

use super::util::{
    fanuc_call_start, has, is_drilling_cycle, is_emc2, lit, near_integer, word_item,
};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks literal values against the ranges the control accepts: negative feeds,
    /// speeds, tool numbers and dwell times; repeat counts that are not positive integers;
    /// peck depths that are not positive; and the dialect's specific limits (ServoWorks
    /// `T`/`H` 0–256, `M98 R` 1–999,999, `G30 P2`–`P4`, `G54.1 P1`–`P58`, direct output `L`
    /// 0–65535, spindle number 1–16; LinuxCNC `G10 L2 P`, `M50`–`M53 P`, `G76` values;
    /// FANUC program numbers 1–9999 and cycle repeats `K` 0–9999; ServoWorks `G10` axis
    /// numbers, axis types, smoothing modes and position-loop gains).
    ///
    /// ## Why is this bad?
    /// The control stops with a range error or alarm when it reaches the block, or —
    /// for the warnings — silently uses another value than the one written (a negative
    /// peck depth loses its sign, `K0` stores the cycle without drilling).
    ///
    /// ## Example
    /// ```servoworks
    /// G30 P5 X0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G30 P3 X0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// All; errors where the control stops, warnings where it changes the value. Values
    /// given by parameters or expressions are checked when the program runs.
    ///
    /// Reported by this rule, not C002, when both see a negative peck depth Q on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not X002, when both see a minus sign on an M or G code on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not T007, when both see a negative offset number on the same text (one diagnostic per fault).
    ///
    /// Implements: SW022, SW030, SW040, SW041, SW044, SW045, SW054, SW061, SW062, SW063, SW065, SW073, SW091, SW102, SW110, SW122, SW123, SW130, SW136, SW137, SW138, SW140, SW141, SW143, NGC215, NGC224, NGC304, NGC305, NGC308, NGC332, NGC334, NGC401, NGC410, NGC413, NGC426, NGC500, NGC501, NGC502, NGC509, NGC809, FAN003, FAN005, FAN011, FAN073, FAN074, FAN076
    pub static WORD_VALUE_RANGE = {
        code: "W007",
        name: "word-value-range",
        summary: "Literal word value outside the accepted range",
        implements: &["SW022", "SW030", "SW040", "SW041", "SW044", "SW045", "SW054", "SW061", "SW062", "SW063", "SW065", "SW073", "SW091", "SW102", "SW110", "SW122", "SW123", "SW130", "SW136", "SW137", "SW138", "SW140", "SW141", "SW143", "NGC215", "NGC224", "NGC304", "NGC305", "NGC308", "NGC332", "NGC334", "NGC401", "NGC410", "NGC413", "NGC426", "NGC500", "NGC501", "NGC502", "NGC509", "NGC809", "FAN003", "FAN005", "FAN011", "FAN073", "FAN074", "FAN076"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct WordValueRange;

struct Ctx<'a, 'b> {
    cx: &'a BlockCx<'b>,
    out: &'a mut Vec<Diagnostic>,
    /// The letters of the block's words not after a comma ([`letter_bit`]).
    present: u128,
}

/// A letter's bit in [`Ctx::present`].
fn letter_bit(letter: u8) -> u128 {
    1u128 << (letter & 127)
}

impl Ctx<'_, '_> {
    /// Reports `letter` when its literal value fails `ok`.
    fn check(
        &mut self,
        letter: u8,
        sev: Severity,
        ok: impl Fn(f64) -> bool,
        msg: impl Fn(&str) -> String,
    ) {
        // A rule checks up to a dozen letters a block, and most are absent: one pass
        // over the words up front answers them all.
        if self.present & letter_bit(letter) == 0 {
            return;
        }
        let Some((item, w)) = word_item(self.cx, letter) else {
            return;
        };
        let Some(v) = lit(w) else { return };
        if !ok(v) {
            let text = self.cx.program.str_of(item.span).into_owned();
            self.out
                .push(WORD_VALUE_RANGE.diagnostic(sev, item.span, msg(&text)));
        }
    }
}

fn int_in(v: f64, lo: f64, hi: f64) -> bool {
    v.fract() == 0.0 && v >= lo && v <= hi
}

impl Rule for WordValueRange {
    fn meta(&self) -> &'static RuleMeta {
        &WORD_VALUE_RANGE
    }

    /// With only axis, arc and feed letters and literal values, the checks that
    /// remain are the sign of F (RS274/NGC), the sign of K and F and the digit
    /// counts (FANUC); ServoWorks checks none of these letters.
    fn interest(&self, settings: &crate::Settings) -> Interest {
        let bit = |l: u8| 1u128 << l;
        match settings.dialect {
            Dialect::Servoworks => Interest::NOT_AXIS_FEED,
            Dialect::Rs274ngc => Interest {
                negative: bit(b'F'),
                ..Interest::NOT_AXIS_FEED
            },
            Dialect::Fanuc => Interest {
                negative: bit(b'K') | bit(b'F'),
                digits_over: 9,
                ..Interest::NOT_AXIS_FEED
            },
        }
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        use Severity::{Error as E, Info as I, Warning as W};
        let d = cx.program.dialect;
        let cycle = cx
            .codes
            .iter()
            .find(|c| c.letter == 'G' && c.num.is_some_and(|n| is_drilling_cycle(d, n.0)));
        let cyc = |t: u32| cycle.is_some_and(|c| c.num.is_some_and(|n| n.0 == t));
        let present = cx.contents.letters;
        let mut k = Ctx { cx, out, present };
        match d {
            Dialect::Servoworks => {
                if has(cx, 'G', 100) {
                    let l = word_item(cx, b'L').and_then(|(_, w)| lit(w));
                    let axis_max = match l {
                        Some(v) if [10.0, 11.0, 20.0, 30.0].contains(&v) => Some(8.0),
                        Some(v) if v == 108.0 || v == 10909.0 => Some(16.0),
                        _ => None,
                    };
                    if let Some(max) = axis_max {
                        k.check(
                            b'P',
                            E,
                            |v| int_in(v, 1.0, max),
                            |t| {
                                format!(
                                    "`{t}`: the axis number of this G10 category is 1 to {max}."
                                )
                            },
                        );
                    }
                    // The category as a whole number (G10 L values are integers).
                    match l.map(|v| v as i64) {
                        Some(20) => {
                            k.check(
                                b'R',
                                E,
                                |v| [1.0, 2.0, 3.0, 10.0, 12.0].contains(&v),
                                |t| format!("`{t}`: the G10 L20 axis type is 1, 2, 3, 10 or 12."),
                            );
                            k.check(b'R', W, |v| v != 12.0, |t| format!("`{t}`: axis type 12 (torque axis) needs MECHATROLINK II/III with Sigma III/V drives."));
                        }
                        Some(106) | Some(107) => {
                            k.check(
                                b'R',
                                E,
                                |v| int_in(v, 0.0, 3.0),
                                |t| format!("`{t}`: the smoothing mode is 0 to 3."),
                            );
                        }
                        Some(10909) => {
                            k.check(
                                b'R',
                                E,
                                |v| (0.0..=999_999.9).contains(&v),
                                |t| format!("`{t}`: the position-loop gain is 0 to 999999.9 Hz."),
                            );
                        }
                        _ => {}
                    }
                }
                let macro_call = has(cx, 'G', 650);
                if has(cx, 'M', 980) {
                    k.check(
                        b'R',
                        E,
                        |v| int_in(v, 1.0, 999_999.0),
                        |t| format!("`{t}`: the M98 repeat count R must be 1 to 999,999."),
                    );
                }
                if has(cx, 'G', 300) {
                    k.check(
                        b'P',
                        E,
                        |v| [2.0, 3.0, 4.0].contains(&v),
                        |t| format!("`{t}`: G30 returns to reference point P2, P3 or P4 only."),
                    );
                }
                if has(cx, 'G', 541) {
                    k.check(
                        b'P',
                        E,
                        |v| int_in(v, 1.0, 58.0),
                        |t| format!("`{t}`: G54.1 selects additional workpiece systems P1 to P58."),
                    );
                }
                if !macro_call {
                    k.check(
                        b'T',
                        E,
                        |v| int_in(v, 0.0, 256.0),
                        |t| format!("`{t}`: tool numbers are 0 to 256 (T0 cancels the offsets)."),
                    );
                    k.check(
                        b'H',
                        E,
                        |v| int_in(v, 0.0, 256.0),
                        |t| format!("`{t}`: tool length offsets H are 0 to 256 (H0 cancels)."),
                    );
                    if let Some((_, w)) = word_item(cx, b'D') {
                        if w.num().is_some_and(|n| !n.has_point) {
                            k.check(b'D', W, |v| int_in(v, 1.0, 256.0), |t| format!("`{t}`: a D offset index is 1 to 256 (with a decimal point, D is a tool diameter)."));
                        }
                    }
                }
                if macro_call {
                    k.check(b'L', W, |v| v.fract() == 0.0 && v >= 1.0, |t| format!("`{t}`: the G65 repeat count L must be a positive integer (default 1)."));
                } else if !has(cx, 'G', 100) {
                    k.check(
                        b'L',
                        E,
                        |v| int_in(v, 0.0, 65535.0),
                        |t| {
                            format!(
                                "`{t}`: a direct digital output L is a 16-bit integer, 0 to 65535."
                            )
                        },
                    );
                }
                if let Some((item, w)) = word_item(cx, b'S') {
                    let text = cx.program.str_of(item.span).into_owned();
                    if let Some(sp) = w.spindle {
                        if !(1..=16).contains(&sp) {
                            k.out.push(WORD_VALUE_RANGE.error(
                                item.span,
                                format!("`{text}`: the spindle number before `_` must be 1 to 16."),
                            ));
                        }
                    }
                    if let Some(n) = w.num() {
                        if n.value.abs() > 99_999.0 {
                            k.out.push(WORD_VALUE_RANGE.warning(
                                item.span,
                                format!(
                                    "`{text}`: a spindle speed has at most 5 digits (0 to 99999)."
                                ),
                            ));
                        } else if n.value < 0.0 {
                            k.out.push(WORD_VALUE_RANGE.warning(item.span, format!("`{text}`: a negative S (reverse rotation) only works on servo spindles; use M04 for other spindles.")));
                        }
                    }
                }
                if has(cx, 'G', 40) {
                    for l in [b'P', b'X'] {
                        k.check(
                            l,
                            E,
                            |v| v >= 0.0,
                            |t| format!("`{t}`: a dwell time cannot be negative."),
                        );
                    }
                }
                if has(cx, 'G', 20) || has(cx, 'G', 30) {
                    k.check(b'Q', W, |v| v > 0.0, |t| format!("`{t}`: Q is the allowed contour error of the arc and must be greater than 0."));
                }
                if has(cx, 'G', 20) || has(cx, 'G', 30) {
                    k.check(
                        b'R',
                        W,
                        |v| v != 0.0,
                        |t| format!("`{t}`: an arc of radius 0 is degenerate."),
                    );
                }
                if has(cx, 'G', 23) || has(cx, 'G', 33) {
                    for l in [b'I', b'J', b'R'] {
                        k.check(l, E, |v| v != 0.0, |t| format!("`{t}`: exponential interpolation is undefined when I, J or R is 0."));
                    }
                }
                if has(cx, 'G', 23) || has(cx, 'G', 33) {
                    for l in [b'I', b'J'] {
                        k.check(l, E, |v| (0.0..=89.0).contains(&v), |t| format!("`{t}`: the taper and helix angles of exponential interpolation are 0 to 89 degrees."));
                    }
                }
                if has(cx, 'G', 510) {
                    for l in [b'P', b'I', b'J', b'K'] {
                        k.check(
                            l,
                            E,
                            |v| (0.001..=999.999).contains(&v),
                            |t| format!("`{t}`: a scaling magnification is 0.001 to 999.999."),
                        );
                    }
                }
                if cyc(730) || cyc(830) {
                    k.check(b'Q', W, |v| v >= 0.0, |t| format!("`{t}`: a negative peck depth is ignored; write Q as a positive incremental depth."));
                }
                if cyc(760) || cyc(870) {
                    k.check(b'Q', W, |v| v >= 0.0, |t| format!("`{t}`: the sign of the shift amount Q is ignored; the direction comes from the machine setup."));
                }
                if cycle.is_some() {
                    k.check(
                        b'K',
                        W,
                        |v| v.fract() == 0.0 && v >= 1.0,
                        |t| format!("`{t}`: the repeat count K must be a positive integer."),
                    );
                }
            }
            Dialect::Rs274ngc => {
                k.check(
                    b'F',
                    E,
                    |v| v >= 0.0,
                    |t| format!("Negative feed rate `{t}`: F cannot be negative."),
                );
                k.check(b'S', E, |v| v >= 0.0, |t| format!("Negative spindle speed `{t}`: the direction comes from M3/M4, S is the magnitude."));
                k.check(
                    b'T',
                    E,
                    |v| v >= 0.0,
                    |t| format!("Negative tool number `{t}`."),
                );
                k.check(
                    b'D',
                    E,
                    |v| v >= 0.0,
                    |t| format!("Negative D word `{t}`: D names a tool."),
                );
                k.check(
                    b'H',
                    E,
                    |v| v >= 0.0 || v == -1.0,
                    |t| format!("Negative H word `{t}`: H names a tool."),
                );
                if has(cx, 'G', 40) {
                    k.check(b'P', E, |v| v >= 0.0, |t| format!("Negative dwell time `{t}`: G4 P is seconds and cannot be negative."));
                }
                if cycle.is_some() {
                    k.check(b'L', E, |v| near_integer(v) && v >= 1.0, |t| format!("`{t}`: the canned-cycle repeat count L must be a positive integer."));
                    k.check(
                        b'P',
                        E,
                        |v| v >= 0.0,
                        |t| {
                            format!(
                                "`{t}`: the dwell at the bottom of the hole cannot be negative."
                            )
                        },
                    );
                    if cyc(730) || cyc(830) {
                        k.check(
                            b'Q',
                            E,
                            |v| v > 0.0,
                            |t| format!("`{t}`: the peck increment Q must be greater than zero."),
                        );
                    }
                }
                let l = word_item(cx, b'L').and_then(|(_, w)| lit(w));
                if has(cx, 'G', 100) && matches!(l, Some(2.0 | 20.0)) {
                    let lo = if is_emc2(cx.settings) { 1.0 } else { 0.0 };
                    let l = l.unwrap_or(2.0);
                    k.check(
                        b'P',
                        E,
                        |v| v.round() >= lo && v.round() <= 9.0,
                        |t| format!("`{t}`: G10 L{l} P selects coordinate system {lo} to 9."),
                    );
                }
                if cx
                    .codes
                    .iter()
                    .any(|c| c.letter == 'M' && c.num.is_some_and(|n| (500..=530).contains(&n.0)))
                {
                    k.check(
                        b'P',
                        W,
                        |v| v == 0.0 || v == 1.0,
                        |t| {
                            format!(
                                "`{t}`: the override switches M50–M53 take P0 (off) or P1 (on)."
                            )
                        },
                    );
                }
                if has(cx, 'G', 760) {
                    for l in [b'J', b'K', b'H'] {
                        k.check(
                            l,
                            E,
                            |v| v >= 0.0,
                            |t| format!("`{t}`: G76 depths and spring passes cannot be negative."),
                        );
                    }
                    let sev = if is_emc2(cx.settings) { E } else { W };
                    k.check(b'R', sev, |v| v >= 1.0, |t| format!("`{t}`: the G76 degression R must be at least 1.0 (LinuxCNC uses 1.0 instead)."));
                }
                if !is_emc2(cx.settings) {
                    if has(cx, 'G', 411) || has(cx, 'G', 421) {
                        k.check(
                            b'L',
                            E,
                            |v| int_in(v, 0.0, 9.0),
                            |t| format!("`{t}`: the G41.1/G42.1 tool orientation L is 0 to 9."),
                        );
                    }
                    if has(cx, 'G', 20) || has(cx, 'G', 30) {
                        k.check(b'P', E, |v| near_integer(v) && v >= 1.0, |t| format!("`{t}`: the number of arc turns P must be an integer of at least 1."));
                    }
                    if has(cx, 'M', 190) {
                        k.check(
                            b'R',
                            E,
                            |v| (0.0..=360.0).contains(&v),
                            |t| format!("`{t}`: the M19 orientation angle R is 0 to 360 degrees."),
                        );
                        k.check(
                            b'P',
                            E,
                            |v| [0.0, 1.0, 2.0].contains(&v),
                            |t| format!("`{t}`: the M19 direction P is 0, 1 or 2."),
                        );
                    }
                }
            }
            Dialect::Fanuc => {
                let macro_call = has(cx, 'G', 650) || has(cx, 'G', 660) || has(cx, 'G', 661);
                let unsigned: &[u8] = if macro_call { b"NPL" } else { b"NPTMSHDLKF" };
                let call = fanuc_call_start(cx.program, cx.block);
                for (item, w) in cx.words() {
                    // Arguments of a macro call are values for #1–#33, not NC words:
                    // an address's digit limit does not apply to them.
                    let argument = call.is_some_and(|c| item.span.start > c)
                        && !matches!(w.letter, b'P' | b'L' | b'N' | b'O');
                    let Some(n) = w.num().filter(|_| !w.comma) else {
                        continue;
                    };
                    // Decoded only when there is something to report.
                    let text = || cx.program.str_of(item.span).into_owned();
                    let l = w.letter_char();
                    if n.value < 0.0 && unsigned.contains(&w.letter) {
                        let text = text();
                        k.out.push(WORD_VALUE_RANGE.error(
                            item.span,
                            format!("`{text}`: address {l} takes no minus sign (alarm PS0006)."),
                        ));
                    }
                    if argument {
                        continue;
                    }
                    let max = match w.letter {
                        b'S' => 5,
                        b'H' | b'D' => 3,
                        b'M' | b'T' | b'P' | b'L' => 8,
                        b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'A' | b'B' | b'C' | b'I'
                        | b'J' | b'K' | b'R' | b'Q' => 9,
                        _ => continue,
                    };
                    if usize::from(n.digits) > max {
                        let text = text();
                        k.out.push(WORD_VALUE_RANGE.error(
                            item.span,
                            format!("`{text}` has {} digits; address {l} takes at most {max} (alarm PS0003).", n.digits),
                        ));
                    }
                }
                for item in cx.items() {
                    if let ItemKind::ProgramHead {
                        number: Some(n), ..
                    } = item.kind
                    {
                        let digits = cx.settings.program_number_digits;
                        let max = 10u32.pow(u32::from(digits.unwrap_or(8))) - 1;
                        if !(1..=max).contains(&n) {
                            let range = match digits {
                                None => "1 to 9999 (1 to 99999999 with the 8-digit program number option)".to_string(),
                                Some(4) if n > max => format!("1 to {max} (or set machine.program_number_digits = 8 for the 8-digit program number option)"),
                                Some(_) => format!("1 to {max}"),
                            };
                            k.out.push(WORD_VALUE_RANGE.error(item.span, format!("Program number O{n}: FANUC program numbers are {range} (alarm PS0074).")));
                        } else if digits.is_none() && n > 9999 {
                            // The program is the evidence the shop's control has the option.
                            k.out.push(WORD_VALUE_RANGE.info(item.span, format!("Program number O{n} needs the 8-digit program number option (the standard control takes 1 to 9999): checked as if the control has it. Set machine.program_number_digits = 4 or 8 to say which.")));
                        }
                    }
                }
                if cycle.is_some() {
                    k.check(
                        b'K',
                        E,
                        |v| int_in(v, 0.0, 9999.0),
                        |t| format!("`{t}`: the repeat count K is an integer 0 to 9999."),
                    );
                    k.check(
                        b'K',
                        I,
                        |v| v != 0.0,
                        |t| format!("`{t}`: K0 stores the drilling data but drills no hole."),
                    );
                }
                if cyc(730) || cyc(760) || cyc(830) || cyc(870) {
                    k.check(
                        b'Q',
                        W,
                        |v| v >= 0.0,
                        |t| {
                            format!(
                                "`{t}`: the sign of Q is ignored; write it as a positive value."
                            )
                        },
                    );
                }
            }
        }
    }
}
