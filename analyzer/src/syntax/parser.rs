//! The parser: one pass over the bytes, emitting tokens (every byte belongs to
//! exactly one) and the block/item/expression structure at the same time.
//!
//! It never fails: anything it does not understand becomes an `Unknown` or
//! `Ignored` token and an `Error` item with a located diagnostic, and parsing
//! resumes at the next item.

use std::sync::Arc;

use super::ast::*;
use crate::diagnostic::Severity;
use crate::dialect::{Dialect, Variant};
use crate::span::Span;

// The parser's diagnostics are made from their rules' metadata, declared and
// documented with the other rules.
use crate::rules::syntax_rules as codes;
use crate::rules::RuleMeta;

/// Options that change how text is read.
#[derive(Debug, Clone, Copy)]
pub struct ParseOptions {
    pub dialect: Dialect,
    pub variant: Variant,
}

impl ParseOptions {
    pub fn new(dialect: Dialect) -> ParseOptions {
        ParseOptions {
            dialect,
            variant: dialect.default_variant(),
        }
    }
}

/// The UTF-8 encoding of U+FEFF, which some editors put before the first line.
const BOM: &[u8] = &[0xEF, 0xBB, 0xBF];
/// Expressions nested deeper than this are cut off with a diagnostic so that
/// hostile input cannot overflow the stack.
const MAX_EXPR_DEPTH: u32 = 64;
/// Binary operators per block: `1+1+…` puts each `+` above the previous one, so
/// together with [`MAX_EXPR_DEPTH`] this bounds the height of every expression tree
/// (see [`MAX_EXPR_HEIGHT`]). LinuxCNC reads at most 256 characters a line.
const MAX_BLOCK_OPERATORS: u32 = 256;
/// No expression tree is higher than this (a nesting level adds at most two nodes
/// to a path, a binary operator one), so the recursive walkers over expressions in
/// every crate need at most this many frames.
pub const MAX_EXPR_HEIGHT: u32 = 2 * (MAX_EXPR_DEPTH + 2) + MAX_BLOCK_OPERATORS;

/// Parses a whole file.
pub fn parse(opts: ParseOptions, text: impl Into<Arc<[u8]>>) -> Program {
    parse_serial(opts, text)
}

/// An empty program with room for the tree of `len` bytes of typical text, so the
/// vectors do not grow (and copy) while a large file is read; room for tokens only
/// when they are recorded.
fn with_capacity(dialect: Dialect, text: Arc<[u8]>, len: usize, tokens: bool) -> Program {
    Program {
        dialect,
        text,
        base: 0,
        tokens: if tokens {
            Vec::with_capacity(len / 2 + 1)
        } else {
            Vec::new()
        },
        blocks: Vec::with_capacity(len / 16 + 1),
        items: Vec::with_capacity(len / 5 + 1),
        exprs: Vec::new(),
        expr_lists: Vec::new(),
        diagnostics: Vec::new(),
    }
}

/// Parses a whole file on the calling thread.
pub fn parse_serial(opts: ParseOptions, text: impl Into<Arc<[u8]>>) -> Program {
    let text: Arc<[u8]> = text.into();
    let mut program = with_capacity(opts.dialect, text.clone(), text.len(), true);
    let mut parser = Parser::new(opts, text);
    parser.parse_blocks(&mut program, usize::MAX);
    program
}

/// Parses a whole file on the calling thread without recording tokens: the blocks,
/// items, expressions and diagnostics are those of [`parse_serial`], and
/// `tokens` stays empty. For hosts that only lint or run (the CLI), which never
/// look at tokens; it saves their time and about a quarter of the tree's memory.
pub fn parse_lean(opts: ParseOptions, text: impl Into<Arc<[u8]>>) -> Program {
    let text: Arc<[u8]> = text.into();
    let mut program = with_capacity(opts.dialect, text.clone(), text.len(), false);
    let mut parser = Parser::new(opts, text).without_tokens();
    parser.parse_blocks(&mut program, usize::MAX);
    program
}

/// The tokens of one block, read again from the text: for programs parsed by
/// [`parse_lean`], or to look at one block without walking the token list. Equal to
/// the slice of a full parse's tokens that lies in the block, terminator included.
///
/// A block depends on no parser state but the `%` lines before it, which only
/// decide the kind of `%` and ignored blocks; those are rebuilt from the kind
/// recorded in the block.
pub fn block_tokens(program: &Program, block: &Block) -> Vec<Token> {
    let Some(start) = block.span.start.checked_sub(program.base) else {
        return Vec::new();
    };
    let start = start as usize;
    if start >= program.text.len() {
        return Vec::new();
    }
    let state = ParserState {
        percent_seen: matches!(block.kind, BlockKind::Percent | BlockKind::Ignored),
        after_end: block.kind == BlockKind::Ignored,
        seen_content: true,
    };
    let opts = ParseOptions::new(program.dialect);
    let mut scratch = Program {
        dialect: program.dialect,
        text: program.text.clone(),
        base: 0,
        tokens: Vec::new(),
        blocks: Vec::new(),
        items: Vec::new(),
        exprs: Vec::new(),
        expr_lists: Vec::new(),
        diagnostics: Vec::new(),
    };
    let mut parser = Parser::resume(opts, program.text.clone(), start, block.line, state);
    parser.parse_blocks(&mut scratch, 1);
    for t in &mut scratch.tokens {
        t.start = t.start.saturating_add(program.base);
    }
    scratch.tokens
}

/// Parses one window of a file: `text` holds whole lines starting at file
/// offset `base` on 0-based line `line`, and `state` is what the parser
/// carried out of the window before ([`ParserState::default`] for the first).
/// The tree has the file's spans and lines ([`Program::rebase`]); the state
/// returned goes to the next window. A host that reads a file too large to
/// hold parses it window by window with this.
pub fn parse_window(
    opts: ParseOptions,
    text: Arc<[u8]>,
    base: u32,
    line: u32,
    state: ParserState,
) -> (Program, ParserState) {
    let mut program = with_capacity(opts.dialect, text.clone(), text.len(), false);
    let mut parser = Parser::resume(opts, text, 0, 0, state).without_tokens();
    parser.parse_blocks(&mut program, usize::MAX);
    let state = parser.state();
    program.rebase(base, line);
    (program, state)
}

/// A resumable parser over one file's text.
pub struct Parser {
    opts: ParseOptions,
    text: Arc<[u8]>,
    pos: usize,
    line: u32,
    /// FANUC/RS274NGC: a `%` line has been seen.
    percent_seen: bool,
    /// A closing `%` ended the useful content.
    after_end: bool,
    /// At least one non-blank line has been seen (RS274/NGC opening `%` rule).
    seen_content: bool,
    /// Plain lines take [`plain_words`] (off only to test it against the general path).
    plain_fast: bool,
    /// Whether tokens are recorded (see [`parse_lean`]).
    tokens: bool,
}

/// The state a [`Parser`] carries across block boundaries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ParserState {
    pub percent_seen: bool,
    pub after_end: bool,
    pub seen_content: bool,
}

/// Per-block working state.
struct Cx<'p> {
    p: &'p mut Program,
    /// The file's text up to the end of this block's content: nothing a block
    /// item reads lies beyond it, and one bound check covers both limits.
    text: &'p [u8],
    pos: usize,
    /// Byte where the block ends (before its terminator).
    limit: usize,
    dialect: Dialect,
    depth: u32,
    /// Binary operators read in this block (see [`MAX_BLOCK_OPERATORS`]).
    operators: u32,
    /// Whether tokens are recorded.
    tokens: bool,
    /// The spindle number of the word being read (`S2_1500`).
    spindle: Option<u16>,
}

fn is_ws(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | 0x0b | 0x0c)
}

fn is_digit(b: u8) -> bool {
    b.is_ascii_digit()
}

impl Parser {
    pub fn new(opts: ParseOptions, text: Arc<[u8]>) -> Parser {
        Parser {
            opts,
            text,
            pos: 0,
            line: 0,
            percent_seen: false,
            after_end: false,
            seen_content: false,
            plain_fast: true,
            tokens: true,
        }
    }

    /// Turns the fast path for plain lines off, so that tests can compare it with
    /// the general path on the same text.
    #[doc(hidden)]
    pub fn without_fast_path(mut self) -> Parser {
        self.plain_fast = false;
        self
    }

    /// A parser that records no tokens (see [`parse_lean`]).
    pub fn without_tokens(mut self) -> Parser {
        self.tokens = false;
        self
    }

    pub fn is_done(&self) -> bool {
        self.pos >= self.text.len()
    }

    /// Byte offset and 0-based line where the next block starts.
    pub fn position(&self) -> (usize, u32) {
        (self.pos, self.line)
    }

    /// What the parser carries from one block to the next besides its position.
    /// Two parsers at the same position with equal states parse the rest of
    /// the text identically, which is what lets incremental hosts stop early.
    pub fn state(&self) -> ParserState {
        ParserState {
            percent_seen: self.percent_seen,
            after_end: self.after_end,
            seen_content: self.seen_content,
        }
    }

    /// A parser that continues at a block boundary recorded earlier (`pos`,
    /// `line` and `state` as [`Parser::position`] and [`Parser::state`] gave
    /// them before that block), so that a host can re-parse from the middle
    /// of a file.
    pub fn resume(
        opts: ParseOptions,
        text: Arc<[u8]>,
        pos: usize,
        line: u32,
        state: ParserState,
    ) -> Parser {
        Parser {
            opts,
            pos: pos.min(text.len()),
            text,
            line,
            percent_seen: state.percent_seen,
            after_end: state.after_end,
            seen_content: state.seen_content,
            plain_fast: true,
            tokens: true,
        }
    }

    /// Parses up to `max_blocks` blocks into `program`, appending. Returns the
    /// number of blocks parsed (0 at end of input).
    pub fn parse_blocks(&mut self, program: &mut Program, max_blocks: usize) -> usize {
        // One handle on the text for the whole run: cloning the `Arc` per block
        // cost two atomic operations per line.
        let text = self.text.clone();
        let limit = text.len();
        let mut n = 0;
        let quick = self.plain_fast && !self.tokens;
        while n < max_blocks && self.pos < limit {
            if quick {
                n += self.plain_blocks(program, &text, max_blocks - n, limit);
                if n >= max_blocks || self.pos >= limit {
                    break;
                }
            }
            self.parse_block(program, &text);
            n += 1;
        }
        n
    }

    /// [`Parser::plain_block`] over the plain lines from here on, up to `max` of
    /// them and before byte `limit`: one call per run of CAM output rather than per
    /// line. Returns how many it parsed; unless a bound stopped it, the line after
    /// them is not plain.
    fn plain_blocks(&mut self, p: &mut Program, text: &[u8], max: usize, limit: usize) -> usize {
        let mut n = 0;
        while n < max && self.pos < limit && self.plain_block(p, text) {
            n += 1;
        }
        n
    }

