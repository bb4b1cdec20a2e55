//! Incremental re-analysis of an edited file.
//!
//! Blocks are line-based and the parser carries only a few flags from one
//! block to the next ([`ParserState`]), so after an edit only the blocks from
//! just before the change up to the first block boundary where the new parse
//! meets the old one again (same position after the shift, same parser state)
//! are parsed anew, into a scratch program that is spliced into the previous
//! program's vectors in place; the blocks after it keep their place in memory
//! and get their offsets, lines and indices shifted there
//! ([`Incremental::update_owned`]; [`Incremental::update`] does the same on a
//! copy). Block-local static rules run again only on the re-parsed blocks, on
//! blocks whose "skipped" status changed, and on the few blocks whose verdict
//! looks at earlier blocks (G10). Whole-file rules run in full, but over
//! stretches of blocks: a run of plain blocks (literal words only, the bulk
//! of CAM output; the flag is kept per block and re-derived only for
//! re-parsed blocks) is visited once. The result is equal to
//! [`crate::analyze`] on the new text; `tests/incremental.rs` checks that over
//! random edit sequences in all dialects, and that visiting plain runs once
//! gives the whole-file rules' results of visiting every block.

use std::sync::Arc;

use crate::rules::{self, ProgramCx};
use crate::syntax::{
    Block, Expr, ExprId, ExprNode, Item, ItemKind, MacroStmt, OLabel, Parser, ParserState, Program,
    WordValue,
};
use crate::{Analysis, Diagnostic, Settings, Span};

/// Where two versions of a text differ: bytes `start..old_end` of the old
/// text became bytes `start..new_end` of the new one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edit {
    pub start: usize,
    pub old_end: usize,
    pub new_end: usize,
}

/// The smallest single edit that turns `old` into `new` (common prefix and
/// suffix), or `None` when they are equal.
pub fn diff(old: &[u8], new: &[u8]) -> Option<Edit> {
    if old == new {
        return None;
    }
    let max = old.len().min(new.len());
    // Whole chunks compare with `memcmp`; only the differing chunk goes byte by byte.
    const CHUNK: usize = 4096;
    let mut prefix = 0;
    while prefix + CHUNK <= max && old[prefix..prefix + CHUNK] == new[prefix..prefix + CHUNK] {
        prefix += CHUNK;
    }
    while prefix < max && old[prefix] == new[prefix] {
        prefix += 1;
    }
    let room = max - prefix;
    let (o, n) = (old.len(), new.len());
    let mut suffix = 0;
    while suffix + CHUNK <= room
        && old[o - suffix - CHUNK..o - suffix] == new[n - suffix - CHUNK..n - suffix]
    {
        suffix += CHUNK;
    }
    while suffix < room && old[o - suffix - 1] == new[n - suffix - 1] {
        suffix += 1;
    }
    Some(Edit {
        start: prefix,
        old_end: o - suffix,
        new_end: n - suffix,
    })
}

/// What was recorded before each block while parsing, so that a parse can
/// resume there and the vectors can be cut there.
#[derive(Debug, Clone, Default)]
struct Index {
    states: Vec<ParserState>,
    exprs: Vec<u32>,
    lists: Vec<u32>,
    diags: Vec<u32>,
}

impl Index {
    fn record(&mut self, parser: &Parser, p: &Program) {
        self.states.push(parser.state());
        self.exprs.push(p.exprs.len() as u32);
        self.lists.push(p.expr_lists.len() as u32);
        self.diags.push(p.diagnostics.len() as u32);
    }
}

/// The static rules' results kept per block.
#[derive(Debug, Clone, Default)]
struct RuleState {
    /// Block-rule diagnostics in block order, with their block.
    diags: Vec<(u32, Diagnostic)>,
    /// Blocks the block rules pass over ([`rules::skipped_blocks`]).
    skipped: Vec<bool>,
    /// Blocks whose block-rule verdict depends on earlier blocks.
    looks_back: Vec<u32>,
    /// Which blocks are plain ([`rules::util::is_plain`]): the per-block fact
    /// the whole-file rules group blocks by. Re-derived only for re-parsed
    /// blocks, so the whole-file pass visits runs of plain blocks once
    /// without looking at their items.
    plain: Vec<bool>,
}

