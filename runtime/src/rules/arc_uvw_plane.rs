//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::Diagnostic;

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags G2/G3 while a UVW plane (G17.1, G18.1, G19.1) is selected.
    ///
    /// ## Why is this bad?
    /// LinuxCNC makes arcs only in the XYZ planes and stops.
    ///
    /// ## Example
    /// ```gcode
    /// G17.1
    /// G2 X1 Y1 I1 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G17
    /// G2 X1 Y1 I1 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error; interpretation stops.
    ///
    /// Implements: NGC214
    pub static ARC_UVW_PLANE = {
        code: "A011",
        name: "arc-uvw-plane",
        summary: "Arc in a UVW plane",
        implements: &["NGC214"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// A UVW plane (G17.1/G18.1/G19.1) is selected.
    pub(crate) uvw_plane: bool,
}

/// RS274/NGC: arcs in a UVW plane (G17.1/G18.1/G19.1).
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Diagnostic> {
    let w = cx.w;
    // The plane codes are not motion codes: a block with motion codes only has none.
    let gm = |codes: &[u32]| w.has_other_g() && codes.iter().any(|c| w.has_g(*c));
    // Plane selection for arcs in UVW planes.
    if let Some(&(g, s)) = cx.motion.as_ref().filter(|m| matches!(m.0, 20 | 30)) {
        if mem.uvw_plane && !gm(&[170, 180, 190]) {
            return Err(cx.out.err(&ARC_UVW_PLANE, s, format!("G{} in a UVW plane (G17.1/G18.1/G19.1): LinuxCNC cannot make arcs there; select G17, G18 or G19", g / 10)));
        }
    }
    if gm(&[171, 181, 191]) {
        mem.uvw_plane = true;
    } else if gm(&[170, 180, 190]) {
        mem.uvw_plane = false;
    }
    Ok(())
}