    /// [`Parser::parse_block`] for a line [`plain_words`] accepts, in a lean parse:
    /// such a line starts with its first word's letter, so it is a normal, non-blank
    /// block without a block-skip mark or tokens to record, and none of the general
    /// bookkeeping applies. Returns `false`, having changed nothing, for any other
    /// line.
    #[inline(always)]
    fn plain_block(&mut self, p: &mut Program, text: &[u8]) -> bool {
        let start = self.pos;
        if self.after_end || !text.get(start).is_some_and(u8::is_ascii_uppercase) {
            return false;
        }
        let item_start = p.items.len() as u32;
        let Some(content_end) = plain_words::<false>(p, text, start, self.opts.dialect) else {
            return false;
        };
        let (end, newline) = terminator(text, content_end);
        self.seen_content = true;
        p.blocks.push(Block {
            span: Span::new(start as u32, content_end as u32),
            term_end: end as u32,
            line: self.line,
            kind: BlockKind::Normal,
            skip_level: 0,
            skip_len: 0,
            skip_at: 0,
            items: (item_start, p.items.len() as u32),
        });
        if newline {
            self.line += 1;
        }
        // The line starts with a letter, so `end > start`.
        self.pos = end.min(text.len());
        true
    }

    /// Finds the end of the current block's content and of its terminator.
    fn block_bounds(&self) -> (usize, usize, bool) {
        let t = &self.text;
        let mut i = self.pos;
        let semicolon_ends = self.opts.dialect == Dialect::Fanuc;
        if !semicolon_ends {
            // Only a line break ends the block: a vectorised search.
            i = memchr::memchr2(b'\n', b'\r', &t[i..]).map_or(t.len(), |k| i + k);
        } else if let Some(k) = memchr::memchr3(b'\n', b'\r', b';', &t[i..])
            .filter(|k| memchr::memchr(b'(', &t[i..i + k]).is_none())
        {
            // No comment before the first line break or `;`: that ends the block.
            i += k;
        } else {
            // A comment may contain `;` without ending the block; parentheses do not span lines.
            let mut in_comment = false;
            while i < t.len() {
                match t[i] {
                    b'\n' | b'\r' => break,
                    b'(' => in_comment = true,
                    b')' => in_comment = false,
                    b';' if !in_comment => break,
                    _ => {}
                }
                i += 1;
            }
        }
        let (end, newline) = terminator(t, i);
        (i, end, newline)
    }

    fn parse_block(&mut self, p: &mut Program, text: &[u8]) {
        let start = self.pos;
        let (content_end, end, newline) = self.block_bounds();
        let line = self.line;
        let item_start = p.items.len() as u32;
        let dialect = self.opts.dialect;
        // A UTF-8 byte-order mark before the first line: one located diagnostic,
        // and the line is read as if it were not there.
        let bom = if start == 0 && text[..content_end].starts_with(BOM) {
            BOM.len()
        } else {
            0
        };
        let start = start + bom;
        let content = &text[start..content_end];
        // First and last non-blank bytes decide the line's kind without allocating.
        let first_nb = content.iter().position(|b| !is_ws(*b));
        let blank = first_nb.is_none();
        let first_byte = first_nb.map(|i| content[i]);
        let only_percent = first_byte == Some(b'%')
            && first_nb.is_some_and(|i| content[i + 1..].iter().all(|b| is_ws(*b)));

        let mut kind = BlockKind::Normal;
        let mut skip = None;
        let mut cx = Cx {
            p,
            text: &text[..content_end],
            pos: start,
            limit: content_end,
            dialect,
            depth: 0,
            operators: 0,
            tokens: self.tokens,
            spindle: None,
        };
        if bom > 0 {
            let (kind, sev, msg) = if dialect == Dialect::Rs274ngc {
                (TokenKind::Unknown, Severity::Error, "the file starts with a UTF-8 byte-order mark (bytes EF BB BF), which LinuxCNC reads as a bad character and stops (rs274: Bad character '\\357' used): save the file without it")
            } else {
                (TokenKind::Whitespace, Severity::Info, "the file starts with a UTF-8 byte-order mark (bytes EF BB BF): Partscope skips it, but a control that reads the file as ISO/EIA code may not; save the file without it if the control rejects it")
            };
            cx.token(0, kind);
            cx.diag(
                &codes::UNKNOWN_CHARACTER,
                sev,
                Span::new(0, bom as u32),
                msg,
            );
        }

        if self.after_end {
            kind = BlockKind::Ignored;
            if content_end > start {
                cx.token(start, TokenKind::Ignored);
            }
        } else if dialect == Dialect::Servoworks && content.first() == Some(&b'%') {
            // ServoWorks: `%` in column 1 deletes the whole line, unconditionally.
            kind = if only_percent {
                BlockKind::Percent
            } else {
                BlockKind::Deleted
            };
            cx.token(
                start,
                if kind == BlockKind::Percent {
                    TokenKind::Percent
                } else {
                    TokenKind::LineComment
                },
            );
        } else if first_byte == Some(b'%') && (dialect == Dialect::Fanuc || only_percent) {
            kind = BlockKind::Percent;
            cx.ws();
            let pct = cx.pos;
            cx.token(pct, TokenKind::Percent);
            cx.pos += 1;
            if dialect == Dialect::Fanuc && self.percent_seen {
                self.after_end = true;
            } else if dialect == Dialect::Rs274ngc {
                if !self.seen_content {
                    self.percent_seen = true;
                } else if self.percent_seen {
                    self.after_end = true;
                } else {
                    cx.diag(
                        &codes::MISPLACED_PERCENT,
                        Severity::Error,
                        Span::new(pct as u32, pct as u32 + 1),
                        "`%` ends the program only when the file opened with a `%` line; here it is an illegal character (rs274: Bad character '%' used)",
                    );
                }
            } else {
                self.percent_seen = true;
            }
            // The rest of the line: FANUC leader / title, otherwise blanks.
            cx.ws();
            if cx.pos < content_end {
                cx.token(cx.pos, TokenKind::Ignored);
                cx.pos = content_end;
            }
        } else {
            if !blank {
                self.seen_content = true;
            }
            if !(self.plain_fast
                && plain_words_to(cx.p, text, start, content_end, dialect, self.tokens))
            {
                skip = cx.block_start(start);
                cx.items();
            }
        }
        if kind == BlockKind::Normal && !blank {
            self.seen_content = true;
        }
        // Terminator token(s).
        if end > content_end {
            let t = &text[content_end..end];
            let mut off = content_end;
            if t.first() == Some(&b';') {
                cx.token(off, TokenKind::Eob);
                off += 1;
                let mut j = off;
                while j < end && is_ws(text[j]) {
                    j += 1;
                }
                if j > off {
                    cx.token(off, TokenKind::Whitespace);
                    off = j;
                }
            }
            if off < end {
                cx.token(off, TokenKind::Newline);
            }
        }
        let item_end = cx.p.items.len() as u32;
        let mut block = Block {
            span: Span::new(start as u32, content_end as u32),
            term_end: end as u32,
            line,
            kind,
            skip_level: 0,
            skip_len: 0,
            skip_at: 0,
            items: (item_start, item_end),
        };
        block.set_skip(skip);
        p.blocks.push(block);
        if newline {
            self.line += 1;
        }
        self.pos = end.max(start + 1).min(text.len());
        if end + bom == start {
            // Cannot happen (an empty block at EOF is not parsed), but guard the loop.
            self.pos = text.len();
        }
    }
}

/// The end of the terminator of a block whose content ends at `content_end` (a
/// line break, `;`, `;` and blanks before a line break, or nothing at the end of
/// the text), and whether it holds a line break.
fn terminator(t: &[u8], content_end: usize) -> (usize, bool) {
    let mut end = content_end;
    let mut newline = false;
    if end < t.len() && t[end] == b';' {
        end += 1;
        // `;` directly followed by (blanks and) a newline is one end of block.
        let mut j = end;
        while j < t.len() && is_ws(t[j]) {
            j += 1;
        }
        if j < t.len() && (t[j] == b'\n' || t[j] == b'\r') {
            end = j;
        }
    }
    if end < t.len() && t[end] == b'\r' {
        end += 1;
        newline = true;
        if end < t.len() && t[end] == b'\n' {
            end += 1;
        }
    } else if end < t.len() && t[end] == b'\n' {
        end += 1;
        newline = true;
    }
    (end, newline)
}

/// [`plain_words`] over a block whose content end is known: `false`, leaving `p`
/// as it was, unless the block is plain and its content ends there.
fn plain_words_to(
    p: &mut Program,
    text: &[u8],
    start: usize,
    content_end: usize,
    dialect: Dialect,
    tokens: bool,
) -> bool {
    let (tokens_before, items_before) = (p.tokens.len(), p.items.len());
    let end = if tokens {
        plain_words::<true>(p, text, start, dialect)
    } else {
        plain_words::<false>(p, text, start, dialect)
    };
    match end {
        Some(end) if end == content_end => true,
        Some(_) => {
            p.tokens.truncate(tokens_before);
            p.items.truncate(items_before);
            false
        }
        None => false,
    }
}

/// The fast path for plain lines: address letters each followed directly by a
/// literal number (`X1.25 Y-0.5 F300`), separated by blanks. Such lines are most of
/// what CAM systems write, and for them the general path (keywords, program heads,
/// names, expressions, blanks inside numbers, diagnostics) reduces to the tokens and
/// word items built here, identical to what it would build (the differential test
/// `plain_lines_parse_as_the_general_path_does` compares the two).
///
/// Reads from `start` to the end of the block's content, which it finds on the way
/// (a line break, a FANUC `;`, or the end of the text), so a plain line's bytes are
/// read once. Returns that end, or `None`, leaving `p` as it was, when the line
/// holds anything else; the general path then reads it.
#[inline(always)]
fn plain_words<const TOKENS: bool>(
    p: &mut Program,
    text: &[u8],
    start: usize,
    dialect: Dialect,
) -> Option<usize> {
    let (tokens_before, items_before) = (p.tokens.len(), p.items.len());
    let end = plain_words_inner::<TOKENS>(p, text, start, dialect);
    if end.is_none() {
        p.tokens.truncate(tokens_before);
        p.items.truncate(items_before);
    }
    end
}

