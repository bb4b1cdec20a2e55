//! Syntax tree types.

use std::sync::Arc;

use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TokenKind {
    /// Spaces and tabs (and form feeds / vertical tabs).
    Whitespace,
    /// `\n`, `\r\n` or `\r`.
    Newline,
    /// `( … )`, possibly unclosed.
    Comment,
    /// A comment to end of line: `; …` in RS274/NGC, a `%` block-delete line in ServoWorks.
    LineComment,
    /// Explicit end of block `;` (ServoWorks, FANUC).
    Eob,
    /// A `%` tape/demarcation line.
    Percent,
    /// `/` or `/n` block skip at the start of a block.
    BlockSkip,
    /// An address letter.
    Letter,
    /// A numeric literal (in RS274/NGC and FANUC it may contain blanks).
    Number,
    /// `#` introducing a parameter/variable reference.
    Hash,
    /// `#<name>` named parameter (RS274/NGC).
    NamedParam,
    LBracket,
    RBracket,
    /// `+ - * / ** =`
    Operator,
    Comma,
    /// Function, operator and keyword names (`SIN`, `MOD`, `GOTO`, `sub`, …).
    Keyword,
    /// A program/subprogram name (`MoveXY`, `<name>`).
    Name,
    /// Text the control ignores (ServoWorks lower case, data after `;`, FANUC leader).
    Ignored,
    /// Literal text a statement sends out unchanged (`DPRNT[X#101[53]*MM]`).
    Text,
    /// Bytes that are not part of the language.
    Unknown,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Token {
    pub start: u32,
    pub kind: TokenKind,
}

/// A numeric literal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num {
    pub value: f64,
    pub span: Span,
    /// Whether the literal has a decimal point (`10.` or `1.5`).
    pub has_point: bool,
    /// Whether an explicit `+` or `-` sign was written.
    pub signed: bool,
    /// Number of digits written (integer + fraction).
    pub digits: u16,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExprId(pub u32);

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Pow,
    And,
    Or,
    Xor,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
}

