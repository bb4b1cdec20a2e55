//! Checking a file too large to hold: windows and a skeleton.
//!
//! A host reads the file in windows of whole lines and parses each with
//! [`crate::syntax::parse_window`], which gives the tree the file's spans and
//! lines. Block rules need nothing beyond their block, so each window is
//! linted on its own ([`WindowChecks`]). The whole-file rules run over a
//! [`Skeleton`]: a stand-in program holding every block that is not plain and
//! the first block of each run of plain blocks, which is all they read (they
//! treat a run of plain blocks like its first block,
//! [`crate::rules::ProgramCx::segments`]). Their findings are moved back to the
//! file's offsets, and what only the whole file knows (its suppression
//! comments, the text the control never reads) goes to every window's
//! [`crate::finish_window`] as [`FileFacts`].
//!
//! A host makes two passes: the first feeds every window to the skeleton, the
//! second lints the windows (and runs them) knowing the file's facts.

use crate::diagnostic::Diagnostic;
use crate::rules::{self, util, BlockRules, ProgramCx};
use crate::settings::{Settings, Suppressions};
use crate::span::Span;
use crate::syntax::{self, Program};
use crate::Dialect;

/// What a window's findings need to know about the whole file.
#[derive(Debug, Default)]
pub struct FileFacts {
    pub suppressions: Suppressions,
    /// RS274/NGC: text LinuxCNC never reads (after a top-level M2/M30), as
    /// sorted disjoint ranges of the blocks' offsets.
    dead: Vec<Span>,
    /// FANUC: text an unconditional GOTO, M99 or M30 jumps over.
    jumped: Vec<Span>,
    /// The file has a G70-G72 lathe cycle (its U and W words are relative X and Z).
    pub(crate) lathe_cycle: bool,
    dialect: Option<Dialect>,
}

fn within(ranges: &[Span], at: u32) -> bool {
    let i = ranges.partition_point(|r| r.start <= at);
    i > 0 && ranges.get(i - 1).is_some_and(|r| at < r.end)
}

impl FileFacts {
    /// Whether the control never reads the text at `at` (what [`crate::finish`]
    /// works out from the whole program).
    pub fn never_read(&self, at: u32) -> bool {
        match self.dialect {
            Some(Dialect::Rs274ngc) => within(&self.dead, at),
            Some(Dialect::Fanuc) => within(&self.jumped, at),
            _ => false,
        }
    }

    /// Whether the block rules pass over the block starting at `at`
    /// (as [`rules::skipped_blocks`] does for a whole program).
    pub fn dead_block(&self, at: u32) -> bool {
        within(&self.dead, at)
    }
}

/// The blocks a run of the skeleton stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Run {
    /// [`util::is_plain`].
    Plain,
    /// [`util::is_numbered_plain`].
    Numbered,
}

/// One block of the skeleton, or a run of plain blocks kept as its first.
#[derive(Debug, Clone, Copy)]
struct Piece {
    /// Offset of the kept bytes in the skeleton's text and in the file.
    skel: u32,
    file: u32,
    /// 0-based line of the block in the file.
    line: u32,
    /// Length of the first block's content (its span).
    content: u32,
    /// Blocks of the file the piece stands for (1, or the run's length).
    blocks: u32,
    /// The last block of the run: where its content and terminator end.
    run_content_end: u32,
    run_term_end: u32,
}

impl Piece {
    /// The piece of block `b` alone, its bytes at `skel` in the skeleton's text.
    fn of(b: &crate::syntax::Block, skel: u32) -> Piece {
        Piece {
            skel,
            file: b.span.start,
            line: b.line,
            content: b.span.len(),
            blocks: 1,
            run_content_end: b.span.end,
            run_term_end: b.term_end.max(b.span.end),
        }
    }
}

/// The stand-in program the whole-file rules run over (see the module doc).
#[derive(Debug, Default)]
pub struct Skeleton {
    text: Vec<u8>,
    pieces: Vec<Piece>,
    /// The kind of run the last block added belongs to: a block of the same
    /// kind next continues it.
    run: Option<Run>,
    /// Runs of numbered plain blocks are kept as their first too
    /// ([`Skeleton::numbered`]).
    numbered: bool,
    /// A block that branches to a sequence number was added.
    branches: bool,
    /// File offset just past the last window added.
    end: u32,
    /// The latest block of the current run of plain blocks, after its first:
    /// its bytes and piece, and the ends of the block before it. The file's
    /// last block is kept too (rules report there), so a run at the end of
    /// the file ends with it.
    run_tail: Option<(Vec<u8>, Piece, (u32, u32))>,
    lathe_cycle: bool,
}

