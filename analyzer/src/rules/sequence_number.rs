//! P007: sequence numbers (`N` words) the control rejects or cannot search.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::{Block, ItemKind, Program, WordValue};

use super::util::{branch_targets, is_emc2, BranchTargets};
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
        if cx.program.dialect == Dialect::Servoworks {
            return;
        }
        // A duplicate matters only where a branch searches for that number.
        let targets = (cx.program.dialect == Dialect::Fanuc).then(|| branch_targets(cx));
        let mut walk = Numbers::new(cx.settings, targets);
        // Plain blocks hold no N word and no program head.
        for b in cx.non_plain_blocks() {
            walk.block(cx.program, b, out);
        }
        walk.finish(out);
    }
}

/// The rule's walk over a file's blocks in order ([`Numbers::block`] on each
/// block that may hold an N word, then [`Numbers::finish`]); a host that reads
/// the file in windows walks every window with one.
pub struct Numbers {
    dialect: Dialect,
    emc2: bool,
    digits: u8,
    max_digits: usize,
    max_value: f64,
    targets: Option<BranchTargets>,
    /// Sequence numbers of the current program that a branch searches for,
    /// by the bits of their value.
    seen: std::collections::HashMap<u64, Span>,
    /// RS274/NGC line numbers with more than five digits: the first and how
    /// many, reported once per file.
    long: Option<(Span, String)>,
    long_count: usize,
    /// FANUC numbers past the format: the first, the last and how many, one
    /// report for the whole run of them.
    too_long: Option<((Span, String), (Span, String))>,
    too_long_count: usize,
}

impl Numbers {
    /// `targets`: the numbers the file's branches search for (FANUC), `None`
    /// where nothing branches.
    pub fn new(settings: &crate::Settings, targets: Option<BranchTargets>) -> Numbers {
        let digits = settings.sequence_number_digits;
        Numbers {
            dialect: settings.dialect,
            emc2: is_emc2(settings),
            digits,
            max_digits: usize::from(digits),
            max_value: 10f64.powi(i32::from(digits)) - 1.0,
            targets,
            seen: std::collections::HashMap::new(),
            long: None,
            long_count: 0,
            too_long: None,
            too_long_count: 0,
        }
    }

    pub fn block(&mut self, p: &Program, b: &Block, out: &mut Vec<Diagnostic>) {
        let d = self.dialect;
        if d == Dialect::Servoworks {
            return;
        }
        let items = p.items_of(b);
        if items
            .iter()
            .any(|i| matches!(i.kind, ItemKind::ProgramHead { .. }))
        {
            self.seen.clear();
        }
        for (idx, item) in items.iter().enumerate() {
            let ItemKind::Word(w) = &item.kind else {
                continue;
            };
            if w.letter != b'N' || w.comma {
                continue;
            }
            let text = || p.str_of(item.span).into_owned();
            let n = match &w.value {
                WordValue::Num(n) => *n,
                WordValue::Missing => continue,
                _ => {
                    if d == Dialect::Fanuc {
                        out.push(SEQUENCE_NUMBER.error(item.span, format!("`{}`: a sequence number cannot be given by a variable or expression. Write a literal number.", text())));
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
                        out.push(SEQUENCE_NUMBER.error(item.span, format!("`{}`: a line number must be the first item of the line (after an optional `/`). Move it to the start or remove it.", text())));
                    }
                    if n.value > 99_999.0 || int_digits > 5 {
                        self.long_count += 1;
                        if self.long.is_none() {
                            self.long = Some((item.span, text()));
                        }
                    }
                    if self.emc2 && n.value.fract() != 0.0 {
                        out.push(SEQUENCE_NUMBER.warning(
                            item.span,
                            format!(
                                "`{}`: the 2007 interpreter reads only whole line numbers.",
                                text()
                            ),
                        ));
                    }
                }
                Dialect::Fanuc => {
                    if int_digits > self.max_digits || n.value > self.max_value {
                        self.too_long_count += 1;
                        let here = (item.span, text());
                        match &mut self.too_long {
                            Some((_, last)) => *last = here,
                            None => self.too_long = Some((here.clone(), here)),
                        }
                    } else if n.value == 0.0 {
                        out.push(SEQUENCE_NUMBER.warning(
                            item.span,
                            "N0 must not be used as a sequence number. Start numbering at N1.",
                        ));
                    } else if self.targets.as_ref().is_some_and(|t| t.contains(n.value)) {
                        match self.seen.get(&n.value.to_bits()) {
                            Some(first) => out.push(
                                SEQUENCE_NUMBER.warning(item.span, format!("`{}` is used twice in this program: GOTO and M99 P branch to whichever block the control finds first. Give each block its own number.", text()))
                                    .with_related(*first, "first use"),
                            ),
                            None => {
                                self.seen.insert(n.value.to_bits(), item.span);
                            }
                        }
                    }
                }
                Dialect::Servoworks => {}
            }
        }
    }

    pub fn finish(self, out: &mut Vec<Diagnostic>) {
        if let Some(((span, text), (last, last_text))) = &self.too_long {
            let digits = self.digits;
            let max_value = self.max_value;
            let option = if digits == 5 {
                ", or set machine.sequence_number_digits = 8 for the 8-digit sequence number option"
            } else {
                ""
            };
            let message = if self.too_long_count == 1 {
                format!("`{text}`: sequence numbers have at most {digits} digits, 1 to {max_value} (alarm PS0003). Renumber the block{option}.")
            } else {
                format!("`{text}` and {} more sequence numbers up to `{last_text}` have more than {digits} digits: the control takes 1 to {max_value} (alarm PS0003). Renumber the program{option}.", self.too_long_count - 1)
            };
            let mut diag = SEQUENCE_NUMBER.error(*span, message);
            if self.too_long_count > 1 {
                diag = diag.with_related(*last, "the last one");
            }
            out.push(diag);
        }
        if let Some((span, text)) = &self.long {
            let more = match self.long_count {
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
