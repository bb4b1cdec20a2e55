//! Small helpers shared by the static rules.

use crate::dialect::{CodeNum, Dialect, Variant};
use crate::settings::Settings;
use crate::span::Span;
use crate::syntax::{Block, Item, ItemKind, Program, Word, WordValue};

use super::context::BlockCx;

/// The literal numeric value of a word, if it is a plain number.
pub fn lit(w: &Word) -> Option<f64> {
    match &w.value {
        WordValue::Num(n) => Some(n.value),
        _ => None,
    }
}

/// Whether a letter is an axis of the configured machine.
pub fn is_machine_axis(settings: &Settings, letter: u8) -> bool {
    settings.axes.iter().any(|a| *a as u32 == letter as u32)
}

/// The words of the block that are configured axes.
pub fn axis_words<'a>(cx: &BlockCx<'a>) -> impl Iterator<Item = (&'a Item, &'a Word)> + 'a {
    let settings = cx.settings;
    cx.words()
        .filter(move |(_, w)| !w.comma && is_machine_axis(settings, w.letter))
}

/// Whether the block has an axis word of the machine ([`axis_words`] without collecting).
pub fn has_axis_word(cx: &BlockCx<'_>) -> bool {
    axis_words(cx).next().is_some()
}

/// Whether the block holds the code `letter``tenths` written as a literal.
pub fn has(cx: &BlockCx<'_>, letter: char, tenths: u32) -> bool {
    cx.has_code(letter, tenths)
}

/// The first code of the block among `tenths` (G letter).
pub fn first_g<'a>(cx: &BlockCx<'a>, tenths: &[u32]) -> Option<&'a super::BlockCode> {
    cx.codes
        .iter()
        .find(|c| c.letter == 'G' && c.num.is_some_and(|n| tenths.contains(&n.0)))
}

/// The word of `letter` (not after a comma), with its item.
pub fn word_item<'a>(cx: &BlockCx<'a>, letter: u8) -> Option<(&'a Item, &'a Word)> {
    if !cx.has_letter(letter) {
        return None;
    }
    cx.words().find(|(_, w)| w.letter == letter && !w.comma)
}

/// Whether the dialect's table has any code of this letter (the tables are
/// filled in stages; an empty table must not make every code "unknown").
pub fn table_has_letter(dialect: Dialect, letter: char) -> bool {
    dialect.codes().iter().any(|c| c.letter == letter)
}

/// Whether `code` (e.g. `G100`, `M150`, `G05.1`) is in the settings' custom codes.
pub fn is_custom(settings: &Settings, letter: char, num: CodeNum) -> bool {
    settings.custom_codes.iter().any(|c| {
        let c = c.trim();
        let mut chars = c.chars();
        let Some(l) = chars.next() else { return false };
        l.eq_ignore_ascii_case(&letter)
            && chars
                .as_str()
                .parse::<f64>()
                .ok()
                .and_then(CodeNum::from_value)
                == Some(num)
    })
}

/// Name of a code as the dialect writes it (`G02.3` style for ServoWorks and
/// FANUC, `G2.3` for RS274/NGC).
pub fn code_name(dialect: Dialect, letter: char, num: CodeNum) -> String {
    let d = num.display();
    match dialect {
        Dialect::Rs274ngc => format!("{letter}{d}"),
        _ if num.0 < 100 => format!("{letter}0{d}"),
        _ => format!("{letter}{d}"),
    }
}

/// Where a FANUC G65/G66/G66.1 macro call starts in the block: the words after
/// it are arguments (`M2.0` is #13, `H14.` is #11), not NC words.
pub fn fanuc_call_start(program: &Program, b: &Block) -> Option<u32> {
    if program.dialect != Dialect::Fanuc {
        return None;
    }
    program.words(b).find_map(|(i, w)| {
        let is_call = w.letter == b'G'
            && !w.comma
            && lit(w).is_some_and(|v| [65.0, 66.0, 66.1].iter().any(|c| (v - c).abs() < 1e-9));
        is_call.then_some(i.span.start)
    })
}