/// [`plain_words`] without the clean-up on failure: it may leave some of the line's
/// words behind when it returns `None`.
fn plain_words_inner<const TOKENS: bool>(
    p: &mut Program,
    text: &[u8],
    start: usize,
    dialect: Dialect,
) -> Option<usize> {
    let classes = plain_classes(dialect);
    let mut i = start;
    loop {
        let Some(&b) = text.get(i) else {
            return Some(i);
        };
        match classes[usize::from(b)] {
            PlainClass::Letter => {}
            PlainClass::End => return Some(i),
            PlainClass::Blank => {
                let s = i;
                while text.get(i).is_some_and(|c| is_ws(*c)) {
                    i += 1;
                }
                if TOKENS {
                    p.tokens.push(Token {
                        start: s as u32,
                        kind: TokenKind::Whitespace,
                    });
                }
                continue;
            }
            PlainClass::Other => return None,
        }
        let ls = i;
        i += 1;
        let ns = i;
        let sign = text.get(i).copied();
        let signed = sign == Some(b'-') || sign == Some(b'+');
        if signed {
            i += 1;
        }
        let (mant, digits, frac_digits, has_point, after) = decimal(text, i);
        i = after;
        if digits == 0 || digits > 15 {
            return None;
        }
        // The number must end here: at the end of the line, before a letter, or before
        // blanks that do not continue it (RS274/NGC and FANUC read `X1 5` as `X15`).
        // Those blanks are read here, once, and stepped over below.
        // (A letter that cannot start a plain word, `O` or a ServoWorks `P`, fails the
        // line here rather than at the top of the loop.)
        let mut next = i;
        match text.get(i).map(|c| classes[usize::from(*c)]) {
            None | Some(PlainClass::End | PlainClass::Letter) => {}
            Some(PlainClass::Blank) => {
                while text.get(next).is_some_and(|c| is_ws(*c)) {
                    next += 1;
                }
                if dialect != Dialect::Servoworks
                    && text
                        .get(next)
                        .is_some_and(|c| c.is_ascii_digit() || *c == b'.')
                {
                    return None;
                }
            }
            Some(PlainClass::Other) => return None,
        }
        // At most 15 digits: the mantissa is exact, below 2^63 (so the signed
        // conversion, one instruction, is exact too), and `frac_digits` indexes the table.
        let v = mant as i64 as f64 / POW10[frac_digits];
        if TOKENS {
            p.tokens.push(Token {
                start: ls as u32,
                kind: TokenKind::Letter,
            });
            p.tokens.push(Token {
                start: ns as u32,
                kind: TokenKind::Number,
            });
        }
        p.items.push(Item {
            kind: ItemKind::Word(Word {
                letter: b,
                comma: false,
                spindle: None,
                value: WordValue::Num(Num {
                    value: if sign == Some(b'-') { -v } else { v },
                    span: Span::new(ns as u32, i as u32),
                    has_point,
                    signed,
                    digits: digits as u16,
                }),
            }),
            span: Span::new(ls as u32, i as u32),
        });
        if next > i {
            if TOKENS {
                p.tokens.push(Token {
                    start: i as u32,
                    kind: TokenKind::Whitespace,
                });
            }
            i = next;
        }
    }
}

/// What a byte is where a plain line may have a word ([`plain_words`]).
#[derive(Clone, Copy, PartialEq, Eq)]
enum PlainClass {
    /// An address letter that a plain word may start with.
    Letter,
    /// The end of the block's content: a line break, or `;` in FANUC.
    End,
    /// A blank.
    Blank,
    /// Anything else: the line is not plain.
    Other,
}

/// [`PlainClass`] of every byte, per dialect: one load decides what the next byte
/// starts instead of a chain of comparisons.
const fn plain_class_table(dialect: Dialect) -> [PlainClass; 256] {
    let mut t = [PlainClass::Other; 256];
    let mut b = b'A';
    while b <= b'Z' {
        t[b as usize] = PlainClass::Letter;
        b += 1;
    }
    // `O` starts program heads and O-words; a ServoWorks `P` may be a name.
    t[b'O' as usize] = PlainClass::Other;
    if matches!(dialect, Dialect::Servoworks) {
        t[b'P' as usize] = PlainClass::Other;
    }
    t[b'\n' as usize] = PlainClass::End;
    t[b'\r' as usize] = PlainClass::End;
    if matches!(dialect, Dialect::Fanuc) {
        t[b';' as usize] = PlainClass::End;
    }
    // The blanks of `is_ws`.
    t[b' ' as usize] = PlainClass::Blank;
    t[b'\t' as usize] = PlainClass::Blank;
    t[0x0b] = PlainClass::Blank;
    t[0x0c] = PlainClass::Blank;
    t
}

fn plain_classes(dialect: Dialect) -> &'static [PlainClass; 256] {
    static SERVOWORKS: [PlainClass; 256] = plain_class_table(Dialect::Servoworks);
    static RS274NGC: [PlainClass; 256] = plain_class_table(Dialect::Rs274ngc);
    static FANUC: [PlainClass; 256] = plain_class_table(Dialect::Fanuc);
    match dialect {
        Dialect::Servoworks => &SERVOWORKS,
        Dialect::Rs274ngc => &RS274NGC,
        Dialect::Fanuc => &FANUC,
    }
}

/// Exact powers of ten: a mantissa of at most 15 digits divided by one of them is
/// the correctly rounded value of the decimal.
const POW10: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

const POW10_U64: [u64; 16] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
    10_000_000_000,
    100_000_000_000,
    1_000_000_000_000,
    10_000_000_000_000,
    100_000_000_000_000,
    1_000_000_000_000_000,
];

/// The unsigned decimal number from `i` on (`12`, `12.5`, `.5`, `12.`): the value of
/// its digits without the point (wrapping past 19 digits, which callers reject), the
/// number of digits, how many follow the point, whether there is a point, and where
/// it ends. A number that ends within the next eight bytes (most of what CAM output
/// writes) is read from one load with one conversion.
#[inline(always)]
fn decimal(text: &[u8], i: usize) -> (u64, usize, usize, bool, usize) {
    if let Some(chunk) = text.get(i..).and_then(|s| s.first_chunk::<8>()) {
        let word = u64::from_le_bytes(*chunk);
        let flags = non_digit_flags(word);
        let int = (flags.trailing_zeros() / 8) as usize;
        if int < 7 && (word >> (8 * int)) as u8 == b'.' {
            // Digits after the point within the load (the count is 8 past the end).
            let frac = ((flags >> (8 * (int + 1))).trailing_zeros() / 8) as usize;
            let frac = frac.min(7 - int);
            let digits = int + frac;
            let end = i + int + 1 + frac;
            let ends = int + 1 + frac < 8 || !text.get(end).is_some_and(u8::is_ascii_digit);
            if ends && digits > 0 {
                // The digits before the point, then those after it, in the low bytes.
                let low = |n: usize| (1u64 << (8 * n)) - 1;
                let joined =
                    (word & low(int)) | (((word >> (8 * (int + 1))) & low(frac)) << (8 * int));
                let value = eight_digits_value(joined << (8 * (8 - digits)));
                return (value, digits, frac, true, end);
            }
        } else if (1..8).contains(&int) && (word >> (8 * int)) as u8 != b'.' {
            let value = eight_digits_value(word << (8 * (8 - int)));
            return (value, int, 0, false, i + int);
        }
    }
    let (int, int_digits, end) = digit_run(text, i);
    if text.get(end) != Some(&b'.') {
        return (int, int_digits, 0, false, end);
    }
    let (frac, frac_digits, end) = digit_run(text, end + 1);
    let value = int
        .wrapping_mul(POW10_U64.get(frac_digits).copied().unwrap_or(0))
        .wrapping_add(frac);
    (value, int_digits + frac_digits, frac_digits, true, end)
}

/// The decimal digits from `i` on: their value (wrapping past 19 digits, which
/// callers reject), their count, and where they end. Eight bytes at a time where the
/// text has them: a number's length varies from word to word, and a loop per digit
/// pays a mispredicted exit branch on most of them.
fn digit_run(text: &[u8], mut i: usize) -> (u64, usize, usize) {
    let mut value = 0u64;
    let mut count = 0usize;
    while let Some(chunk) = text.get(i..).and_then(|s| s.first_chunk::<8>()) {
        let word = u64::from_le_bytes(*chunk);
        let k = leading_digits(word);
        if k > 0 {
            value = value
                .wrapping_mul(POW10_U64[k])
                .wrapping_add(eight_digits_value(word << (8 * (8 - k))));
        }
        count += k;
        i += k;
        if k < 8 {
            return (value, count, i);
        }
    }
    while let Some(d) = text.get(i).filter(|c| c.is_ascii_digit()) {
        value = value.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
        count += 1;
        i += 1;
    }
    (value, count, i)
}

/// How many of the eight bytes of `word` (first byte lowest) are ASCII digits
/// before the first that is not.
fn leading_digits(word: u64) -> usize {
    (non_digit_flags(word).trailing_zeros() / 8) as usize
}

/// Bit 7 of each byte of `word` set where the byte is not an ASCII digit, all other
/// bits clear.
fn non_digit_flags(word: u64) -> u64 {
    const LO: u64 = 0x0F0F_0F0F_0F0F_0F0F;
    const HI: u64 = 0xF0F0_F0F0_F0F0_F0F0;
    const LOW7: u64 = 0x7F7F_7F7F_7F7F_7F7F;
    // A byte is a digit when its high nibble is 3 and its low nibble at most 9; both
    // tests stay inside the byte (0x0F + 0x06 carries into bit 4, never further).
    let not_digit = ((word & HI) ^ 0x3030_3030_3030_3030)
        | ((word & LO) + 0x0606_0606_0606_0606) & 0x1010_1010_1010_1010;
    // Bit 7 of each byte set when the byte is non-zero, again without carries.
    (((not_digit & LOW7) + LOW7) | not_digit) & !LOW7
}

/// The value of eight ASCII digits (first byte lowest, most significant); bytes
/// that are zero count as leading zeros.
fn eight_digits_value(word: u64) -> u64 {
    let d = word & 0x0F0F_0F0F_0F0F_0F0F;
    let d = (d.wrapping_mul(10) + (d >> 8)) & 0x00FF_00FF_00FF_00FF;
    let d = (d.wrapping_mul(100) + (d >> 16)) & 0x0000_FFFF_0000_FFFF;
    (d.wrapping_mul(10_000) + (d >> 32)) & 0xFFFF_FFFF
}

impl<'p> Cx<'p> {
    fn at(&self, i: usize) -> Option<u8> {
        self.text.get(i).copied()
    }

    fn peek(&self) -> Option<u8> {
        self.at(self.pos)
    }

    /// Starts a token at `start` unless the previous token has the same kind
    /// and is mergeable (whitespace, unknown runs).
    fn token(&mut self, start: usize, kind: TokenKind) {
        if !self.tokens {
            return;
        }
        let start = start as u32;
        if let Some(last) = self.p.tokens.last() {
            if last.start == start {
                // A zero-length previous token: replace it.
                let n = self.p.tokens.len();
                self.p.tokens[n - 1].kind = kind;
                return;
            }
            if last.kind == kind && matches!(kind, TokenKind::Whitespace | TokenKind::Unknown) {
                return;
            }
        }
        self.p.tokens.push(Token { start, kind });
    }

