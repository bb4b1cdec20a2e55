//! The one place where byte offsets (what the analyzer speaks) meet LSP
//! positions (0-based line, UTF-16 code unit column).
//!
//! Documents are kept in a [`Rope`] built with CR, LF and CRLF as the only line
//! breaks (the `cr_lines` feature without `unicode_lines`), which is exactly the
//! LSP definition and the analyzer's `LineIndex` definition, so line numbers
//! agree everywhere.

use analyzer::Span;
use ropey::Rope;
use tower_lsp_server::ls_types::{Position, Range};

pub use crate::document::rope_bytes;

/// Converts a byte offset into an LSP position. Offsets past the end clamp to
/// the end; an offset inside a multi-byte character maps to that character.
pub fn offset_to_position(rope: &Rope, offset: usize) -> Position {
    let offset = offset.min(rope.len_bytes());
    let line = rope.byte_to_line(offset);
    let line_char = rope.line_to_char(line);
    let ch = rope.byte_to_char(offset);
    let col = rope.char_to_utf16_cu(ch) - rope.char_to_utf16_cu(line_char);
    Position::new(line as u32, col as u32)
}

/// Converts a byte span into an LSP range.
pub fn span_to_range(rope: &Rope, span: Span) -> Range {
    let start = offset_to_position(rope, span.start as usize);
    let end = offset_to_position(rope, (span.end as usize).max(span.start as usize));
    Range::new(start, end)
}

/// The byte offset of the end of a line's content (before its line break).
fn line_content_end_char(rope: &Rope, line: usize) -> usize {
    let start = rope.line_to_char(line);
    let slice = rope.line(line);
    let mut len = slice.len_chars();
    // Strip the line break: CRLF, LF or CR.
    if len > 0 && slice.char(len - 1) == '\n' {
        len -= 1;
    }
    if len > 0 && slice.char(len - 1) == '\r' {
        len -= 1;
    }
    start + len
}

/// Converts an LSP position into a byte offset. A line past the end maps to the
/// end of the text; a column past the end of its line maps to the end of the
/// line's content (as the LSP specification asks); a column in the middle of a
/// surrogate pair maps to the start of that character.
pub fn position_to_offset(rope: &Rope, pos: Position) -> usize {
    let line = pos.line as usize;
    if line >= rope.len_lines() {
        return rope.len_bytes();
    }
    let line_char = rope.line_to_char(line);
    let end_char = line_content_end_char(rope, line);
    let base_cu = rope.char_to_utf16_cu(line_char);
    let max_cu = rope.char_to_utf16_cu(end_char);
    let target_cu = (base_cu + pos.character as usize).min(max_cu);
    let mut ch = rope.utf16_cu_to_char(target_cu).clamp(line_char, end_char);
    // Inside a surrogate pair ropey answers the next character; step back to
    // the character that holds the unit.
    if ch > line_char && rope.char_to_utf16_cu(ch) > target_cu {
        ch -= 1;
    }
    rope.char_to_byte(ch)
}

/// Converts an LSP range into a byte range `(start, end)` with `start <= end`.
pub fn range_to_offsets(rope: &Rope, range: Range) -> (usize, usize) {
    let a = position_to_offset(rope, range.start);
    let b = position_to_offset(rope, range.end);
    (a.min(b), a.max(b))
}

