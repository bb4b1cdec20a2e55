//! P007: sequence numbers (`N` words) the control rejects or cannot search.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{ItemKind, WordValue};

use super::util::{branch_targets, is_emc2};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks sequence numbers: an RS274/NGC `N` must be the first item of its line and
    /// have at most five digits; a FANUC `N` is 1 to 99999 (8 digits with the option,
    /// `machine.sequence_number_digits = 8`), cannot come from a variable, and should be
    /// unique within its program when `GOTO` or `M99 P` search for it. Numbers past the
    /// format are reported once for the whole program, with their count.
    ///
    /// ## Why is this bad?
    /// LinuxCNC rejects an `N` later in the line. FANUC raises PS0003 for more than five
    /// digits, `N0` is reserved, `N#1` is not allowed, and with duplicate numbers a branch
    /// lands on whichever block the control finds first.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// N10 G00 X0;
    /// N10 G00 X1.;
    /// GOTO 10;
    /// M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// N10 G00 X0;
    /// N20 G00 X1.;
    /// GOTO 20;
    /// M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error for a misplaced `N`, warning for more than five digits (and a
    /// fractional `N` in `emc2`). FANUC: errors for too many digits or a variable,
    /// warnings for `N0` and duplicates. ServoWorks: not checked.
    ///
    /// Implements: NGC008, NGC009, FAN007, FAN008, FAN009, FAN017
    pub static SEQUENCE_NUMBER = {
        code: "P007",
        name: "sequence-number",
        summary: "Sequence number the control rejects or cannot search",
        implements: &["NGC008", "NGC009", "FAN007", "FAN008", "FAN009", "FAN017"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct SequenceNumber;

impl Rule for SequenceNumber {
    fn meta(&self) -> &'static RuleMeta {
        &SEQUENCE_NUMBER
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        let d = p.dialect;
        if d == Dialect::Servoworks {
            return;
        }
        // Sequence numbers of the current program, by the bits of their value.
        let mut seen: std::collections::HashMap<u64, crate::span::Span> =
            std::collections::HashMap::new();
        // RS274/NGC line numbers with more than five digits: reported once per file.
        let mut long: Vec<(crate::span::Span, String)> = Vec::new();
        // FANUC numbers past the format: one report for the whole run of them.
        let mut too_long: Vec<(crate::span::Span, String)> = Vec::new();
        // A duplicate matters only where a branch searches for that number.
        let targets = (d == Dialect::Fanuc).then(|| branch_targets(cx));
        let max_digits = usize::from(cx.settings.sequence_number_digits);
        let max_value = 10f64.powi(i32::from(cx.settings.sequence_number_digits)) - 1.0;
        // Plain blocks hold no N word and no program head.
        for b in cx.non_plain_blocks() {
            let items = p.items_of(b);
            if items
                .iter()
                .any(|i| matches!(i.kind, ItemKind::ProgramHead { .. }))
            {
                seen.clear();
            }
            for (idx, item) in items.iter().enumerate() {
                let ItemKind::Word(w) = &item.kind else {
                    continue;
                };
                if w.letter != b'N' || w.comma {
                    continue;
                }
                let text = p.str_of(item.span).into_owned();
                let n = match &w.value {
                    WordValue::Num(n) => *n,
                    WordValue::Missing => continue,
                    _ => {
                        if d == Dialect::Fanuc {
                            out.push(SEQUENCE_NUMBER.error(item.span, format!("`{text}`: a sequence number cannot be given by a variable or expression. Write a literal number.")));
                        }
                        continue;
                    }
                };
                let int_digits = p
                    .str_of(n.span)
                    .trim_start_matches(['+', '-'])
                    .split('.')
                    .next()
                    .map(|s| s.chars().filter(|c| c.is_ascii_digit()).count())
                    .unwrap_or(0);
                match d {
                    Dialect::Rs274ngc => {
                        if idx > 0 {
                            out.push(SEQUENCE_NUMBER.error(item.span, format!("`{text}`: a line number must be the first item of the line (after an optional `/`). Move it to the start or remove it.")));
                        }
                        if n.value > 99_999.0 || int_digits > 5 {
                            long.push((item.span, text.clone()));
                        }
                        if is_emc2(cx.settings) && n.value.fract() != 0.0 {
                            out.push(SEQUENCE_NUMBER.warning(
                                item.span,
                                format!(
                                    "`{text}`: the 2007 interpreter reads only whole line numbers."
                                ),
                            ));
                        }
                    }
                    Dialect::Fanuc => {
                        if int_digits > max_digits || n.value > max_value {
                            too_long.push((item.span, text));
                        } else if n.value == 0.0 {
                            out.push(SEQUENCE_NUMBER.warning(
                                item.span,
                                "N0 must not be used as a sequence number. Start numbering at N1.",
                            ));
                        } else if let Some(first) = seen
                            .get(&n.value.to_bits())
                            .filter(|_| targets.as_ref().is_some_and(|t| t.contains(n.value)))
                        {
                            out.push(
                                SEQUENCE_NUMBER.warning(item.span, format!("`{text}` is used twice in this program: GOTO and M99 P branch to whichever block the control finds first. Give each block its own number."))
                                    .with_related(*first, "first use"),
                            );
                        } else {
                            seen.insert(n.value.to_bits(), item.span);
                        }
                    }
                    Dialect::Servoworks => {}
                }
            }
        }
        if let (Some((span, text)), Some((last, last_text))) = (too_long.first(), too_long.last()) {
            let digits = cx.settings.sequence_number_digits;
            let option = if digits == 5 {
                ", or set machine.sequence_number_digits = 8 for the 8-digit sequence number option"
            } else {
                ""
            };
            let message = if too_long.len() == 1 {
                format!("`{text}`: sequence numbers have at most {digits} digits, 1 to {max_value} (alarm PS0003). Renumber the block{option}.")
            } else {
                format!("`{text}` and {} more sequence numbers up to `{last_text}` have more than {digits} digits: the control takes 1 to {max_value} (alarm PS0003). Renumber the program{option}.", too_long.len() - 1)
            };
            let mut diag = SEQUENCE_NUMBER.error(*span, message);
            if too_long.len() > 1 {
                diag = diag.with_related(*last, "the last one");
            }
            out.push(diag);
        }
        if let Some((span, text)) = long.first() {
            let more = match long.len() {
                1 => String::new(),
                n => format!(" ({} more lines like it)", n - 1),
            };
            out.push(SEQUENCE_NUMBER.warning(
                *span,
                format!("`{text}`: line numbers have at most five digits (0 to 99999) in RS274/NGC; LinuxCNC accepts more, other readers may not{more}."),
            ));
        }
    }
}