/// An analysis that can be updated after an edit.
#[derive(Debug, Clone)]
pub struct Incremental {
    pub analysis: Analysis,
    syntax_only: bool,
    /// The settings the analysis used (their debug form: a change of any
    /// field means a full analysis).
    settings_key: String,
    /// `None` when the file was analysed as binary (no parse to reuse).
    index: Option<(Index, RuleState)>,
}

fn settings_key(s: &Settings) -> String {
    format!("{s:?}")
}

fn empty_program(settings: &Settings, text: Arc<[u8]>, like: Option<&Program>) -> Program {
    let n = text.len();
    let cap = |old: Option<usize>, guess: usize| old.map_or(guess, |c| c + c / 16 + 16);
    Program {
        dialect: settings.dialect,
        tokens: Vec::with_capacity(cap(like.map(|p| p.tokens.len()), n / 2 + 1)),
        blocks: Vec::with_capacity(cap(like.map(|p| p.blocks.len()), n / 16 + 1)),
        items: Vec::with_capacity(cap(like.map(|p| p.items.len()), n / 5 + 1)),
        exprs: Vec::with_capacity(cap(like.map(|p| p.exprs.len()), 0)),
        expr_lists: Vec::with_capacity(cap(like.map(|p| p.expr_lists.len()), 0)),
        diagnostics: Vec::new(),
        text,
        base: 0,
    }
}

