//! The registry: every rule of the analyzer, by stable code.
//!
//! Codes never change meaning once released. The runtime keeps its own list of
//! flow-sensitive rules (`runtime::rules::REGISTRY`); hosts combine the two.

use super::syntax_rules as syn;
use super::{Rule, RuleMeta};

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
];

/// The static rules that run over parsed programs.
pub static STATIC_RULES: &[&dyn Rule] = &[];

pub fn lookup(code: &str) -> Option<&'static RuleMeta> {
    RULES
        .iter()
        .copied()
        .find(|r| r.code.eq_ignore_ascii_case(code) || r.name.eq_ignore_ascii_case(code))
}