impl Skeleton {
    /// A skeleton that also keeps a run of numbered plain blocks (`N120 G1
    /// X1.5`) as its first, so that Fusion-style output, numbered on every
    /// line, makes a small skeleton too. Only the sequence-number rule reads
    /// those numbers when nothing branches: with this skeleton the host runs
    /// that rule over the windows ([`WindowChecks`]), and must start again
    /// with [`Skeleton::default`] when [`Skeleton::branches`] says a block
    /// branches to a number.
    pub fn numbered() -> Skeleton {
        Skeleton {
            numbered: true,
            ..Skeleton::default()
        }
    }

    /// [`Skeleton::numbered`] unless the settings enable a rule that reads
    /// every line number (the style rules on line numbers).
    pub fn for_settings(settings: &Settings) -> Skeleton {
        use rules::style_line_numbers::{LINE_NUMBERS, LINE_NUMBER_ORDER};
        if settings.rule_enabled(&LINE_NUMBERS) || settings.rule_enabled(&LINE_NUMBER_ORDER) {
            Skeleton::default()
        } else {
            Skeleton::numbered()
        }
    }

    /// Whether a block added branches to a sequence number (`GOTO`, `M99 P`, `M97 P`).
    pub fn branches(&self) -> bool {
        self.branches
    }

    /// Whether runs of numbered plain blocks are kept as their first.
    pub fn is_numbered(&self) -> bool {
        self.numbered
    }

    /// Adds the next window of the file (in file order).
    pub fn add(&mut self, window: &Program) {
        self.lathe_cycle |= rules::unknown_address::has_lathe_cycle(window);
        let blocks = &window.blocks;
        for (i, b) in blocks.iter().enumerate() {
            let kind = if util::is_plain(window, b) {
                Some(Run::Plain)
            } else if self.numbered && util::is_numbered_plain(window, b) {
                Some(Run::Numbered)
            } else {
                self.branches |= branches_in(window, b);
                None
            };
            let to = blocks
                .get(i + 1)
                .map_or(window.end_offset(), |n| n.span.start);
            if kind.is_some() && kind == self.run {
                if let Some(p) = self.pieces.last_mut() {
                    let before = (p.run_content_end, p.run_term_end);
                    p.blocks += 1;
                    p.run_content_end = b.span.end;
                    p.run_term_end = b.term_end.max(b.span.end);
                    let tail = Piece::of(b, 0);
                    let bytes = window.slice(Span::new(b.span.start, to)).to_vec();
                    self.run_tail = Some((bytes, tail, before));
                    continue;
                }
            }
            self.run = kind;
            self.run_tail = None;
            // The bytes up to the next block, so that nothing between blocks is lost.
            let from = if self.pieces.is_empty() {
                window.base
            } else {
                b.span.start
            };
            let bytes = window.slice(Span::new(from, to));
            self.pieces
                .push(Piece::of(b, self.text.len() as u32 + (b.span.start - from)));
            self.text.extend_from_slice(bytes);
        }
        self.end = window.end_offset();
    }

    /// The text and pieces with the file's last block kept on its own.
    fn sealed(&self) -> (Vec<u8>, Vec<Piece>) {
        let (mut text, mut pieces) = (self.text.clone(), self.pieces.clone());
        if let (Some((bytes, tail, before)), Some(run)) = (&self.run_tail, pieces.last_mut()) {
            run.blocks -= 1;
            (run.run_content_end, run.run_term_end) = *before;
            pieces.push(Piece {
                skel: text.len() as u32,
                ..*tail
            });
            text.extend_from_slice(bytes);
        }
        (text, pieces)
    }

    /// Bytes the skeleton holds (its memory is about ten times this).
    pub fn len(&self) -> usize {
        self.text.len()
    }

    pub fn is_empty(&self) -> bool {
        self.text.is_empty()
    }

