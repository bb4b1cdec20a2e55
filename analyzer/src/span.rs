//! Byte spans into one source file.

/// A half-open byte range `[start, end)` into the source text of one file.
///
/// Spans are byte offsets, never characters: conversion to editor positions
/// (UTF-16 columns) happens only in the server.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct Span {
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub const fn new(start: u32, end: u32) -> Span {
        Span { start, end }
    }

    pub fn len(self) -> u32 {
        self.end.saturating_sub(self.start)
    }

    pub fn is_empty(self) -> bool {
        self.end <= self.start
    }

    /// The smallest span covering both.
    pub fn cover(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }

    pub fn contains(self, offset: u32) -> bool {
        self.start <= offset && offset < self.end
    }

    pub fn range(self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }

    /// The bytes of `src` this span covers; empty when the span is out of range
    /// (spans are produced by the parser, but a caller may pair them with the wrong text).
    pub fn slice(self, src: &[u8]) -> &[u8] {
        src.get(self.range()).unwrap_or(&[])
    }
}

/// Where the lines after the first start: after each `\n`, `\r\n` or lone `\r`.
fn line_starts(src: &[u8]) -> impl Iterator<Item = u32> + '_ {
    let mut i = 0usize;
    std::iter::from_fn(move || {
        while let Some(&b) = src.get(i) {
            i += 1;
            match b {
                b'\n' => return Some(i as u32),
                b'\r' => {
                    if src.get(i) == Some(&b'\n') {
                        i += 1;
                    }
                    return Some(i as u32);
                }
                _ => {}
            }
        }
        None
    })
}

/// How many line breaks `src` holds, as [`LineIndex`] counts them: its
/// lines less one.
pub fn line_breaks(src: &[u8]) -> u32 {
    line_starts(src).count() as u32
}

/// Maps byte offsets to 0-based (line, byte column) pairs.
#[derive(Debug, Clone, Default)]
pub struct LineIndex {
    /// Byte offset of the start of each line.
    starts: Vec<u32>,
    len: u32,
}

impl LineIndex {
    pub fn new(src: &[u8]) -> LineIndex {
        LineIndex {
            starts: std::iter::once(0).chain(line_starts(src)).collect(),
            len: src.len() as u32,
        }
    }

    /// 0-based line and byte column of `offset`.
    pub fn line_col(&self, offset: u32) -> (u32, u32) {
        let offset = offset.min(self.len);
        let line = match self.starts.binary_search(&offset) {
            Ok(l) => l,
            Err(l) => l - 1,
        };
        (line as u32, offset - self.starts[line])
    }

    pub fn line_start(&self, line: u32) -> Option<u32> {
        self.starts.get(line as usize).copied()
    }

    pub fn line_count(&self) -> u32 {
        self.starts.len() as u32
    }

    pub fn text_len(&self) -> u32 {
        self.len
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_handles_all_line_endings() {
        let idx = LineIndex::new(b"G0\nG1\r\nG2\rG3");
        assert_eq!(idx.line_col(0), (0, 0));
        assert_eq!(idx.line_col(3), (1, 0));
        assert_eq!(idx.line_col(7), (2, 0));
        assert_eq!(idx.line_col(10), (3, 0));
        assert_eq!(idx.line_col(11), (3, 1));
        assert_eq!(idx.line_count(), 4);
    }
}