    fn diag(&mut self, rule: &RuleMeta, sev: Severity, span: Span, msg: impl Into<String>) {
        self.p.diagnostics.push(rule.diagnostic(sev, span, msg));
    }

    fn push_item(&mut self, kind: ItemKind, start: usize) {
        let span = Span::new(start as u32, self.pos as u32);
        self.p.items.push(Item { kind, span });
    }

    fn push_expr(&mut self, expr: Expr, start: usize) -> ExprId {
        let id = ExprId(self.p.exprs.len() as u32);
        self.p.exprs.push(ExprNode {
            expr,
            span: Span::new(start as u32, self.pos as u32),
        });
        id
    }

    /// Skips blanks, emitting a whitespace token.
    fn ws(&mut self) {
        let s = self.pos;
        while let Some(b) = self.peek() {
            if !is_ws(b) {
                break;
            }
            self.pos += 1;
        }
        if self.pos > s {
            self.token(s, TokenKind::Whitespace);
        }
    }

    fn sev_for_unknown(&self) -> Severity {
        match self.dialect {
            // ServoWorks silently drops data it does not recognise (§3.6).
            Dialect::Servoworks => Severity::Warning,
            _ => Severity::Error,
        }
    }

    /// Block skip and other things only allowed at the start of a block.
    fn block_start(&mut self, start: usize) -> Option<(Span, u8)> {
        if self.dialect != Dialect::Servoworks {
            self.ws();
        }
        if self.peek() != Some(b'/') {
            return None;
        }
        let s = self.pos;
        if self.dialect == Dialect::Servoworks && s != start {
            return None;
        }
        self.token(s, TokenKind::BlockSkip);
        self.pos += 1;
        let mut level = 1u8;
        if self.dialect == Dialect::Fanuc {
            if let Some(d) = self.peek().filter(|b| (b'1'..=b'9').contains(b)) {
                level = d - b'0';
                self.pos += 1;
            }
        }
        Some((Span::new(s as u32, self.pos as u32), level))
    }

    fn items(&mut self) {
        let mut first = true;
        while self.pos < self.limit {
            let Some(b) = self.peek() else { break };
            let start = self.pos;
            match b {
                b' ' | b'\t' | 0x0b | 0x0c => self.ws(),
                b'(' => self.comment(),
                b';' => self.semicolon(),
                b'#' => self.assignment(),
                b'/' => {
                    let (sev, msg) = match self.dialect {
                        Dialect::Servoworks => (Severity::Error, "`/` (optional skip) must be the first character of the line; anywhere else the control reports a parse error"),
                        Dialect::Rs274ngc => (Severity::Error, "`/` is only allowed as the block-delete character at the start of the line (rs274: Bad character '/' used)"),
                        Dialect::Fanuc => (Severity::Warning, "`/` in the middle of a block: depending on parameters the control skips the rest of the block or rejects it; put block skip at the start of the block"),
                    };
                    self.pos += 1;
                    self.token(start, TokenKind::BlockSkip);
                    self.diag(
                        &codes::MISPLACED_BLOCK_SKIP,
                        sev,
                        Span::new(start as u32, self.pos as u32),
                        msg,
                    );
                    self.push_item(ItemKind::Error, start);
                }
                b'%' => {
                    self.pos += 1;
                    self.token(start, TokenKind::Unknown);
                    let (sev, msg) = match self.dialect {
                        Dialect::Servoworks => (Severity::Warning, "`%` deletes a block only in the first column; here it is ignored and the words after it are executed"),
                        Dialect::Rs274ngc => (Severity::Error, "`%` must stand alone on its line (rs274: Bad character '%' used)"),
                        Dialect::Fanuc => (Severity::Error, "`%` marks the start or end of the tape and must stand alone on its line"),
                    };
                    self.diag(
                        &codes::MISPLACED_PERCENT,
                        sev,
                        Span::new(start as u32, self.pos as u32),
                        msg,
                    );
                    self.push_item(ItemKind::Error, start);
                }
                b'<' if self.dialect == Dialect::Fanuc && first => self.fanuc_name_head(),
                b':' if self.dialect == Dialect::Fanuc => {
                    // `:` is the ISO synonym of `O` for program numbers.
                    self.pos += 1;
                    self.token(start, TokenKind::Letter);
                    self.program_number(start);
                }
                b',' if self.dialect == Dialect::Fanuc
                    && self
                        .at(self.pos + 1)
                        .is_some_and(|c| matches!(c.to_ascii_uppercase(), b'C' | b'R' | b'A')) =>
                {
                    self.token(start, TokenKind::Comma);
                    self.pos += 1;
                    self.word(true);
                }
                b'$' | b'@' | b'^' if self.dialect == Dialect::Rs274ngc => self.word(false),
                c if c.is_ascii_alphabetic() => self.letter_item(first),
                _ => self.unknown_run(),
            }
            first = false;
        }
    }

    fn unknown_run(&mut self) {
        let start = self.pos;
        // Consume a run of bytes that cannot start an item, so one stray sequence
        // gives one diagnostic.
        while let Some(b) = self.peek() {
            if b.is_ascii_alphabetic()
                || matches!(b, b'(' | b';' | b'#' | b'/' | b'%' | b' ' | b'\t')
            {
                break;
            }
            self.pos += 1;
        }
        if self.pos == start {
            self.pos += 1;
        }
        let span = Span::new(start as u32, self.pos as u32);
        let text = String::from_utf8_lossy(span.slice(self.text)).into_owned();
        let sev = self.sev_for_unknown();
        let msg = match self.dialect {
            Dialect::Servoworks => format!(
                "unrecognised data `{}` is ignored by the control",
                printable(&text)
            ),
            _ => format!(
                "unexpected `{}`: not a word, comment or statement",
                printable(&text)
            ),
        };
        self.token(start, TokenKind::Unknown);
        self.diag(&codes::UNKNOWN_CHARACTER, sev, span, msg);
        self.push_item(ItemKind::Error, start);
    }

    fn comment(&mut self) {
        let start = self.pos;
        self.pos += 1;
        let mut closed = false;
        let mut nested = None;
        // After a nested `(` (an error in itself) the comment runs to the `)` that
        // balances it, so the rest of the text is not misread as words.
        let mut depth = 1u32;
        while let Some(b) = self.peek() {
            self.pos += 1;
            if b == b')' {
                depth -= 1;
                if depth == 0 || self.dialect == Dialect::Servoworks {
                    closed = true;
                    break;
                }
            }
            if b == b'(' {
                depth += 1;
                if nested.is_none() {
                    nested = Some(self.pos - 1);
                }
            }
        }
        self.token(start, TokenKind::Comment);
        let span = Span::new(start as u32, self.pos as u32);
        if !closed {
            let sev = Severity::Error;
            self.diag(
                &codes::UNCLOSED_COMMENT,
                sev,
                span,
                "comment is not closed with `)` before the end of the block",
            );
            let d = self.p.diagnostics.len() - 1;
            self.p.diagnostics[d].fixes.push(crate::diagnostic::Fix {
                title: "Close the comment".into(),
                edits: vec![crate::diagnostic::TextEdit {
                    span: Span::new(span.end, span.end),
                    new_text: ")".into(),
                }],
            });
        }
        if let Some(n) = nested {
            if self.dialect != Dialect::Servoworks {
                self.diag(
                    &codes::NESTED_COMMENT,
                    Severity::Error,
                    Span::new(n as u32, n as u32 + 1),
                    "comments do not nest: `(` inside a comment is an error",
                );
            }
        }
        let kind = comment_kind(span.slice(self.text));
        self.push_item(ItemKind::Comment(kind), start);
    }

    fn semicolon(&mut self) {
        let start = self.pos;
        match self.dialect {
            Dialect::Rs274ngc => {
                self.pos = self.limit;
                self.token(start, TokenKind::LineComment);
                let kind = comment_kind(Span::new(start as u32, self.pos as u32).slice(self.text));
                self.push_item(ItemKind::Comment(kind), start);
            }
            _ => {
                // ServoWorks: `;` ends the block's words; the rest of the line is data the
                // control does not use (FANUC never gets here: `;` ends its blocks).
                self.pos += 1;
                self.token(start, TokenKind::Eob);
                self.ws();
                if self.pos < self.limit {
                    let s = self.pos;
                    self.pos = self.limit;
                    self.token(s, TokenKind::Ignored);
                    self.diag(
                        &codes::TEXT_AFTER_EOB,
                        Severity::Info,
                        Span::new(s as u32, self.pos as u32),
                        "text after `;` is not executed (the manual does not define `;`; it is read as end of block)",
                    );
                }
            }
        }
    }

    /// `#… = expr` at item position.
    fn assignment(&mut self) {
        let start = self.pos;
        let target = self.param_ref();
        self.ws();
        if self.peek() == Some(b'=') {
            let s = self.pos;
            self.pos += 1;
            self.token(s, TokenKind::Operator);
            self.ws();
            // Custom Macro B (and ServoWorks macros) allow an unbracketed expression on the
            // right-hand side; RS274/NGC requires brackets around operators.
            let value = if self.dialect == Dialect::Rs274ngc {
                self.value_expr()
            } else {
                self.binary(0)
            };
            self.push_item(ItemKind::Assign { target, value }, start);
        } else {
            let span = Span::new(start as u32, self.pos as u32);
            self.diag(
                &codes::BAD_EXPRESSION,
                Severity::Error,
                span,
                "a parameter reference here must be an assignment: `#n = value` (equal sign missing)",
            );
            self.push_item(ItemKind::Error, start);
        }
    }

