//! What a rule sees: the program, the block, the analysis settings and the
//! G/M codes of the block already looked up in the dialect table.

use crate::dialect::{self, CodeInfo, CodeNum};
use crate::settings::Settings;
use crate::span::Span;
use crate::syntax::{Block, ItemKind, Program, WordValue};

/// A G or M word of a block with a literal value, looked up in the dialect table.
#[derive(Debug, Clone, Copy)]
pub struct BlockCode {
    /// Index of the item within the block's items.
    pub item: usize,
    /// `'G'` or `'M'`.
    pub letter: char,
    /// `None` when the value is not a valid code number (negative, too many decimals).
    pub num: Option<CodeNum>,
    /// The table entry, when the dialect knows the code.
    pub info: Option<&'static CodeInfo>,
    /// The whole word.
    pub span: Span,
}

impl BlockCode {
    pub fn is(&self, letter: char, tenths: u32) -> bool {
        self.letter == letter && self.num == Some(CodeNum(tenths))
    }

    pub fn group(&self) -> Option<u8> {
        self.info.and_then(|i| i.group)
    }
}

pub struct BlockCx<'a> {
    pub program: &'a Program,
    pub block: &'a Block,
    /// Index of the block in `program.blocks`.
    pub index: usize,
    pub settings: &'a Settings,
    pub codes: &'a [BlockCode],
    /// What the block holds ([`block_words`]).
    pub contents: BlockWords,
    /// What is known of the whole file when `program` is one window of it.
    pub file: Option<&'a crate::stream::FileFacts>,
}

impl<'a> BlockCx<'a> {
    /// The context of block `index`, its codes collected into `codes`.
    pub fn new(
        program: &'a Program,
        index: usize,
        settings: &'a Settings,
        codes: &'a mut Vec<BlockCode>,
    ) -> Option<BlockCx<'a>> {
        let block = program.blocks.get(index)?;
        codes.clear();
        collect_codes(program, block, codes);
        Some(BlockCx {
            program,
            block,
            index,
            settings,
            codes,
            contents: block_words(program, block),
            file: None,
        })
    }

    /// Whether the block has a word of `letter` without a comma: one bit test.
    pub fn has_letter(&self, letter: u8) -> bool {
        self.contents.letters & (1u128 << (letter & 127)) != 0
    }

    pub fn items(&self) -> &'a [crate::syntax::Item] {
        self.program.items_of(self.block)
    }

    pub fn has_code(&self, letter: char, tenths: u32) -> bool {
        self.codes.iter().any(|c| c.is(letter, tenths))
    }

    /// The words of this block.
    pub fn words(
        &self,
    ) -> impl Iterator<Item = (&'a crate::syntax::Item, &'a crate::syntax::Word)> + 'a {
        self.program.words(self.block)
    }

    pub fn word(&self, letter: u8) -> Option<&'a crate::syntax::Word> {
        if !self.has_letter(letter) {
            return None;
        }
        self.words()
            .find(|(_, w)| w.letter == letter && !w.comma)
            .map(|(_, w)| w)
    }
}

pub struct ProgramCx<'a> {
    pub program: &'a Program,
    pub settings: &'a Settings,
    /// Which blocks are plain ([`super::util::is_plain`]), when the host
    /// keeps that per block (an incremental update re-derives it only for
    /// the blocks it re-parsed); computed on first use otherwise.
    pub plain: Option<&'a [bool]>,
    /// How many blocks of the file each block stands for, when the program is
    /// a stand-in for a larger file (`crate::stream::Skeleton`: a run of plain
    /// blocks kept as its first). `None`: each block is itself.
    pub stands_for: Option<&'a [u32]>,
    /// What is known of the whole file when the program is one window of it
    /// (`crate::stream`); `None` for a whole file.
    pub file: Option<&'a crate::stream::FileFacts>,
    segments: std::sync::OnceLock<Vec<Seg>>,
}

