//! P003: FANUC `GOTO` targets that do not exist or jump into a loop.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::syntax::{ItemKind, MacroStmt};

use super::macro_loop_structure::{literal, loops};
use super::util::lit;
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks the targets of `GOTO n` and `IF […] GOTO n` when `n` is a number: a block
    /// with sequence number `N n` must exist in the same `O` program, and it must not lie
    /// inside a `DO … END` loop that the `GOTO` is outside of.
    ///
    /// ## Why is this bad?
    /// A missing target stops the program with alarm PS0128 when the branch is taken —
    /// possibly late in a long run. Branching into a loop skips its `WHILE`, so the
    /// control does not know which loop the `END` belongs to.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// IF [#1 EQ 1] GOTO 20;
    /// N10 G00 X0;
    /// M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// IF [#1 EQ 1] GOTO 20;
    /// N10 G00 X0;
    /// N20 M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// FANUC, error. Computed targets (`GOTO #1`) are checked when the program runs.
    ///
    /// Reported by this rule, not F007, when both see a GOTO to a sequence number that does not exist on the same text (one diagnostic per fault).
    ///
    /// Implements: FAN124, FAN125
    pub static GOTO_TARGET = {
        code: "P003",
        name: "goto-target",
        summary: "GOTO target missing or inside a loop",
        implements: &["FAN124", "FAN125"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct GotoTarget;

impl Rule for GotoTarget {
    fn meta(&self) -> &'static RuleMeta {
        &GOTO_TARGET
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Fanuc {
            return;
        }
        // Program sections: a new `O` head starts a new search scope.
        // Plain blocks (words only, no N) hold no head, sequence number or GOTO, so
        // a run of them takes one step in each pass below.
        let segs = cx.segments();
        let mut section = vec![0usize; p.blocks.len()];
        let mut cur = 0;
        for seg in segs {
            let Some(b) = p.blocks.get(seg.first) else {
                break;
            };
            if !seg.plain
                && p.items_of(b)
                    .iter()
                    .any(|i| matches!(i.kind, ItemKind::ProgramHead { .. }))
            {
                cur += 1;
            }
            if let Some(run) = section.get_mut(seg.first..seg.first + seg.len) {
                run.fill(cur);
            }
        }
        let non_plain = || {
            segs.iter()
                .filter(|s| !s.plain)
                .filter_map(|s| p.blocks.get(s.first).map(|b| (s.first, b)))
        };
        let mut numbers: Vec<(usize, f64)> = Vec::new();
        for (bi, b) in non_plain() {
            for (_, w) in p.words(b) {
                if w.letter == b'N' {
                    if let Some(v) = lit(w) {
                        numbers.push((bi, v));
                    }
                }
            }
        }
        // (program section, value bits) → first block with that sequence number.
        let mut index: std::collections::HashMap<(usize, u64), usize> =
            std::collections::HashMap::new();
        for &(tb, v) in &numbers {
            index.entry((section[tb], v.to_bits())).or_insert(tb);
        }
        let ranges = loops(p, segs, None);
        for (bi, b) in non_plain() {
            for item in p.items_of(b) {
                let target = match item.kind {
                    ItemKind::Macro(MacroStmt::Goto { target })
                    | ItemKind::Macro(MacroStmt::IfGoto { target, .. }) => target,
                    _ => continue,
                };
                let Some(n) = literal(p, target) else {
                    continue;
                };
                let Some(&tb) = index.get(&(section[bi], n.to_bits())) else {
                    out.push(GOTO_TARGET.error(
                        item.span,
                        format!("GOTO {n}: no block N{n} in this program, so the branch stops with alarm PS0128. Add the sequence number or fix the target."),
                    ));
                    continue;
                };
                if let Some(&(s, _)) = ranges
                    .iter()
                    .find(|(s, e)| *s < tb && tb <= *e && !(*s <= bi && bi <= *e))
                {
                    let mut d = GOTO_TARGET.error(
                        item.span,
                        format!("GOTO {n} jumps into a DO … END loop from outside it: the loop's WHILE is skipped and its END has no open DO. Branch to the WHILE block instead."),
                    );
                    if let Some(w) = p.blocks.get(s) {
                        d = d.with_related(w.span, "loop start");
                    }
                    out.push(d);
                }
            }
        }
    }
}
