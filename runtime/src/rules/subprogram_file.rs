//! Flow-sensitive rule: its metadata and its check, which the interpreter runs on
//! each ServoWorks subprogram file it loads (`Interp::spec_file_loaded`).

use analyzer::declare_rule;
use analyzer::syntax::{BlockKind, ItemKind, Program};
use analyzer::{Severity, Span};

use super::check::Sink;

declare_rule! {
    /// ## What it does
    /// Flags (in the called file) a ServoWorks subprogram that does not end with M99 (warning) and one whose first line is not `O<name>` with the name it was called by (info).
    ///
    /// ## Why is this bad?
    /// A subprogram returns only at M99; without it execution runs off the end of the file. The O line names the program; a different name is confusing.
    ///
    /// ## Example
    /// ```gcode
    /// M98 PNoReturn
    /// M02
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// M98 PMoveXY
    /// M02
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks. Warning (no M99), info (O line).
    ///
    /// Implements: SW025, SW027
    pub static SUBPROGRAM_FILE = {
        code: "F017",
        name: "subprogram-file",
        summary: "Subprogram without M99 or without its O line",
        implements: &["SW025", "SW027"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// The shape of a ServoWorks subprogram file just loaded for `M98 P<name>`:
/// its O line and its closing M99.
pub(crate) fn check(prog: &Program, name: &str, out: &mut Sink<'_>) {
    let mut head: Option<(String, Span)> = None;
    let mut first_code: Option<Span> = None;
    let mut last_block: Option<(Span, bool)> = None;
    for b in &prog.blocks {
        let items = prog.items_of(b);
        if items.is_empty() || !matches!(b.kind, BlockKind::Normal) {
            continue;
        }
        let mut has_code = false;
        let mut m99 = false;
        for it in items {
            match &it.kind {
                ItemKind::ProgramHead { name, .. } if first_code.is_none() => {
                    head = Some((prog.str_of(*name).into_owned(), it.span));
                    has_code = true;
                }
                ItemKind::Word(wd) => {
                    has_code = true;
                    if wd.letter == b'M' && wd.num().is_some_and(|n| n.value == 99.0) {
                        m99 = true;
                    }
                }
                ItemKind::Assign { .. } | ItemKind::Macro(_) => has_code = true,
                _ => {}
            }
        }
        if has_code {
            first_code.get_or_insert(b.span);
            last_block = Some((b.span, m99));
        }
    }
    let Some((last_span, ends_m99)) = last_block else {
        return;
    };
    if !ends_m99 {
        out.diag(&SUBPROGRAM_FILE, Severity::Warning, last_span, format!("subprogram O{name} does not end with M99: a ServoWorks subprogram returns to its caller only at M99; end it with M99"));
    }
    match head {
        Some((n, s)) if !n.eq_ignore_ascii_case(name) => {
            out.diag(&SUBPROGRAM_FILE, Severity::Info, s, format!("the O line names O{n} but the file was called as O{name}: name the subprogram after its file"));
        }
        None => {
            out.diag(&SUBPROGRAM_FILE, Severity::Info, first_code.unwrap_or_default(), format!("subprogram O{name} has no O{name} line: a ServoWorks subprogram starts with its name"));
        }
        _ => {}
    }
}
