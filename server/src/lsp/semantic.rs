//! Semantic tokens: the highlighted ranges of [`crate::ide::highlight`]
//! in LSP's legend and delta encoding. The legend follows
//! [`Class`]: comments, numbers, keywords (`GOTO`, `sub`, `SIN`), G/M
//! codes as functions, other address letters as parameters, variables,
//! operators, names as namespaces, and tape/skip marks as macros.

use analyzer::syntax::Program;
use tower_lsp_server::ls_types::{SemanticToken, SemanticTokenType, SemanticTokensLegend};

use crate::ide::highlight::{highlights, Class};

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

/// The legend index of a class.
fn token_type(class: Class) -> u32 {
    match class {
        Class::Comment => COMMENT,
        Class::Number => NUMBER,
        Class::Keyword => KEYWORD,
        Class::Code => FUNCTION,
        Class::Address => PARAMETER,
        Class::Variable => VARIABLE,
        Class::Operator => OPERATOR,
        Class::Name => NAMESPACE,
        Class::Mark => MACRO,
        Class::Text => STRING,
    }
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

/// Moves `line` and the UTF-16 `col` from byte `from` to byte `to` of `text`
/// (line breaks: CR, LF, CRLF).
fn advance(text: &[u8], from: usize, to: usize, line: &mut u32, col: &mut u32) {
    let gap = text.get(from..to).unwrap_or_default();
    for (k, &b) in gap.iter().enumerate() {
        match b {
            b'\n' => {
                *line += 1;
                *col = 0;
            }
            b'\r' if text.get(from + k + 1) != Some(&b'\n') => {
                *line += 1;
                *col = 0;
            }
            b'\r' => {}
            _ => *col += utf16_len(&[b]),
        }
    }
}

/// Encodes the highlighted tokens whose start lies in `[from, to)` bytes (all
/// for `0..u32::MAX`). At most `limit` tokens; `None` when there are more.
pub fn encode(program: &Program, from: u32, to: u32, limit: usize) -> Option<Vec<SemanticToken>> {
    let text = &program.text;
    // Line and UTF-16 column of byte `pos`; a token's own bytes move the
    // column only (no token but a line break holds one).
    let (mut pos, mut line, mut col) = (0usize, 0u32, 0u32);
    let (mut prev_line, mut prev_col) = (0u32, 0u32);
    let mut out = Vec::new();
    for h in highlights(program, from, to) {
        let (start, end) = (h.span.start as usize, h.span.end as usize);
        advance(text, pos, start, &mut line, &mut col);
        let len = utf16_len(text.get(start..end).unwrap_or_default());
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
                token_type: token_type(h.class),
                token_modifiers_bitset: 0,
            });
            prev_line = line;
            prev_col = col;
        }
        col += len;
        pos = end.max(start);
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
        assert_eq!(
            flat(&p),
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

    /// The whole program's tokens as (delta line, delta start, length, type).
    fn flat(p: &Program) -> Vec<(u32, u32, u32, u32)> {
        encode(p, 0, u32::MAX, 1000)
            .unwrap()
            .iter()
            .map(|t| (t.delta_line, t.delta_start, t.length, t.token_type))
            .collect()
    }

    #[test]
    fn crlf_and_cr_each_end_one_line() {
        let p = parse(
            ParseOptions::new(Dialect::Rs274ngc),
            b"G1\r\nM2\rX1 (\xf0\x9f\x98\x80) Y2".to_vec(),
        );
        assert_eq!(
            flat(&p),
            vec![
                (0, 0, 1, FUNCTION),
                (0, 1, 1, NUMBER),
                (1, 0, 1, FUNCTION),
                (0, 1, 1, NUMBER),
                (1, 0, 1, PARAMETER),
                (0, 1, 1, NUMBER),
                (0, 2, 4, COMMENT),
                (0, 5, 1, PARAMETER),
                (0, 1, 1, NUMBER),
            ]
        );
    }
}
