//! Flow-sensitive rule metadata. The check is part of executing the block, where
//! the state it needs is computed: `interp/exec.rs`.

use analyzer::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a move whose end point lies outside an axis's travel (`min_travel` /
    /// `max_travel` of the `[[machine.axes]]` entry), in machine coordinates after all
    /// offsets.
    ///
    /// ## Why is this bad?
    /// The control stops with a soft-limit alarm before or during the move, often in
    /// the middle of a cut.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X500
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X50
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All; only axes with both limits in the profile are checked. Warning, at most
    /// one per block and axis, and at most 100 per run.
    ///
    /// Implements: — (no catalogue id)
    pub static TRAVEL_LIMIT = {
        code: "K002",
        name: "travel-limit-exceeded",
        summary: "Move beyond an axis's travel limits",
        implements: &[],
        origin: Runtime,
        default_enabled: true,
    }
}
