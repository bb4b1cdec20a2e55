//! W006: decimal values in words that must be integers.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity, TextEdit};
use crate::dialect::Dialect;

use super::util::{has, is_drilling_cycle, near_integer};
use super::{BlockCx, Interest, Rule, RuleMeta};

/// The replacement word a message names, as a fix (upper-case letter, so that
/// a lower-case `p1.5` is mended in one step). None when the value cannot be
/// written as the integer the message asks for.
fn replace_fix(span: crate::Span, letter: char, value: f64) -> Option<(String, Vec<TextEdit>)> {
    if !value.is_finite() || value.abs() >= 1e15 {
        return None;
    }
    // `-0` is not a number a programmer writes.
    let v = if value == 0.0 { 0.0 } else { value };
    let new_text = format!("{letter}{v}");
    Some((
        format!("Write `{new_text}`"),
        vec![TextEdit { span, new_text }],
    ))
}

fn with_replacement(d: Diagnostic, fix: Option<(String, Vec<TextEdit>)>) -> Diagnostic {
    match fix {
        Some((title, edits)) => d.with_fix(title, edits),
        None => d,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a number with a decimal point (FANUC, ServoWorks) or a fractional value
    /// (RS274/NGC) in a word that must be an integer: tool, offset and program numbers,
    /// repeat counts, M codes, and dwell `P` in milliseconds. On ServoWorks it also flags a
    /// `G04 X` dwell written without a decimal point.
    ///
    /// ## Why is this bad?
    /// FANUC raises PS0007 for `M3.0`, `S1000.0`, `G04 P1.5`. LinuxCNC accepts a value
    /// within 0.0001 of an integer and otherwise stops with `Non integer value for integer`.
    /// ServoWorks reads integers and decimals differently: `G04 P` is milliseconds and must
    /// be an integer, `G04 X` is seconds and must have a decimal point.
    ///
    /// ## Example
    /// ```fanuc
    /// G04 P1.5;
    /// M30;
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// G04 P1500;
    /// M30;
    /// ```
    ///
    /// ## Dialects
    /// FANUC: error at N, O, P, H, D, L, K, warning at M, S, T (in a macro call only P and L
    /// are checked; the others are arguments). ServoWorks: warning at S, T, H, L, `M98 R`, `G04 P`, `G30 P`,
    /// `G54.1 P`, and canned-cycle P and K. RS274/NGC: error at M, T, D, H, L and `G10 P`
    /// when the value is more than 0.0001 from an integer.
    ///
    /// Implements: SW012, SW051, SW052, NGC031, FAN004, FAN147, FAN150
    pub static INTEGER_WORD = {
        code: "W006",
        name: "integer-word",
        summary: "Decimal value in a word that must be an integer",
        implements: &["SW012", "SW051", "SW052", "NGC031", "FAN004", "FAN147", "FAN150"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct IntegerWord;

impl Rule for IntegerWord {
    fn meta(&self) -> &'static RuleMeta {
        &INTEGER_WORD
    }

    /// Only literal words of the letters each dialect reads as integers are
    /// reported (a ServoWorks dwell X needs its G04).
    fn interest(&self, settings: &crate::Settings) -> Interest {
        let letters: &[u8] = match settings.dialect {
            Dialect::Fanuc => b"NOPHDTMLSK",
            Dialect::Servoworks => b"STHLRPKG",
            Dialect::Rs274ngc => b"MTHLDP",
        };
        Interest::letters(letters)
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let cycle = cx
            .codes
            .iter()
            .any(|c| c.letter == 'G' && c.num.is_some_and(|n| is_drilling_cycle(d, n.0)));
        let dwell = has(cx, 'G', 40);
        let macro_call = has(cx, 'G', 650) || has(cx, 'G', 660) || has(cx, 'G', 661);
        // P, K, L, R and Q are read by each code of the block (G51 P2.0 G04
        // P1.5): a rewrite is certain only when one code reads them.
        let shared = |l: u8| matches!(l, b'P' | b'K' | b'L' | b'R' | b'Q') && cx.codes.len() > 1;
        for (item, w) in cx.words() {
            if w.comma {
                continue;
            }
            let Some(n) = w.num() else { continue };
            let l = w.letter_char();
            // Only a diagnostic needs the word's text.
            let text = || cx.program.str_of(item.span);
            match d {
                Dialect::Fanuc => {
                    let int_letters: &[u8] = if macro_call { b"PL" } else { b"NOPHDTMLSK" };
                    if !n.has_point
                        || !int_letters.contains(&w.letter)
                        || (w.letter == b'K' && !cycle)
                    {
                        continue;
                    }
                    let replacement = if dwell && w.letter == b'P' {
                        (n.value * 1000.0).round()
                    } else {
                        n.value.round()
                    };
                    let msg = if dwell && w.letter == b'P' {
                        format!("`{}`: G04 P is an integer number of milliseconds and takes no decimal point (alarm PS0007). Write `P{}`, or use X in seconds.", text(), replacement)
                    } else {
                        format!("`{}`: address {l} takes an integer without a decimal point (alarm PS0007). Write `{l}{}`.", text(), replacement)
                    };
                    // The digest grades M/S/T literals (FAN147) below the other addresses (FAN004).
                    let sev = if matches!(w.letter, b'M' | b'S' | b'T') {
                        Severity::Warning
                    } else {
                        Severity::Error
                    };
                    let fix = replace_fix(item.span, l, replacement).filter(|_| !shared(w.letter));
                    out.push(with_replacement(
                        INTEGER_WORD.diagnostic(sev, item.span, msg),
                        fix,
                    ));
                }
                Dialect::Servoworks => {
                    let int_here = match w.letter {
                        b'S' | b'T' | b'H' | b'L' => true,
                        b'R' => has(cx, 'M', 980),
                        b'P' => dwell || has(cx, 'G', 300) || has(cx, 'G', 541) || cycle,
                        b'K' => cycle,
                        _ => false,
                    };
                    if int_here && n.has_point {
                        let ms = dwell && w.letter == b'P';
                        let replacement = if ms {
                            (n.value * 1000.0).round()
                        } else {
                            n.value.round()
                        };
                        let msg = if ms {
                            format!("`{}`: G04 P is milliseconds and must be an integer without a decimal point. Write `P{}`, or use `X{}` (seconds).", text(), replacement, n.value)
                        } else {
                            format!("`{}`: {l} must be an integer here; ServoWorks reads a number with a decimal point differently. Write `{l}{}`.", text(), replacement)
                        };
                        // `S2_1500.` names its spindle in the word; no fix rewrites that.
                        let fix = replace_fix(item.span, l, replacement)
                            .filter(|_| w.spindle.is_none() && !shared(w.letter));
                        out.push(with_replacement(INTEGER_WORD.warning(item.span, msg), fix));
                    } else if dwell && w.letter == b'X' && !n.has_point {
                        let new_text = format!("X{:.1}", n.value);
                        out.push(INTEGER_WORD.warning(
                            item.span,
                            format!("`{}`: G04 X is the dwell in seconds and is written with a decimal point. Write `{new_text}` (or P in milliseconds).", text()),
                        ).with_fix(format!("Write `{new_text}`"), vec![TextEdit { span: item.span, new_text }]));
                    }
                }
                Dialect::Rs274ngc => {
                    // LinuxCNC's D is a diameter, speed or clearance with these codes.
                    let real_d = || {
                        [411, 421, 960, 730, 830, 700, 710, 711, 712, 720, 721, 722]
                            .into_iter()
                            .any(|t| has(cx, 'G', t))
                    };
                    let int_here = matches!(w.letter, b'M' | b'T' | b'H' | b'L')
                        || (w.letter == b'D' && !real_d())
                        || (w.letter == b'P' && has(cx, 'G', 100));
                    if int_here && !near_integer(n.value) {
                        out.push(INTEGER_WORD.error(
                            item.span,
                            format!("Non integer value for integer: `{}`; {l} must be within 0.0001 of a whole number.", text()),
                        ));
                    }
                }
            }
        }
    }
}
