//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Diagnostic;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags M72 (restore modal state) when no M70 or M73 saved one at the same call level.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops: there is nothing to restore ("missing M70/M73?").
    ///
    /// ## Example
    /// ```gcode
    /// M72
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M70
    /// G91
    /// M72
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC813
    pub static CONTEXT_RESTORE = {
        code: "F013",
        name: "context-restore",
        summary: "M72 without a saved modal state",
        implements: &["NGC813"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// Call levels (frame depth) at which M70/M73 saved the modal state.
    pub(crate) saved_levels: Vec<usize>,
}

/// RS274/NGC: M70/M73 save the modal state of a call level; M72 needs one saved.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Diagnostic> {
    let w = cx.w;
    // M70/M73 save the modal state of this call level; M72 restores it.
    let level = cx.call_level;
    if (w.has_m(700) || w.has_m(730)) && !mem.saved_levels.contains(&level) {
        mem.saved_levels.push(level);
    }
    if w.has_m(720) && !mem.saved_levels.contains(&level) {
        return Err(cx.out.err(&CONTEXT_RESTORE, w.m_span(720), "M72 restores a modal state that no M70 or M73 saved at this call level: LinuxCNC stops (missing M70/M73?)"));
    }
    mem.saved_levels.retain(|l| *l <= level);
    Ok(())
}
