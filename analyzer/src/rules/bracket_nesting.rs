//! W014: FANUC brackets nested deeper than five levels.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::TokenKind;

use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags FANUC macro expressions whose brackets `[ ]` nest more than five levels
    /// deep. Function brackets (`SIN[…]`) count as levels too.
    ///
    /// ## Why is this bad?
    /// Custom Macro B evaluates at most five levels of brackets; a sixth raises alarm
    /// PS0118 when the block runs.
    ///
    /// ## Example
    /// ```fanuc
    /// %
    /// O1000;
    /// #1 = [[[[[[1]]]]]];
    /// M30;
    /// %
    /// ```
    ///
    /// Use instead:
    /// ```fanuc
    /// %
    /// O1000;
    /// #2 = [[[1]]];
    /// #1 = [[[#2]]];
    /// M30;
    /// %
    /// ```
    ///
    /// ## Dialects
    /// FANUC, error. Split the expression with intermediate variables.
    ///
    /// Implements: FAN120
    pub static BRACKET_NESTING = {
        code: "W014",
        name: "bracket-nesting",
        summary: "FANUC brackets nested deeper than five levels",
        implements: &["FAN120"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct BracketNesting;

/// The deepest nesting Custom Macro B evaluates.
const MAX_DEPTH: u32 = 5;

impl Rule for BracketNesting {
    fn meta(&self) -> &'static RuleMeta {
        &BRACKET_NESTING
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Fanuc {
            return;
        }
        // Only blocks with a `[` can nest; their tokens are read again from the text,
        // since hosts may parse without tokens.
        for block in &p.blocks {
            if memchr::memchr(b'[', p.slice(block.span)).is_none() {
                continue;
            }
            let mut depth = 0u32;
            let tokens = crate::syntax::block_tokens(p, block);
            for (i, t) in tokens.iter().enumerate() {
                match t.kind {
                    TokenKind::LBracket => {
                        depth += 1;
                        if depth > MAX_DEPTH {
                            let end = tokens.get(i + 1).map_or(t.start + 1, |n| n.start);
                            out.push(BRACKET_NESTING.error(
                                Span::new(t.start, end),
                                "Brackets nested more than five levels deep: Custom Macro B evaluates at most five (alarm PS0118). Compute part of the expression into a variable first.",
                            ));
                            break;
                        }
                    }
                    TokenKind::RBracket => depth = depth.saturating_sub(1),
                    _ => {}
                }
            }
        }
    }
}
