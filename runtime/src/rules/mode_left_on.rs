//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! at M2/M30 (`Interp::end_checks` in `interp/checks.rs`).

use analyzer::declare_rule;
use analyzer::{Dialect, Severity, Span};

use super::check::Sink;
use crate::interp::State;

declare_rule! {
    /// ## What it does
    /// Flags M2/M30 reached with a mode still on that the program should cancel: cutter compensation, a G92/G52 offset, 3D-DLACC, a canned cycle, polar coordinates, G66, rotation or scaling (which ones depends on the dialect).
    ///
    /// ## Why is this bad?
    /// The end code does not reset these modes on every control (LinuxCNC keeps G92, ServoWorks keeps G52 and DLACC, FANUC keeps G16/G66/G68/G51 unless reset is configured), so the next program or MDI command starts in an unexpected mode.
    ///
    /// ## Example
    /// ```gcode
    /// G41.1 D0.2
    /// G1 X1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G41.1 D0.2
    /// G1 X1 F100
    /// G40 G1 X2
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Warning. RS274/NGC: cutter comp, G92/G52. ServoWorks: cutter comp, DLACC, G52, canned cycle. FANUC: G16, G66, G68, G51.
    ///
    /// Implements: SW058, SW086, SW111, SW135, NGC422, NGC428, FAN063
    pub static MODE_LEFT_ON = {
        code: "F008",
        name: "mode-left-on-at-end",
        summary: "A mode still active at program end",
        implements: &["SW058", "SW086", "SW111", "SW135", "NGC422", "NGC428", "FAN063"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// Modes a program should cancel before M2/M30: each one left on is reported.
pub(crate) fn check(st: &State, dialect: Dialect, span: Span, out: &mut Sink<'_>) {
    let d = dialect;
    let m = &st.modal;
    let mut left: Vec<&str> = Vec::new();
    if m.comp != 400 && d != Dialect::Fanuc {
        left.push("cutter radius compensation (cancel with G40)");
    }
    match d {
        Dialect::Rs274ngc => {
            if st.g92.iter().any(|v| *v != 0.0) {
                left.push("a G92/G52 offset (clear with G92.1, or G52 with zeros)");
            }
        }
        Dialect::Servoworks => {
            if m.dlacc {
                left.push("3D-DLACC look-ahead (cancel with G08)");
            }
            if st.g52.iter().any(|v| *v != 0.0) {
                left.push("a G52 local coordinate system (cancel with G52 and zero axes)");
            }
            if m.modal_cycle() {
                left.push("a canned cycle (cancel with G80)");
            }
        }
        Dialect::Fanuc => {
            if m.polar {
                left.push("polar coordinates (cancel with G15)");
            }
            if st.g66.is_some() {
                left.push("a G66 modal macro call (cancel with G67)");
            }
            if m.rotation {
                left.push("coordinate rotation (cancel with G69)");
            }
            if m.scaling {
                left.push("scaling (cancel with G50)");
            }
        }
    }
    for what in left {
        out.diag(
            &MODE_LEFT_ON,
            Severity::Warning,
            span,
            format!("the program ends with {what} still active: the next program or MDI command starts in that mode"),
        );
    }
}
