//! G005: codes the selected variant or profile lacks.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::{Dialect, Variant};

use super::util::{code_name, is_custom};
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags G and M codes that the dialect has but the selected product variant or
    /// language profile does not: exponential interpolation `G02.3`/`G03.3` on a
    /// ServoWorks S-100M, tool centre point control `G43.2` on anything but an S-140M, or a
    /// LinuxCNC 2.9 code (`G5`, `G33.1`, `M19` …) in the 2007 `emc2` profile.
    ///
    /// ## Why is this bad?
    /// The control does not have the function: ServoWorks ignores the code or stops,
    /// the 2007 interpreter reports an unknown code.
    ///
    /// ## Example
    /// ```servoworks variant=S-120M
    /// G43.2 H1
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks variant=S-120M
    /// G43 Z0 H1
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks (variant S-100M/S-120M/S-140M) and RS274/NGC (profile `linuxcnc`/`emc2`),
    /// error. The variant is set with `variant = …` in `partscope.toml` (S-140M by default).
    ///
    /// Implements: SW043, SW097
    pub static CODE_NOT_ON_VARIANT = {
        code: "G005",
        name: "code-not-on-variant",
        summary: "Code the selected variant or profile lacks",
        implements: &["SW043", "SW097"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct CodeNotOnVariant;

impl Rule for CodeNotOnVariant {
    fn meta(&self) -> &'static RuleMeta {
        &CODE_NOT_ON_VARIANT
    }

    /// Only G and M codes are looked up.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::letters(b"GM")
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        let v = cx.settings.variant;
        if v.dialect() != d {
            return;
        }
        for c in cx.codes {
            let (Some(info), Some(num)) = (c.info, c.num) else {
                continue;
            };
            if info.on_variant(v) || is_custom(cx.settings, c.letter, num) {
                continue;
            }
            let name = code_name(d, c.letter, num);
            let have: Vec<&str> = [
                Variant::S100M,
                Variant::S120M,
                Variant::S140M,
                Variant::Linuxcnc,
                Variant::Emc2,
                Variant::Fanuc30i,
            ]
            .into_iter()
            .filter(|x| x.dialect() == d && info.on_variant(*x))
            .map(|x| x.as_str())
            .collect();
            let msg = match d {
                Dialect::Rs274ngc => format!(
                    "{name} is not available in the `{}` profile (only in {}): the interpreter reports an unknown code. Select the matching profile, or avoid the code.",
                    v.as_str(),
                    have.join(", ")
                ),
                _ => format!(
                    "{name} is only available on {}; this program is checked for {}, where the code does not exist. Set `variant` in partscope.toml if the machine is another model.",
                    have.join(" and "),
                    v.as_str()
                ),
            };
            out.push(CODE_NOT_ON_VARIANT.error(c.span, msg));
        }
    }
}