    /// The skeleton as a program, its blocks on their lines in the file,
    /// which the whole-file rules run over ([`Sealed::check`]).
    pub fn seal(&self, settings: &Settings) -> Sealed {
        let (text, pieces) = self.sealed();
        let mut program = syntax::parse_lean(settings.parse_options(), text);
        let aligned = aligned(&program, &pieces);
        if aligned {
            for (b, p) in program.blocks.iter_mut().zip(&pieces) {
                b.line = p.line;
            }
        }
        // The window parses reported the syntax errors already.
        program.diagnostics.clear();
        Sealed {
            program,
            pieces,
            aligned,
            end: self.end,
            numbered: self.numbered,
            lathe_cycle: self.lathe_cycle,
        }
    }
}

/// A [`Skeleton`] read as a program.
pub struct Sealed {
    program: Program,
    pieces: Vec<Piece>,
    /// The program's blocks are the kept blocks, one for one (the skeleton's
    /// text re-reads as them), so block-level facts map back to the file.
    aligned: bool,
    end: u32,
    numbered: bool,
    lathe_cycle: bool,
}

impl Sealed {
    /// The stand-in program (a whole-file view of the file's flow: its
    /// subprogram definitions, ends and program heads are all there).
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// File offset just past the file's last byte.
    pub fn end(&self) -> u32 {
        self.end
    }

    /// Runs the whole-file rules: their findings, through [`crate::finish`]
    /// and at the file's offsets, and the facts every window's findings need.
    pub fn check(&self, settings: &Settings) -> (Vec<Diagnostic>, FileFacts) {
        let (program, pieces) = (&self.program, &self.pieces);
        let map = Map {
            pieces,
            len: program.text.len(),
            end: self.end,
        };
        let stands_for: Vec<u32> = pieces.iter().map(|p| p.blocks).collect();
        let mut enabled = rules::enabled_rules(settings);
        // Numbered runs keep only their first number: the windows walk them all.
        if self.numbered {
            enabled.retain(|r| r.meta().code != rules::sequence_number::SEQUENCE_NUMBER.code);
        }
        let mut found = Vec::new();
        {
            let mut cx = ProgramCx::new(program, settings);
            if self.aligned {
                cx.stands_for = Some(&stands_for);
            }
            rules::check_whole_program(&cx, &enabled, &mut found);
        }
        let mut found = crate::finish(program, settings, found);
        for d in &mut found {
            map.diagnostic_to_file(d);
        }
        let mut facts = FileFacts {
            suppressions: Suppressions::collect(program),
            dialect: Some(settings.dialect),
            lathe_cycle: self.lathe_cycle,
            ..FileFacts::default()
        };
        facts.suppressions.map_spans(|s| {
            let start = map.to_file(s.start);
            // A block's range ends where the next kept block starts, or never.
            let end = if s.end == u32::MAX {
                u32::MAX
            } else {
                map.to_file(s.end)
            };
            Span::new(start, end.max(start))
        });
        let ranges = |flags: Vec<bool>| -> Vec<Span> {
            let mut out: Vec<Span> = Vec::new();
            for (p, _) in pieces.iter().zip(flags).filter(|(_, f)| *f) {
                let r = Span::new(p.file, p.run_term_end.max(p.file + 1));
                match out.last_mut() {
                    Some(last) if last.end >= r.start => last.end = last.end.max(r.end),
                    _ => out.push(r),
                }
            }
            out
        };
        if self.aligned {
            facts.dead = ranges(util::dead_blocks(program));
            if settings.dialect == Dialect::Fanuc {
                facts.jumped = ranges(util::jumped_over_blocks(program));
            }
        }
        (found, facts)
    }
}

/// Whether `program`'s blocks are the kept blocks, one for one (the
/// skeleton's text re-reads as them).
fn aligned(program: &Program, pieces: &[Piece]) -> bool {
    program.blocks.len() == pieces.len()
        && program
            .blocks
            .iter()
            .zip(pieces)
            .all(|(b, p)| b.span.start == p.skel)
}

/// Moves the skeleton's offsets to the file's.
struct Map<'a> {
    pieces: &'a [Piece],
    /// Length of the skeleton's text, and of the file.
    len: usize,
    end: u32,
}

