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
}

impl<'a> BlockCx<'a> {
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

/// [`AXIS_FEED_LETTERS`] as bits `1 << letter`.
const AXIS_FEED_MASK: u128 = {
    let mut m = 0u128;
    let mut i = 0;
    while i < AXIS_FEED_LETTERS.len() {
        m |= 1u128 << AXIS_FEED_LETTERS[i];
        i += 1;
    }
    m
};

/// What the block rules that do run on an axis/feed block need to know to tell,
/// without walking the words again, that they have nothing to report
/// ([`super::Rule::silent_on_axis_feed`]). Letters are bits `1 << letter`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct AxisFeedWords {
    /// The letters of the block's words.
    pub letters: u128,
    /// Some letter appears more than once.
    pub repeated: bool,
    /// The letters with a negative value.
    pub negative: u128,
    /// The most digits of any number of the block.
    pub max_digits: u16,
}

/// [`is_axis_feed_block`] and, for such a block, its [`AxisFeedWords`], in one
/// pass over the items.
pub fn axis_feed_words(program: &Program, block: &Block) -> Option<AxisFeedWords> {
    let items = program.items_of(block);
    if items.is_empty() || block.skip().is_some() {
        return None;
    }
    let mut s = AxisFeedWords::default();
    for it in items {
        let ItemKind::Word(w) = &it.kind else {
            return None;
        };
        let WordValue::Num(n) = &w.value else {
            return None;
        };
        let bit = 1u128 << (w.letter & 127);
        if w.comma || w.letter >= 128 || AXIS_FEED_MASK & bit == 0 {
            return None;
        }
        s.repeated |= s.letters & bit != 0;
        s.letters |= bit;
        // NaN counts as negative: a check `v >= 0` rejects it.
        if n.value < 0.0 || n.value.is_nan() {
            s.negative |= bit;
        }
        s.max_digits = s.max_digits.max(n.digits);
    }
    Some(s)
}

/// Whether every item of the block is a plain axis/feed word with a literal value
/// (`X1.5 Z-0.2`, `I3 J0 F200`): no G or M code, no expression, comment, statement
/// or other letter. Such blocks make up most of a CAM program, and the block rules
/// that answer `false` to [`super::Rule::reports_on_axis_feed_blocks`] skip them.
/// A block-skip `/` or an empty block does not count.
pub fn is_axis_feed_block(program: &Program, block: &Block) -> bool {
    let items = program.items_of(block);
    !items.is_empty()
        && block.skip().is_none()
        && items.iter().all(|it| match &it.kind {
            ItemKind::Word(w) => {
                !w.comma
                    && matches!(w.value, WordValue::Num(_))
                    && AXIS_FEED_LETTERS.contains(&w.letter)
            }
            _ => false,
        })
}
