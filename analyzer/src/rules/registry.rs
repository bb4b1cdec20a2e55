//! The registry: every rule of the analyzer, by stable code.
//!
//! Codes never change meaning once released. The runtime keeps its own list of
//! flow-sensitive rules (`runtime::rules::REGISTRY`); hosts combine the two.

use super::syntax_rules as syn;
use super::{Rule, RuleMeta};

pub(crate) use super::axis_word_conflict::{AxisWordConflict, AXIS_WORD_CONFLICT};
pub(crate) use super::block_too_long::{BlockTooLong, BLOCK_TOO_LONG};
pub(crate) use super::bracket_nesting::{BracketNesting, BRACKET_NESTING};
pub(crate) use super::code_not_on_variant::{CodeNotOnVariant, CODE_NOT_ON_VARIANT};
pub(crate) use super::comment_use::{CommentUse, COMMENT_USE};
pub(crate) use super::conflicting_words::{ConflictingWords, CONFLICTING_WORDS};
pub(crate) use super::constant_expression::{ConstantExpression, CONSTANT_EXPRESSION};
pub(crate) use super::control_mismatch::{ControlMismatch, CONTROL_MISMATCH};
pub(crate) use super::control_notes::{ControlNotes, CONTROL_NOTES};
pub(crate) use super::cycle_words::{CycleWords, CYCLE_WORDS};
pub(crate) use super::dlacc_form::{DlaccForm, DLACC_FORM};
pub(crate) use super::duplicate_word::{DuplicateWord, DUPLICATE_WORD};
pub(crate) use super::endless_loop::{EndlessLoop, ENDLESS_LOOP};
pub(crate) use super::eq_non_integer::{EqNonInteger, EQ_NON_INTEGER};
pub(crate) use super::expression_form::{ExpressionForm, EXPRESSION_FORM};
pub(crate) use super::g54_with_words::{G54WithWords, G54_WITH_WORDS};
pub(crate) use super::goto_target::{GotoTarget, GOTO_TARGET};
pub(crate) use super::integer_machine_unit::{IntegerMachineUnit, INTEGER_MACHINE_UNIT};
pub(crate) use super::integer_word::{IntegerWord, INTEGER_WORD};
pub(crate) use super::m98_with_motion::{M98WithMotion, M98_WITH_MOTION};
pub(crate) use super::m_group_conflict::{MGroupConflict, M_GROUP_CONFLICT};
pub(crate) use super::macro_call_arguments::{MacroCallArguments, MACRO_CALL_ARGUMENTS};
pub(crate) use super::macro_loop_structure::{MacroLoopStructure, MACRO_LOOP_STRUCTURE};
pub(crate) use super::macro_with_nc_words::{MacroWithNcWords, MACRO_WITH_NC_WORDS};
pub(crate) use super::missing_required_word::{MissingRequiredWord, MISSING_REQUIRED_WORD};
pub(crate) use super::modal_group_conflict::{ModalGroupConflict, MODAL_GROUP_CONFLICT};
pub(crate) use super::oword_calls::{OwordCalls, OWORD_CALLS};
pub(crate) use super::oword_structure::{OwordStructure, OWORD_STRUCTURE};
pub(crate) use super::parameter_number::{ParameterNumber, PARAMETER_NUMBER};
pub(crate) use super::parameter_same_line::{ParameterSameLine, PARAMETER_SAME_LINE};
pub(crate) use super::program_end::{ProgramEnd, PROGRAM_END};
pub(crate) use super::sequence_number::{SequenceNumber, SEQUENCE_NUMBER};
pub(crate) use super::style_decimals::{TooFewDecimals, TOO_FEW_DECIMALS};
pub(crate) use super::style_g92::{G92Offset, G92_OFFSET};
pub(crate) use super::style_line_numbers::{
    LineNumberOrder, LineNumbers, LINE_NUMBERS, LINE_NUMBER_ORDER,
};
pub(crate) use super::style_lowercase_o::{LowercaseO, LOWERCASE_O};
pub(crate) use super::style_number_whitespace::{NumberWhitespace, NUMBER_WHITESPACE};
pub(crate) use super::style_order_of_execution::{OrderOfExecution, ORDER_OF_EXECUTION};
pub(crate) use super::style_preamble::{Preamble, PREAMBLE};
pub(crate) use super::style_radius_arc::{RadiusArc, RADIUS_ARC};
pub(crate) use super::style_start_with_g40::{StartWithG40, START_WITH_G40};
pub(crate) use super::style_units::{UnitsSetting, UNITS_SETTING};
pub(crate) use super::subprogram_name_glued::{SubprogramNameGlued, SUBPROGRAM_NAME_GLUED};
pub(crate) use super::too_many_m_words::{TooManyMWords, TOO_MANY_M_WORDS};
pub(crate) use super::unknown_address::{UnknownAddress, UNKNOWN_ADDRESS};
pub(crate) use super::unknown_code::{UnknownCode, UNKNOWN_CODE};
pub(crate) use super::unreachable_after_end::{UnreachableAfterEnd, UNREACHABLE_AFTER_END};
pub(crate) use super::word_value_range::{WordValueRange, WORD_VALUE_RANGE};
pub(crate) use super::word_without_user::{WordWithoutUser, WORD_WITHOUT_USER};

