//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).
//! `involute::comma_words` also reports this code (`,C`/`,R` in polar mode).

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags G00 in polar coordinate interpolation (G12.1) and optional chamfering or corner R (`,C` `,R`) in polar coordinate modes (G12.1, G16).
    ///
    /// ## Why is this bad?
    /// Polar coordinate interpolation allows only G01, G02, G03, G02.2 and G03.2 (the FANUC alarm list); chamfering and corner R are not allowed in polar coordinate mode.
    ///
    /// ## Example
    /// ```gcode
    /// G12.1
    /// G00 X10.
    /// G13.1
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G12.1
    /// G01 X10. F100
    /// G13.1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// FANUC. Warning (G00), error (chamfer/corner R).
    ///
    /// Implements: FAN158, FAN061
    pub static POLAR_INTERP = {
        code: "K004",
        name: "polar-interp",
        summary: "G00 or chamfer/corner R in polar modes",
        implements: &["FAN158", "FAN061"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// FANUC: polar coordinate interpolation (G12.1) is on.
    pub(crate) on: bool,
}

/// FANUC: G12.1/G13.1 switch polar coordinate interpolation; a G00 in it is flagged
/// (`motion` as `involute::check` answers it).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem, motion: Option<(u32, Span)>) {
    let w = cx.w;
    if w.has_g(121) {
        mem.on = true;
    } else if w.has_g(131) {
        mem.on = false;
    }
    if let Some((0, s)) = motion.filter(|_| mem.on) {
        cx.out.diag(&POLAR_INTERP, Severity::Warning, s, "G00 in polar coordinate interpolation (G12.1): only G01, G02, G03, G02.2 and G03.2 are allowed there; cancel with G13.1 before rapids");
    }
}