    /// `#n`, `##n`, `#[e]`, `#<name>`. The cursor is on `#`.
    fn param_ref(&mut self) -> ExprId {
        let start = self.pos;
        if self.dialect == Dialect::Rs274ngc {
            // `#<name>`: the name may contain anything but `>`.
            let mut j = self.pos + 1;
            while self.at(j).is_some_and(is_ws) {
                j += 1;
            }
            if self.at(j) == Some(b'<') {
                let mut k = j + 1;
                while let Some(c) = self.at(k) {
                    if c == b'>' {
                        break;
                    }
                    k += 1;
                }
                if self.at(k) == Some(b'>') {
                    self.pos = k + 1;
                    self.token(start, TokenKind::NamedParam);
                    let name = Span::new(j as u32 + 1, k as u32);
                    return self.push_expr(Expr::Named { name }, start);
                }
                self.pos = self.limit;
                self.token(start, TokenKind::NamedParam);
                self.diag(
                    &codes::BAD_EXPRESSION,
                    Severity::Error,
                    Span::new(start as u32, self.pos as u32),
                    "named parameter is missing its closing `>`",
                );
                return self.push_expr(Expr::Error, start);
            }
        }
        self.token(start, TokenKind::Hash);
        self.pos += 1;
        self.ws();
        let index = match self.peek() {
            Some(b'#') => {
                if self.dialect == Dialect::Fanuc {
                    let s = self.pos;
                    self.diag(
                        &codes::BAD_EXPRESSION,
                        Severity::Error,
                        Span::new(s as u32, s as u32 + 1),
                        "`##n` is not allowed in Custom Macro B; write `#[#n]`",
                    );
                }
                // Through `value_expr`, so that a run of `#` counts against the depth.
                self.value_expr()
            }
            Some(b'[') => self.group(),
            Some(c) if is_digit(c) || c == b'.' => {
                let n = self.number(false);
                let s = n.span.start as usize;
                self.push_expr(Expr::Num(n), s)
            }
            Some(b'-') | Some(b'+') => {
                let n = self.number(true);
                let s = n.span.start as usize;
                self.push_expr(Expr::Num(n), s)
            }
            // LinuxCNC reads the number after `#` as any value, so a function call
            // such as `#atan[1]/[1]` (parameter 45) is a parameter too.
            Some(c) if c.is_ascii_alphabetic() && self.dialect == Dialect::Rs274ngc => {
                self.value_expr()
            }
            _ => {
                let span = Span::new(start as u32, self.pos as u32);
                self.diag(
                    &codes::MISSING_VALUE,
                    Severity::Error,
                    span,
                    "`#` must be followed by a parameter number, `[expression]` or `<name>`",
                );
                self.push_expr(Expr::Error, self.pos)
            }
        };
        self.push_expr(Expr::Var { index }, start)
    }

    /// A numeric literal; `allow_sign` admits a leading `+`/`-`. Blanks inside the
    /// number are allowed in RS274/NGC and FANUC (they are removed before reading).
    /// The digits are read by [`decimal`], the reader of plain lines too.
    fn number(&mut self, allow_sign: bool) -> Num {
        let start = self.pos;
        let inner_ws = self.dialect != Dialect::Servoworks;
        let t = self.text;
        let mut i = self.pos;
        let sign = t
            .get(i)
            .copied()
            .filter(|c| allow_sign && matches!(c, b'+' | b'-'));
        if sign.is_some() {
            i += 1;
        }
        let (mut mant, mut digits, mut frac_digits, mut has_point, end) = decimal(t, i);
        i = end;
        let mut bad = false;
        let mut had_ws = false;
        // What `decimal` leaves: a second point (malformed, but read to its end) and
        // blanks before more digits (`X1 5` is `X15` in RS274/NGC and FANUC).
        loop {
            match t.get(i).copied() {
                Some(b'.') => {
                    bad |= has_point;
                    has_point = true;
                    i += 1;
                }
                Some(c) if c.is_ascii_digit() => {}
                Some(c) if inner_ws && is_ws(c) => {
                    let mut j = i;
                    while t.get(j).is_some_and(|c| is_ws(*c)) {
                        j += 1;
                    }
                    if !t.get(j).is_some_and(|c| c.is_ascii_digit() || *c == b'.') {
                        break;
                    }
                    had_ws = true;
                    i = j;
                    continue;
                }
                _ => break,
            }
            let (run, n, e) = digit_run(t, i);
            // Past 15 digits the value is read from the text below.
            mant = mant
                .wrapping_mul(POW10_U64.get(n).copied().unwrap_or(0))
                .wrapping_add(run);
            digits += n;
            if has_point {
                frac_digits += n;
            }
            i = e;
        }
        let end = i;
        self.pos = end;
        let span = Span::new(start as u32, end as u32);
        if end > start {
            self.token(start, TokenKind::Number);
        }
        let value = if digits == 0 || bad {
            None
        } else if digits <= 15 {
            // At most 15 digits: the mantissa is exact and one division by an exact
            // power of ten rounds correctly.
            let v = mant as f64 / POW10[frac_digits];
            Some(if sign == Some(b'-') { -v } else { v })
        } else {
            let raw = span.slice(t);
            let compact: Vec<u8>;
            let raw = if had_ws {
                compact = raw.iter().copied().filter(|b| !is_ws(*b)).collect();
                &compact[..]
            } else {
                raw
            };
            std::str::from_utf8(raw)
                .ok()
                .and_then(|s| s.parse::<f64>().ok())
        };
        let digits = u16::try_from(digits).unwrap_or(u16::MAX);
        let value = match value {
            Some(v) if v.is_finite() => v,
            _ => self.bad_number(bad, digits, start, end),
        };
        Num {
            value,
            span,
            has_point,
            signed: sign.is_some(),
            digits,
        }
    }

    /// Reports a number that cannot be read; kept out of line so the hot path stays small.
    #[cold]
    #[inline(never)]
    fn bad_number(&mut self, bad: bool, digits: u16, start: usize, end: usize) -> f64 {
        let what = if bad {
            "more than one decimal point in a number"
        } else if digits == 0 {
            "no digits where a number should be"
        } else {
            "number out of range"
        };
        let (code, span) = if end == start {
            (&codes::MISSING_VALUE, Span::new(start as u32, start as u32))
        } else {
            (
                &codes::MALFORMED_NUMBER,
                Span::new(start as u32, end as u32),
            )
        };
        self.diag(
            code,
            Severity::Error,
            span,
            format!("bad number format: {what}"),
        );
        f64::NAN
    }

    /// Reads a real value after a letter: number, `#…`, `[expr]`, function, signed forms.
    fn value_expr(&mut self) -> ExprId {
        self.depth += 1;
        let r = self.value_expr_inner();
        self.depth -= 1;
        r
    }

    /// Ends the block's expression at `start` with L014: the rest of the block is
    /// one unknown token.
    fn too_deep(&mut self, start: usize, what: &str) -> ExprId {
        self.pos = self.limit;
        self.token(start, TokenKind::Unknown);
        self.diag(
            &codes::EXPRESSION_TOO_DEEP,
            Severity::Error,
            Span::new(start as u32, self.pos as u32),
            format!("{what}; the rest of the block is not read"),
        );
        self.push_expr(Expr::Error, start)
    }

    fn value_expr_inner(&mut self) -> ExprId {
        let start = self.pos;
        if self.depth > MAX_EXPR_DEPTH {
            return self.too_deep(start, "expression nested too deeply (more than 64 levels)");
        }
        match self.peek() {
            Some(b'[') => self.group(),
            Some(b'#') => self.param_ref(),
            Some(c) if is_digit(c) || c == b'.' => {
                let n = self.number(false);
                self.push_expr(Expr::Num(n), start)
            }
            Some(c @ (b'+' | b'-')) => {
                // A sign before a literal belongs to the number; before anything else it is
                // a unary operator (LinuxCNC 2.9, FANUC).
                let mut j = self.pos + 1;
                while self.at(j).is_some_and(is_ws) {
                    j += 1;
                }
                if self.at(j).is_some_and(|d| is_digit(d) || d == b'.') {
                    let n = self.number(true);
                    return self.push_expr(Expr::Num(n), start);
                }
                self.token(start, TokenKind::Operator);
                self.pos += 1;
                self.ws();
                let arg = self.value_expr();
                let e = if c == b'-' {
                    Expr::Neg { arg }
                } else {
                    Expr::Plus { arg }
                };
                self.push_expr(e, start)
            }
            Some(c) if c.is_ascii_alphabetic() => self.function(),
            _ => {
                let span = Span::new(start as u32, start as u32);
                self.diag(
                    &codes::MISSING_VALUE,
                    Severity::Error,
                    span,
                    "a value is missing here",
                );
                self.push_expr(Expr::Error, start)
            }
        }
    }

    /// `[ expr ]`, cursor on `[`.
    fn group(&mut self) -> ExprId {
        let start = self.pos;
        self.token(start, TokenKind::LBracket);
        self.pos += 1;
        self.depth += 1;
        let inner = self.binary(0);
        self.depth -= 1;
        self.ws();
        if self.peek() == Some(b']') {
            let s = self.pos;
            self.token(s, TokenKind::RBracket);
            self.pos += 1;
        } else {
            self.diag(
                &codes::UNBALANCED_BRACKET,
                Severity::Error,
                Span::new(start as u32, start as u32 + 1),
                "unclosed expression: this `[` has no matching `]`",
            );
            // Skip to the end of the block so the rest is not misread.
            if self.pos < self.limit {
                let s = self.pos;
                self.pos = self.limit;
                self.token(s, TokenKind::Unknown);
            }
        }
        self.push_expr(Expr::Group { inner }, start)
    }

    fn binop_at(&self) -> Option<(BinOp, usize)> {
        let c = self.peek()?;
        let op = match c {
            b'+' => (BinOp::Add, 1),
            b'-' => (BinOp::Sub, 1),
            b'*' if self.at(self.pos + 1) == Some(b'*') => (BinOp::Pow, 2),
            b'*' => (BinOp::Mul, 1),
            b'/' => (BinOp::Div, 1),
            c if c.is_ascii_alphabetic() => {
                let mut j = self.pos;
                while self.at(j).is_some_and(|c| c.is_ascii_alphabetic()) {
                    j += 1;
                }
                let w = Span::new(self.pos as u32, j as u32)
                    .slice(self.text)
                    .to_ascii_uppercase();
                let named = |w: &[u8]| match w {
                    b"MOD" => Some(BinOp::Mod),
                    b"AND" => Some(BinOp::And),
                    b"OR" => Some(BinOp::Or),
                    b"XOR" => Some(BinOp::Xor),
                    b"EQ" => Some(BinOp::Eq),
                    b"NE" => Some(BinOp::Ne),
                    b"GT" => Some(BinOp::Gt),
                    b"GE" => Some(BinOp::Ge),
                    b"LT" => Some(BinOp::Lt),
                    b"LE" => Some(BinOp::Le),
                    _ => None,
                };
                if let Some(op) = named(&w) {
                    (op, j - self.pos)
                } else {
                    // An operator glued to the function after it (`GEABS[#2]`,
                    // `ANDSQRT[…]`): the controls read the letters up to the `[`.
                    let glued = self.at(j) == Some(b'[');
                    [3, 2]
                        .into_iter()
                        .filter(|n| glued && w.len() > *n)
                        .find_map(|n| {
                            let rest = std::str::from_utf8(&w[n..]).ok()?;
                            crate::syntax::Func::from_name(rest)?;
                            Some((named(&w[..n])?, n))
                        })?
                }
            }
            _ => return None,
        };
        Some(op)
    }

