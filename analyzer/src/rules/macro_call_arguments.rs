//! W012: word order and argument letters of a G65 macro call.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;

use super::util::has;
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks the words of a `G65` (and FANUC `G66`) macro call: on ServoWorks `G65` must
    /// come before its arguments; on FANUC the letters G and N cannot be arguments (a G
    /// code *before* the call is the block's own code, not an argument),
    /// argument specification I (letters) and II (repeated I/J/K) should not be mixed where
    /// two words then set the same local variable (`I1. I2. D3.`: `I2.` and `D3.` both
    /// set #7), and
    /// argument values other than zero should have a decimal point (except at H, D, M, S
    /// and T, addresses that never take one and pass their number as written).
    ///
    /// ## Why is this bad?
    /// ServoWorks requires `G65` first in the block. FANUC raises PS0129 for a G word
    /// among the arguments; when both specifications set the same local variable the later
    /// word silently wins; and an argument without a decimal point is read in the least
    /// input increment, so `A1` may arrive as 0.001.
    ///
    /// ## Example
    /// ```servoworks
    /// Z20.0 G65 P100 R2.5
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G65 P100 Z20.0 R2.5
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks: error for an argument before `G65`. FANUC: error for a G argument,
    /// warnings for N as an argument, mixed specifications and integer argument values.
    ///
    /// Implements: SW029, FAN134, FAN135, FAN136, FAN137
    pub static MACRO_CALL_ARGUMENTS = {
        code: "W012",
        name: "macro-call-arguments",
        summary: "Word order and argument letters of a G65 call",
        implements: &["SW029", "FAN134", "FAN135", "FAN136", "FAN137"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct MacroCallArguments;

impl Rule for MacroCallArguments {
    fn meta(&self) -> &'static RuleMeta {
        &MACRO_CALL_ARGUMENTS
    }

    /// It needs G65 or G66.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NOT_AXIS_FEED
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let Some(call) = cx
            .codes
            .iter()
            .find(|c| c.is('G', 650) || (d == Dialect::Fanuc && c.is('G', 660)))
        else {
            return;
        };
        let words: Vec<_> = cx.words().filter(|(_, w)| !w.comma).collect();
        match d {
            Dialect::Servoworks => {
                let before = words.iter().find(|(i, w)| {
                    i.span.start < call.span.start && !matches!(w.letter, b'N' | b'G')
                });
                if let Some((i, _)) = before {
                    out.push(
                        MACRO_CALL_ARGUMENTS.error(
                            i.span,
                            format!("`{}` comes before G65: ServoWorks requires G65 before its arguments. Move G65 to the front of the block.", cx.program.str_of(i.span)),
                        )
                        .with_related(call.span, "macro call"),
                    );
                }
            }
            Dialect::Fanuc => {
                let every_block = has(cx, 'G', 661);
                for (i, w) in &words {
                    let text = cx.program.str_of(i.span).into_owned();
                    match w.letter {
                        // G codes before G65 are the block's own codes, not arguments:
                        // arguments follow the call (FANUC: "G65 must precede its
                        // arguments"), and no manual page forbids a G code before it.
                        b'G' if !every_block && i.span.start > call.span.start => out.push(MACRO_CALL_ARGUMENTS.error(
                            i.span,
                            format!("`{text}` in a macro call: G cannot be an argument (alarm PS0129; only G66.1 passes G words). Put the G code in its own block."),
                        )),
                        b'N' if i.span.start > call.span.start => out.push(MACRO_CALL_ARGUMENTS.warning(
                            i.span,
                            format!("`{text}` after the macro call is not an argument: N is a sequence number and belongs at the start of the block."),
                        )),
                        b'G' | b'N' | b'P' | b'L' | b'O' => {}
                        // Addresses that never take a decimal point (H, D, M, S, T:
                        // fanuc.md §1.8) pass their number as written.
                        b'H' | b'D' | b'M' | b'S' | b'T' => {}
                        _ => {
                            // Zero is zero in every increment.
                            if w.num().is_some_and(|n| !n.has_point && n.value != 0.0) {
                                out.push(MACRO_CALL_ARGUMENTS.warning(
                                    i.span,
                                    format!("`{text}`: a macro argument without a decimal point is read in the least input increment of its address (A1 may arrive as 0.001). Write `{text}.`."),
                                ).with_fix(format!("Write `{text}.`"), vec![TextEdit { span: crate::Span::new(i.span.end, i.span.end), new_text: ".".into() }]));
                            }
                        }
                    }
                }
                let count = |l: u8| words.iter().filter(|(_, w)| w.letter == l).count();
                let type2 = [b'I', b'J', b'K'].into_iter().any(|l| count(l) > 1);
                if type2 {
                    // Mixed specifications matter only where two words set one variable.
                    let letters: Vec<u8> = words
                        .iter()
                        .filter(|(i, _)| i.span.start > call.span.start)
                        .map(|(_, w)| w.letter)
                        .collect();
                    let vars = mixed_argument_variables(&letters);
                    let args: Vec<_> = words
                        .iter()
                        .filter(|(i, _)| i.span.start > call.span.start)
                        .collect();
                    for (k, var) in vars.iter().enumerate() {
                        let Some(var) = var else { continue };
                        let Some(first) = vars[..k].iter().position(|v| v == &Some(*var)) else {
                            continue;
                        };
                        let (earlier, _) = args[first];
                        let (later, _) = args[k];
                        out.push(
                            MACRO_CALL_ARGUMENTS.warning(
                                later.span,
                                format!(
                                    "`{}` and `{}` both set #{var}: argument specifications I and II are mixed (repeated I/J/K fill #4–#33 in sets of three) and the later word wins. Use one specification.",
                                    cx.program.str_of(earlier.span),
                                    cx.program.str_of(later.span)
                                ),
                            )
                            .with_related(earlier.span, "sets the same variable"),
                        );
                    }
                }
            }
            Dialect::Rs274ngc => {}
        }
    }
}

/// The local variable each argument letter of a FANUC macro call sets when argument
/// specifications I and II are mixed: I, J and K count in specification II sets
/// (the n-th set's I, J, K are #(3n+1), #(3n+2), #(3n+3); a set ends when a letter
/// does not follow the previous one in I, J, K order), the other letters take their
/// specification I variable. `None` for letters that are not arguments.
fn mixed_argument_variables(letters: &[u8]) -> Vec<Option<u32>> {
    let mut set = 0u32;
    let mut last: Option<u32> = None;
    letters
        .iter()
        .map(|&l| {
            let ijk = match l {
                b'I' => Some(0),
                b'J' => Some(1),
                b'K' => Some(2),
                _ => None,
            };
            if let Some(pos) = ijk {
                if last.is_some_and(|p| pos <= p) {
                    set += 1;
                }
                last = Some(pos);
                return (set < 10).then_some(4 + 3 * set + pos);
            }
            crate::dialect::fanuc::macro_argument_variable(l)
        })
        .collect()
}