impl Map<'_> {
    /// A file offset for an offset of the skeleton's text.
    fn to_file(&self, at: u32) -> u32 {
        if at as usize >= self.len {
            return self.end;
        }
        let i = self.pieces.partition_point(|p| p.skel <= at);
        let Some(p) = i.checked_sub(1).and_then(|i| self.pieces.get(i)) else {
            return at;
        };
        let rel = at - p.skel;
        if p.blocks > 1 && rel >= p.content {
            // The end of a run's first block stands for the end of the run.
            return if rel == p.content {
                p.run_content_end
            } else {
                p.run_term_end
            };
        }
        p.file + rel
    }

    fn span_to_file(&self, s: Span) -> Span {
        let start = self.to_file(s.start);
        Span::new(start, self.to_file(s.end).max(start))
    }

    fn diagnostic_to_file(&self, d: &mut Diagnostic) {
        d.span = self.span_to_file(d.span);
        let file = d.file;
        for r in d.related.iter_mut().filter(|r| r.file == file) {
            r.span = self.span_to_file(r.span);
        }
        for f in &mut d.fixes {
            for e in &mut f.edits {
                e.span = self.span_to_file(e.span);
            }
        }
    }
}

/// The parser's and the block rules' findings in one window, not yet finished.
fn check_window_raw(
    window: &Program,
    settings: &Settings,
    rules: &BlockRules,
    facts: &FileFacts,
    utf8: bool,
) -> Vec<Diagnostic> {
    let mut out = window.diagnostics.clone();
    if utf8 {
        if let Some(mut d) = crate::utf8_check(&window.text) {
            d.shift(window.base);
            out.push(d);
        }
    }
    let mut cx = ProgramCx::new(window, settings);
    cx.file = Some(facts);
    let unreadable = util::unreadable_blocks(window);
    let mut codes = Vec::new();
    for (i, b) in window.blocks.iter().enumerate() {
        if facts.dead_block(b.span.start) || unreadable.get(i).copied().unwrap_or(false) {
            continue;
        }
        rules::check_block_at(&cx, rules, i, &mut codes, &mut out);
    }
    out
}

/// The block rules a file's settings enable (one set for all its windows).
fn block_rules(settings: &Settings) -> BlockRules {
    BlockRules::new(&rules::enabled_rules(settings), settings)
}

/// The P010 finding of a file's signature (read window by window with
/// [`crate::control::SignScan`]), before selection and suppression.
pub fn mismatch_finding(sig: &crate::Signature) -> Option<Diagnostic> {
    rules::control_mismatch::signature_diagnostic(sig)
}

/// Whether a finding is P010, which leaves a file no other.
pub fn is_mismatch(d: &Diagnostic) -> bool {
    d.code == rules::control_mismatch::CONTROL_MISMATCH.code
}

/// Whether a block branches to a sequence number: `GOTO n`, `IF … GOTO n`,
/// `M99 P`, `M97 P`.
fn branches_in(p: &Program, b: &crate::syntax::Block) -> bool {
    use crate::syntax::{ItemKind, MacroStmt};
    let items = p.items_of(b);
    let m_with_p = || {
        let lit = |w: &crate::syntax::Word, l: u8, v: f64| {
            w.letter == l && !w.comma && w.num().is_some_and(|n| n.value == v)
        };
        p.words(b)
            .any(|(_, w)| lit(w, b'M', 99.0) || lit(w, b'M', 97.0))
            && p.words(b).any(|(_, w)| w.letter == b'P' && !w.comma)
    };
    items.iter().any(|it| {
        matches!(
            it.kind,
            ItemKind::Macro(MacroStmt::Goto { .. } | MacroStmt::IfGoto { .. })
        )
    }) || m_with_p()
}

/// The checks each window gets: the block rules, and with a
/// [`Skeleton::numbered`] skeleton the sequence-number rule's walk.
pub struct WindowChecks {
    rules: BlockRules,
    numbers: Option<rules::sequence_number::Numbers>,
}

impl WindowChecks {
    pub fn new(settings: &Settings, skeleton: &Skeleton) -> WindowChecks {
        let walk =
            skeleton.numbered && settings.rule_enabled(&rules::sequence_number::SEQUENCE_NUMBER);
        WindowChecks {
            rules: block_rules(settings),
            numbers: walk.then(|| rules::sequence_number::Numbers::new(settings, None)),
        }
    }

    /// The findings in one window: the parser's, the block rules' (with
    /// what `facts` knows of the file) and the walk's over its numbers,
    /// finished but not bounded: the host bounds the file's with one
    /// [`crate::Limiter`]. `utf8`: whether to look for invalid UTF-8 (a file
    /// reports the first only).
    pub fn check(
        &mut self,
        window: &Program,
        settings: &Settings,
        facts: &FileFacts,
        utf8: bool,
    ) -> Vec<Diagnostic> {
        let mut out = check_window_raw(window, settings, &self.rules, facts, utf8);
        if let Some(walk) = &mut self.numbers {
            for b in window.blocks.iter().filter(|b| !util::is_plain(window, b)) {
                walk.block(window, b, &mut out);
            }
        }
        crate::finish_in(window, Some(facts), settings, out, false)
    }