/// Metadata of every syntax and static rule, in code order.
pub static RULES: &[&RuleMeta] = &[
    &syn::IO_ERROR,
    &syn::UNCLOSED_COMMENT,
    &syn::NESTED_COMMENT,
    &syn::MISSING_VALUE,
    &syn::MALFORMED_NUMBER,
    &syn::UNKNOWN_CHARACTER,
    &syn::UNBALANCED_BRACKET,
    &syn::MISPLACED_BLOCK_SKIP,
    &syn::LOWERCASE,
    &syn::NOT_TEXT,
    &syn::BAD_EXPRESSION,
    &syn::MISPLACED_PERCENT,
    &syn::TEXT_AFTER_EOB,
    &syn::EXPRESSION_TOO_DEEP,
    &syn::BLOCK_TOO_MANY_ITEMS,
    &syn::CONFIG_ISSUE,
    &MODAL_GROUP_CONFLICT,
    &M_GROUP_CONFLICT,
    &TOO_MANY_M_WORDS,
    &UNKNOWN_CODE,
    &CODE_NOT_ON_VARIANT,
    &DUPLICATE_WORD,
    &CONFLICTING_WORDS,
    &MISSING_REQUIRED_WORD,
    &AXIS_WORD_CONFLICT,
    &UNKNOWN_ADDRESS,
    &INTEGER_WORD,
    &WORD_VALUE_RANGE,
    &DLACC_FORM,
    &G54_WITH_WORDS,
    &M98_WITH_MOTION,
    &BLOCK_TOO_LONG,
    &MACRO_CALL_ARGUMENTS,
    &SUBPROGRAM_NAME_GLUED,
    &BRACKET_NESTING,
    &CONSTANT_EXPRESSION,
    &PARAMETER_NUMBER,
    &EXPRESSION_FORM,
    &PARAMETER_SAME_LINE,
    &COMMENT_USE,
    &CYCLE_WORDS,
    &EQ_NON_INTEGER,
    &INTEGER_MACHINE_UNIT,
    &CONTROL_NOTES,
    &WORD_WITHOUT_USER,
    &OWORD_STRUCTURE,
    &MACRO_LOOP_STRUCTURE,
    &GOTO_TARGET,
    &MACRO_WITH_NC_WORDS,
    &PROGRAM_END,
    &UNREACHABLE_AFTER_END,
    &SEQUENCE_NUMBER,
    &OWORD_CALLS,
    &ENDLESS_LOOP,
    &CONTROL_MISMATCH,
    &LINE_NUMBERS,
    &LINE_NUMBER_ORDER,
    &RADIUS_ARC,
    &NUMBER_WHITESPACE,
    &TOO_FEW_DECIMALS,
    &UNITS_SETTING,
    &PREAMBLE,
    &ORDER_OF_EXECUTION,
    &LOWERCASE_O,
    &G92_OFFSET,
    &START_WITH_G40,
];

/// The static rules that run over parsed programs.
pub static STATIC_RULES: &[&dyn Rule] = &[
    &ModalGroupConflict,
    &MGroupConflict,
    &TooManyMWords,
    &UnknownCode,
    &CodeNotOnVariant,
    &DuplicateWord,
    &ConflictingWords,
    &MissingRequiredWord,
    &AxisWordConflict,
    &UnknownAddress,
    &IntegerWord,
    &WordValueRange,
    &DlaccForm,
    &G54WithWords,
    &M98WithMotion,
    &BlockTooLong,
    &MacroCallArguments,
    &SubprogramNameGlued,
    &BracketNesting,
    &ConstantExpression,
    &ParameterNumber,
    &ExpressionForm,
    &ParameterSameLine,
    &CommentUse,
    &CycleWords,
    &EqNonInteger,
    &IntegerMachineUnit,
    &ControlNotes,
    &WordWithoutUser,
    &OwordStructure,
    &MacroLoopStructure,
    &GotoTarget,
    &MacroWithNcWords,
    &ProgramEnd,
    &UnreachableAfterEnd,
    &SequenceNumber,
    &OwordCalls,
    &EndlessLoop,
    &ControlMismatch,
    &LineNumbers,
    &LineNumberOrder,
    &RadiusArc,
    &NumberWhitespace,
    &TooFewDecimals,
    &UnitsSetting,
    &Preamble,
    &OrderOfExecution,
    &LowercaseO,
    &G92Offset,
    &StartWithG40,
];

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
        for r in STATIC_RULES {
            assert!(
                RULES.iter().any(|m| std::ptr::eq(*m, r.meta())),
                "{} not in RULES",
                r.meta().code
            );
            assert_eq!(r.meta().origin, super::super::Origin::Static);
        }
    }
}
