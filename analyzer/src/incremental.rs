//! Incremental re-analysis of an edited file.
//!
//! Blocks are line-based and the parser carries only a few flags from one
//! block to the next ([`ParserState`]), so after an edit only the blocks from
//! just before the change up to the first block boundary where the new parse
//! meets the old one again (same position after the shift, same parser state)
//! are parsed anew; the blocks after it are copied from the previous parse
//! with their offsets, lines and indices shifted. Block-local static rules run
//! again only on the re-parsed blocks, on blocks whose "skipped" status
//! changed, and on the few blocks whose verdict looks at earlier blocks (G10);
//! whole-file rules run in full (they are linear scans). The result is equal
//! to [`crate::analyze`] on the new text; `tests/incremental.rs` checks that
//! over random edit sequences in all dialects.

use std::sync::Arc;

use crate::rules::{self, ProgramCx};
use crate::syntax::{
    Block, Expr, ExprId, ExprNode, Item, ItemKind, MacroStmt, OLabel, ParseOptions, Parser,
    ParserState, Program, Token, WordValue,
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

fn opts(settings: &Settings) -> ParseOptions {
    ParseOptions {
        dialect: settings.dialect,
        variant: settings.variant,
    }
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
    }
}

/// The analysis `syntax_only` asks for: [`crate::analyze`], or (for files
/// above a host's size limit) the parse with its syntax diagnostics only.
pub fn reference(text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Analysis {
    if syntax_only {
        let program = crate::syntax::parse(opts(settings), text);
        let diagnostics = crate::finish(&program, settings, program.diagnostics.clone());
        Analysis {
            program,
            diagnostics,
        }
    } else {
        crate::analyze(text, settings)
    }
}

impl Incremental {
    /// Analyses a whole text.
    pub fn new(text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Incremental {
        if !syntax_only && crate::binary_check(&text).is_some() {
            return Incremental {
                analysis: crate::analyze(text, settings),
                syntax_only,
                settings_key: settings_key(settings),
                index: None,
            };
        }
        let mut program = empty_program(settings, text.clone(), None);
        let mut index = Index::default();
        let mut parser = Parser::new(opts(settings), text);
        while !parser.is_done() {
            index.record(&parser, &program);
            parser.parse_blocks(&mut program, 1);
        }
        let (analysis, rule_state) = if syntax_only {
            (finish_syntax_only(program, settings), RuleState::default())
        } else {
            let enabled = rules::enabled_rules(settings);
            let mut rs = RuleState::default();
            if !enabled.is_empty() {
                let cx = ProgramCx {
                    program: &program,
                    settings,
                };
                rs.skipped = rules::skipped_blocks(&program);
                let mut codes = Vec::new();
                let mut out = Vec::new();
                for i in 0..program.blocks.len() {
                    note_looks_back(&program, i, &mut rs.looks_back);
                    if rs.skipped.get(i).copied().unwrap_or(false) {
                        continue;
                    }
                    rules::check_block_at(&cx, &enabled, i, &mut codes, &mut out);
                    rs.diags.extend(out.drain(..).map(|d| (i as u32, d)));
                }
            }
            (finish_full(program, settings, &enabled, &rs), rs)
        };
        Incremental {
            analysis,
            syntax_only,
            settings_key: settings_key(settings),
            index: Some((index, rule_state)),
        }
    }

    /// The analysis of `text`, reusing this one where the edit left it valid.
    pub fn update(&self, text: Arc<[u8]>, settings: &Settings, syntax_only: bool) -> Incremental {
        let full = || Incremental::new(text.clone(), settings, syntax_only);
        let Some((index, rs)) = &self.index else {
            return full();
        };
        if self.syntax_only != syntax_only || self.settings_key != settings_key(settings) {
            return full();
        }
        if !syntax_only && crate::binary_check(&text).is_some() {
            return full();
        }
        let old = &self.analysis.program;
        let Some(edit) = diff(&old.text, &text) else {
            return Incremental {
                analysis: Analysis {
                    program: Program {
                        text,
                        ..old.clone()
                    },
                    diagnostics: self.analysis.diagnostics.clone(),
                },
                ..self.clone()
            };
        };
        if old.blocks.is_empty() || index.states.len() != old.blocks.len() {
            return full();
        }
        self.splice(index, rs, edit, text, settings)
    }

    fn splice(
        &self,
        index: &Index,
        rs: &RuleState,
        edit: Edit,
        text: Arc<[u8]>,
        settings: &Settings,
    ) -> Incremental {
        let old = &self.analysis.program;
        let nb = old.blocks.len();
        // The block before the edited one too: its terminator may look ahead
        // (FANUC `;` + blanks + newline, `\r` + `\n`).
        let first = old
            .block_at(edit.start as u32)
            .unwrap_or(0)
            .saturating_sub(1)
            .min(nb - 1);
        let start_pos = old.blocks[first].span.start as usize;
        let tok_cut = old
            .tokens
            .partition_point(|t| (t.start as usize) < start_pos);
        let mut p = empty_program(settings, text.clone(), Some(old));
        p.tokens.extend_from_slice(&old.tokens[..tok_cut]);
        p.blocks.extend_from_slice(&old.blocks[..first]);
        p.items
            .extend_from_slice(&old.items[..old.blocks[first].items.0 as usize]);
        p.exprs
            .extend_from_slice(&old.exprs[..index.exprs[first] as usize]);
        p.expr_lists
            .extend_from_slice(&old.expr_lists[..index.lists[first] as usize]);
        p.diagnostics
            .extend_from_slice(&old.diagnostics[..index.diags[first] as usize]);
        let mut ix = Index {
            states: index.states[..first].to_vec(),
            exprs: index.exprs[..first].to_vec(),
            lists: index.lists[..first].to_vec(),
            diags: index.diags[..first].to_vec(),
        };
        let delta = edit.new_end as i64 - edit.old_end as i64;
        let mut parser = Parser::resume(
            opts(settings),
            text.clone(),
            start_pos,
            old.blocks[first].line,
            index.states[first],
        );
        // The old block where the new parse meets the old one again.
        let mut tail: Option<usize> = None;
        while !parser.is_done() {
            let (pos, _) = parser.position();
            if pos >= edit.new_end {
                let old_pos = (pos as i64 - delta) as usize;
                let j = old
                    .blocks
                    .partition_point(|b| (b.span.start as usize) < old_pos);
                if j < nb
                    && old.blocks[j].span.start as usize == old_pos
                    && index.states[j] == parser.state()
                {
                    tail = Some(j);
                    break;
                }
            }
            ix.record(&parser, &p);
            parser.parse_blocks(&mut p, 1);
        }
        let parsed_end = p.blocks.len();
        let mut block_delta = 0i64;
        if let Some(j) = tail {
            let (_, line) = parser.position();
            let old_pos = old.blocks[j].span.start;
            let sh = Shift {
                bytes: delta,
                items: p.items.len() as i64 - old.blocks[j].items.0 as i64,
                exprs: p.exprs.len() as i64 - index.exprs[j] as i64,
                lists: p.expr_lists.len() as i64 - index.lists[j] as i64,
            };
            let lines = line as i64 - old.blocks[j].line as i64;
            let diags = p.diagnostics.len() as i64 - index.diags[j] as i64;
            block_delta = parsed_end as i64 - j as i64;
            let tok_j = old.tokens.partition_point(|t| t.start < old_pos);
            p.tokens.extend(old.tokens[tok_j..].iter().map(|t| Token {
                start: add(t.start, delta),
                kind: t.kind,
            }));
            p.blocks.extend(old.blocks[j..].iter().map(|b| Block {
                span: sh.span(b.span),
                end: sh.span(b.end),
                line: add(b.line, lines),
                kind: b.kind,
                skip: b.skip.map(|(s, n)| (sh.span(s), n)),
                items: (add(b.items.0, sh.items), add(b.items.1, sh.items)),
            }));
            p.items.extend(
                old.items[old.blocks[j].items.0 as usize..]
                    .iter()
                    .map(|it| sh.item(it)),
            );
            p.exprs.extend(
                old.exprs[index.exprs[j] as usize..]
                    .iter()
                    .map(|e| sh.expr(e)),
            );
            p.expr_lists.extend(
                old.expr_lists[index.lists[j] as usize..]
                    .iter()
                    .map(|e| sh.id(*e)),
            );
            p.diagnostics.extend(
                old.diagnostics[index.diags[j] as usize..]
                    .iter()
                    .map(|d| shift_diag(d, delta)),
            );
            ix.states.extend_from_slice(&index.states[j..]);
            ix.exprs
                .extend(index.exprs[j..].iter().map(|v| add(*v, sh.exprs)));
            ix.lists
                .extend(index.lists[j..].iter().map(|v| add(*v, sh.lists)));
            ix.diags
                .extend(index.diags[j..].iter().map(|v| add(*v, diags)));
        }
        let (analysis, rule_state) = if self.syntax_only {
            (finish_syntax_only(p, settings), RuleState::default())
        } else {
            let enabled = rules::enabled_rules(settings);
            let rs = if enabled.is_empty() {
                RuleState::default()
            } else {
                recheck(
                    &p,
                    settings,
                    &enabled,
                    rs,
                    Reuse {
                        first,
                        parsed_end,
                        tail,
                        block_delta,
                        bytes: delta,
                    },
                )
            };
            (finish_full(p, settings, &enabled, &rs), rs)
        };
        Incremental {
            analysis,
            syntax_only: self.syntax_only,
            settings_key: self.settings_key.clone(),
            index: Some((ix, rule_state)),
        }
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
    let skipped = rules::skipped_blocks(p);
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
    let cx = ProgramCx {
        program: p,
        settings,
    };
    let mut fresh: Vec<(u32, Diagnostic)> = Vec::new();
    let mut codes = Vec::new();
    let mut out = Vec::new();
    for &b in &again {
        if skipped.get(b as usize).copied().unwrap_or(false) {
            continue;
        }
        rules::check_block_at(&cx, enabled, b as usize, &mut codes, &mut out);
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
fn finish_full(
    program: Program,
    settings: &Settings,
    enabled: &[&'static dyn rules::Rule],
    rs: &RuleState,
) -> Analysis {
    let mut diagnostics = program.diagnostics.clone();
    if let Some(d) = crate::utf8_check(&program.text) {
        diagnostics.push(d);
    }
    if !enabled.is_empty() {
        diagnostics.extend(rs.diags.iter().map(|(_, d)| d.clone()));
        let cx = ProgramCx {
            program: &program,
            settings,
        };
        rules::check_whole_program(&cx, enabled, &mut diagnostics);
    }
    let diagnostics = crate::finish(&program, settings, diagnostics);
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

    fn id(&self, e: ExprId) -> ExprId {
        ExprId(add(e.0, self.exprs))
    }

    fn item(&self, it: &Item) -> Item {
        let kind = match it.kind {
            ItemKind::Word(mut w) => {
                w.letter_span = self.span(w.letter_span);
                w.value = match w.value {
                    WordValue::Num(mut n) => {
                        n.span = self.span(n.span);
                        WordValue::Num(n)
                    }
                    WordValue::Expr(e) => WordValue::Expr(self.id(e)),
                    WordValue::Name(s) => WordValue::Name(self.span(s)),
                    WordValue::Indexed(i, mut n) => {
                        n.span = self.span(n.span);
                        WordValue::Indexed(i, n)
                    }
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
                    OLabel::Name(s) => OLabel::Name(self.span(s)),
                    OLabel::Expr(e) => OLabel::Expr(self.id(e)),
                    other => other,
                };
                o.label_span = self.span(o.label_span);
                o.keyword_span = self.span(o.keyword_span);
                o.args = (add(o.args.0, self.lists), add(o.args.1, self.lists));
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
    d.span = shift_span(d.span, by);
    for r in &mut d.related {
        r.span = shift_span(r.span, by);
    }
    for f in &mut d.fixes {
        for e in &mut f.edits {
            e.span = shift_span(e.span, by);
        }
    }
    d
}
