//! G002: two M codes of one M modal group in a block (RS274/NGC).

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;

use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags two M codes of the same M modal group on one RS274/NGC line, for example
    /// `M3 M5` (spindle) or `M7 M8` (coolant).
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses the line with `Two M codes used from same modal group`. Note that
    /// mist and flood coolant (`M7`, `M8`) share a group: they may both be on, but they must
    /// be switched on by separate lines.
    ///
    /// ## Example
    /// ```ngc
    /// M7 M8
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// M7
    /// M8
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC, error. ServoWorks and FANUC have no M-code groups (see W001 and G003).
    ///
    /// Implements: NGC102, NGC511
    pub static M_GROUP_CONFLICT = {
        code: "G002",
        name: "m-group-conflict",
        summary: "Two M codes of one M modal group in a line",
        implements: &["NGC102", "NGC511"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct MGroupConflict;

impl Rule for MGroupConflict {
    fn meta(&self) -> &'static RuleMeta {
        &M_GROUP_CONFLICT
    }

    /// A report needs two M codes.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::repeated(b"M")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Rs274ngc {
            return;
        }
        let m: Vec<_> = cx
            .codes
            .iter()
            .filter(|c| c.letter == 'M' && c.info.is_some())
            .collect();
        for (j, later) in m.iter().enumerate() {
            let (Some(li), Some(ln)) = (later.info, later.num) else {
                continue;
            };
            let Some(earlier) = m[..j]
                .iter()
                .find(|e| e.info.is_some_and(|ei| ei.same_group(li)))
            else {
                continue;
            };
            let Some(en) = earlier.num else { continue };
            let coolant = [en.0, ln.0] == [70, 80] || [en.0, ln.0] == [80, 70];
            let msg = if coolant {
                "Two M codes used from same modal group: M7 and M8 may both be on, but LinuxCNC refuses them on one line. Put M7 and M8 on separate lines.".to_string()
            } else {
                format!(
                    "Two M codes used from same modal group: M{} and M{} are both in M group {}, and the interpreter refuses the line. Keep one, or put them on separate lines.",
                    en.display(),
                    ln.display(),
                    li.group.unwrap_or(0)
                )
            };
            out.push(
                M_GROUP_CONFLICT
                    .error(later.span, msg)
                    .with_related(earlier.span, "the other code of the group"),
            );
        }
    }
}
