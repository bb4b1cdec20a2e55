//! The registry: every rule of the analyzer, by stable code.
//!
//! Codes never change meaning once released. The runtime keeps its own list of
//! flow-sensitive rules (`runtime::rules::REGISTRY`); hosts combine the two.

use super::syntax_rules as syn;
use super::{Rule, RuleMeta};

/// Declares the registry from one list: the syntax rules' metadata, then each
/// static rule once as `module::Type => STATIC`, both in code order. It makes
/// [`RULES`] (every rule's metadata), [`STATIC_RULES`] (the static rules, in the
/// same order) and a `pub(crate) use` of each static rule's type and metadata
/// (`twins.rs` names them as `registry::STATIC`).
macro_rules! registry {
    (
        syntax: [$($syntax:ident),* $(,)?],
        static_rules: [$($module:ident::$rule:ident => $meta:ident),* $(,)?] $(,)?
    ) => {
        $(pub(crate) use super::$module::{$rule, $meta};)*

        /// Metadata of every syntax and static rule, in code order.
        pub static RULES: &[&RuleMeta] = &[$(&syn::$syntax,)* $(&$meta,)*];

        /// The static rules that run over parsed programs, in code order.
        pub static STATIC_RULES: &[&dyn Rule] = &[$(&$rule,)*];
    };
}

registry! {
    syntax: [
        IO_ERROR,
        UNCLOSED_COMMENT,
        NESTED_COMMENT,
        MISSING_VALUE,
        MALFORMED_NUMBER,
        UNKNOWN_CHARACTER,
        UNBALANCED_BRACKET,
        MISPLACED_BLOCK_SKIP,
        LOWERCASE,
        NOT_TEXT,
        BAD_EXPRESSION,
        MISPLACED_PERCENT,
        TEXT_AFTER_EOB,
        EXPRESSION_TOO_DEEP,
        BLOCK_TOO_MANY_ITEMS,
        CONFIG_ISSUE,
    ],
    static_rules: [
        modal_group_conflict::ModalGroupConflict => MODAL_GROUP_CONFLICT,
        m_group_conflict::MGroupConflict => M_GROUP_CONFLICT,
        too_many_m_words::TooManyMWords => TOO_MANY_M_WORDS,
        unknown_code::UnknownCode => UNKNOWN_CODE,
        code_not_on_variant::CodeNotOnVariant => CODE_NOT_ON_VARIANT,
        duplicate_word::DuplicateWord => DUPLICATE_WORD,
        conflicting_words::ConflictingWords => CONFLICTING_WORDS,
        missing_required_word::MissingRequiredWord => MISSING_REQUIRED_WORD,
        axis_word_conflict::AxisWordConflict => AXIS_WORD_CONFLICT,
        unknown_address::UnknownAddress => UNKNOWN_ADDRESS,
        integer_word::IntegerWord => INTEGER_WORD,
        word_value_range::WordValueRange => WORD_VALUE_RANGE,
        dlacc_form::DlaccForm => DLACC_FORM,
        g54_with_words::G54WithWords => G54_WITH_WORDS,
        m98_with_motion::M98WithMotion => M98_WITH_MOTION,
        block_too_long::BlockTooLong => BLOCK_TOO_LONG,
        macro_call_arguments::MacroCallArguments => MACRO_CALL_ARGUMENTS,
        subprogram_name_glued::SubprogramNameGlued => SUBPROGRAM_NAME_GLUED,
        bracket_nesting::BracketNesting => BRACKET_NESTING,
        constant_expression::ConstantExpression => CONSTANT_EXPRESSION,
        parameter_number::ParameterNumber => PARAMETER_NUMBER,
        expression_form::ExpressionForm => EXPRESSION_FORM,
        parameter_same_line::ParameterSameLine => PARAMETER_SAME_LINE,
        comment_use::CommentUse => COMMENT_USE,
        cycle_words::CycleWords => CYCLE_WORDS,
        eq_non_integer::EqNonInteger => EQ_NON_INTEGER,
        integer_machine_unit::IntegerMachineUnit => INTEGER_MACHINE_UNIT,
        control_notes::ControlNotes => CONTROL_NOTES,
        word_without_user::WordWithoutUser => WORD_WITHOUT_USER,
        oword_structure::OwordStructure => OWORD_STRUCTURE,
        macro_loop_structure::MacroLoopStructure => MACRO_LOOP_STRUCTURE,
        goto_target::GotoTarget => GOTO_TARGET,
        macro_with_nc_words::MacroWithNcWords => MACRO_WITH_NC_WORDS,
        program_end::ProgramEnd => PROGRAM_END,
        unreachable_after_end::UnreachableAfterEnd => UNREACHABLE_AFTER_END,
        sequence_number::SequenceNumber => SEQUENCE_NUMBER,
        oword_calls::OwordCalls => OWORD_CALLS,
        endless_loop::EndlessLoop => ENDLESS_LOOP,
        control_mismatch::ControlMismatch => CONTROL_MISMATCH,
        style_line_numbers::LineNumbers => LINE_NUMBERS,
        style_line_numbers::LineNumberOrder => LINE_NUMBER_ORDER,
        style_radius_arc::RadiusArc => RADIUS_ARC,
        style_number_whitespace::NumberWhitespace => NUMBER_WHITESPACE,
        style_decimals::TooFewDecimals => TOO_FEW_DECIMALS,
        style_units::UnitsSetting => UNITS_SETTING,
        style_preamble::Preamble => PREAMBLE,
        style_order_of_execution::OrderOfExecution => ORDER_OF_EXECUTION,
        style_lowercase_o::LowercaseO => LOWERCASE_O,
        style_g92::G92Offset => G92_OFFSET,
        style_start_with_g40::StartWithG40 => START_WITH_G40,
    ],
}

pub fn lookup(code: &str) -> Option<&'static RuleMeta> {
    RULES
        .iter()
        .copied()
        .find(|r| r.code.eq_ignore_ascii_case(code) || r.name.eq_ignore_ascii_case(code))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_and_names_are_unique_and_static_rules_are_registered() {
        for (i, a) in RULES.iter().enumerate() {
            for b in &RULES[i + 1..] {
                assert_ne!(a.code, b.code);
                assert_ne!(a.name, b.name);
            }
        }
        // Each `Type => STATIC` of the declaration pairs a rule with its own metadata.
        let statics = &RULES[RULES.len() - STATIC_RULES.len()..];
        for (r, m) in STATIC_RULES.iter().zip(statics) {
            assert!(
                std::ptr::eq(r.meta(), *m),
                "{} is listed beside {}",
                r.meta().code,
                m.code
            );
            assert_eq!(r.meta().origin, super::super::Origin::Static);
        }
        for m in &RULES[..RULES.len() - STATIC_RULES.len()] {
            assert_eq!(m.origin, super::super::Origin::Syntax, "{}", m.code);
        }
    }
}