/// The analysis `syntax_only` asks for: [`crate::analyze`], or (for files
/// above a host's size limit) the parse with its syntax diagnostics only.
pub fn reference(text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Analysis {
    if syntax_only {
        let program = crate::syntax::parse(settings.parse_options(), text);
        let diagnostics = crate::finish(&program, settings, program.diagnostics.clone());
        Analysis {
            program,
            diagnostics,
        }
    } else {
        crate::analyze(text, settings)
    }
}

/// A whole text parsed for an [`Incremental`] analysis whose static rules have
/// not run yet ([`Incremental::parse`]). The rules only read the tree
/// ([`Parse::rules`]), so a host can interpret the program on one thread while
/// they run on another, and join the two with [`Parse::with_rules`].
#[derive(Debug, Clone)]
pub struct Parse {
    program: Program,
    syntax_only: bool,
    settings_key: String,
    /// `None` when the file was read as binary (no parse to reuse).
    index: Option<Index>,
}

/// The static rules' results for a [`Parse`]: the file's diagnostics and what
/// an update needs to re-check only what an edit touched.
#[derive(Debug, Clone)]
pub struct StaticRules {
    /// Syntax and static-rule diagnostics, as [`crate::analyze`] gives them.
    pub diagnostics: Vec<Diagnostic>,
    state: RuleState,
}

impl Parse {
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Runs the static rules on the tree (`settings` as for the parse).
    pub fn rules(&self, settings: &Settings) -> StaticRules {
        let program = &self.program;
        if self.index.is_none() {
            // A binary file is reported once ([`crate::lint`] keeps its `L009` unfiltered).
            return StaticRules {
                diagnostics: crate::binary_check(&program.text).into_iter().collect(),
                state: RuleState::default(),
            };
        }
        if self.syntax_only {
            return StaticRules {
                diagnostics: crate::finish(program, settings, program.diagnostics.clone()),
                state: RuleState::default(),
            };
        }
        let enabled = rules::enabled_rules(settings);
        let mut rs = RuleState::default();
        if !enabled.is_empty() {
            rs.plain = program
                .blocks
                .iter()
                .map(|b| rules::util::is_plain(program, b))
                .collect();
            let cx = ProgramCx::with_plain(program, settings, &rs.plain);
            rs.skipped = rules::skipped_blocks_in(program, cx.segments());
            let block_rules = rules::BlockRules::new(&enabled, settings);
            let mut codes = Vec::new();
            let mut out = Vec::new();
            for i in 0..program.blocks.len() {
                note_looks_back(program, i, &mut rs.looks_back);
                if rs.skipped.get(i).copied().unwrap_or(false) {
                    continue;
                }
                rules::check_block_at(&cx, &block_rules, i, &mut codes, &mut out);
                rs.diags.extend(out.drain(..).map(|d| (i as u32, d)));
            }
        }
        StaticRules {
            diagnostics: full_diagnostics(program, settings, &enabled, &rs),
            state: rs,
        }
    }

    /// The analysis of this parse with its rules' results.
    pub fn with_rules(self, rules: StaticRules) -> Incremental {
        Incremental {
            analysis: Analysis {
                program: self.program,
                diagnostics: rules.diagnostics,
            },
            syntax_only: self.syntax_only,
            settings_key: self.settings_key,
            index: self.index.map(|ix| (ix, rules.state)),
        }
    }

    /// [`Incremental::update`] of this parse with its `rules`, without taking
    /// either: a copy of both is made only when the update can reuse them.
    pub fn update(
        &self,
        rules: &StaticRules,
        text: Arc<[u8]>,
        settings: &Settings,
        syntax_only: bool,
    ) -> Incremental {
        let reusable = self.index.as_ref().is_some_and(|ix| {
            reusable(
                &self.program,
                ix,
                (self.syntax_only, &self.settings_key),
                &text,
                settings,
                syntax_only,
            )
        });
        if !reusable {
            return Incremental::new(text, settings, syntax_only);
        }
        self.clone()
            .with_rules(rules.clone())
            .update_owned(text, settings, syntax_only)
    }
}

/// Whether an update of `program` (parsed with the settings and mode of
/// `was`, described by `ix`) to `text` can start from it (else: a full analysis).
fn reusable(
    program: &Program,
    ix: &Index,
    was: (bool, &str),
    text: &[u8],
    settings: &Settings,
    syntax_only: bool,
) -> bool {
    was.0 == syntax_only
        && was.1 == settings_key(settings)
        && (syntax_only || crate::binary_check(text).is_none())
        && !program.blocks.is_empty()
        && ix.states.len() == program.blocks.len()
}

impl Incremental {
    /// Analyses a whole text.
    pub fn new(text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Incremental {
        let parse = Incremental::parse(text, settings, syntax_only);
        let rules = parse.rules(settings);
        parse.with_rules(rules)
    }

    /// The first half of [`Incremental::new`]: the parse, without the static rules.
    pub fn parse(text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Parse {
        if !syntax_only && crate::binary_check(&text).is_some() {
            return Parse {
                program: crate::parse_text(text, settings).program,
                syntax_only,
                settings_key: settings_key(settings),
                index: None,
            };
        }
        let mut program = empty_program(settings, text.clone(), None);
        let mut index = Index::default();
        let mut parser = Parser::new(settings.parse_options(), text);
        while !parser.is_done() {
            index.record(&parser, &program);
            parser.parse_blocks(&mut program, 1);
        }
        Parse {
            program,
            syntax_only,
            settings_key: settings_key(settings),
            index: Some(index),
        }
    }

    /// This analysis as its parse and its rules' results.
    pub fn into_parts(self) -> (Parse, StaticRules) {
        let (index, state) = match self.index {
            Some((ix, rs)) => (Some(ix), rs),
            None => (None, RuleState::default()),
        };
        (
            Parse {
                program: self.analysis.program,
                syntax_only: self.syntax_only,
                settings_key: self.settings_key,
                index,
            },
            StaticRules {
                diagnostics: self.analysis.diagnostics,
                state,
            },
        )
    }

    /// The analysis of `text`, reusing this one where the edit left it valid.
    /// Works on a copy: [`Incremental::update_owned`] avoids it when the
    /// caller can give up this analysis.
    pub fn update(&self, text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Incremental {
        if !self.reusable(&text, settings, syntax_only) {
            return Incremental::new(text, settings, syntax_only);
        }
        self.clone().update_owned(text, settings, syntax_only)
    }

    /// Whether an update can start from this analysis (else: a full one).
    fn reusable(&self, text: &[u8], settings: &Settings, syntax_only: bool) -> bool {
        self.index.as_ref().is_some_and(|(ix, _)| {
            reusable(
                &self.analysis.program,
                ix,
                (self.syntax_only, &self.settings_key),
                text,
                settings,
                syntax_only,
            )
        })
    }

    /// [`Incremental::update`] on this analysis itself: the program's vectors
    /// are edited in place (the changed blocks replaced, the blocks after
    /// them shifted), so an edit of a large file neither allocates nor
    /// copies a second program.
    pub fn update_owned(
        self,
        text: Arc<[u8]>,
        settings: &Settings,
        syntax_only: bool,
    ) -> Incremental {
        if !self.reusable(&text, settings, syntax_only) {
            return Incremental::new(text, settings, syntax_only);
        }
        let Some(edit) = diff(&self.analysis.program.text, &text) else {
            let mut same = self;
            same.analysis.program.text = text;
            return same;
        };
        let Incremental {
            analysis,
            syntax_only,
            settings_key,
            index,
        } = self;
        let Some((mut ix, rs)) = index else {
            return Incremental::new(text, settings, syntax_only);
        };
        let mut p = analysis.program;
        let reuse = splice_in_place(&mut p, &mut ix, edit, text, settings);
        let (analysis, rule_state) = if syntax_only {
            (finish_syntax_only(p, settings), RuleState::default())
        } else {
            let enabled = rules::enabled_rules(settings);
            let rs = if enabled.is_empty() {
                RuleState::default()
            } else {
                recheck(&p, settings, &enabled, &rs, reuse)
            };
            (finish_full(p, settings, &enabled, &rs), rs)
        };
        Incremental {
            analysis,
            syntax_only,
            settings_key,
            index: Some((ix, rule_state)),
        }
    }
}

/// Re-parses the blocks an edit touched and splices them into `p` (whose
/// text becomes `text`) and its index, shifting the blocks after them.
/// `p` must be non-empty and `ix` must describe it.
fn splice_in_place(
    p: &mut Program,
    ix: &mut Index,
    edit: Edit,
    text: Arc<[u8]>,
    settings: &Settings,
) -> Reuse {
    let nb = p.blocks.len();
    // The block before the edited one too: its terminator may look ahead
    // (FANUC `;` + blanks + newline, `\r` + `\n`).
    let first = p
        .block_at(edit.start as u32)
        .unwrap_or(0)
        .saturating_sub(1)
        .min(nb - 1);
    let start_pos = p.blocks[first].span.start as usize;
    let tok_cut = p.tokens.partition_point(|t| (t.start as usize) < start_pos);
    let base = Shift {
        bytes: 0,
        items: p.blocks[first].items.0 as i64,
        exprs: ix.exprs[first] as i64,
        lists: ix.lists[first] as i64,
    };
    let diags_first = ix.diags[first] as usize;
    // The changed blocks are parsed into a scratch program (item and
    // expression ids from 0, moved by `base` when spliced in). Its first
    // token is the token before the cut, so that a run of blanks merges
    // across the cut as it does in a full parse.
    let mut s = Program {
        dialect: p.dialect,
        tokens: p.tokens[..tok_cut].last().copied().into_iter().collect(),
        blocks: Vec::new(),
        items: Vec::new(),
        exprs: Vec::new(),
        expr_lists: Vec::new(),
        diagnostics: Vec::new(),
        text: text.clone(),
        base: 0,
    };
    let seeded = s.tokens.len();
    let mut sx = Index::default();
    let delta = edit.new_end as i64 - edit.old_end as i64;
    let mut parser = Parser::resume(
        settings.parse_options(),
        text.clone(),
        start_pos,
        p.blocks[first].line,
        ix.states[first],
    );
    // The old block where the new parse meets the old one again.
    let mut tail: Option<usize> = None;
    while !parser.is_done() {
        let (pos, _) = parser.position();
        if pos >= edit.new_end {
            let old_pos = (pos as i64 - delta) as usize;
            let j = p
                .blocks
                .partition_point(|b| (b.span.start as usize) < old_pos);
            if j < nb
                && p.blocks[j].span.start as usize == old_pos
                && ix.states[j] == parser.state()
            {
                tail = Some(j);
                break;
            }
        }
        sx.states.push(parser.state());
        sx.exprs.push(s.exprs.len() as u32);
        sx.lists.push(s.expr_lists.len() as u32);
        sx.diags.push(s.diagnostics.len() as u32);
        parser.parse_blocks(&mut s, 1);
    }
    let (_, line) = parser.position();
    let parsed = s.blocks.len();
    // Where the replaced stretch of each old vector ends (the old tail's start).
    let j = tail.unwrap_or(nb);
    let tok_j = match tail {
        Some(j) => {
            let at = p.blocks[j].span.start;
            p.tokens.partition_point(|t| t.start < at)
        }
        None => p.tokens.len(),
    };
    let items_j = tail.map_or(p.items.len(), |j| p.blocks[j].items.0 as usize);
    let exprs_j = tail.map_or(p.exprs.len(), |j| ix.exprs[j] as usize);
    let lists_j = tail.map_or(p.expr_lists.len(), |j| ix.lists[j] as usize);
    let diags_j = tail.map_or(p.diagnostics.len(), |j| ix.diags[j] as usize);
    let sh = Shift {
        bytes: delta,
        items: base.items + s.items.len() as i64 - items_j as i64,
        exprs: base.exprs + s.exprs.len() as i64 - exprs_j as i64,
        lists: base.lists + s.expr_lists.len() as i64 - lists_j as i64,
    };
    let lines = tail.map_or(0, |j| line as i64 - p.blocks[j].line as i64);
    let diags_shift = diags_first as i64 + s.diagnostics.len() as i64 - diags_j as i64;

    // Splice each vector: the scratch part moved by `base`, the tail by `sh`.
    let new_tokens = s.tokens.len() - seeded;
    p.tokens.splice(tok_cut..tok_j, s.tokens.drain(seeded..));
    for t in &mut p.tokens[tok_cut + new_tokens..] {
        t.start = add(t.start, delta);
    }
    p.blocks
        .splice(first..j, s.blocks.iter().map(|b| base.block(b, 0)));
    for b in &mut p.blocks[first + parsed..] {
        *b = sh.block(b, lines);
    }
    let items_first = base.items as usize;
    let new_items = s.items.len();
    p.items
        .splice(items_first..items_j, s.items.iter().map(|it| base.item(it)));
    for it in &mut p.items[items_first + new_items..] {
        *it = sh.item(it);
    }
    let exprs_first = base.exprs as usize;
    let new_exprs = s.exprs.len();
    p.exprs
        .splice(exprs_first..exprs_j, s.exprs.iter().map(|e| base.expr(e)));
    for e in &mut p.exprs[exprs_first + new_exprs..] {
        *e = sh.expr(e);
    }
    let lists_first = base.lists as usize;
    let new_lists = s.expr_lists.len();
    p.expr_lists.splice(
        lists_first..lists_j,
        s.expr_lists.iter().map(|e| base.id(*e)),
    );
    for e in &mut p.expr_lists[lists_first + new_lists..] {
        *e = sh.id(*e);
    }
    let new_diags = s.diagnostics.len();
    p.diagnostics
        .splice(diags_first..diags_j, s.diagnostics.drain(..));
    for d in &mut p.diagnostics[diags_first + new_diags..] {
        shift_diag_in_place(d, delta);
    }
    p.text = text;

    // The index: the re-parsed blocks' entries (moved by `base`), then the
    // tail's (moved like the tail).
    ix.states.splice(first..j, sx.states);
    ix.exprs
        .splice(first..j, sx.exprs.iter().map(|v| add(*v, base.exprs)));
    ix.lists
        .splice(first..j, sx.lists.iter().map(|v| add(*v, base.lists)));
    ix.diags.splice(
        first..j,
        sx.diags.iter().map(|v| add(*v, diags_first as i64)),
    );
    let tail_ix = first + parsed;
    for v in &mut ix.exprs[tail_ix..] {
        *v = add(*v, sh.exprs);
    }
    for v in &mut ix.lists[tail_ix..] {
        *v = add(*v, sh.lists);
    }
    for v in &mut ix.diags[tail_ix..] {
        *v = add(*v, diags_shift);
    }
    Reuse {
        first,
        parsed_end: first + parsed,
        tail,
        block_delta: (first + parsed) as i64 - j as i64,
        bytes: delta,
    }
}

/// Which blocks of a new parse were re-parsed and how the rest maps to the old.
struct Reuse {
    /// New blocks `first..parsed_end` are new; blocks before `first` are the old ones.
    first: usize,
    parsed_end: usize,
    /// The old block the copied tail starts with.
    tail: Option<usize>,
    block_delta: i64,
    bytes: i64,
}

impl Reuse {
    /// The old index of new block `b`, unless it was re-parsed.
    fn old_block(&self, b: usize) -> Option<usize> {
        if b < self.first {
            Some(b)
        } else if b >= self.parsed_end && self.tail.is_some() {
            Some((b as i64 - self.block_delta) as usize)
        } else {
            None
        }
    }
}

fn note_looks_back(p: &Program, i: usize, out: &mut Vec<u32>) {
    if let Some(b) = p.blocks.get(i) {
        if rules::block_looks_back(p, b) {
            out.push(i as u32);
        }
    }
}

/// The block-rule results for a spliced program: the old ones where the block
/// and everything its verdict depends on are unchanged, new ones elsewhere.
fn recheck(
    p: &Program,
    settings: &Settings,
    enabled: &[&'static dyn rules::Rule],
    old: &RuleState,
    r: Reuse,
) -> RuleState {
    // Plain flags: the old ones outside the re-parsed blocks.
    let mut plain: Vec<bool> = Vec::with_capacity(p.blocks.len());
    plain.extend(old.plain.iter().take(r.first));
    plain.extend(
        p.blocks
            .get(r.first..r.parsed_end)
            .unwrap_or_default()
            .iter()
            .map(|b| rules::util::is_plain(p, b)),
    );
    if let Some(j) = r.tail {
        plain.extend(old.plain.iter().skip(j));
    }
    if plain.len() != p.blocks.len() {
        // Cannot happen when the old state matched the old program; stay exact anyway.
        plain = p
            .blocks
            .iter()
            .map(|b| rules::util::is_plain(p, b))
            .collect();
    }
    let segs = rules::context::segments_of(plain.iter().copied());
    let skipped = rules::skipped_blocks_in(p, &segs);
    let mut again: Vec<u32> = (r.first..r.parsed_end).map(|b| b as u32).collect();
    // Blocks that became skipped or live.
    for (b, s) in skipped.iter().enumerate() {
        if let Some(ob) = r.old_block(b) {
            if old.skipped.get(ob).copied().unwrap_or(false) != *s {
                again.push(b as u32);
            }
        }
    }
    let mut looks_back = Vec::new();
    for &ob in &old.looks_back {
        let ob = ob as usize;
        if ob < r.first {
            looks_back.push(ob as u32);
        } else if let Some(j) = r.tail.filter(|j| ob >= *j) {
            let _ = j;
            let b = (ob as i64 + r.block_delta) as u32;
            looks_back.push(b);
            // An edit before it may have changed what it looks back at.
            again.push(b);
        }
    }
    for b in r.first..r.parsed_end {
        note_looks_back(p, b, &mut looks_back);
    }
    looks_back.sort_unstable();
    again.sort_unstable();
    again.dedup();
    let mut kept: Vec<(u32, Diagnostic)> = Vec::with_capacity(old.diags.len());
    for (ob, d) in &old.diags {
        let ob = *ob as usize;
        let nb = if ob < r.first {
            Some((ob as u32, d.clone()))
        } else {
            r.tail
                .filter(|j| ob >= *j)
                .map(|_| ((ob as i64 + r.block_delta) as u32, shift_diag(d, r.bytes)))
        };
        if let Some((b, d)) = nb {
            if again.binary_search(&b).is_err() {
                kept.push((b, d));
            }
        }
    }
    let cx = ProgramCx::new(p, settings);
    let block_rules = rules::BlockRules::new(enabled, settings);
    let mut fresh: Vec<(u32, Diagnostic)> = Vec::new();
    let mut codes = Vec::new();
    let mut out = Vec::new();
    for &b in &again {
        if skipped.get(b as usize).copied().unwrap_or(false) {
            continue;
        }
        rules::check_block_at(&cx, &block_rules, b as usize, &mut codes, &mut out);
        fresh.extend(out.drain(..).map(|d| (b, d)));
    }
    // Merge by block: a block's diagnostics are all kept or all fresh.
    let mut diags = Vec::with_capacity(kept.len() + fresh.len());
    let (mut k, mut f) = (kept.into_iter().peekable(), fresh.into_iter().peekable());
    loop {
        let take_kept = match (k.peek(), f.peek()) {
            (Some(a), Some(b)) => a.0 <= b.0,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => break,
        };
        let next = if take_kept { k.next() } else { f.next() };
        diags.extend(next);
    }
    RuleState {
        diags,
        skipped,
        looks_back,
        plain,
    }
}

fn finish_syntax_only(program: Program, settings: &Settings) -> Analysis {
    let diagnostics = crate::finish(&program, settings, program.diagnostics.clone());
    Analysis {
        program,
        diagnostics,
    }
}

/// Assembles the diagnostics in the order [`crate::analyze`] produces them
/// (parser, UTF-8, block rules, whole-file rules), so that sorting and
/// de-duplication give the same list.
fn full_diagnostics(
    program: &Program,
    settings: &Settings,
    enabled: &[&'static dyn rules::Rule],
    rs: &RuleState,
) -> Vec<Diagnostic> {
    let mut diagnostics = program.diagnostics.clone();
    if let Some(d) = crate::utf8_check(&program.text) {
        diagnostics.push(d);
    }
    if !enabled.is_empty() {
        diagnostics.extend(rs.diags.iter().map(|(_, d)| d.clone()));
        let cx = ProgramCx::with_plain(program, settings, &rs.plain);
        rules::check_whole_program(&cx, enabled, &mut diagnostics);
    }
    crate::finish(program, settings, diagnostics)
}

fn finish_full(
    program: Program,
    settings: &Settings,
    enabled: &[&'static dyn rules::Rule],
    rs: &RuleState,
) -> Analysis {
    let diagnostics = full_diagnostics(&program, settings, enabled, rs);
    Analysis {
        program,
        diagnostics,
    }
}

fn add(v: u32, d: i64) -> u32 {
    (v as i64 + d) as u32
}

/// How the copied tail moves: bytes, item indices and expression ids.
struct Shift {
    bytes: i64,
    items: i64,
    exprs: i64,
    lists: i64,
}

impl Shift {
    fn span(&self, s: Span) -> Span {
        shift_span(s, self.bytes)
    }

    fn block(&self, b: &Block, lines: i64) -> Block {
        let mut block = Block {
            span: self.span(b.span),
            term_end: self.span(b.end()).end,
            line: add(b.line, lines),
            kind: b.kind,
            skip_level: 0,
            skip_len: 0,
            skip_at: 0,
            items: (add(b.items.0, self.items), add(b.items.1, self.items)),
        };
        block.set_skip(b.skip().map(|(s, n)| (self.span(s), n)));
        block
    }

    fn id(&self, e: ExprId) -> ExprId {
        ExprId(add(e.0, self.exprs))
    }

    fn item(&self, it: &Item) -> Item {
        let kind = match it.kind {
            ItemKind::Word(mut w) => {
                w.value = match w.value {
                    WordValue::Num(mut n) => {
                        n.span = self.span(n.span);
                        WordValue::Num(n)
                    }
                    WordValue::Expr(e) => WordValue::Expr(self.id(e)),
                    WordValue::Name(s) => WordValue::Name(self.span(s)),
                    WordValue::Missing => WordValue::Missing,
                };
                ItemKind::Word(w)
            }
            ItemKind::Assign { target, value } => ItemKind::Assign {
                target: self.id(target),
                value: self.id(value),
            },
            ItemKind::Comment(c) => ItemKind::Comment(c),
            ItemKind::OWord(mut o) => {
                o.label = match o.label {
                    OLabel::Expr(e) => OLabel::Expr(self.id(e)),
                    other => other,
                };
                o.label_span = self.span(o.label_span);
                o.args_start = add(o.args_start, self.lists);
                ItemKind::OWord(o)
            }
            ItemKind::Macro(m) => ItemKind::Macro(match m {
                MacroStmt::Goto { target } => MacroStmt::Goto {
                    target: self.id(target),
                },
                MacroStmt::IfGoto { cond, target } => MacroStmt::IfGoto {
                    cond: self.id(cond),
                    target: self.id(target),
                },
                MacroStmt::IfThen { cond } => MacroStmt::IfThen {
                    cond: self.id(cond),
                },
                MacroStmt::While { cond, m } => MacroStmt::While {
                    cond: self.id(cond),
                    m: self.id(m),
                },
                MacroStmt::Do { m } => MacroStmt::Do { m: self.id(m) },
                MacroStmt::End { m } => MacroStmt::End { m: self.id(m) },
                MacroStmt::Output => MacroStmt::Output,
            }),
            ItemKind::ProgramHead { name, number } => ItemKind::ProgramHead {
                name: self.span(name),
                number,
            },
            ItemKind::Error => ItemKind::Error,
        };
        Item {
            kind,
            span: self.span(it.span),
        }
    }

    fn expr(&self, e: &ExprNode) -> ExprNode {
        let expr = match e.expr {
            Expr::Num(mut n) => {
                n.span = self.span(n.span);
                Expr::Num(n)
            }
            Expr::Var { index } => Expr::Var {
                index: self.id(index),
            },
            Expr::Named { name } => Expr::Named {
                name: self.span(name),
            },
            Expr::Neg { arg } => Expr::Neg { arg: self.id(arg) },
            Expr::Plus { arg } => Expr::Plus { arg: self.id(arg) },
            Expr::Binary { op, lhs, rhs } => Expr::Binary {
                op,
                lhs: self.id(lhs),
                rhs: self.id(rhs),
            },
            Expr::Call { func, arg, arg2 } => Expr::Call {
                func,
                arg: self.id(arg),
                arg2: arg2.map(|a| self.id(a)),
            },
            Expr::Group { inner } => Expr::Group {
                inner: self.id(inner),
            },
            Expr::Error => Expr::Error,
        };
        ExprNode {
            expr,
            span: self.span(e.span),
        }
    }
}

fn shift_span(s: Span, d: i64) -> Span {
    Span {
        start: add(s.start, d),
        end: add(s.end, d),
    }
}

fn shift_diag(d: &Diagnostic, by: i64) -> Diagnostic {
    let mut d = d.clone();
    shift_diag_in_place(&mut d, by);
    d
}

fn shift_diag_in_place(d: &mut Diagnostic, by: i64) {
    if by == 0 {
        return;
    }
    d.span = shift_span(d.span, by);
    for r in &mut d.related {
        r.span = shift_span(r.span, by);
    }
    for f in &mut d.fixes {
        for e in &mut f.edits {
            e.span = shift_span(e.span, by);
        }
    }
}
