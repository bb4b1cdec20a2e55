//! S001/S002: RS274/NGC line-number style.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;

use super::util::{lit, removal_span};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out `N` line numbers in RS274/NGC programs.
    ///
    /// ## Why is this bad?
    /// Line numbers add nothing: LinuxCNC's error messages give the file's line number,
    /// not the N value, and numbers that drift out of order mislead readers. The seed's
    /// style chapter recommends leaving them out.
    ///
    /// ## Example
    /// ```ngc
    /// N10 G0 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default; a fix removes the number.
    ///
    /// Implements: NGC707
    pub static LINE_NUMBERS = {
        code: "S001",
        name: "line-numbers",
        summary: "RS274/NGC line numbers are unnecessary",
        implements: &["NGC707"],
        origin: Static,
        default_enabled: false,
    }
}

declare_rule! {
    /// ## What it does
    /// Points out RS274/NGC line numbers that repeat or go backwards.
    ///
    /// ## Why is this bad?
    /// The interpreter accepts them, but a reader (or an operator searching for a block)
    /// expects each number once and in increasing order.
    ///
    /// ## Example
    /// ```ngc
    /// N20 G0 X1
    /// N10 G0 X2
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// N10 G0 X1
    /// N20 G0 X2
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default.
    ///
    /// Implements: NGC708
    pub static LINE_NUMBER_ORDER = {
        code: "S002",
        name: "line-number-order",
        summary: "Duplicate or decreasing line numbers",
        implements: &["NGC708"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct LineNumbers;
pub struct LineNumberOrder;

impl Rule for LineNumbers {
    fn meta(&self) -> &'static RuleMeta {
        &LINE_NUMBERS
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        for b in &p.blocks {
            for (item, w) in p.words(b) {
                if w.letter == b'N' {
                    out.push(
                        LINE_NUMBERS.diagnostic(
                            crate::diagnostic::Severity::Hint,
                            item.span,
                            "Line numbers are unnecessary: error messages report file lines, not N values. Remove it.",
                        )
                        .with_fix("Remove the line number", vec![TextEdit { span: removal_span(p, item.span), new_text: String::new() }]),
                    );
                }
            }
        }
    }
}

impl Rule for LineNumberOrder {
    fn meta(&self) -> &'static RuleMeta {
        &LINE_NUMBER_ORDER
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let mut last: Option<(f64, crate::span::Span)> = None;
        for b in &p.blocks {
            for (item, w) in p.words(b) {
                let (b'N', Some(v)) = (w.letter, lit(w)) else {
                    continue;
                };
                if let Some((prev, span)) = last {
                    if v <= prev {
                        let what = if v == prev {
                            "repeats"
                        } else {
                            "is lower than"
                        };
                        out.push(
                            LINE_NUMBER_ORDER.diagnostic(
                                crate::diagnostic::Severity::Hint,
                                item.span,
                                format!("`{}` {what} the previous line number; number lines once, in increasing order (or not at all).", p.str_of(item.span)),
                            )
                            .with_related(span, "previous line number"),
                        );
                    }
                }
                last = Some((v, item.span));
            }
        }
    }
}
