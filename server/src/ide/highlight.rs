//! Syntax highlighting: the lexer's tokens as byte ranges with a class
//! ([`Class`]). Line breaks, blanks and unknown bytes are not highlighted.

use analyzer::syntax::{Program, TokenKind};
use analyzer::Span;

/// What a highlighted range is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// Comments, line comments and text the control ignores.
    Comment,
    Number,
    /// Macro and O-word keywords and functions (`GOTO`, `sub`, `SIN`).
    Keyword,
    /// The letter of a G or M code.
    Code,
    /// Any other address letter.
    Address,
    /// `#` and named parameters.
    Variable,
    /// Operators, brackets and commas.
    Operator,
    /// Names (an o-word's `<name>`, the program number of a FANUC `O` line).
    Name,
    /// Quoted text.
    Text,
    /// Tape marks, block skips and end-of-block marks.
    Mark,
}

/// One highlighted token.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Highlight {
    pub span: Span,
    pub class: Class,
}

fn class(kind: TokenKind, first_byte: u8) -> Option<Class> {
    Some(match kind {
        TokenKind::Comment | TokenKind::LineComment | TokenKind::Ignored => Class::Comment,
        TokenKind::Number => Class::Number,
        TokenKind::Keyword => Class::Keyword,
        TokenKind::Letter => match first_byte.to_ascii_uppercase() {
            b'G' | b'M' => Class::Code,
            _ => Class::Address,
        },
        TokenKind::Hash | TokenKind::NamedParam => Class::Variable,
        TokenKind::Operator | TokenKind::LBracket | TokenKind::RBracket | TokenKind::Comma => {
            Class::Operator
        }
        TokenKind::Name => Class::Name,
        TokenKind::Text => Class::Text,
        TokenKind::Percent | TokenKind::BlockSkip | TokenKind::Eob => Class::Mark,
        TokenKind::Whitespace | TokenKind::Newline | TokenKind::Unknown => return None,
    })
}

/// The highlighted tokens whose start lies in `[from, to)` bytes (all of them
/// for `0..u32::MAX`), in order; empty tokens are left out. Lazy, so a caller
/// that caps the count stops early.
pub fn highlights(program: &Program, from: u32, to: u32) -> impl Iterator<Item = Highlight> + '_ {
    let first = program.tokens.partition_point(|t| t.start < from);
    let text = &program.text;
    (first..program.tokens.len())
        .take_while(move |&ti| program.tokens.get(ti).is_some_and(|t| t.start < to))
        .filter_map(move |ti| {
            let tok = program.tokens.get(ti)?;
            let span = program.token_span(ti);
            let first_byte = *span.slice(text).first()?;
            Some(Highlight {
                span,
                class: class(tok.kind, first_byte)?,
            })
        })
}
