//! Semantic tokens from the lexer's tokens. The legend follows
//! [`TokenKind`]: comments, numbers, keywords (`GOTO`, `sub`, `SIN`), G/M
//! codes as functions, other address letters as parameters, variables,
//! operators, names as namespaces, and tape/skip marks as macros.

use analyzer::syntax::{Program, TokenKind};
use tower_lsp_server::ls_types::{SemanticToken, SemanticTokenType, SemanticTokensLegend};

/// Legend indices.
const COMMENT: u32 = 0;
const NUMBER: u32 = 1;
const KEYWORD: u32 = 2;
const FUNCTION: u32 = 3;
const PARAMETER: u32 = 4;
const VARIABLE: u32 = 5;
const OPERATOR: u32 = 6;
const NAMESPACE: u32 = 7;
const MACRO: u32 = 8;
const STRING: u32 = 9;

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: vec![
            SemanticTokenType::COMMENT,
            SemanticTokenType::NUMBER,
            SemanticTokenType::KEYWORD,
            SemanticTokenType::FUNCTION,
            SemanticTokenType::PARAMETER,
            SemanticTokenType::VARIABLE,
            SemanticTokenType::OPERATOR,
            SemanticTokenType::NAMESPACE,
            SemanticTokenType::MACRO,
            SemanticTokenType::STRING,
        ],
        token_modifiers: vec![],
    }
}

fn token_type(kind: TokenKind, first_byte: u8) -> Option<u32> {
    Some(match kind {
        TokenKind::Comment | TokenKind::LineComment | TokenKind::Ignored => COMMENT,
        TokenKind::Number => NUMBER,
        TokenKind::Keyword => KEYWORD,
        TokenKind::Letter => match first_byte.to_ascii_uppercase() {
            b'G' | b'M' => FUNCTION,
            _ => PARAMETER,
        },
        TokenKind::Hash | TokenKind::NamedParam => VARIABLE,
        TokenKind::Operator | TokenKind::LBracket | TokenKind::RBracket | TokenKind::Comma => {
            OPERATOR
        }
        TokenKind::Name => NAMESPACE,
        TokenKind::Text => STRING,
        TokenKind::Percent | TokenKind::BlockSkip | TokenKind::Eob => MACRO,
        TokenKind::Whitespace | TokenKind::Newline | TokenKind::Unknown => return None,
    })
}

/// UTF-16 length of a byte run, counted per byte so that runs that cut a
/// character in two still add up (lead bytes count, continuation bytes do not).
fn utf16_len(bytes: &[u8]) -> u32 {
    bytes
        .iter()
        .map(|&b| match b {
            0x00..=0x7f => 1,
            0x80..=0xbf => 0,
            0xf0..=0xff => 2,
            _ => 1,
        })
        .sum()
}

/// Encodes the tokens whose start lies in `[from, to)` bytes (all for
/// `0..u32::MAX`). At most `limit` tokens; `None` when there are more.
pub fn encode(program: &Program, from: u32, to: u32, limit: usize) -> Option<Vec<SemanticToken>> {
    let text = &program.text;
    let first = program.tokens.partition_point(|t| t.start < from);
    // Line and UTF-16 column of `first`'s start: computed from the line start.
    let start_off = program
        .tokens
        .get(first)
        .map(|t| t.start as usize)
        .unwrap_or(text.len());
    let mut line: u32 = 0;
    let mut line_start = 0usize;
    let mut i = 0usize;
    // Count lines before start_off (CR, LF, CRLF).
    while i < start_off {
        match text[i] {
            b'\n' => {
                line += 1;
                line_start = i + 1;
            }
            b'\r' if text.get(i + 1) != Some(&b'\n') => {
                line += 1;
                line_start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    let mut col = utf16_len(&text[line_start..start_off]);
    let (mut prev_line, mut prev_col) = (0u32, 0u32);
    let mut out = Vec::new();
    for ti in first..program.tokens.len() {
        let tok = program.tokens[ti];
        if tok.start >= to {
            break;
        }
        let span = program.token_span(ti);
        let bytes = span.slice(text);
        if tok.kind == TokenKind::Newline {
            line += 1;
            col = 0;
            continue;
        }
        let len = utf16_len(bytes);
        if let Some(ty) = bytes.first().and_then(|&b| token_type(tok.kind, b)) {
            if len > 0 {
                if out.len() >= limit {
                    return None;
                }
                let delta_line = line - prev_line;
                let delta_start = if delta_line == 0 { col - prev_col } else { col };
                out.push(SemanticToken {
                    delta_line,
                    delta_start,
                    length: len,
                    token_type: ty,
                    token_modifiers_bitset: 0,
                });
                prev_line = line;
                prev_col = col;
            }
        }
        col += len;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use analyzer::syntax::{parse, ParseOptions};
    use analyzer::Dialect;

    #[test]
    fn tokens_are_delta_encoded_in_utf16() {
        let text = "(é) G1 X#1\nM2\n";
        let p = parse(
            ParseOptions {
                dialect: Dialect::Rs274ngc,
                variant: Dialect::Rs274ngc.default_variant(),
            },
            text.as_bytes().to_vec(),
        );
        let toks = encode(&p, 0, u32::MAX, 1000).unwrap();
        let flat: Vec<(u32, u32, u32, u32)> = toks
            .iter()
            .map(|t| (t.delta_line, t.delta_start, t.length, t.token_type))
            .collect();
        assert_eq!(
            flat,
            vec![
                (0, 0, 3, COMMENT),
                (0, 4, 1, FUNCTION),
                (0, 1, 1, NUMBER),
                (0, 2, 1, PARAMETER),
                (0, 1, 1, VARIABLE),
                (0, 1, 1, NUMBER),
                (1, 0, 1, FUNCTION),
                (0, 1, 1, NUMBER),
            ]
        );
        // A range starting on line 1 starts counting from that line.
        let second = encode(&p, 11, u32::MAX, 1000).unwrap();
        assert_eq!(second[0].delta_line, 1);
        assert_eq!(second.len(), 2);
        assert_eq!(encode(&p, 0, u32::MAX, 3), None);
    }
}