    /// What the walk reports once for the file (`tail`: a window at its end).
    pub fn finish(self, tail: &Program, facts: &FileFacts, settings: &Settings) -> Vec<Diagnostic> {
        let mut out = Vec::new();
        if let Some(walk) = self.numbers {
            walk.finish(&mut out);
        }
        crate::finish_window(tail, facts, settings, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::{parse_lean, parse_window, ParseOptions, ParserState};
    use std::sync::Arc;

    /// The windows of `text`, cut after every `lines` lines, parsed in order.
    fn windows(text: &str, dialect: Dialect, lines: usize) -> Vec<Program> {
        let opts = ParseOptions::new(dialect);
        let (mut base, mut line, mut state) = (0u32, 0u32, ParserState::default());
        let all: Vec<&str> = text.split_inclusive('\n').collect();
        all.chunks(lines)
            .map(|c| {
                let bytes: Vec<u8> = c.concat().into_bytes();
                let len = bytes.len() as u32;
                let (p, s) = parse_window(opts, Arc::from(bytes), base, line, state);
                (base, line, state) = (base + len, line + c.len() as u32, s);
                p
            })
            .collect()
    }

    #[test]
    fn windows_carry_the_files_spans_and_lines() {
        let text = "%\nO1000 (HEAD)\nN10 G0 X1. Y2.\nG1 Z-1. F100.\n#1=[#2+3]\nX4.\nM30\n%\n";
        let whole = parse_lean(ParseOptions::new(Dialect::Fanuc), text.as_bytes().to_vec());
        let parts = windows(text, Dialect::Fanuc, 3);
        let blocks: Vec<_> = parts
            .iter()
            .flat_map(|p| p.blocks.iter().copied())
            .collect();
        let spans = |b: &[crate::syntax::Block]| -> Vec<(Span, u32, u32)> {
            b.iter().map(|b| (b.span, b.term_end, b.line)).collect()
        };
        assert_eq!(spans(&blocks), spans(&whole.blocks));
        // A window reads its items' text at the file's offsets.
        let last = parts.last().expect("windows");
        let m30 = last.blocks.iter().find(|b| last.slice(b.span) == b"M30");
        assert!(m30.is_some_and(|b| b.line == 6), "{:?}", last.blocks);
    }

    #[test]
    fn a_run_of_plain_blocks_is_kept_as_its_first_and_the_files_last_block() {
        let mut text = String::from("G21 G90 (setup)\n");
        for i in 0..1000 {
            text.push_str(&format!("G1 X{i} Y{i} Z-1\n"));
        }
        let mut sk = Skeleton::default();
        for w in windows(&text, Dialect::Rs274ngc, 7) {
            sk.add(&w);
        }
        let settings = Settings::new(Dialect::Rs274ngc);
        let sealed = sk.seal(&settings);
        let lines: Vec<u32> = sealed.program().blocks.iter().map(|b| b.line).collect();
        assert_eq!(lines, [0, 1, 1000]);
        // The missing end is reported where the whole file's check reports it.
        let (found, _) = sealed.check(&settings);
        let whole = crate::analyze(text.as_bytes().to_vec(), &settings);
        let p005 = |ds: &[Diagnostic]| ds.iter().find(|d| d.code == "P005").map(|d| d.span);
        assert_eq!(p005(&found), p005(&whole.diagnostics));
        assert!(p005(&found).is_some());
    }

    #[test]
    fn numbered_lines_make_a_small_skeleton_unless_something_branches() {
        let mut text = String::from("%\nO1000\n");
        for i in 1..2000 {
            text.push_str(&format!("N{i} G1 X{i}. Y1.\n"));
        }
        let mut sk = Skeleton::numbered();
        for w in windows(&text, Dialect::Fanuc, 50) {
            sk.add(&w);
        }
        assert!(!sk.branches());
        assert!(sk.len() < 100, "{} bytes", sk.len());
        text.push_str("GOTO 10\nM30\n%\n");
        let mut sk = Skeleton::numbered();
        for w in windows(&text, Dialect::Fanuc, 50) {
            sk.add(&w);
        }
        assert!(sk.branches());
    }
}