/// The sequence numbers a FANUC program can branch to: literal `GOTO n` and
/// `IF […] GOTO n` targets and `M99 Pn`; any number when a target is computed.
pub struct BranchTargets {
    numbers: Vec<f64>,
    computed: bool,
}

impl BranchTargets {
    pub fn contains(&self, n: f64) -> bool {
        self.computed || self.numbers.contains(&n)
    }
}

/// The program's [`BranchTargets`], from every item that is not in a plain block
/// (plain blocks hold literal axis and feed words only).
pub fn branch_targets(cx: &super::ProgramCx<'_>) -> BranchTargets {
    use crate::syntax::MacroStmt;
    let p = cx.program;
    let mut t = BranchTargets {
        numbers: Vec::new(),
        computed: false,
    };
    for item in &p.items {
        if let ItemKind::Macro(MacroStmt::Goto { target } | MacroStmt::IfGoto { target, .. }) =
            item.kind
        {
            match super::macro_loop_structure::literal(p, target) {
                Some(n) => t.numbers.push(n),
                None => t.computed = true,
            }
        }
    }
    for b in cx.non_plain_blocks() {
        let words = || p.words(b);
        if words().any(|(_, w)| w.letter == b'M' && lit(w) == Some(99.0)) {
            if let Some((_, w)) = words().find(|(_, w)| w.letter == b'P' && !w.comma) {
                match lit(w) {
                    Some(n) => t.numbers.push(n),
                    None => t.computed = true,
                }
            }
        }
    }
    t
}

/// Whether the block has items other than comments.
pub fn has_code_items(program: &Program, b: &Block) -> bool {
    program
        .items_of(b)
        .iter()
        .any(|i| !matches!(i.kind, ItemKind::Comment(_)))
}

/// The profile is the 2007 seed (`emc2`).
pub fn is_emc2(settings: &Settings) -> bool {
    settings.variant == Variant::Emc2
}

/// Whether a value is within 0.0001 of an integer (the RS274/NGC rule).
pub fn near_integer(v: f64) -> bool {
    (v - v.round()).abs() <= 0.0001
}

/// The span of an item plus the blanks after it, for a fix that removes it.
/// When nothing but the end of the line follows, the blanks before it go
/// instead, so that no stray blank is left at the end of the block.
pub fn removal_span(program: &Program, span: Span) -> Span {
    let blank = |b: Option<u8>| matches!(b, Some(b' ') | Some(b'\t'));
    let mut end = span.end as usize;
    while blank(program.byte_at(end)) {
        end += 1;
    }
    let line_ends = matches!(
        program.byte_at(end),
        None | Some(b'\n') | Some(b'\r') | Some(b';')
    );
    // A `;` ends a block only in FANUC and ServoWorks; in RS274/NGC it starts a comment.
    let line_ends =
        line_ends && !(program.dialect == Dialect::Rs274ngc && program.byte_at(end) == Some(b';'));
    if !line_ends {
        return Span::new(span.start, end as u32);
    }
    let mut start = span.start as usize;
    while start > program.base as usize && blank(program.byte_at(start - 1)) {
        start -= 1;
    }
    // An item alone on its line keeps the line's indentation rule simple: only
    // the blanks after it go.
    if start == program.base as usize
        || matches!(program.byte_at(start - 1), Some(b'\n') | Some(b'\r'))
    {
        return Span::new(span.start, end as u32);
    }
    Span::new(start as u32, end as u32)
}