    fn precedence(&self, op: BinOp) -> u8 {
        match self.dialect {
            // LinuxCNC's five levels (used by both profiles, see the digest §1.8).
            Dialect::Rs274ngc => match op {
                BinOp::Pow => 5,
                BinOp::Mul | BinOp::Div | BinOp::Mod => 4,
                BinOp::Add | BinOp::Sub => 3,
                BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Ge | BinOp::Lt | BinOp::Le => 2,
                BinOp::And | BinOp::Or | BinOp::Xor => 1,
            },
            // Custom Macro B: `* / AND MOD` over `+ - OR XOR`; relations lowest.
            _ => match op {
                BinOp::Pow => 4,
                BinOp::Mul | BinOp::Div | BinOp::Mod | BinOp::And => 3,
                BinOp::Add | BinOp::Sub | BinOp::Or | BinOp::Xor => 2,
                _ => 1,
            },
        }
    }

    /// Precedence climbing; all operators are left-associative.
    fn binary(&mut self, min_prec: u8) -> ExprId {
        self.ws();
        let start = self.pos;
        let mut lhs = self.value_expr();
        loop {
            self.ws();
            let Some((op, len)) = self.binop_at() else {
                break;
            };
            let prec = self.precedence(op);
            if prec < min_prec {
                break;
            }
            let s = self.pos;
            self.operators += 1;
            if self.operators > MAX_BLOCK_OPERATORS {
                let rhs = self.too_deep(s, "more than 256 operators in one block");
                return self.push_expr(Expr::Binary { op, lhs, rhs }, start);
            }
            self.token(
                s,
                if len > 1 && op != BinOp::Pow {
                    TokenKind::Keyword
                } else {
                    TokenKind::Operator
                },
            );
            self.pos += len;
            let rhs = self.binary(prec + 1);
            lhs = self.push_expr(Expr::Binary { op, lhs, rhs }, start);
        }
        lhs
    }

    /// A function call `NAME[…]`; cursor on the first letter.
    fn function(&mut self) -> ExprId {
        let start = self.pos;
        let mut j = self.pos;
        while self.at(j).is_some_and(|c| c.is_ascii_alphabetic()) {
            j += 1;
        }
        let name = String::from_utf8_lossy(Span::new(start as u32, j as u32).slice(self.text))
            .into_owned();
        let func = Func::from_name(&name).filter(|f| f.in_dialect(self.dialect));
        let Some(func) = func else {
            // Not a function: leave the letter for the caller (it is the next word).
            let span = Span::new(start as u32, start as u32);
            self.diag(
                &codes::MISSING_VALUE,
                Severity::Error,
                span,
                "a value is missing here",
            );
            return self.push_expr(Expr::Error, start);
        };
        self.pos = j;
        self.token(start, TokenKind::Keyword);
        self.ws();
        if self.peek() != Some(b'[') {
            let span = Span::new(start as u32, self.pos as u32);
            self.diag(
                &codes::BAD_EXPRESSION,
                Severity::Error,
                span,
                format!("`{}` must be followed by `[`", name.to_ascii_uppercase()),
            );
            return self.push_expr(Expr::Error, start);
        }
        // Two-argument forms: `ATAN[a]/[b]`, `ATAN[a,b]`, `POW[a,b]`.
        let two = matches!(func, Func::Atan | Func::Pow);
        let (arg, arg2) = if two && self.dialect != Dialect::Rs274ngc {
            self.bracket_args()
        } else {
            (self.group(), None)
        };
        let mut arg2 = arg2;
        if func == Func::Atan && arg2.is_none() {
            self.ws();
            if self.peek() == Some(b'/') {
                let s = self.pos;
                self.token(s, TokenKind::Operator);
                self.pos += 1;
                self.ws();
                if self.peek() == Some(b'[') {
                    arg2 = Some(self.group());
                } else {
                    self.diag(
                        &codes::BAD_EXPRESSION,
                        Severity::Error,
                        Span::new(s as u32, self.pos as u32),
                        "`[` missing after the slash of ATAN[y]/[x]",
                    );
                }
            } else if self.dialect != Dialect::Fanuc {
                // The 30i also has a one-argument arc tangent, `ATAN[#j]` (−90° to 90°).
                self.diag(
                    &codes::BAD_EXPRESSION,
                    Severity::Error,
                    Span::new(start as u32, self.pos as u32),
                    "ATAN needs two arguments: ATAN[y]/[x]",
                );
            }
        }
        self.push_expr(Expr::Call { func, arg, arg2 }, start)
    }

    /// `[a]` or `[a,b]` for FANUC two-argument functions.
    fn bracket_args(&mut self) -> (ExprId, Option<ExprId>) {
        let start = self.pos;
        self.token(start, TokenKind::LBracket);
        self.pos += 1;
        self.depth += 1;
        let a = self.binary(0);
        self.ws();
        let mut b = None;
        if self.peek() == Some(b',') {
            let s = self.pos;
            self.token(s, TokenKind::Comma);
            self.pos += 1;
            b = Some(self.binary(0));
            self.ws();
        }
        self.depth -= 1;
        if self.peek() == Some(b']') {
            let s = self.pos;
            self.token(s, TokenKind::RBracket);
            self.pos += 1;
        } else {
            self.diag(
                &codes::UNBALANCED_BRACKET,
                Severity::Error,
                Span::new(start as u32, start as u32 + 1),
                "unclosed expression: this `[` has no matching `]`",
            );
        }
        let g = self.push_expr(Expr::Group { inner: a }, start);
        (g, b)
    }

    /// An item starting with a letter: keyword statement, program head, O-word or word.
    fn letter_item(&mut self, first: bool) {
        let start = self.pos;
        let mut j = self.pos + 1;
        // Only FANUC and ServoWorks have multi-letter statements (IF, GOTO, WHILE …).
        if self.dialect != Dialect::Rs274ngc {
            while self.at(j).is_some_and(|c| c.is_ascii_alphabetic()) {
                j += 1;
            }
        }
        let run = Span::new(start as u32, j as u32).slice(self.text);
        let c = run.first().map(|c| c.to_ascii_uppercase()).unwrap_or(b'?');
        match self.dialect {
            Dialect::Rs274ngc if c == b'O' => return self.oword(),
            Dialect::Fanuc | Dialect::Servoworks => {
                if let Some(kw) = (run.len() >= 2).then(|| macro_keyword(run)).flatten() {
                    return self.macro_stmt(kw);
                }
                if c == b'O' && self.text[start] == b'O' {
                    if self.dialect == Dialect::Servoworks {
                        return self.sw_program_head();
                    }
                    if first || self.at(start + 1).is_some_and(is_digit) {
                        self.pos += 1;
                        self.token(start, TokenKind::Letter);
                        return self.program_number(start);
                    }
                }
            }
            _ => {}
        }
        let lower = self.text[start].is_ascii_lowercase();
        if lower && self.dialect == Dialect::Servoworks {
            // ServoWorks ignores lower-case letters outside comments and names (§3.1):
            // the letter and its value are dropped.
            self.pos += 1;
            while self
                .peek()
                .is_some_and(|b| is_digit(b) || b == b'.' || b == b'-' || b == b'+')
            {
                self.pos += 1;
            }
            self.token(start, TokenKind::Ignored);
            self.diag(
                &codes::LOWERCASE,
                Severity::Warning,
                Span::new(start as u32, self.pos as u32),
                "ServoWorks ignores lower-case letters outside comments and subprogram names; this word is not executed",
            );
            self.push_item(ItemKind::Error, start);
            return;
        }
        if lower && self.dialect == Dialect::Fanuc {
            // Spec FAN015 (warning): a 30i reads lower case only with a setting.
            self.diag(
                &codes::LOWERCASE,
                Severity::Warning,
                Span::new(start as u32, start as u32 + 1),
                "lower-case address letter; FANUC programs are upper case (accepted here as upper case)",
            );
            let d = self.p.diagnostics.len() - 1;
            let upper = (self.text[start] as char).to_ascii_uppercase();
            // Upper case is read the same way only for a word with a value: an
            // upper-case `O` may open a program head, and a run of letters may
            // become a macro keyword.
            let mut j = start + 1;
            while self.at(j).is_some_and(|c| c == b' ' || c == b'\t') {
                j += 1;
            }
            let valued = self
                .at(j)
                .is_some_and(|c| is_digit(c) || matches!(c, b'.' | b'-' | b'+' | b'[' | b'#'));
            if upper != 'O' && valued {
                self.p.diagnostics[d].fixes.push(crate::diagnostic::Fix {
                    title: format!("Write `{upper}`"),
                    edits: vec![crate::diagnostic::TextEdit {
                        span: Span::new(start as u32, start as u32 + 1),
                        new_text: upper.to_string(),
                    }],
                });
            }
        }
        self.word(false)
    }

    /// An address letter and its value.
    fn word(&mut self, comma: bool) {
        let start = if comma { self.pos - 1 } else { self.pos };
        let ls = self.pos;
        let letter = self.text[ls].to_ascii_uppercase();
        self.pos += 1;
        self.token(ls, TokenKind::Letter);
        self.ws();
        self.spindle = None;
        let value = self.word_value(letter);
        self.push_item(
            ItemKind::Word(Word {
                letter,
                comma,
                spindle: self.spindle,
                value,
            }),
            start,
        );
    }

    fn in_m98_block(&self) -> bool {
        // The block's text mentions M98 (subprogram call): P is then a name.
        let b = Span::new(0, self.limit as u32);
        let line_start = self.text[..self.pos]
            .iter()
            .rposition(|c| *c == b'\n' || *c == b'\r')
            .map(|i| i + 1)
            .unwrap_or(0);
        let s = Span::new(line_start as u32, b.end).slice(self.text);
        let up: Vec<u8> = s.iter().map(|c| c.to_ascii_uppercase()).collect();
        up.windows(3)
            .enumerate()
            .any(|(i, w)| w == b"M98" && !up.get(i + 3).is_some_and(|d| d.is_ascii_digit()))
            || up.windows(4).any(|w| w == b"M098")
    }

