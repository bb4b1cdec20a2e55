//! P010: a lathe or Haas mill program checked as a FANUC 30i mill program.

use crate::control::{control_signature, Control, Signature};
use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::syntax::Program;

use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Recognises a FANUC or Haas lathe program (a `T0101` tool and offset, `G50 S`
    /// speed clamp, `G70`/`G71`/`G72` with `P`/`Q`, `G28 U W`, `G99` feed per revolution)
    /// or a Haas mill program (`G187`, `G103`, a 5-digit O number, `G04 P1.` in seconds,
    /// `M97`, `G154 P`), or a program in another control's macro language (LNC 6800,
    /// Syntec, Fadal Format 2: `//` comments, `@100` variables, names such as `END_IF`,
    /// a `%@MACRO` header, `#V10` or `#PRINT`, `'` comments, `!=`, `"…"` strings) checked
    /// in the `fanuc` dialect, from two signs of different kinds, and reports it once, at
    /// the first sign. Every other finding of the file is dropped and the program is not
    /// interpreted.
    ///
    /// ## Why is this bad?
    /// The `fanuc` dialect models the FANUC 30i mill. A lathe program read as a mill
    /// program gets a flood of false findings (U and W are not axes, X is a diameter)
    /// and a cycle time that means nothing; a Haas program uses codes and units the
    /// FANUC mill does not have.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000
    /// T0101
    /// G50 S2000
    /// G0 X2. Z0.1
    /// M30
    /// %
    /// ```
    ///
    /// Use instead (a FANUC mill program):
    /// ```fanuc
    /// %
    /// O1000
    /// T1 M6
    /// G0 G90 G54 X0 Y0
    /// M30
    /// %
    /// ```
    ///
    /// ## Dialects
    /// FANUC: warning. Lathe and Haas programs are not checked; one sign alone (a `T101`
    /// tool number, a `G99` return level) is ordinary in mill programs and never fires.
    ///
    /// Implements: — (no catalogue id)
    pub static CONTROL_MISMATCH = {
        code: "P010",
        name: "control-mismatch",
        summary: "Program for a lathe, a Haas mill or another macro language checked as a FANUC 30i mill program",
        implements: &[],
        origin: Static,
        default_enabled: true,
    }
}

pub struct ControlMismatch;

/// The P010 diagnostic of a program, if it looks written for another control.
pub fn mismatch_diagnostic(program: &Program) -> Option<Diagnostic> {
    signature_diagnostic(&control_signature(program)?)
}

/// The P010 diagnostic of a signature.
pub fn signature_diagnostic(sig: &Signature) -> Option<Diagnostic> {
    let first = sig.evidence.first()?;
    let what = match sig.control {
        Control::Lathe { .. } => "lathe programs",
        Control::HaasMill => "Haas mill programs",
        Control::OtherMacro => "programs in other languages",
    };
    Some(CONTROL_MISMATCH.warning(
        first.span,
        format!(
            "This looks like {} ({}): Partscope checks FANUC 30i mill programs; {what} are not checked. No other finding and no cycle time is reported for this file.",
            sig.control.name(),
            sig.describe()
        ),
    ))
}

impl Rule for ControlMismatch {
    fn meta(&self) -> &'static RuleMeta {
        &CONTROL_MISMATCH
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        out.extend(mismatch_diagnostic(cx.program));
    }
}
