//! Per-file indexes: O-word control structures, subprogram labels, program
//! heads, sequence numbers and Macro B `DO`/`END` pairs.

use std::collections::HashMap;
use std::sync::Arc;

use analyzer::rules::BAD_EXPRESSION;
use analyzer::syntax::{Expr, ItemKind, MacroStmt, OKeyword, OLabel, Program};
use analyzer::FileId;

/// A parsed program, borrowed (the main file) or shared (resolved files).
#[derive(Clone)]
pub enum ProgRef<'a> {
    Borrowed(&'a Program),
    Shared(Arc<Program>),
}

impl std::ops::Deref for ProgRef<'_> {
    type Target = Program;
    fn deref(&self) -> &Program {
        match self {
            ProgRef::Borrowed(p) => p,
            ProgRef::Shared(p) => p,
        }
    }
}

/// Partner blocks of an O-word statement.
#[derive(Debug, Clone, Default)]
pub struct Ctrl {
    /// sub → endsub, while → endwhile, do → closing while, closing while → do,
    /// repeat → endrepeat, if → endif, endwhile/endrepeat → loop head,
    /// break/continue → loop head, elseif/else → endif.
    pub partner: Option<u32>,
    /// For `if`: the `elseif` and `else` blocks in order.
    pub branches: Vec<u32>,
    /// For `while`: whether it closes a `do`.
    pub closes_do: bool,
}

pub struct FileEntry<'a> {
    pub prog: ProgRef<'a>,
    pub id: FileId,
    pub ctrl: HashMap<u32, Ctrl>,
    /// NGC subroutine label key → `sub` block.
    pub subs: HashMap<String, u32>,
    /// FANUC/ServoWorks program number → head block.
    pub heads: HashMap<u32, u32>,
    /// Sequence number → blocks carrying it.
    pub seq: HashMap<u64, Vec<u32>>,
    /// Macro B loop pairs: WHILE/DO block ↔ END block.
    pub loops: HashMap<u32, u32>,
    /// Blocks with a syntax error (the control stops there).
    pub error_blocks: std::collections::HashSet<u32>,
    /// The file branches to sequence numbers (GOTO, IF … GOTO, M99 P, M97 P), so a
    /// numbered block may run although nothing before it leads there.
    pub branches: bool,
    /// The file holds a tapping cycle (G84 or G74): only then is its M29 the
    /// rigid-tapping M code (on some machines M29 is a builder's M code).
    pub taps: bool,
    /// The file returns to a caller somewhere (M99): run as the main program, its
    /// locals #1–#33 may be the arguments of a G65 call the check does not see.
    pub returns: bool,
    /// A called file that looks written for another control (`P010`): its text is
    /// not FANUC's, so a call of it is skipped instead of run.
    pub foreign: bool,
}

/// A tapping cycle, G84 or G74 ([`FileEntry::taps`]).
pub fn is_tapping_cycle(w: &analyzer::syntax::Word) -> bool {
    w.letter == b'G' && w.num().is_some_and(|n| n.value == 84.0 || n.value == 74.0)
}

/// The key of an O-word label (`100`, `name`).
pub fn label_key(p: &Program, ow: &analyzer::syntax::OWord) -> Option<String> {
    match ow.label {
        OLabel::Number(n) => Some(n.to_string()),
        OLabel::Name => Some(p.str_of(ow.name_span()).trim().to_ascii_lowercase()),
        _ => None,
    }
}

fn literal(p: &Program, id: analyzer::syntax::ExprId) -> Option<f64> {
    match p.expr(id).expr {
        Expr::Num(n) => Some(n.value),
        Expr::Group { inner } => literal(p, inner),
        _ => None,
    }
}