    fn word_value(&mut self, letter: u8) -> WordValue {
        let start = self.pos;
        let Some(c) = self.peek() else {
            return self.missing(letter, start);
        };
        // ServoWorks: `M98 P<name>`: a name made of letters, digits and `_`.
        if self.dialect == Dialect::Servoworks
            && letter == b'P'
            && (c.is_ascii_alphabetic() || c == b'_' || (is_digit(c) && self.in_m98_block()))
        {
            let mut j = self.pos;
            while self
                .at(j)
                .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_')
            {
                j += 1;
            }
            self.pos = j;
            self.token(start, TokenKind::Name);
            return WordValue::Name(Span::new(start as u32, j as u32));
        }
        match c {
            b'0'..=b'9' | b'.' | b'+' | b'-' => {
                let signed_non_literal = matches!(c, b'+' | b'-') && {
                    let mut j = self.pos + 1;
                    while self.at(j).is_some_and(is_ws) {
                        j += 1;
                    }
                    !self.at(j).is_some_and(|d| is_digit(d) || d == b'.')
                };
                if signed_non_literal {
                    if self.dialect == Dialect::Rs274ngc
                        && !self.at(self.pos + 1).is_some_and(|d| {
                            d == b'#' || d == b'[' || d.is_ascii_alphabetic() || is_ws(d)
                        })
                    {
                        // `X-` followed by nothing usable.
                        return self.missing(letter, start);
                    }
                    return WordValue::Expr(self.value_expr());
                }
                let n = self.number(true);
                // ServoWorks multi-spindle `S2_1500`.
                if self.dialect == Dialect::Servoworks
                    && letter == b'S'
                    && self.peek() == Some(b'_')
                    && !n.has_point
                {
                    self.pos += 1;
                    let speed_start = self.pos;
                    let speed = self.number(false);
                    // The `_` is part of the number token run.
                    let _ = speed_start;
                    self.spindle = Some(n.value.clamp(0.0, f64::from(u16::MAX)) as u16);
                    return WordValue::Num(speed);
                }
                WordValue::Num(n)
            }
            b'#' | b'[' => WordValue::Expr(self.value_expr()),
            c if c.is_ascii_alphabetic() && self.dialect != Dialect::Servoworks => {
                // A function value (`X sin[30]`) — otherwise the letter has no value.
                let mut j = self.pos;
                while self.at(j).is_some_and(|c| c.is_ascii_alphabetic()) {
                    j += 1;
                }
                let name =
                    String::from_utf8_lossy(Span::new(start as u32, j as u32).slice(self.text))
                        .into_owned();
                if Func::from_name(&name).is_some_and(|f| f.in_dialect(self.dialect))
                    && self.next_non_ws(j) == Some(b'[')
                {
                    WordValue::Expr(self.value_expr())
                } else {
                    self.missing(letter, start)
                }
            }
            _ => self.missing(letter, start),
        }
    }

    fn next_non_ws(&self, mut j: usize) -> Option<u8> {
        while self.at(j).is_some_and(is_ws) {
            j += 1;
        }
        self.at(j)
    }

    fn missing(&mut self, letter: u8, at: usize) -> WordValue {
        self.diag(
            &codes::MISSING_VALUE,
            Severity::Error,
            Span::new(at.saturating_sub(1) as u32, at as u32),
            format!("address {} has no value", letter as char),
        );
        WordValue::Missing
    }

    /// FANUC `O1234` / `:1234`; the cursor is after `O`/`:`.
    fn program_number(&mut self, start: usize) {
        self.ws();
        let ns = self.pos;
        while self.peek().is_some_and(is_digit) {
            self.pos += 1;
        }
        let name = Span::new(ns as u32, self.pos as u32);
        let number = std::str::from_utf8(name.slice(self.text))
            .ok()
            .and_then(|s| s.parse::<u32>().ok());
        if self.pos > ns {
            self.token(ns, TokenKind::Name);
        } else {
            self.diag(
                &codes::MISSING_VALUE,
                Severity::Error,
                Span::new(start as u32, self.pos as u32),
                "program number missing after O",
            );
        }
        self.push_item(ItemKind::ProgramHead { name, number }, start);
    }

    /// FANUC 30i `<name>` program head.
    fn fanuc_name_head(&mut self) {
        let start = self.pos;
        let mut j = self.pos + 1;
        while self.at(j).is_some_and(|c| c != b'>') {
            j += 1;
        }
        if self.at(j) == Some(b'>') {
            self.pos = j + 1;
            self.token(start, TokenKind::Name);
            let name = Span::new(start as u32 + 1, j as u32);
            self.push_item(ItemKind::ProgramHead { name, number: None }, start);
        } else {
            self.unknown_run();
        }
    }

    /// ServoWorks `OMoveXY` / `O100`.
    fn sw_program_head(&mut self) {
        let start = self.pos;
        self.pos += 1;
        self.token(start, TokenKind::Letter);
        self.ws();
        let ns = self.pos;
        while self
            .peek()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_')
        {
            self.pos += 1;
        }
        let name = Span::new(ns as u32, self.pos as u32);
        if self.pos > ns {
            self.token(ns, TokenKind::Name);
        } else {
            self.diag(
                &codes::MISSING_VALUE,
                Severity::Error,
                Span::new(start as u32, self.pos as u32),
                "program name missing after O",
            );
        }
        let number = std::str::from_utf8(name.slice(self.text))
            .ok()
            .and_then(|s| s.parse::<u32>().ok());
        self.push_item(ItemKind::ProgramHead { name, number }, start);
    }

    /// RS274/NGC O-word statement; cursor on `o`.
    fn oword(&mut self) {
        let start = self.pos;
        self.token(start, TokenKind::Letter);
        self.pos += 1;
        self.ws();
        let ls = self.pos;
        let label = match self.peek() {
            Some(b'<') => {
                let mut j = self.pos + 1;
                while self.at(j).is_some_and(|c| c != b'>') {
                    j += 1;
                }
                if self.at(j) == Some(b'>') {
                    self.pos = j + 1;
                    self.token(ls, TokenKind::Name);
                    OLabel::Name
                } else {
                    self.pos = self.limit;
                    self.token(ls, TokenKind::Unknown);
                    self.diag(
                        &codes::BAD_EXPRESSION,
                        Severity::Error,
                        Span::new(ls as u32, self.pos as u32),
                        "o-word name is missing its closing `>`",
                    );
                    OLabel::Missing
                }
            }
            Some(c) if is_digit(c) => {
                let n = self.number(false);
                if n.value.is_finite() && n.value >= 0.0 && n.value <= u32::MAX as f64 {
                    OLabel::Number(n.value.round() as u32)
                } else {
                    OLabel::Missing
                }
            }
            Some(b'#') | Some(b'[') => OLabel::Expr(self.value_expr()),
            _ => {
                self.diag(
                    &codes::MISSING_VALUE,
                    Severity::Error,
                    Span::new(start as u32, self.pos as u32),
                    "o-word label missing after O",
                );
                OLabel::Missing
            }
        };
        let label_span = Span::new(ls as u32, self.pos as u32);
        self.ws();
        let ks = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_alphabetic()) {
            self.pos += 1;
        }
        let mut keyword = OKeyword::from_name(&String::from_utf8_lossy(&self.text[ks..self.pos]));
        // LinuxCNC drops blanks before it reads a line, so `else if`, `end sub` or
        // `end while` are the keywords `elseif`, `endsub`, `endwhile`.
        let mut joined: Vec<u8> = self.text[ks..self.pos].to_vec();
        let mut j = self.pos;
        while !joined.is_empty() {
            let mut k = j;
            while self.at(k).is_some_and(is_ws) {
                k += 1;
            }
            if k == j || !self.at(k).is_some_and(|c| c.is_ascii_alphabetic()) {
                break;
            }
            while let Some(c) = self.at(k).filter(|c| c.is_ascii_alphabetic()) {
                joined.push(c);
                k += 1;
            }
            j = k;
            if let Some(kw) = OKeyword::from_name(&String::from_utf8_lossy(&joined)) {
                keyword = Some(kw);
                self.pos = j;
            }
        }
        let kw_span = Span::new(ks as u32, self.pos as u32);
        if self.pos > ks {
            self.token(ks, TokenKind::Keyword);
        }
        // A bare `O100` (LinuxCNC 2.9: the head of an M98 subprogram or a title) has no
        // keyword; only an unknown word after the label is an error.
        let bare = kw_span.is_empty() && matches!(label, OLabel::Number(_) | OLabel::Name) && {
            let mut j = self.pos;
            while self.at(j).is_some_and(is_ws) {
                j += 1;
            }
            matches!(self.at(j), None | Some(b'(') | Some(b';'))
        };
        if keyword.is_none() && !bare {
            let msg = if kw_span.is_empty() {
                "o-word without a keyword (sub, endsub, call, do, while, if, repeat, …)".to_string()
            } else {
                format!(
                    "unknown o-word keyword `{}`",
                    String::from_utf8_lossy(kw_span.slice(self.text))
                )
            };
            self.diag(
                &codes::BAD_EXPRESSION,
                Severity::Error,
                if kw_span.is_empty() {
                    Span::new(start as u32, self.pos as u32)
                } else {
                    kw_span
                },
                msg,
            );
        }
        // Arguments: bracketed expressions (call args, conditions, return values).
        let args_start = self.p.expr_lists.len() as u32;
        let mut args = Vec::new();
        loop {
            self.ws();
            match self.peek() {
                Some(b'[') => args.push(self.group()),
                Some(b'#')
                    if keyword == Some(OKeyword::Call)
                        || keyword == Some(OKeyword::Return)
                        || keyword == Some(OKeyword::Endsub) =>
                {
                    args.push(self.value_expr())
                }
                Some(b'(') => self.comment(),
                Some(b';') => self.semicolon(),
                None => break,
                Some(c) if is_digit(c) || c == b'-' || c == b'+' || c == b'.' => {
                    // LinuxCNC accepts bare numbers as call arguments only inside brackets.
                    args.push(self.value_expr());
                    let id = *args.last().unwrap_or(&ExprId(0));
                    let span = self.p.expr(id).span;
                    self.diag(
                        &codes::BAD_EXPRESSION,
                        Severity::Error,
                        span,
                        "o-word arguments must be in brackets: `[value]`",
                    );
                }
                Some(_) => {
                    self.unknown_run();
                }
            }
        }
        // Hostile input aside, calls have a handful of arguments.
        args.truncate(usize::from(u16::MAX));
        let args_len = args.len() as u16;
        self.p.expr_lists.extend(args);
        let ow = OWord {
            label,
            label_span,
            keyword,
            args_start,
            args_len,
        };
        // The O-word item spans up to the end of its arguments.
        self.push_item(ItemKind::OWord(ow), start);
    }

    fn macro_stmt(&mut self, kw: &'static str) {
        let start = self.pos;
        let kw_len = kw.len();
        self.token(start, TokenKind::Keyword);
        self.pos += kw_len;
        self.ws();
        let stmt = match kw {
            "GOTO" => MacroStmt::Goto {
                target: self.value_expr(),
            },
            "IF" => {
                let cond = self.cond();
                self.ws();
                if self.eat_keyword(&["GOTO"]) {
                    self.ws();
                    MacroStmt::IfGoto {
                        cond,
                        target: self.value_expr(),
                    }
                } else if self.eat_keyword(&["THEN"]) {
                    MacroStmt::IfThen { cond }
                } else {
                    self.diag(
                        &codes::BAD_EXPRESSION,
                        Severity::Error,
                        Span::new(start as u32, self.pos as u32),
                        "IF [condition] must be followed by GOTO n or THEN statement",
                    );
                    MacroStmt::IfThen { cond }
                }
            }
            "WHILE" => {
                let cond = self.cond();
                self.ws();
                if self.eat_keyword(&["DO"]) {
                    self.ws();
                    MacroStmt::While {
                        cond,
                        m: self.value_expr(),
                    }
                } else {
                    self.diag(
                        &codes::BAD_EXPRESSION,
                        Severity::Error,
                        Span::new(start as u32, self.pos as u32),
                        "WHILE [condition] must be followed by DO m",
                    );
                    let m = self.push_expr(Expr::Error, self.pos);
                    MacroStmt::While { cond, m }
                }
            }
            "DO" => MacroStmt::Do {
                m: self.value_expr(),
            },
            "END" => MacroStmt::End {
                m: self.value_expr(),
            },
            _ => {
                if self.peek() == Some(b'[') {
                    self.output_text();
                }
                MacroStmt::Output
            }
        };
        self.push_item(ItemKind::Macro(stmt), start);
    }

    /// The bracketed argument of `DPRNT`/`BPRNT`: characters sent out as written, with
    /// `#n[ab]` formats inside, so it is text, not an expression. The `]` that closes it
    /// is the one at depth zero; an unclosed one runs to the end of the block.
    fn output_text(&mut self) {
        let open = self.pos;
        self.token(open, TokenKind::LBracket);
        self.pos += 1;
        let text = self.pos;
        let mut depth = 0usize;
        while self.pos < self.limit {
            match self.text[self.pos] {
                b'[' => depth += 1,
                b']' if depth == 0 => break,
                b']' => depth -= 1,
                b'\n' | b'\r' => break,
                _ => {}
            }
            self.pos += 1;
        }
        if self.pos > text {
            self.token(text, TokenKind::Text);
        }
        if self.peek() == Some(b']') {
            let s = self.pos;
            self.token(s, TokenKind::RBracket);
            self.pos += 1;
        } else {
            self.diag(
                &codes::UNBALANCED_BRACKET,
                Severity::Error,
                Span::new(open as u32, open as u32 + 1),
                "unclosed output text: this `[` has no matching `]`",
            );
        }
    }

    /// Consumes the run of letters at the cursor when it is one of `words` (any case),
    /// as a keyword token; otherwise leaves the cursor where it is.
    fn eat_keyword(&mut self, words: &[&str]) -> bool {
        let ks = self.pos;
        let mut j = self.pos;
        while self.at(j).is_some_and(|c| c.is_ascii_alphabetic()) {
            j += 1;
        }
        let run = Span::new(ks as u32, j as u32).slice(self.text);
        if !words.iter().any(|w| run.eq_ignore_ascii_case(w.as_bytes())) {
            return false;
        }
        self.pos = j;
        self.token(ks, TokenKind::Keyword);
        true
    }

    fn cond(&mut self) -> ExprId {
        if self.peek() == Some(b'[') {
            self.group()
        } else {
            let s = self.pos;
            self.diag(
                &codes::BAD_EXPRESSION,
                Severity::Error,
                Span::new(s as u32, s as u32),
                "condition must be in brackets: [ … ]",
            );
            self.push_expr(Expr::Error, s)
        }
    }
}

