//! Flow-sensitive rule metadata; the check runs in the interpreter.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Reports that the dry run stopped after the configured number of blocks.
    ///
    /// ## Why is this bad?
    /// A loop whose condition never changes runs forever on the machine.
    ///
    /// ## Example
    /// ```gcode
    /// #1=0
    /// o1 while [#1 LT 1]
    /// o1 endwhile
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// #1=0
    /// o1 while [#1 LT 1]
    /// #1=[#1+1]
    /// o1 endwhile
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Warning.
    ///
    /// Implements: —
    pub static STEP_BUDGET = {
        code: "F004",
        name: "step-budget-exceeded",
        summary: "Execution stopped by the step budget",
        implements: &[],
        origin: Runtime,
        default_enabled: true,
    }
}
