//! W022: ServoWorks integer coordinates under "Integer Programming with Machine Unit".

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, TextEdit};
use crate::dialect::Dialect;

use super::{BlockCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// When the machine profile enables ServoWorks "Integer Programming with Machine Unit"
    /// (`machine.integer_machine_unit = true`), notes coordinates written without a decimal
    /// point (`X14`), which the control reads as a number of machine units.
    ///
    /// ## Why is this bad?
    /// With the option on, `X14` means 14 machine units (0.014 mm with a 0.001 mm unit)
    /// while `X14.` means 14 mm. Mixing the two forms in one program gives unintended
    /// moves.
    ///
    /// ## Example
    /// ```servoworks integer_machine_unit
    /// G00 X14 Y14.5
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks integer_machine_unit
    /// G00 X14.0 Y14.5
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, info, only with the option enabled. Applies to axis words, I/J/K, R and Q
    /// (zero is the same in both forms), not to `G10` data, `G04 X` seconds, `G51` factors,
    /// the `G68` angle or `G65` arguments.
    ///
    /// Implements: SW007
    pub static INTEGER_MACHINE_UNIT = {
        code: "W022",
        name: "integer-machine-unit",
        summary: "Integer coordinate read as machine units",
        implements: &["SW007"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct IntegerMachineUnit;

impl Rule for IntegerMachineUnit {
    fn meta(&self) -> &'static RuleMeta {
        &INTEGER_MACHINE_UNIT
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        if cx.program.dialect != Dialect::Servoworks || !cx.settings.integer_machine_unit {
            return;
        }
        // Data words that are never lengths: G10 values (ms, Hz, types), G04 X seconds,
        // G51 factors, the G68 angle, G65 arguments.
        if [100, 40, 650].iter().any(|t| cx.has_code('G', *t)) {
            return;
        }
        // An M98 block only calls (its motion is ignored, W010) and its words are
        // the call's integers (W006): no length advice there.
        if cx.has_code('M', 980) {
            return;
        }
        let scaling = cx.has_code('G', 510);
        let rotation = cx.has_code('G', 680);
        for (item, w) in cx.words() {
            if !b"XYZABCUVWEIJKRQ".contains(&w.letter) || w.comma {
                continue;
            }
            if (scaling && matches!(w.letter, b'I' | b'J' | b'K')) || (rotation && w.letter == b'R')
            {
                continue;
            }
            let Some(n) = w.num() else { continue };
            if !n.has_point && n.value != 0.0 {
                let text = cx.program.str_of(item.span).into_owned();
                out.push(INTEGER_MACHINE_UNIT.info(
                    item.span,
                    format!("`{text}` has no decimal point, so with Integer Programming with Machine Unit it counts machine units, not mm or inches. Write `{text}.0` if you mean {}.", n.value),
                ).with_fix(format!("Write `{text}.0`"), vec![TextEdit { span: crate::Span::new(item.span.end, item.span.end), new_text: ".0".into() }]));
            }
        }
    }
}
