//! Flow-sensitive rule: its metadata and its check, which the interpreter calls
//! for every block from `interp/checks.rs` (in the order there).

use analyzer::declare_rule;
use analyzer::{Diagnostic, Severity};

use super::check::Cx;

declare_rule! {
    /// ## What it does
    /// Flags M100–M199 unless the number is listed in `machine.user_m_codes`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC runs a user M code from a program file of that name; without it the interpreter stops with "Unknown m code used".
    ///
    /// ## Example
    /// ```gcode
    /// M101
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC. Error, and interpretation stops, when `machine.user_m_codes` is
    /// configured or the machine's search path is (`machine.subroutine_path`).
    /// Without either the program file may well exist on the machine: information,
    /// once per code, and the dry run continues as if the code did nothing.
    ///
    /// Implements: NGC507
    pub static UNKNOWN_USER_M = {
        code: "X009",
        name: "unknown-user-m",
        summary: "User M code M100–M199 that is not configured",
        implements: &["NGC507"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// What the check remembers between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Mem {
    /// User M codes already noted as unconfigured.
    pub(crate) noted: Vec<i64>,
}

/// RS274/NGC: user M codes M100–M199 against the configured list.
#[inline(always)]
pub(crate) fn check(cx: &mut Cx<'_, '_>, mem: &mut Mem) -> Result<(), Diagnostic> {
    let w = cx.w;
    // User M codes M100–M199 run a program from the configured list.
    if let Some(&(m, s)) = w.m.iter().find(|(m, _)| (1000..=1990).contains(m)) {
        let n = i64::from(m / 10);
        let listed = cx.input.machine.user_m_codes.as_ref();
        let known = listed.is_some_and(|a| a.contains(&n));
        // Without a list and without the machine's search path the program file
        // M<n> may well exist on the machine: say so once per code, go on.
        if !known && listed.is_none() && !cx.input.resolver.searches_like_the_control() {
            if !mem.noted.contains(&n) {
                mem.noted.push(n);
                cx.out.diag(&UNKNOWN_USER_M, Severity::Info, s, format!("M{n} is a user M code: LinuxCNC runs the program file M{n} from its USER_M_PATH. None is configured here, so the dry run takes it as doing nothing; list the codes the machine has in `machine.user_m_codes` to have the others reported"));
            }
        } else if !known {
            return Err(cx.out.err(&UNKNOWN_USER_M, s, format!("Unknown m code used: M{n}: no user M-code program M{n} is configured; list it in `machine.user_m_codes` or remove it")));
        }
    }
    Ok(())
}
