//! The motion budget (`RunInput::motion_budget`): one block can multiply motions
//! (`L100000000` repeats, pecks), so the step budget alone does not bound memory.

use super::*;
use crate::rules::step_budget::STEP_BUDGET;

impl Interp<'_, '_> {
    /// Motions produced so far, those already streamed out included.
    fn motion_count(&self) -> u64 {
        (self.motions_drained + self.out.motions.len()) as u64
    }

    /// Whether the motion budget is used up. The first time, reports it at `span`
    /// (F004), which makes the run's result partial.
    pub(super) fn motion_budget_reached(&mut self, span: Span) -> bool {
        let budget = self.input.motion_budget.max(1);
        if self.motion_count() < budget {
            return false;
        }
        let reported = self
            .out
            .diagnostics
            .iter()
            .any(|d| d.code == STEP_BUDGET.code && d.message.contains("motion budget"));
        if !reported {
            self.diag(
                &STEP_BUDGET,
                Severity::Warning,
                span,
                format!("execution stopped after {budget} motions: the motion budget was reached and the rest of the program is not simulated; raise it with --motion-budget"),
            );
        }
        true
    }
}
