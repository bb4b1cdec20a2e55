//! S008: RS274/NGC lines whose meaning depends on the order of execution.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;

use super::util::{code_name, has_axis_word};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Points out lines that combine motion with a code whose effect depends on the fixed
    /// order in which a line is executed: tool change `M6`, `T`, `G43`, the `G92` family,
    /// `G10`, `G28`/`G30`, `G54`–`G59.3`, `G20`/`G21`, `G40`–`G42`, program stops and ends,
    /// spindle start with `S`, or a dwell `G4`.
    ///
    /// ## Why is this bad?
    /// RS274/NGC executes the items of a line in a fixed order that is not the written
    /// order, so such a line only does what it seems to do if the reader knows that order.
    /// One action per line is easier to check.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X1 T2 M6
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// T2 M6
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, hint, off by default.
    ///
    /// Implements: NGC705
    pub static ORDER_OF_EXECUTION = {
        code: "S008",
        name: "order-of-execution",
        summary: "Line relies on the order of execution",
        implements: &["NGC705"],
        origin: Static,
        default_enabled: false,
    }
}

pub struct OrderOfExecution;

const G_WITH: &[u32] = &[
    40, 100, 200, 210, 280, 300, 400, 410, 420, 430, 540, 550, 560, 570, 580, 590, 591, 592, 593,
    920, 921, 922, 923,
];
const M_WITH: &[u32] = &[0, 10, 20, 60, 300, 600];

impl Rule for OrderOfExecution {
    fn meta(&self) -> &'static RuleMeta {
        &ORDER_OF_EXECUTION
    }

    /// It needs a G, M, T or S word besides the motion.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NOT_AXIS_FEED
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Rs274ngc {
            return;
        }
        let explicit_motion = cx
            .codes
            .iter()
            .any(|c| c.letter == 'G' && c.group() == Some(1) && !c.is('G', 800));
        let consumer = cx.codes.iter().any(|c| {
            c.letter == 'G'
                && c.num
                    .is_some_and(|n| [100, 280, 300, 520, 920].contains(&n.0))
        });
        let motion = explicit_motion || (has_axis_word(cx) && !consumer);
        if !motion {
            return;
        }
        let g = cx
            .codes
            .iter()
            .find(|c| c.letter == 'G' && c.num.is_some_and(|n| G_WITH.contains(&n.0)));
        let m = cx
            .codes
            .iter()
            .find(|c| c.letter == 'M' && c.num.is_some_and(|n| M_WITH.contains(&n.0)));
        let spindle =
            cx.word(b'S').is_some() && cx.codes.iter().any(|c| c.is('M', 30) || c.is('M', 40));
        let tool = cx
            .words()
            .find(|(_, w)| w.letter == b'T')
            .map(|(i, _)| i.span);
        let other = g
            .map(|c| {
                (
                    c.span,
                    c.num
                        .map(|n| code_name(cx.program.dialect, 'G', n))
                        .unwrap_or_default(),
                )
            })
            .or_else(|| {
                m.map(|c| {
                    (
                        c.span,
                        c.num
                            .map(|n| format!("M{}", n.display()))
                            .unwrap_or_default(),
                    )
                })
            })
            .or_else(|| tool.map(|s| (s, "a T word".to_string())))
            .or_else(|| spindle.then(|| (cx.block.span, "a spindle start with S".to_string())));
        if let Some((span, what)) = other {
            out.push(ORDER_OF_EXECUTION.diagnostic(
                Severity::Hint,
                span,
                format!("Motion on the same line as {what}: what happens first depends on RS274/NGC's order of execution, not on the written order. Put them on separate lines."),
            ));
        }
    }
}