/// Recognises Custom Macro B keywords at the start of a letter run.
fn macro_keyword(run: &[u8]) -> Option<&'static str> {
    for kw in [
        "GOTO", "WHILE", "IF", "DO", "END", "POPEN", "PCLOS", "DPRNT", "BPRNT",
    ] {
        if run.starts_with(kw.as_bytes()) {
            // `IF` must be followed by `[` (I and F are also addresses); the caller's run
            // stops at non-letters, so `IF[` gives run "IF", while `IF10.` gives run "IF".
            let exact = run.len() == kw.len();
            let ok = match kw {
                "IF" | "DO" | "END" | "GOTO" | "WHILE" => exact,
                _ => true,
            };
            if ok {
                return Some(kw);
            }
        }
    }
    None
}

fn comment_kind(text: &[u8]) -> CommentKind {
    let body = text
        .strip_prefix(b"(")
        .or_else(|| text.strip_prefix(b";"))
        .unwrap_or(text);
    let body: Vec<u8> = body
        .iter()
        .skip_while(|c| is_ws(**c))
        .map(|c| c.to_ascii_lowercase())
        .collect();
    let starts = |p: &[u8]| body.starts_with(p);
    if starts(b"msg,") {
        CommentKind::Msg
    } else if starts(b"debug,") {
        CommentKind::Debug
    } else if starts(b"print,") {
        CommentKind::Print
    } else if starts(b"logopen,") {
        CommentKind::LogOpen
    } else if starts(b"logappend,") {
        CommentKind::LogAppend
    } else if starts(b"logclose") {
        CommentKind::LogClose
    } else if starts(b"log,") {
        CommentKind::Log
    } else if starts(b"abort,") {
        CommentKind::Abort
    } else if starts(b"probeopen") {
        CommentKind::ProbeOpen
    } else if starts(b"probeclose") {
        CommentKind::ProbeClose
    } else if starts(b"py,") || starts(b"pyrun,") || starts(b"pyreload") {
        CommentKind::Py
    } else if starts(b"partscope:") || starts(b"partscope ") {
        CommentKind::Partscope
    } else {
        CommentKind::Plain
    }
}

fn printable(s: &str) -> String {
    let mut out: String = s
        .chars()
        .take(20)
        .map(|c| if c.is_control() { '\u{FFFD}' } else { c })
        .collect();
    if s.chars().count() > 20 {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{decimal, digit_run, leading_digits, parse, ParseOptions};
    use crate::dialect::Dialect;
    use crate::syntax::{ItemKind, WordValue};

    /// The value the parser reads for the number `s` after an X, on a plain line
    /// (`general` false) or on one the general path reads (a comment follows).
    fn read_value(s: &str, general: bool) -> Option<u64> {
        let text = if general {
            format!("X{s} (c)\n")
        } else {
            format!("X{s}\n")
        };
        let program = parse(ParseOptions::new(Dialect::Rs274ngc), text.into_bytes());
        match program.items.first().map(|i| i.kind) {
            Some(ItemKind::Word(w)) => match w.value {
                WordValue::Num(n) if n.value.is_finite() => Some(n.value.to_bits()),
                _ => None,
            },
            _ => None,
        }
    }

    /// One step of the fixed-seed generator the tests below draw from.
    fn lcg(x: &mut u64) -> u64 {
        *x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *x
    }

    /// `count` deterministic texts of 1 to 16 (`long`: 32) bytes for the number
    /// readers: mostly digits, so that long runs occur, and one byte in `every` from
    /// `others`.
    fn digit_texts(
        seed: u64,
        count: usize,
        long: bool,
        others: &[u8],
        every: usize,
    ) -> Vec<Vec<u8>> {
        let mut x = seed;
        (0..count)
            .map(|_| {
                let x = lcg(&mut x);
                let len = (x >> if long { 59 } else { 60 }) as usize + 1;
                (0..len)
                    .map(|k| {
                        let r = (x >> (k * 3 % 48)) as usize;
                        if r.is_multiple_of(every) {
                            others[(r / every) % others.len()]
                        } else {
                            b'0' + (r % 10) as u8
                        }
                    })
                    .collect()
            })
            .collect()
    }

    /// The eight-byte digit reader against a byte-by-byte reading, on every mix of
    /// digits and the bytes next to them in ASCII, at every offset and length.
    #[test]
    fn digit_runs_read_as_byte_by_byte() {
        for text in digit_texts(99, 20000, true, b"/:. X\n\0\xff", 5) {
            for start in 0..=text.len() {
                let n = text[start..]
                    .iter()
                    .take_while(|c| c.is_ascii_digit())
                    .count();
                let want = text[start..start + n].iter().fold(0u64, |v, d| {
                    v.wrapping_mul(10).wrapping_add(u64::from(d - b'0'))
                });
                assert_eq!(
                    digit_run(&text, start),
                    (want, n, start + n),
                    "{text:?} at {start}"
                );
            }
        }
    }

    /// The one-load decimal reader against two digit runs around the point.
    #[test]
    fn decimals_read_as_digit_runs() {
        for text in digit_texts(7, 50000, false, b"..-X \n", 4) {
            for start in 0..=text.len() {
                let (int, n, end) = digit_run(&text, start);
                let want = if text.get(end) == Some(&b'.') {
                    let (frac, f, end) = digit_run(&text, end + 1);
                    let scale = 10u64.checked_pow(f as u32).unwrap_or(0);
                    (
                        int.wrapping_mul(scale).wrapping_add(frac),
                        n + f,
                        f,
                        true,
                        end,
                    )
                } else {
                    (int, n, 0, false, end)
                };
                let got = decimal(&text, start);
                if want.1 <= 15 {
                    assert_eq!(got, want, "{:?} at {start}", String::from_utf8_lossy(&text));
                } else {
                    assert_eq!(
                        (got.1, got.2, got.3, got.4),
                        (want.1, want.2, want.3, want.4)
                    );
                }
            }
        }
    }

    /// The digit mask stops at the first byte of any value that is not a digit.
    #[test]
    fn leading_digit_counts() {
        for b in 0..=255u8 {
            let word = u64::from_le_bytes([b'1', b'2', b, b'3', b'4', b'5', b'6', b'7']);
            let want = if b.is_ascii_digit() { 8 } else { 2 };
            assert_eq!(leading_digits(word), want, "byte {b}");
        }
    }

    /// Both paths through the one number reader give the correctly rounded value
    /// that `str::parse` gives, whether the number has 15 digits or more.
    #[test]
    fn numbers_read_as_std_reads_them() {
        let samples = [
            "0",
            "-0",
            "1",
            "+1",
            ".5",
            "5.",
            "-.5",
            "0.1",
            "0.3",
            "123.456",
            "-99999.999",
            "0.0001",
            "1234567890.12345",
            "123456789012345",
            "1234567890123456",
            "12345678901234567890",
            "0.000000000000001",
            "3.14159265358979",
        ];
        for s in samples {
            for general in [false, true] {
                assert_eq!(
                    read_value(s, general),
                    s.parse::<f64>().ok().map(f64::to_bits),
                    "{s}, general path {general}"
                );
            }
        }
        // A deterministic sweep of short decimals.
        let mut x: u64 = 12345;
        for _ in 0..20000 {
            let x = lcg(&mut x);
            let int = (x >> 40) % 100000;
            let frac = (x >> 10) % 10000;
            let s = format!("{int}.{frac:04}");
            let want = s.parse::<f64>().ok().map(f64::to_bits);
            assert_eq!(read_value(&s, false), want, "{s}");
            assert_eq!(read_value(&s, true), want, "{s}");
        }
    }
}