impl BinOp {
    pub fn as_str(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Mod => "MOD",
            BinOp::Pow => "**",
            BinOp::And => "AND",
            BinOp::Or => "OR",
            BinOp::Xor => "XOR",
            BinOp::Eq => "EQ",
            BinOp::Ne => "NE",
            BinOp::Gt => "GT",
            BinOp::Ge => "GE",
            BinOp::Lt => "LT",
            BinOp::Le => "LE",
        }
    }

    pub fn is_relational(self) -> bool {
        matches!(
            self,
            BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Ge | BinOp::Lt | BinOp::Le
        )
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Func {
    Abs,
    Acos,
    Asin,
    Atan,
    Cos,
    Exp,
    Fix,
    Fup,
    Ln,
    Round,
    Sin,
    Sqrt,
    Tan,
    Exists,
    Bin,
    Bcd,
    Pow,
    Adp,
}

impl Func {
    pub fn from_name(name: &str) -> Option<Func> {
        Some(match name.to_ascii_uppercase().as_str() {
            "ABS" => Func::Abs,
            "ACOS" => Func::Acos,
            "ASIN" => Func::Asin,
            "ATAN" => Func::Atan,
            "COS" => Func::Cos,
            "EXP" => Func::Exp,
            "FIX" => Func::Fix,
            "FUP" => Func::Fup,
            "LN" => Func::Ln,
            "ROUND" => Func::Round,
            "SIN" => Func::Sin,
            "SQRT" => Func::Sqrt,
            "TAN" => Func::Tan,
            "EXISTS" => Func::Exists,
            "BIN" => Func::Bin,
            "BCD" => Func::Bcd,
            "POW" => Func::Pow,
            "ADP" => Func::Adp,
            _ => return None,
        })
    }

    /// Whether the dialect has this function.
    pub fn in_dialect(self, d: Dialect) -> bool {
        match self {
            Func::Exists => d == Dialect::Rs274ngc,
            Func::Bin | Func::Bcd | Func::Pow | Func::Adp => d != Dialect::Rs274ngc,
            _ => true,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Expr {
    Num(Num),
    /// `#n`, `##n`, `#[expr]`: the variable whose number is the value of `index`.
    Var {
        index: ExprId,
    },
    /// `#<name>`; the span of the whole token.
    Named {
        name: Span,
    },
    /// Unary minus or plus.
    Neg {
        arg: ExprId,
    },
    Plus {
        arg: ExprId,
    },
    Binary {
        op: BinOp,
        lhs: ExprId,
        rhs: ExprId,
    },
    /// `NAME[a]`, `ATAN[a]/[b]`, `ATAN[a,b]`, `POW[a,b]`.
    Call {
        func: Func,
        arg: ExprId,
        arg2: Option<ExprId>,
    },
    /// `[ inner ]`
    Group {
        inner: ExprId,
    },
    /// Something that could not be parsed; a diagnostic was emitted.
    Error,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExprNode {
    pub expr: Expr,
    pub span: Span,
}

/// The value of a word.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WordValue {
    Num(Num),
    /// A parameter, expression or function value.
    Expr(ExprId),
    /// A name (`M98 PMoveXY` in ServoWorks).
    Name(Span),
    /// The letter had no value; a diagnostic was emitted.
    Missing,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// Upper-case address letter (`b'$'`, `b'@'`, `b'^'` for RS274/NGC's extra words).
    pub letter: u8,
    /// Written after a comma (`,C` / `,R` chamfer and corner in FANUC).
    pub comma: bool,
    /// `S2_1500` (ServoWorks multi-spindle): the spindle number; the value is the speed.
    pub spindle: Option<u16>,
    pub value: WordValue,
}

// The syntax tree holds one `Item` per word: its size is most of the tree's memory.
// A word fits 32 bytes (the item kind's tag goes into a niche of `comma`), so every
// other item kind must fit beside it; this assertion keeps it so.
const _: () = assert!(std::mem::size_of::<Item>() <= 40);

impl Word {
    /// The literal numeric value, if the word has one.
    pub fn num(&self) -> Option<&Num> {
        match &self.value {
            WordValue::Num(n) => Some(n),
            _ => None,
        }
    }

    /// The span of the address letter, given the word's item span.
    pub fn letter_span(&self, item: Span) -> Span {
        let at = item.start + u32::from(self.comma);
        Span::new(at, at + 1)
    }

    pub fn letter_char(&self) -> char {
        self.letter as char
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CommentKind {
    Plain,
    Msg,
    Debug,
    Print,
    Log,
    LogOpen,
    LogAppend,
    LogClose,
    Abort,
    ProbeOpen,
    ProbeClose,
    Py,
    /// `(partscope: …)` directive.
    Partscope,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OKeyword {
    Sub,
    Endsub,
    Return,
    Call,
    Do,
    While,
    Endwhile,
    Break,
    Continue,
    If,
    Elseif,
    Else,
    Endif,
    Repeat,
    Endrepeat,
}

impl OKeyword {
    pub fn from_name(s: &str) -> Option<OKeyword> {
        Some(match s.to_ascii_lowercase().as_str() {
            "sub" => OKeyword::Sub,
            "endsub" => OKeyword::Endsub,
            "return" => OKeyword::Return,
            "call" => OKeyword::Call,
            "do" => OKeyword::Do,
            "while" => OKeyword::While,
            "endwhile" => OKeyword::Endwhile,
            "break" => OKeyword::Break,
            "continue" => OKeyword::Continue,
            "if" => OKeyword::If,
            "elseif" => OKeyword::Elseif,
            "else" => OKeyword::Else,
            "endif" => OKeyword::Endif,
            "repeat" => OKeyword::Repeat,
            "endrepeat" => OKeyword::Endrepeat,
            _ => return None,
        })
    }

    pub fn as_str(self) -> &'static str {
        match self {
            OKeyword::Sub => "sub",
            OKeyword::Endsub => "endsub",
            OKeyword::Return => "return",
            OKeyword::Call => "call",
            OKeyword::Do => "do",
            OKeyword::While => "while",
            OKeyword::Endwhile => "endwhile",
            OKeyword::Break => "break",
            OKeyword::Continue => "continue",
            OKeyword::If => "if",
            OKeyword::Elseif => "elseif",
            OKeyword::Else => "else",
            OKeyword::Endif => "endif",
            OKeyword::Repeat => "repeat",
            OKeyword::Endrepeat => "endrepeat",
        }
    }
}

/// The label of an O-word: `o100` or `o<name>`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OLabel {
    Number(u32),
    /// `o<name>`: the name lies between the `<` and `>` of the label span
    /// ([`OWord::name_span`]).
    Name,
    /// Computed label (`o#1`, `o[…]`).
    Expr(ExprId),
    Missing,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OWord {
    pub label: OLabel,
    pub label_span: Span,
    pub keyword: Option<OKeyword>,
    /// First of the arguments in [`Program::expr_lists`].
    pub args_start: u32,
    /// Number of arguments (a call with more is cut at `u16::MAX`).
    pub args_len: u16,
}

impl OWord {
    /// Range of the arguments in [`Program::expr_lists`].
    pub fn args(&self) -> (u32, u32) {
        (self.args_start, self.args_start + u32::from(self.args_len))
    }

    /// The name of an `o<name>` label, without its brackets.
    pub fn name_span(&self) -> Span {
        let s = self.label_span;
        Span::new(
            (s.start + 1).min(s.end),
            s.end.saturating_sub(1).max(s.start),
        )
    }
}

/// FANUC Custom Macro B (and ServoWorks macro) statements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MacroStmt {
    /// `GOTO n`
    Goto { target: ExprId },
    /// `IF [cond] GOTO n`
    IfGoto { cond: ExprId, target: ExprId },
    /// `IF [cond] THEN` — the statement follows as the next item of the block.
    IfThen { cond: ExprId },
    /// `WHILE [cond] DO m`
    While { cond: ExprId, m: ExprId },
    /// `DO m` without WHILE (endless loop).
    Do { m: ExprId },
    /// `END m`
    End { m: ExprId },
    /// `POPEN`, `PCLOS`, `DPRNT[…]`, `BPRNT[…]`: external output, not interpreted.
    Output,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ItemKind {
    Word(Word),
    /// `#n = expr` / `#<name> = expr`; `target` is a `Var` or `Named` node.
    Assign {
        target: ExprId,
        value: ExprId,
    },
    Comment(CommentKind),
    OWord(OWord),
    Macro(MacroStmt),
    /// A program head: `O1234`, `:1234`, `OMoveXY`, `<name>`. `name` is the span of the
    /// number or name after the `O`.
    ProgramHead {
        name: Span,
        number: Option<u32>,
    },
    /// Input that could not be parsed (a diagnostic was emitted).
    Error,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Item {
    pub kind: ItemKind,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BlockKind {
    Normal,
    /// A `%` line (tape start/end or RS274/NGC demarcation).
    Percent,
    /// A ServoWorks `%` block-delete line: a comment.
    Deleted,
    /// FANUC leader after the first `%`, or text after the closing `%`.
    Ignored,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block {
    /// The block's content, without its terminator.
    pub span: Span,
    /// Where the terminator (newline, `;`, `;` + newline, or nothing at end of file)
    /// ends; it starts at `span.end` ([`Block::end`]).
    pub term_end: u32,
    /// 0-based physical line of the block's first byte.
    pub line: u32,
    pub kind: BlockKind,
    /// Block skip switch number (1 for a bare `/`), 0 when the block has none
    /// ([`Block::skip`]).
    pub skip_level: u8,
    /// Length of the block skip mark (`/` or `/n`).
    pub skip_len: u8,
    /// Where the block skip mark starts.
    pub skip_at: u32,
    /// Range into [`Program::items`].
    pub items: (u32, u32),
}

// One `Block` per line: kept to 32 bytes (spans as offsets, the skip mark unboxed).
const _: () = assert!(std::mem::size_of::<Block>() <= 32);

impl Block {
    /// The terminator: newline, `;`, `;` + newline, or empty at end of file.
    pub fn end(&self) -> Span {
        Span::new(self.span.end, self.term_end.max(self.span.end))
    }

    /// Block skip `/` or `/n`: its span and switch number (1 for a bare `/`).
    pub fn skip(&self) -> Option<(Span, u8)> {
        (self.skip_level > 0).then(|| {
            (
                Span::new(self.skip_at, self.skip_at + u32::from(self.skip_len)),
                self.skip_level,
            )
        })
    }

    /// Sets or clears the block skip mark.
    pub fn set_skip(&mut self, skip: Option<(Span, u8)>) {
        match skip {
            Some((s, level)) => {
                self.skip_at = s.start;
                self.skip_len = s.len().min(u32::from(u8::MAX)) as u8;
                self.skip_level = level.max(1);
            }
            None => {
                self.skip_at = 0;
                self.skip_len = 0;
                self.skip_level = 0;
            }
        }
    }

    pub fn full_span(&self) -> Span {
        self.span.cover(self.end())
    }
}

/// A parsed file: flat vectors indexed by `u32`.
#[derive(Debug, Clone)]
pub struct Program {
    pub dialect: Dialect,
    /// The bytes this tree was parsed from: the whole file, or one window of it
    /// starting at file offset [`Program::base`].
    pub text: Arc<[u8]>,
    /// File offset of `text[0]`: 0 for a whole file. Spans and lines are the
    /// file's, so a window's findings need no translation ([`Program::rebase`]).
    pub base: u32,
    pub tokens: Vec<Token>,
    pub blocks: Vec<Block>,
    pub items: Vec<Item>,
    pub exprs: Vec<ExprNode>,
    pub expr_lists: Vec<ExprId>,
    /// Syntax diagnostics.
    pub diagnostics: Vec<Diagnostic>,
}

impl Program {
    /// An RS274/NGC subroutine library: `o<name> sub … endsub` definitions, and
    /// outside them nothing but comments, parameter assignments (a library may
    /// initialise its globals) and `%` lines. LinuxCNC calls it by name and
    /// never reads it as a main program, so it needs no M2.
    /// The number expression of a bare variable reference (`#n`, `#[e]`), through
    /// any brackets around it; `None` for anything else.
    pub fn variable_index(&self, e: ExprId) -> Option<ExprId> {
        match self.expr(e).expr {
            Expr::Group { inner } => self.variable_index(inner),
            Expr::Var { index } => Some(index),
            _ => None,
        }
    }

    pub fn is_ngc_library(&self) -> bool {
        self.is_ngc_library_named(None)
    }

    /// [`Program::is_ngc_library`] for the file `stem`: LinuxCNC finds a subroutine
    /// file by the subroutine's name, so a file of definitions none of which is named
    /// after the file is no library anyone can call — run, it ends without M2.
    pub fn is_ngc_library_named(&self, stem: Option<&str>) -> bool {
        if !self.is_ngc_library_any() {
            return false;
        }
        let Some(stem) = stem else { return true };
        self.items.iter().any(|it| match it.kind {
            ItemKind::OWord(o) if o.keyword == Some(OKeyword::Sub) && o.label == OLabel::Name => {
                self.str_of(o.name_span())
                    .trim()
                    .eq_ignore_ascii_case(stem.trim())
            }
            _ => false,
        })
    }

    fn is_ngc_library_any(&self) -> bool {
        if self.dialect != Dialect::Rs274ngc {
            return false;
        }
        let (mut depth, mut subs) = (0usize, 0usize);
        for b in &self.blocks {
            if b.kind != BlockKind::Normal {
                continue;
            }
            for it in self.items_of(b) {
                match it.kind {
                    ItemKind::Comment(_) => {}
                    ItemKind::OWord(o) if o.keyword == Some(OKeyword::Sub) => {
                        depth += 1;
                        subs += 1;
                    }
                    ItemKind::OWord(o) if o.keyword == Some(OKeyword::Endsub) => {
                        depth = depth.saturating_sub(1);
                    }
                    _ if depth > 0 => {}
                    ItemKind::Assign { .. } => {}
                    // Code outside every definition: the file is a main program.
                    _ => return false,
                }
            }
        }
        subs > 0
    }

    pub fn items_of(&self, block: &Block) -> &[Item] {
        self.items
            .get(block.items.0 as usize..block.items.1 as usize)
            .unwrap_or(&[])
    }

    pub fn expr(&self, id: ExprId) -> &ExprNode {
        static ERROR: ExprNode = ExprNode {
            expr: Expr::Error,
            span: Span { start: 0, end: 0 },
        };
        self.exprs.get(id.0 as usize).unwrap_or(&ERROR)
    }

    pub fn expr_list(&self, range: (u32, u32)) -> &[ExprId] {
        self.expr_lists
            .get(range.0 as usize..range.1 as usize)
            .unwrap_or(&[])
    }

    pub fn slice(&self, span: Span) -> &[u8] {
        if self.base == 0 {
            return span.slice(&self.text);
        }
        let (Some(start), Some(end)) = (
            span.start.checked_sub(self.base),
            span.end.checked_sub(self.base),
        ) else {
            return &[];
        };
        Span::new(start, end).slice(&self.text)
    }

    /// The byte at file offset `at`, if this tree's text holds it.
    pub fn byte_at(&self, at: usize) -> Option<u8> {
        self.text.get(at.checked_sub(self.base as usize)?).copied()
    }

    /// File offset just past the last byte of this tree's text.
    pub fn end_offset(&self) -> u32 {
        self.base.saturating_add(self.text.len() as u32)
    }

    /// Moves every position of the tree by `bytes` and its lines by `lines`:
    /// a window parsed on its own gets the file's spans and lines, so every
    /// rule and the interpreter read it as they read the whole file.
    pub fn rebase(&mut self, bytes: u32, lines: u32) {
        let sp = |s: &mut Span| {
            s.start = s.start.saturating_add(bytes);
            s.end = s.end.saturating_add(bytes);
        };
        self.base = self.base.saturating_add(bytes);
        for t in &mut self.tokens {
            t.start = t.start.saturating_add(bytes);
        }
        for b in &mut self.blocks {
            sp(&mut b.span);
            b.term_end = b.term_end.saturating_add(bytes);
            if b.skip_level > 0 {
                b.skip_at = b.skip_at.saturating_add(bytes);
            }
            b.line = b.line.saturating_add(lines);
        }
        for it in &mut self.items {
            sp(&mut it.span);
            match &mut it.kind {
                ItemKind::Word(w) => match &mut w.value {
                    WordValue::Num(n) => sp(&mut n.span),
                    WordValue::Name(s) => sp(s),
                    WordValue::Expr(_) | WordValue::Missing => {}
                },
                ItemKind::OWord(o) => sp(&mut o.label_span),
                ItemKind::ProgramHead { name, .. } => sp(name),
                ItemKind::Assign { .. }
                | ItemKind::Comment(_)
                | ItemKind::Macro(_)
                | ItemKind::Error => {}
            }
        }
        for e in &mut self.exprs {
            sp(&mut e.span);
            match &mut e.expr {
                Expr::Num(n) => sp(&mut n.span),
                Expr::Named { name } => sp(name),
                _ => {}
            }
        }
        for d in &mut self.diagnostics {
            d.shift(bytes);
        }
    }

    /// The text of a span, lossily decoded.
    pub fn str_of(&self, span: Span) -> std::borrow::Cow<'_, str> {
        String::from_utf8_lossy(self.slice(span))
    }

    pub fn token_span(&self, i: usize) -> Span {
        let start = self.tokens[i].start;
        let end = self
            .tokens
            .get(i + 1)
            .map(|t| t.start)
            .unwrap_or(self.end_offset());
        Span::new(start, end)
    }

    /// Reassembles the source from the tokens. Equal to the input for every input.
    pub fn print(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.text.len());
        for i in 0..self.tokens.len() {
            out.extend_from_slice(self.slice(self.token_span(i)));
        }
        out
    }

    /// The words of a block.
    pub fn words<'a>(
        &'a self,
        block: &'a Block,
    ) -> impl Iterator<Item = (&'a Item, &'a Word)> + 'a {
        self.items_of(block).iter().filter_map(|it| match &it.kind {
            ItemKind::Word(w) => Some((it, w)),
            _ => None,
        })
    }

    /// The index of the block containing `offset` (binary search).
    pub fn block_at(&self, offset: u32) -> Option<usize> {
        if self.blocks.is_empty() {
            return None;
        }
        let i = self.blocks.partition_point(|b| b.span.start <= offset);
        Some(i.saturating_sub(1))
    }
}
