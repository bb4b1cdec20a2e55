//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec/budget.rs`, `interp/exec/cycles.rs`, `interp/exec/g7x.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Reports that the dry run stopped at one of its budgets: blocks executed
    /// (`--step-budget`), motions produced (`--motion-budget`) or, for `run --svg`,
    /// the size of the SVG picture (`--max-svg-mb`). The message names the budget and the
    /// flag that raises it; the run's figures then cover only part of the program.
    /// `check` also reports here a program above 128 MB (read in windows) that calls
    /// subprograms or has flow control: its dry run needs the whole program in memory, so
    /// it is not made, and the static checks alone cover the file.
    ///
    /// ## Why is this bad?
    /// A loop whose condition never changes runs forever on the machine; a program
    /// that really runs this long is only partly simulated.
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
    /// Implements: NGC615, FAN145
    pub static STEP_BUDGET = {
        code: "F004",
        name: "step-budget-exceeded",
        summary: "Execution stopped by a run budget",
        implements: &["NGC615", "FAN145"],
        origin: Runtime,
        default_enabled: true,
    }
}
