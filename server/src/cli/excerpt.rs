//! The few lines of a file that one human-output report shows, as miette's
//! source: handing miette the whole file made every report scan it from the
//! start, so the human output of N diagnostics cost N × the file. Bytes a
//! terminal would act on (escape sequences, other controls) are shown as their
//! Unicode control pictures (`␛`), and invalid UTF-8 as `�`.

use miette::{MietteError, MietteSpanContents, SourceCode, SourceSpan, SpanContents};

/// Lines of context kept around the spans (the report shows one).
const CONTEXT_LINES: usize = 2;
/// A related span further than this from the primary one is left out of the
/// excerpt (its label with it), so one far-away note cannot make it large.
pub const MAX_RELATED_DISTANCE: usize = 16 * 1024;

pub struct Excerpt {
    name: String,
    text: String,
    /// Offset in the file of the excerpt's first byte.
    base: usize,
    /// 0-based line of the excerpt's first byte.
    first_line: usize,
    /// (offset in the file, offset in `text`) at every point where the two stop
    /// moving together (a replaced byte), in order.
    shifts: Vec<(usize, usize)>,
}

impl Excerpt {
    /// The lines of `file` around `start..end` (offsets in the file), where
    /// `start` lies on the 0-based line `start_line`.
    pub fn new(name: String, file: &[u8], start: usize, end: usize, start_line: usize) -> Excerpt {
        let start = start.min(file.len());
        let end = end.clamp(start, file.len());
        let mut from = start;
        let mut lines_back = 0;
        while from > 0 {
            if file[from - 1] == b'\n' {
                if lines_back == CONTEXT_LINES {
                    break;
                }
                lines_back += 1;
            }
            from -= 1;
        }
        let mut to = end;
        let mut lines_on = 0;
        while to < file.len() {
            if file[to] == b'\n' {
                lines_on += 1;
                if lines_on > CONTEXT_LINES {
                    break;
                }
            }
            to += 1;
        }
        let (text, shifts) = visible(&file[from..to], from);
        Excerpt {
            name,
            text,
            base: from,
            first_line: start_line.saturating_sub(lines_back),
            shifts,
        }
    }

    fn len_in_file(&self) -> usize {
        match self.shifts.last() {
            Some(&(f, t)) => f - self.base + (self.text.len() - t),
            None => self.text.len(),
        }
    }

    /// A file offset as an offset in the excerpt's text.
    pub fn map(&self, offset: usize) -> usize {
        let offset = offset.clamp(self.base, self.base + self.len_in_file());
        let i = self.shifts.partition_point(|&(f, _)| f <= offset);
        match i.checked_sub(1).map(|k| self.shifts[k]) {
            Some((f, t)) => t + (offset - f),
            None => offset - self.base,
        }
    }
}

/// `bytes` (which start at file offset `base`) as text a terminal shows as it
/// is, with the shift points of [`Excerpt::shifts`].
fn visible(bytes: &[u8], base: usize) -> (String, Vec<(usize, usize)>) {
    let mut text = String::with_capacity(bytes.len());
    let mut shifts = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let (ok, bad) = match std::str::from_utf8(&bytes[i..]) {
            Ok(s) => (s.len(), 0),
            Err(e) => (
                e.valid_up_to(),
                e.error_len().unwrap_or(bytes.len() - i - e.valid_up_to()),
            ),
        };
        let valid = std::str::from_utf8(&bytes[i..i + ok]).unwrap_or_default();
        for (k, c) in valid.char_indices() {
            let picture = match c {
                '\t' | '\n' | '\r' => None,
                '\u{0}'..='\u{1f}' => char::from_u32(0x2400 + c as u32),
                '\u{7f}' => Some('\u{2421}'),
                '\u{80}'..='\u{9f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' => {
                    Some('\u{fffd}')
                }
                _ => None,
            };
            match picture {
                Some(p) => {
                    text.push(p);
                    shifts.push((base + i + k + c.len_utf8(), text.len()));
                }
                None => text.push(c),
            }
        }
        i += ok;
        if bad > 0 {
            text.push('\u{fffd}');
            i += bad;
            shifts.push((base + i, text.len()));
        }
    }
    (text, shifts)
}

/// Text for a terminal: the control bytes of a message (which may quote the
/// program) as control pictures.
pub fn visible_str(s: &str) -> std::borrow::Cow<'_, str> {
    if s.chars().all(|c| !c.is_control() || c == '\t' || c == '\n') {
        return std::borrow::Cow::Borrowed(s);
    }
    std::borrow::Cow::Owned(visible(s.as_bytes(), 0).0)
}

impl SourceCode for Excerpt {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'a> + 'a>, MietteError> {
        let inner =
            self.text
                .as_str()
                .read_span(span, context_lines_before, context_lines_after)?;
        Ok(Box::new(MietteSpanContents::new_named(
            self.name.clone(),
            inner.data(),
            *inner.span(),
            inner.line() + self.first_line,
            inner.column(),
            inner.line_count(),
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn excerpt_keeps_offsets_and_lines() {
        let file = b"L0\nL1\nL2\nG1 X\x1b[31m1\nL4\nL5\nL6\nL7\n";
        let start = 9; // "G1" on line 3
        let e = Excerpt::new("f".into(), file, start, start + 2, 3);
        assert_eq!(e.first_line, 1);
        assert_eq!(&e.text[e.map(start)..e.map(start) + 2], "G1");
        // The escape is a picture; the byte after it maps to the byte after it.
        assert!(e.text.contains("X\u{241b}[31m1"));
        let one = file.iter().rposition(|b| *b == b'1').unwrap_or(0);
        assert_eq!(&e.text[e.map(one)..e.map(one) + 1], "1");
        assert!(!e.text.contains("L6"));
    }

    #[test]
    fn invalid_utf8_is_one_replacement() {
        let file = b"A\xffB\n";
        let e = Excerpt::new("f".into(), file, 2, 3, 0);
        assert_eq!(e.text, "A\u{fffd}B\n");
        assert_eq!(&e.text[e.map(2)..e.map(2) + 1], "B");
    }
}