/// A stretch of blocks as the whole-file rules walk it: one block that is
/// not plain, or a maximal run of plain blocks (`len` ≥ 1), which every
/// whole-file rule treats like its first block, so one visit stands for all.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Seg {
    pub first: usize,
    pub len: usize,
    pub plain: bool,
}

impl Seg {
    /// The last block of the stretch.
    pub fn last(&self) -> usize {
        self.first + self.len - 1
    }
}

impl<'a> ProgramCx<'a> {
    pub fn new(program: &'a Program, settings: &'a Settings) -> ProgramCx<'a> {
        ProgramCx {
            program,
            settings,
            plain: None,
            stands_for: None,
            file: None,
            segments: std::sync::OnceLock::new(),
        }
    }

    /// A context whose plain-block flags are already known (one per block).
    pub fn with_plain(
        program: &'a Program,
        settings: &'a Settings,
        plain: &'a [bool],
    ) -> ProgramCx<'a> {
        ProgramCx {
            plain: (plain.len() == program.blocks.len()).then_some(plain),
            ..ProgramCx::new(program, settings)
        }
    }

    /// How many blocks of the file a stretch holds.
    pub fn blocks_in(&self, seg: &Seg) -> usize {
        match self
            .stands_for
            .and_then(|w| w.get(seg.first..seg.first + seg.len))
        {
            Some(w) => w.iter().map(|&n| n as usize).sum(),
            None => seg.len,
        }
    }

    /// The blocks that are not plain, in order: all a rule that ignores
    /// plain blocks needs to visit.
    pub fn non_plain_blocks(&self) -> impl Iterator<Item = &'a Block> + '_ {
        let blocks = &self.program.blocks;
        self.segments()
            .iter()
            .filter(|s| !s.plain)
            .filter_map(move |s| blocks.get(s.first))
    }

    /// The program's blocks as stretches, in order; computed once per context.
    pub fn segments(&self) -> &[Seg] {
        self.segments.get_or_init(|| match self.plain {
            Some(flags) => segments_of(flags.iter().copied()),
            None => segments_of(
                self.program
                    .blocks
                    .iter()
                    .map(|b| super::util::is_plain(self.program, b)),
            ),
        })
    }
}

/// Groups per-block plain flags into stretches.
pub fn segments_of(flags: impl Iterator<Item = bool>) -> Vec<Seg> {
    let mut out: Vec<Seg> = Vec::new();
    for (i, plain) in flags.enumerate() {
        match out.last_mut() {
            Some(s) if plain && s.plain => s.len += 1,
            _ => out.push(Seg {
                first: i,
                len: 1,
                plain,
            }),
        }
    }
    out
}

/// Collects the literal G and M codes of a block.
pub fn collect_codes(program: &Program, block: &Block, out: &mut Vec<BlockCode>) {
    for (i, item) in program.items_of(block).iter().enumerate() {
        let ItemKind::Word(w) = &item.kind else {
            continue;
        };
        if w.comma || !(w.letter == b'G' || w.letter == b'M') {
            continue;
        }
        let letter = w.letter as char;
        let num = match &w.value {
            WordValue::Num(n) if !n.signed || n.value >= 0.0 => CodeNum::from_value(n.value),
            _ => None,
        };
        let info = num.and_then(|n| dialect::lookup(program.dialect, letter, n));
        out.push(BlockCode {
            item: i,
            letter,
            num,
            info,
            span: item.span,
        });
    }
}

/// The letters of an axis/feed block: axes, arc centre and radius, feed.
const AXIS_FEED_LETTERS: &[u8] = b"XYZABCUVWIJKRF";

/// The set of ASCII letters in `s`, one bit `1 << letter` per byte value.
pub const fn letter_set(s: &[u8]) -> u128 {
    let mut m = 0u128;
    let mut i = 0;
    while i < s.len() {
        m |= 1u128 << (s[i] & 127);
        i += 1;
    }
    m
}