impl<'a> FileEntry<'a> {
    pub fn new(prog: ProgRef<'a>, id: FileId) -> FileEntry<'a> {
        let mut f = FileEntry {
            prog,
            id,
            ctrl: HashMap::new(),
            subs: HashMap::new(),
            heads: HashMap::new(),
            seq: HashMap::new(),
            loops: HashMap::new(),
            error_blocks: Default::default(),
            branches: false,
            taps: false,
            returns: false,
            foreign: false,
        };
        f.index();
        let p = f.prog.clone();
        for d in &p.diagnostics {
            // A bare O-word (`O1`, `O<name>`) is a program title or M98 target for
            // LinuxCNC 2.9, which runs on; the parser's L010 is stricter.
            if d.severity == analyzer::Severity::Error && d.code != BAD_EXPRESSION.code {
                if let Some(b) = p.block_at(d.span.start) {
                    f.error_blocks.insert(b as u32);
                }
            }
        }
        f
    }

    fn index(&mut self) {
        let p = self.prog.clone();
        // Open O-word structures: (label, keyword, block).
        let mut stack: Vec<(String, OKeyword, u32)> = Vec::new();
        let mut do_stack: Vec<(i64, u32)> = Vec::new();
        for (bi, block) in p.blocks.iter().enumerate() {
            let bi = bi as u32;
            for item in p.items_of(block) {
                match &item.kind {
                    ItemKind::Word(w) if w.letter == b'N' => {
                        if let Some(n) = w.num() {
                            if n.value >= 0.0 {
                                self.seq.entry(n.value as u64).or_default().push(bi);
                            }
                        }
                    }
                    ItemKind::ProgramHead { number, name } => {
                        if let Some(n) = number {
                            self.heads.entry(*n).or_insert(bi);
                        } else if let Ok(n) = p.str_of(*name).trim().parse::<u32>() {
                            self.heads.entry(n).or_insert(bi);
                        }
                    }
                    ItemKind::Macro(MacroStmt::Goto { .. } | MacroStmt::IfGoto { .. }) => {
                        self.branches = true;
                    }
                    ItemKind::Word(w) if is_tapping_cycle(w) => {
                        self.taps = true;
                    }
                    ItemKind::Word(w)
                        if w.letter == b'M' && w.num().is_some_and(|n| n.value == 99.0) =>
                    {
                        self.returns = true;
                        if p.words(block).any(|(_, w)| w.letter == b'P') {
                            self.branches = true;
                        }
                    }
                    ItemKind::Word(w)
                        if w.letter == b'P'
                            && p.words(block).any(|(_, m)| {
                                m.letter == b'M'
                                    && m.num().is_some_and(|n| n.value == 99.0 || n.value == 97.0)
                            }) =>
                    {
                        self.branches = true;
                    }
                    ItemKind::Macro(MacroStmt::While { m, .. })
                    | ItemKind::Macro(MacroStmt::Do { m }) => {
                        do_stack.push((literal(&p, *m).unwrap_or(-1.0) as i64, bi));
                    }
                    ItemKind::Macro(MacroStmt::End { m }) => {
                        let m = literal(&p, *m).unwrap_or(-1.0) as i64;
                        if let Some(pos) = do_stack.iter().rposition(|(k, _)| *k == m) {
                            let (_, head) = do_stack.remove(pos);
                            do_stack.truncate(pos);
                            self.loops.insert(head, bi);
                            self.loops.insert(bi, head);
                        }
                    }
                    ItemKind::OWord(ow) => {
                        let Some(kw) = ow.keyword else {
                            // `O1` alone starts a FANUC-style program (LinuxCNC M98 subs).
                            if let OLabel::Number(n) = ow.label {
                                self.heads.entry(n).or_insert(bi);
                            }
                            continue;
                        };
                        let Some(key) = label_key(&p, ow) else {
                            continue;
                        };
                        self.index_oword(&mut stack, key, kw, bi);
                    }
                    _ => {}
                }
            }
        }
    }

    fn index_oword(
        &mut self,
        stack: &mut Vec<(String, OKeyword, u32)>,
        key: String,
        kw: OKeyword,
        bi: u32,
    ) {
        let find = |stack: &Vec<(String, OKeyword, u32)>, kws: &[OKeyword]| {
            stack
                .iter()
                .rposition(|(k, w, _)| *k == key && kws.contains(w))
        };
        match kw {
            OKeyword::Sub => {
                self.subs.entry(key.clone()).or_insert(bi);
                stack.push((key, kw, bi));
            }
            OKeyword::Do | OKeyword::Repeat | OKeyword::If => stack.push((key, kw, bi)),
            OKeyword::While => {
                if let Some(pos) = find(stack, &[OKeyword::Do]).filter(|p| *p + 1 == stack.len()) {
                    let (_, _, head) = stack.remove(pos);
                    self.ctrl.entry(head).or_default().partner = Some(bi);
                    let c = self.ctrl.entry(bi).or_default();
                    c.partner = Some(head);
                    c.closes_do = true;
                } else {
                    stack.push((key, kw, bi));
                }
            }
            OKeyword::Endsub | OKeyword::Endwhile | OKeyword::Endrepeat | OKeyword::Endif => {
                let open = match kw {
                    OKeyword::Endsub => OKeyword::Sub,
                    OKeyword::Endwhile => OKeyword::While,
                    OKeyword::Endrepeat => OKeyword::Repeat,
                    _ => OKeyword::If,
                };
                if let Some(pos) = find(stack, &[open]) {
                    let (_, _, head) = stack.remove(pos);
                    stack.truncate(pos);
                    self.ctrl.entry(head).or_default().partner = Some(bi);
                    self.ctrl.entry(bi).or_default().partner = Some(head);
                    if open == OKeyword::If {
                        let branches = self
                            .ctrl
                            .get(&head)
                            .map(|c| c.branches.clone())
                            .unwrap_or_default();
                        for b in branches {
                            self.ctrl.entry(b).or_default().partner = Some(bi);
                        }
                    }
                }
            }
            OKeyword::Elseif | OKeyword::Else => {
                if let Some(pos) = find(stack, &[OKeyword::If]) {
                    let head = stack[pos].2;
                    self.ctrl.entry(head).or_default().branches.push(bi);
                }
            }
            OKeyword::Break | OKeyword::Continue => {
                if let Some(pos) = find(stack, &[OKeyword::While, OKeyword::Do, OKeyword::Repeat]) {
                    let head = stack[pos].2;
                    self.ctrl.entry(bi).or_default().partner = Some(head);
                }
            }
            OKeyword::Return | OKeyword::Call => {}
        }
    }
}

/// A subprogram file, which only its callers can run meaningfully: an
/// RS274/NGC library ([`Program::is_ngc_library`]), or a FANUC/ServoWorks file that
/// returns with M99 and never ends with M2/M30 (run on its own, M99 would
/// restart it forever, and its arguments `#1`… would be vacant).
pub fn is_subprogram_file(program: &Program, stem: Option<&str>) -> bool {
    use analyzer::syntax::ItemKind;
    if program.dialect == analyzer::Dialect::Rs274ngc {
        return program.is_ngc_library_named(stem);
    }
    let m = |v: f64| {
        program.items.iter().any(|it| match &it.kind {
            ItemKind::Word(w) => w.letter == b'M' && w.num().is_some_and(|n| n.value == v),
            _ => false,
        })
    };
    // O9000–O9029 are the programs the control calls for T, M and G codes
    // (parameters 6050–6089): they return with M99 whatever else they hold.
    let head = program.items.iter().find_map(|it| match it.kind {
        ItemKind::ProgramHead { number, .. } => Some(number),
        _ => None,
    });
    let code_macro = program.dialect == analyzer::Dialect::Fanuc
        && head.flatten().is_some_and(|n| (9000..=9029).contains(&n));
    m(99.0) && (code_macro || (!m(2.0) && !m(30.0)))
}