/// The edit that adds `code` as a block of its own after the last block that
/// holds code, using the file's own line break and, where the file ends its
/// blocks with `;` (FANUC), a `;` too.
pub fn append_block_edit(program: &Program, code: &str) -> crate::diagnostic::TextEdit {
    let text = &program.text;
    let crlf = text.windows(2).any(|w| w == b"\r\n");
    let nl = if crlf { "\r\n" } else { "\n" };
    let semi =
        program.dialect == Dialect::Fanuc && text.windows(2).any(|w| w == b";\n" || w == b";\r");
    let eob = if semi { ";" } else { "" };
    let last = program
        .blocks
        .iter()
        .rev()
        .find(|b| has_code_items(program, b) && b.kind == crate::syntax::BlockKind::Normal);
    // Right after the last code block's terminator: a `%` or more blocks on
    // the same line stay after the new block.
    let at = last.map_or(text.len(), |b| b.term_end as usize);
    // A lone CR ends a line too; a `\n` after it would make a CR LF of it.
    let line_start = at == 0 || matches!(text.get(at - 1), Some(b'\n') | Some(b'\r'));
    // What follows on the same line (`G00 X1.; %`) goes on a line of its own.
    let rest_of_line = text[at.min(text.len())..]
        .iter()
        .take_while(|b| !matches!(b, b'\n' | b'\r'))
        .any(|b| !b.is_ascii_whitespace());
    let (lead, tail) = match (line_start, at >= text.len()) {
        (true, _) => ("", nl),
        (false, true) => (nl, nl),
        (false, false) if rest_of_line => (nl, nl),
        (false, false) => (nl, ""),
    };
    crate::diagnostic::TextEdit {
        span: Span::new(at as u32, at as u32),
        new_text: format!("{lead}{code}{eob}{tail}"),
    }
}

/// Drilling cycles by code number in tenths (RS274/NGC G76 is threading).
pub fn is_drilling_cycle(d: Dialect, tenths: u32) -> bool {
    match tenths {
        730 | 740 | 810 | 820 | 830 | 840 | 850 | 860 | 870 | 880 | 890 => true,
        760 => d != Dialect::Rs274ngc,
        _ => false,
    }
}

/// Whether a block has a literal word of `letter` with value `v`.
pub fn block_has_word_value(program: &Program, b: &Block, letter: u8, v: f64) -> bool {
    program
        .words(b)
        .any(|(_, w)| w.letter == letter && !w.comma && lit(w) == Some(v))
}

/// The G code values (in tenths) written as literals in a block.
pub fn block_g_codes(program: &Program, b: &Block) -> Vec<u32> {
    program
        .words(b)
        .filter(|(_, w)| w.letter == b'G' && !w.comma)
        .filter_map(|(_, w)| lit(w))
        .filter_map(CodeNum::from_value)
        .map(|n| n.0)
        .collect()
}

/// Whether a block has an axis word of the machine.
pub fn block_has_axis(program: &Program, b: &Block, settings: &Settings) -> bool {
    program
        .words(b)
        .any(|(_, w)| !w.comma && is_machine_axis(settings, w.letter))
}

/// The root expressions of a block: word values, assignment sides, O-word
/// arguments and macro statement operands.
pub fn block_exprs(program: &Program, items: &[Item]) -> Vec<crate::syntax::ExprId> {
    use crate::syntax::MacroStmt as M;
    let mut out = Vec::new();
    for item in items {
        match item.kind {
            ItemKind::Word(Word {
                value: WordValue::Expr(e),
                ..
            }) => out.push(e),
            ItemKind::Assign { target, value } => out.extend([target, value]),
            ItemKind::OWord(o) => out.extend(program.expr_list(o.args()).iter().copied()),
            ItemKind::Macro(m) => match m {
                M::Goto { target } => out.push(target),
                M::IfGoto { cond, target } => out.extend([cond, target]),
                M::IfThen { cond } => out.push(cond),
                M::While { cond, m } => out.extend([cond, m]),
                M::Do { m } | M::End { m } => out.push(m),
                M::Output => {}
            },
            _ => {}
        }
    }
    out
}