/// Applies one `didChange` content change: a ranged edit, or a full replacement
/// when `range` is `None`.
pub fn apply_change(rope: &mut Rope, range: Option<Range>, text: &str) {
    match range {
        None => *rope = Rope::from_str(text),
        Some(range) => {
            let (a, b) = range_to_offsets(rope, range);
            let ca = rope.byte_to_char(a);
            let cb = rope.byte_to_char(b);
            rope.remove(ca..cb);
            rope.insert(ca, text);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(line: u32, character: u32) -> Position {
        Position::new(line, character)
    }

    #[test]
    fn ascii_round_trip() {
        let rope = Rope::from_str("G0 X1\nG1 Y2\n");
        assert_eq!(offset_to_position(&rope, 0), pos(0, 0));
        assert_eq!(offset_to_position(&rope, 6), pos(1, 0));
        assert_eq!(offset_to_position(&rope, 9), pos(1, 3));
        assert_eq!(position_to_offset(&rope, pos(1, 3)), 9);
        assert_eq!(offset_to_position(&rope, 12), pos(2, 0));
        assert_eq!(offset_to_position(&rope, 999), pos(2, 0));
    }

    #[test]
    fn non_ascii_columns_count_utf16_units() {
        // `é` is 2 bytes / 1 unit; `😀` is 4 bytes / 2 units (a surrogate pair).
        let text = "(é😀) G1 X5\n";
        let rope = Rope::from_str(text);
        let g = text.find("G1").unwrap();
        assert_eq!(g, 9);
        assert_eq!(offset_to_position(&rope, g), pos(0, 6));
        assert_eq!(position_to_offset(&rope, pos(0, 6)), g);
        // Inside the surrogate pair: snap to the start of the emoji.
        assert_eq!(position_to_offset(&rope, pos(0, 2)), 3);
        assert_eq!(position_to_offset(&rope, pos(0, 3)), 3);
        assert_eq!(position_to_offset(&rope, pos(0, 4)), 7);
        // An offset inside the emoji's bytes maps to the emoji's position.
        assert_eq!(offset_to_position(&rope, 5), pos(0, 2));
    }

    #[test]
    fn out_of_range_positions_clamp() {
        let rope = Rope::from_str("G0\r\nG1é\rM2");
        // Past the end of a CRLF line's content: the content's end, not inside the break.
        assert_eq!(position_to_offset(&rope, pos(0, 50)), 2);
        // `G1é` then a lone CR: a line break too.
        assert_eq!(position_to_offset(&rope, pos(1, 50)), 4 + 4);
        assert_eq!(offset_to_position(&rope, 9), pos(2, 0));
        assert_eq!(position_to_offset(&rope, pos(2, 1)), 10);
        assert_eq!(position_to_offset(&rope, pos(9, 0)), rope.len_bytes());
    }

    #[test]
    fn unicode_line_separators_are_not_line_breaks() {
        // U+2028 and NEL are not LSP line breaks; the rope must not split there.
        let rope = Rope::from_str("G0\u{2028}X1\u{85}\nG1");
        assert_eq!(rope.len_lines(), 2);
        assert_eq!(offset_to_position(&rope, rope.len_bytes()), pos(1, 2));
    }

    #[test]
    fn edits_apply_in_utf16_coordinates() {
        let mut rope = Rope::from_str("(ü) G0 X1\nG1 X2\n");
        // Replace `X1` (utf-16 columns 7..9 on line 0).
        apply_change(&mut rope, Some(Range::new(pos(0, 7), pos(0, 9))), "Y3");
        assert_eq!(rope.to_string(), "(ü) G0 Y3\nG1 X2\n");
        apply_change(&mut rope, Some(Range::new(pos(1, 0), pos(1, 0))), "N10 ");
        assert_eq!(rope.to_string(), "(ü) G0 Y3\nN10 G1 X2\n");
        // A reversed range is normalised rather than panicking.
        apply_change(&mut rope, Some(Range::new(pos(1, 4), pos(1, 0))), "");
        assert_eq!(rope.to_string(), "(ü) G0 Y3\nG1 X2\n");
        apply_change(&mut rope, None, "M30\n");
        assert_eq!(rope.to_string(), "M30\n");
        assert_eq!(&*rope_bytes(&rope), b"M30\n");
        // Many chunks, multi-byte characters across chunk ends.
        let text = "G1 X1 (é€)\n".repeat(20_000);
        let rope = Rope::from_str(&text);
        assert!(rope.chunks().count() > 100);
        assert_eq!(&*rope_bytes(&rope), text.as_bytes());
    }

    #[test]
    fn span_to_range_on_multibyte_line() {
        let rope = Rope::from_str("G1 X1 (日本)\nG2");
        let text = rope.to_string();
        let s = text.find('日').unwrap() as u32;
        let r = span_to_range(&rope, Span::new(s, s + 6));
        assert_eq!(r, Range::new(pos(0, 7), pos(0, 9)));
    }

    /// A slow, obviously-correct model of LSP position → byte offset over a `&str`.
    fn model_offset(text: &str, pos: Position) -> usize {
        let (mut line, mut col) = (0u32, 0u32);
        let mut chars = text.char_indices().peekable();
        while let Some((i, c)) = chars.next() {
            if line == pos.line {
                if c == '\n' || c == '\r' {
                    return i;
                }
                let w = c.len_utf16() as u32;
                if col + w > pos.character {
                    return i;
                }
                col += w;
                continue;
            }
            if c == '\n' || (c == '\r' && chars.peek().map(|p| p.1) != Some('\n')) {
                line += 1;
                col = 0;
            }
        }
        text.len()
    }

    #[test]
    fn random_positions_and_edits_match_a_model() {
        let alphabet = [
            "G", "1", " ", "X", "\n", "\r\n", "\r", "é", "😀", "日", "(", ")", ";",
        ];
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = move |n: usize| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % n as u64) as usize
        };
        for _ in 0..200 {
            let mut text: String = (0..next(40))
                .map(|_| alphabet[next(alphabet.len())])
                .collect();
            let mut rope = Rope::from_str(&text);
            for _ in 0..10 {
                let lines =
                    text.matches('\n').count() as u32 + text.matches('\r').count() as u32 + 2;
                let a = pos(next(lines as usize) as u32, next(12) as u32);
                let b = pos(next(lines as usize) as u32, next(12) as u32);
                assert_eq!(
                    position_to_offset(&rope, a),
                    model_offset(&text, a),
                    "{text:?} {a:?}"
                );
                // Round trip from every char boundary (except between the CR and
                // LF of a CRLF, which no position can name).
                for (i, _) in text
                    .char_indices()
                    .filter(|&(i, c)| !(c == '\n' && text[..i].ends_with('\r')))
                {
                    assert_eq!(
                        position_to_offset(&rope, offset_to_position(&rope, i)),
                        i,
                        "{text:?} @{i}"
                    );
                }
                let insert: String = (0..next(4))
                    .map(|_| alphabet[next(alphabet.len())])
                    .collect();
                let (x, y) = (model_offset(&text, a), model_offset(&text, b));
                let (x, y) = (x.min(y), x.max(y));
                text.replace_range(x..y, &insert);
                apply_change(&mut rope, Some(Range::new(a, b)), &insert);
                assert_eq!(rope.to_string(), text);
            }
        }
    }
}