/// What is in a block, from one pass over its items: the dispatcher matches each
/// rule's [`Interest`] against it, so a rule is called only on blocks that hold
/// something it may report on. Letters are bits `1 << letter`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BlockWords {
    /// The letters of the block's words written without a comma, whatever their value.
    pub letters: u128,
    /// The letters that appear in more than one word without a comma.
    pub repeated: u128,
    /// The letters with a negative literal value (NaN counts as negative: a check
    /// `v >= 0` rejects it).
    pub negative: u128,
    /// The most digits of any literal value.
    pub max_digits: u16,
    /// The block holds more than words with literal values: a word with another
    /// value (expression, name, none), a comma word, a comment, an assignment, a
    /// statement, an O-word, a program head or an error; or it has a block-skip
    /// mark, or no items at all.
    pub other: bool,
}

/// The [`BlockWords`] of a block.
pub fn block_words(program: &Program, block: &Block) -> BlockWords {
    let items = program.items_of(block);
    let mut s = BlockWords {
        other: items.is_empty() || block.skip().is_some(),
        ..BlockWords::default()
    };
    for it in items {
        let ItemKind::Word(w) = &it.kind else {
            s.other = true;
            continue;
        };
        if w.comma {
            s.other = true;
            continue;
        }
        let bit = 1u128 << (w.letter & 127);
        s.repeated |= s.letters & bit;
        s.letters |= bit;
        match &w.value {
            WordValue::Num(n) => {
                if n.value < 0.0 || n.value.is_nan() {
                    s.negative |= bit;
                }
                s.max_digits = s.max_digits.max(n.digits);
            }
            _ => s.other = true,
        }
    }
    s
}

/// What a block must hold for a rule's `check_block` to report anything on it
/// ([`super::Rule::interest`]): the block is of interest when any one field
/// matches its [`BlockWords`]. A rule may only leave out what it can never
/// report on; `rules::tests` checks every claim on random blocks of all kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Interest {
    /// A word without a comma of one of these letters.
    pub letters: u128,
    /// One of these letters repeated.
    pub repeated: u128,
    /// A negative literal of one of these letters.
    pub negative: u128,
    /// A literal with more digits than this.
    pub digits_over: u16,
    /// Anything but words with literal values ([`BlockWords::other`]).
    pub other: bool,
}

impl Interest {
    /// Every block: the safe answer.
    pub const ALL: Interest = Interest {
        letters: !0,
        repeated: !0,
        negative: !0,
        digits_over: 0,
        other: true,
    };

    /// No block: a whole-file rule without a block check.
    pub const NONE: Interest = Interest {
        letters: 0,
        repeated: 0,
        negative: 0,
        digits_over: u16::MAX,
        other: false,
    };

    /// Blocks with anything but literal words ([`BlockWords::other`]).
    pub const OTHER: Interest = Interest {
        other: true,
        ..Interest::NONE
    };

    /// Blocks with two or more words without a comma of one of `letters`.
    pub const fn repeated(letters: &[u8]) -> Interest {
        Interest {
            repeated: letter_set(letters),
            ..Interest::NONE
        }
    }

    /// Blocks with a word without a comma of one of `letters`.
    pub const fn letters(letters: &[u8]) -> Interest {
        Interest {
            letters: letter_set(letters),
            ..Interest::NONE
        }
    }

    /// Blocks with a word whose letter is not an axis, arc centre, radius or
    /// feed letter, or anything but literal words: the interest of a rule that
    /// needs a G or M code, another address, an expression or a comment.
    pub const NOT_AXIS_FEED: Interest = Interest {
        letters: !letter_set(AXIS_FEED_LETTERS),
        ..Interest::OTHER
    };

    /// Whether a block with these contents is of interest.
    pub fn matches(&self, w: &BlockWords) -> bool {
        w.letters & self.letters != 0
            || (self.other && w.other)
            || w.repeated & self.repeated != 0
            || w.negative & self.negative != 0
            || w.max_digits > self.digits_over
    }
}