/// The direct children of an expression node.
pub fn expr_children(program: &Program, id: crate::syntax::ExprId) -> Vec<crate::syntax::ExprId> {
    use crate::syntax::Expr as E;
    match program.expr(id).expr {
        E::Var { index } => vec![index],
        E::Neg { arg } | E::Plus { arg } => vec![arg],
        E::Binary { lhs, rhs, .. } => vec![lhs, rhs],
        E::Call { arg, arg2, .. } => std::iter::once(arg).chain(arg2).collect(),
        E::Group { inner } => vec![inner],
        E::Num(_) | E::Named { .. } | E::Error => Vec::new(),
    }
}

/// Every node of an expression tree, parents before children.
pub fn expr_nodes(program: &Program, root: crate::syntax::ExprId) -> Vec<crate::syntax::ExprId> {
    let mut out = Vec::new();
    let mut stack = vec![root];
    while let Some(id) = stack.pop() {
        // Guards against malformed trees; the parser caps depth at 64 anyway.
        if out.len() > 100_000 {
            break;
        }
        out.push(id);
        stack.extend(expr_children(program, id));
    }
    out
}

/// A plain block: one line of literal words such as `G1 X1.5 Y2 F300`, the
/// bulk of CAM output. No whole-file rule distinguishes two plain blocks in
/// a row: they hold no O-word, N, M or program head, no comment, expression
/// or assignment, are not `%` or block-delete lines, and (with their line
/// break) are at most 80 bytes, below every line-length limit. The
/// whole-file rules visit a run of them once ([`super::ProgramCx::segments`]).
pub fn is_plain(program: &Program, b: &Block) -> bool {
    plain_from(program, b, 0)
}

/// A plain block but for a literal sequence number first (`N120 G1 X1.5`,
/// the lines of Fusion-style output). In a file without branches only the
/// sequence-number rule reads such a block's number, so a host reading the
/// file in windows may treat a run of them as the whole-file rules treat a
/// run of plain blocks (`crate::stream`).
pub fn is_numbered_plain(program: &Program, b: &Block) -> bool {
    let numbered = program.items_of(b).first().is_some_and(|it| {
        matches!(&it.kind, ItemKind::Word(w)
            if w.letter == b'N' && !w.comma && matches!(w.value, WordValue::Num(_)))
    });
    numbered && plain_from(program, b, 1)
}

/// [`is_plain`] of the block's items after the first `skip`.
fn plain_from(program: &Program, b: &Block, skip: usize) -> bool {
    if b.kind != crate::syntax::BlockKind::Normal
        || b.skip().is_some()
        || b.end().end.saturating_sub(b.span.start) > 80
        // Ends its line, so no line holds two blocks.
        || b.end().end == 0
        || program.byte_at(b.end().end as usize - 1) != Some(b'\n')
    {
        return false;
    }
    let items = program.items_of(b).get(skip..).unwrap_or_default();
    !items.is_empty()
        && items.iter().all(|it| match &it.kind {
            ItemKind::Word(w) => {
                !w.comma
                    && matches!(w.value, WordValue::Num(_))
                    && w.letter.is_ascii_uppercase()
                    && !matches!(w.letter, b'N' | b'M' | b'O')
            }
            _ => false,
        })
}

/// RS274/NGC blocks the interpreter never reads: top-level lines after an
/// `M2`/`M30` that is itself outside every O-word block (an `M30` inside an `if`
/// may not run). Subroutine definitions further down stay reachable, because a
/// call searches the file for them, and so do Fanuc-style `O…` programs.
/// Other dialects: none.
/// FANUC blocks the control never reads: those after an unconditional `GOTO`, `M99`,
/// `M02` or `M30` up to the next sequence number or program head (a branch can only
/// land on a numbered block). A sequence search skips them unread, so their syntax
/// never raises an alarm.
pub fn jumped_over_blocks(program: &Program) -> Vec<bool> {
    use crate::dialect::Dialect;
    use crate::syntax::MacroStmt;
    let mut over = vec![false; program.blocks.len()];
    if program.dialect != Dialect::Fanuc {
        return over;
    }
    let mut skipping = false;
    for (i, b) in program.blocks.iter().enumerate() {
        let items = program.items_of(b);
        let entry = items.iter().any(|it| match it.kind {
            ItemKind::ProgramHead { .. } => true,
            ItemKind::Word(w) => w.letter == b'N',
            _ => false,
        });
        if entry {
            skipping = false;
        }
        if skipping {
            over[i] = true;
            continue;
        }
        // A block-delete slash makes the transfer depend on a switch.
        let skip_slash = b.skip().is_some();
        let leaves = !skip_slash
            && items.iter().any(|it| match it.kind {
                ItemKind::Macro(MacroStmt::Goto { .. }) => true,
                ItemKind::Word(w) => {
                    w.letter == b'M'
                        && w.num()
                            .is_some_and(|n| matches!(n.value, 2.0 | 30.0 | 99.0))
                        && !items
                            .iter()
                            .any(|o| matches!(o.kind, ItemKind::Word(p) if p.letter == b'P'))
                }
                _ => false,
            });
        skipping = leaves;
    }
    over
}

