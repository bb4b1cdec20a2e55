//! S010: G92 offsets, which persist.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::{block_g_codes, block_has_word_value};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out `G92` axis offsets, and warns when a program ends (`M2`/`M30`) with a
    /// `G92` offset that no `G92.1`/`G92.2` has cleared.
    ///
    /// ## Why is this bad?
    /// LinuxCNC keeps `G92` offsets in its parameter file: they survive the program end and
    /// even a restart, and shift the next program. Work offsets `G54`–`G59.3` (or `G52`)
    /// do the same job visibly.
    ///
    /// ## Example
    /// ```ngc
    /// G92 X0 Y0
    /// G0 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G10 L20 P1 X0 Y0
    /// G54
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, off by default: info on each `G92`, warning at an end reached with the
    /// offset still set (file order).
    ///
    /// Implements: NGC431, NGC710
    pub static G92_OFFSET = {
        code: "S010",
        name: "g92-offset",
        summary: "G92 offsets persist after the program",
        implements: &["NGC431", "NGC710"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct G92Offset;

impl Rule for G92Offset {
    fn meta(&self) -> &'static RuleMeta {
        &G92_OFFSET
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let mut active: Option<crate::span::Span> = None;
        for b in &p.blocks {
            let g = block_g_codes(p, b);
            if g.contains(&921) || g.contains(&922) {
                active = None;
            }
            if g.contains(&920) {
                let span = p
                    .words(b)
                    .find(|(_, w)| w.letter == b'G' && w.num().is_some_and(|n| n.value == 92.0))
                    .map(|(i, _)| i.span)
                    .unwrap_or(b.span);
                out.push(G92_OFFSET.diagnostic(
                    Severity::Info,
                    span,
                    "G92 offsets persist after the program ends (LinuxCNC stores them); prefer a work offset G54–G59.3 or G52.",
                ));
                active = Some(span);
            }
            if block_has_word_value(p, b, b'M', 2.0) || block_has_word_value(p, b, b'M', 30.0) {
                if let Some(set) = active.take() {
                    let span = p.items_of(b).first().map(|i| i.span).unwrap_or(b.span);
                    out.push(
                        G92_OFFSET.diagnostic(Severity::Warning, span, "The program ends with a G92 offset still set; it will shift the next program. Clear it with G92.1 before the end.")
                            .with_related(set, "offset set here"),
                    );
                }
            }
        }
        // The file's end ends the program too: the offset outlives it just the same.
        if let Some(set) = active {
            let last = p
                .blocks
                .iter()
                .rev()
                .find(|b| super::util::has_code_items(p, b));
            if let Some(b) = last {
                // Where the program stops: after the last block (which may be the G92 itself).
                let span = crate::span::Span::new(b.span.end, b.span.end);
                out.push(
                    G92_OFFSET.diagnostic(Severity::Warning, span, "The file ends with a G92 offset still set; it will shift the next program. Clear it with G92.1 before the end.")
                        .with_related(set, "offset set here"),
                );
            }
        }
    }
}