pub fn dead_blocks(program: &Program) -> Vec<bool> {
    let segs = super::context::segments_of(program.blocks.iter().map(|b| is_plain(program, b)));
    dead_blocks_in(program, &segs)
}

/// [`dead_blocks`] over known stretches: a run of plain blocks is all dead or
/// all live, since only O-words and M codes change the state.
pub fn dead_blocks_in(program: &Program, segs: &[super::Seg]) -> Vec<bool> {
    use crate::dialect::Dialect;
    use crate::syntax::OKeyword as K;
    let mut dead = vec![false; program.blocks.len()];
    if program.dialect != Dialect::Rs274ngc {
        return dead;
    }
    let mut ended = false;
    // Open O-word blocks: (is a `do`, label text).
    let mut open: Vec<(bool, String)> = Vec::new();
    for seg in segs {
        let i = seg.first;
        let Some(b) = program.blocks.get(i) else {
            break;
        };
        if seg.plain {
            if ended && open.is_empty() {
                if let Some(run) = dead.get_mut(i..i + seg.len) {
                    run.fill(true);
                }
            }
            continue;
        }
        let ow = program.items_of(b).iter().find_map(|it| match it.kind {
            ItemKind::OWord(o) => Some(o),
            _ => None,
        });
        let label = ow
            .map(|o| program.str_of(o.label_span).to_ascii_lowercase())
            .unwrap_or_default();
        match ow.map(|o| o.keyword) {
            // A Fanuc-style `O1000` program header starts a new program; an `o` with
            // no label is only a stray letter in text nobody reads.
            Some(None) if !label.is_empty() => ended = false,
            Some(Some(K::Sub)) => {
                ended = false;
                open.push((false, label.clone()));
            }
            _ => {}
        }
        if ended && open.is_empty() {
            dead[i] = true;
            continue;
        }
        match ow.and_then(|o| o.keyword) {
            Some(K::Do) => open.push((true, label)),
            Some(K::If) | Some(K::Repeat) => open.push((false, label)),
            Some(K::While) if open.last().is_some_and(|(d, l)| *d && *l == label) => {
                open.pop();
            }
            Some(K::While) => open.push((false, label)),
            Some(K::Endsub) | Some(K::Endif) | Some(K::Endwhile) | Some(K::Endrepeat) => {
                open.pop();
            }
            _ => {}
        }
        if open.is_empty()
            && program.words(b).any(|(_, w)| {
                w.letter == b'M' && matches!(lit(w), Some(v) if v == 2.0 || v == 30.0)
            })
        {
            ended = true;
        }
    }
    dead
}

/// Blocks that hold a syntax error (an error-severity parser diagnostic).
pub fn unreadable_blocks(program: &Program) -> Vec<bool> {
    let mut out = vec![false; program.blocks.len()];
    for d in &program.diagnostics {
        if d.severity != crate::diagnostic::Severity::Error {
            continue;
        }
        if let Some(i) = program.block_at(d.span.start) {
            if let Some(flag) = out.get_mut(i) {
                *flag = true;
            }
        }
    }
    out
}
