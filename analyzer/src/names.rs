//! Names in a program and where they occur: subprogram labels, program
//! numbers/names, sequence numbers and variables. Pure functions over the
//! syntax tree; go-to-definition, references, completion and hover use them.

use crate::dialect::Dialect;
use crate::syntax::{
    Block, Expr, ExprId, ItemKind, MacroStmt, OKeyword, OLabel, OWord, Program, WordValue,
};
use crate::Span;

/// Something that can be defined once and referenced elsewhere.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Sym {
    /// An RS274/NGC O-word label (`o100`, `o<name>`, lower-cased; names are
    /// case-insensitive there).
    OLabel(String),
    /// A program: FANUC `O1234` (by number, without leading zeros), ServoWorks
    /// `OMoveXY` (by name), FANUC 30i `<NAME>`.
    Program(String),
    /// A sequence number `N100` (target of `GOTO 100`).
    Seq(u32),
    /// A variable: `#1` or `#<name>` (lower-cased).
    Var(String),
}

impl Sym {
    pub fn display(&self) -> String {
        match self {
            Sym::OLabel(l) if l.chars().all(|c| c.is_ascii_digit()) => format!("o{l}"),
            Sym::OLabel(l) => format!("o<{l}>"),
            Sym::Program(p) => format!("O{p}"),
            Sym::Seq(n) => format!("N{n}"),
            Sym::Var(v) => v.clone(),
        }
    }
}

/// One occurrence of a symbol.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Occ {
    pub span: Span,
    pub sym: Sym,
    /// Whether this occurrence defines the symbol (`sub`, a program head, an
    /// `N` word, an assignment target).
    pub def: bool,
    /// For O-word labels: whether this is a `call`.
    pub call: bool,
}

fn program_key(program: &Program, name: Span, number: Option<u32>) -> String {
    match number {
        Some(n) => n.to_string(),
        None => program.str_of(name).trim().to_ascii_uppercase(),
    }
}

fn label_key(program: &Program, ow: &OWord) -> Option<String> {
    match ow.label {
        OLabel::Number(n) => Some(n.to_string()),
        OLabel::Name => Some(program.str_of(ow.name_span()).trim().to_ascii_lowercase()),
        _ => None,
    }
}

/// Whether a block calls a program through its `P` word.
fn calls_program(program: &Program, block: &Block) -> bool {
    program.words(block).any(|(_, w)| {
        let Some(n) = w.num() else { return false };
        match (w.letter, program.dialect) {
            (b'M', _) => n.value == 98.0 || n.value == 198.0,
            (b'G', Dialect::Fanuc | Dialect::Servoworks) => {
                n.value == 65.0 || n.value == 66.0 || n.value == 66.1
            }
            _ => false,
        }
    })
}

fn literal_int(program: &Program, id: ExprId) -> Option<u32> {
    match program.expr(id).expr {
        Expr::Num(n) if n.value >= 0.0 && n.value.fract() == 0.0 && n.value < 1e9 => {
            Some(n.value as u32)
        }
        Expr::Group { inner } => literal_int(program, inner),
        _ => None,
    }
}

/// The variable an expression node names, when it is a literal `#n` or `#<name>`.
pub fn var_of(program: &Program, id: ExprId) -> Option<Sym> {
    let node = program.expr(id);
    match node.expr {
        Expr::Var { index } => literal_int(program, index).map(|n| Sym::Var(format!("#{n}"))),
        Expr::Named { name } => {
            // Names are case-insensitive and blanks inside them do not count.
            let text: String = program
                .str_of(name)
                .chars()
                .filter(|c| !c.is_whitespace() && !matches!(c, '#' | '<' | '>'))
                .collect();
            Some(Sym::Var(format!("#<{}>", text.to_ascii_lowercase())))
        }
        _ => None,
    }
}

/// The occurrences in one block, except variables (see [`var_occurrences`]).
pub fn block_occurrences(program: &Program, block: &Block, out: &mut Vec<Occ>) {
    let calls = calls_program(program, block);
    // FANUC `M98 P<rrrr><pppp>` without L: the digits above the last four
    // are a repeat count (`M98 P50010` runs O0010 five times).
    let packed_repeat = calls
        && program.dialect == Dialect::Fanuc
        && program
            .words(block)
            .any(|(_, w)| w.letter == b'M' && w.num().is_some_and(|n| n.value == 98.0))
        && !program.words(block).any(|(_, w)| w.letter == b'L');
    for item in program.items_of(block) {
        match &item.kind {
            ItemKind::OWord(ow) => {
                let Some(key) = label_key(program, ow) else {
                    continue;
                };
                out.push(Occ {
                    // From the `o` to the end of the label.
                    span: Span::new(item.span.start, ow.label_span.end.max(item.span.start)),
                    sym: Sym::OLabel(key),
                    def: ow.keyword == Some(OKeyword::Sub),
                    call: ow.keyword == Some(OKeyword::Call),
                });
            }
            ItemKind::ProgramHead { name, number } => {
                out.push(Occ {
                    span: item.span,
                    sym: Sym::Program(program_key(program, *name, *number)),
                    def: true,
                    call: false,
                });
            }
            ItemKind::Word(w) if w.letter == b'N' && !w.comma => {
                if let Some(n) = w
                    .num()
                    .filter(|n| n.value >= 0.0 && n.value.fract() == 0.0 && n.value < 1e9)
                {
                    out.push(Occ {
                        span: item.span,
                        sym: Sym::Seq(n.value as u32),
                        def: true,
                        call: false,
                    });
                }
            }
            ItemKind::Word(w) if w.letter == b'P' && !w.comma && calls => {
                let key = match &w.value {
                    WordValue::Name(span) => {
                        Some(program.str_of(*span).trim().to_ascii_uppercase())
                    }
                    WordValue::Num(n)
                        if n.value >= 0.0 && n.value.fract() == 0.0 && n.value < 1e9 =>
                    {
                        let v = n.value as u32;
                        Some(
                            if packed_repeat && v > 9999 {
                                v % 10000
                            } else {
                                v
                            }
                            .to_string(),
                        )
                    }
                    _ => None,
                };
                if let Some(key) = key {
                    out.push(Occ {
                        span: item.span,
                        sym: Sym::Program(key),
                        def: false,
                        call: true,
                    });
                }
            }
            ItemKind::Macro(MacroStmt::Goto { target } | MacroStmt::IfGoto { target, .. }) => {
                if let Some(n) = literal_int(program, *target) {
                    out.push(Occ {
                        span: program.expr(*target).span,
                        sym: Sym::Seq(n),
                        def: false,
                        call: false,
                    });
                }
            }
            _ => {}
        }
    }
}

/// Every variable occurrence in the file. Assignment targets are definitions.
pub fn var_occurrences(program: &Program, out: &mut Vec<Occ>) {
    let mut targets: Vec<u32> = program
        .items
        .iter()
        .filter_map(|it| match it.kind {
            ItemKind::Assign { target, .. } => Some(target.0),
            _ => None,
        })
        .collect();
    targets.sort_unstable();
    for (i, node) in program.exprs.iter().enumerate() {
        if !matches!(node.expr, Expr::Var { .. } | Expr::Named { .. }) {
            continue;
        }
        if let Some(sym) = var_of(program, ExprId(i as u32)) {
            let def = targets.binary_search(&(i as u32)).is_ok();
            out.push(Occ {
                span: node.span,
                sym,
                def,
                call: false,
            });
        }
    }
}

/// Every occurrence in the file, in no particular order.
pub fn occurrences(program: &Program) -> Vec<Occ> {
    let mut out = Vec::new();
    for block in &program.blocks {
        block_occurrences(program, block, &mut out);
    }
    var_occurrences(program, &mut out);
    out
}

/// The occurrence under `offset` (the innermost, for nested variables like `##1`).
pub fn occurrence_at(program: &Program, offset: u32) -> Option<Occ> {
    let within = |s: Span| s.start <= offset && offset <= s.end;
    let mut out = Vec::new();
    if let Some(bi) = program.block_at(offset) {
        block_occurrences(program, &program.blocks[bi], &mut out);
    }
    // Variables: only the expressions inside this block's span can match.
    for (i, node) in program.exprs.iter().enumerate() {
        if within(node.span) && matches!(node.expr, Expr::Var { .. } | Expr::Named { .. }) {
            if let Some(sym) = var_of(program, ExprId(i as u32)) {
                let def = program.items.iter().any(
                    |it| matches!(it.kind, ItemKind::Assign { target, .. } if target.0 == i as u32),
                );
                out.push(Occ {
                    span: node.span,
                    sym,
                    def,
                    call: false,
                });
            }
        }
    }
    out.into_iter()
        .filter(|o| within(o.span))
        .min_by_key(|o| o.span.len())
}

/// Where a symbol is defined in this file: the `sub`/program head/`N` word/
/// first assignment; for O-word labels without a `sub`, the first statement
/// that uses the label (the `do`, `while`, `if` or `repeat` that opens it).
pub fn definition(program: &Program, sym: &Sym) -> Option<Span> {
    let occs: Vec<Occ> = match sym {
        Sym::Var(_) => {
            let mut v = Vec::new();
            var_occurrences(program, &mut v);
            v
        }
        _ => {
            let mut v = Vec::new();
            for block in &program.blocks {
                block_occurrences(program, block, &mut v);
            }
            v
        }
    };
    let mut same: Vec<&Occ> = occs.iter().filter(|o| &o.sym == sym).collect();
    same.sort_by_key(|o| o.span.start);
    if let Some(d) = same.iter().find(|o| o.def) {
        return Some(d.span);
    }
    match sym {
        Sym::OLabel(_) => same.iter().find(|o| !o.call).map(|o| o.span),
        _ => None,
    }
}

/// Every occurrence of `sym` in the file, sorted by position.
pub fn references(program: &Program, sym: &Sym) -> Vec<Occ> {
    let mut v: Vec<Occ> = occurrences(program)
        .into_iter()
        .filter(|o| &o.sym == sym)
        .collect();
    v.sort_by_key(|o| o.span.start);
    v
}

/// The names defined in a file, for completion: subprogram labels, programs,
/// variables (each once, in first-seen order).
pub fn names(program: &Program) -> Vec<Sym> {
    let mut all = occurrences(program);
    all.sort_by_key(|o| o.span.start);
    let mut seen = std::collections::HashSet::new();
    all.into_iter()
        .filter(|o| match &o.sym {
            Sym::OLabel(_) => o.def,
            Sym::Program(_) => o.def,
            Sym::Var(_) => true,
            Sym::Seq(_) => false,
        })
        .filter_map(|o| seen.insert(o.sym.clone()).then_some(o.sym))
        .collect()
}

/// Why the name under the cursor cannot be renamed.
pub fn rename_refusal(occ: &Occ) -> Option<&'static str> {
    match &occ.sym {
        Sym::Var(v) if !v.starts_with("#<") => Some(
            "numbered variables are memory cells, not names: #100 is the same cell in every program and macro, so it cannot be renamed",
        ),
        Sym::Var(v) if v.starts_with("#<_") => Some(
            "a global parameter (#<_name>) is shared with every file and with the control's predefined ones; only local names are renamed",
        ),
        Sym::Var(_) | Sym::OLabel(_) => None,
        Sym::Program(_) => Some("program numbers and names are not renamed (the file name and the caller's P word must change together); only RS274/NGC o-word labels are"),
        Sym::Seq(_) => Some("sequence numbers are renumbered by formatting, not renamed"),
    }
}

/// Reads a new name typed for `sym` (`o<Name>`, `<name>`, `name`, `o200`,
/// `#<name>`): the symbol it makes, or why it is not a valid name.
pub fn new_symbol(sym: &Sym, typed: &str) -> Result<Sym, String> {
    let t = typed.trim();
    let valid_name = |n: &str| {
        !n.is_empty()
            && n.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
    };
    match sym {
        Sym::Var(_) => {
            let n = t.strip_prefix('#').unwrap_or(t);
            let n = n
                .strip_prefix('<')
                .and_then(|n| n.strip_suffix('>'))
                .unwrap_or(n);
            if n.starts_with('_') {
                return Err(format!("`{t}`: a name starting with `_` is a global parameter; a local one stays local"));
            }
            if !valid_name(n) || n.chars().all(|c| c.is_ascii_digit()) {
                return Err(format!(
                    "`{t}` is not a parameter name (letters, digits and `_`)"
                ));
            }
            Ok(Sym::Var(format!("#<{}>", n.to_ascii_lowercase())))
        }
        Sym::OLabel(_) => {
            let n = t.strip_prefix(['o', 'O']).unwrap_or(t);
            let n = n
                .strip_prefix('<')
                .and_then(|n| n.strip_suffix('>'))
                .unwrap_or(n);
            if n.chars().all(|c| c.is_ascii_digit()) && !n.is_empty() {
                let v: u32 = n
                    .parse()
                    .map_err(|_| format!("`{t}`: label number too large"))?;
                return Ok(Sym::OLabel(v.to_string()));
            }
            if !valid_name(n) {
                return Err(format!(
                    "`{t}` is not an o-word label (a number or a name of letters, digits and `_`)"
                ));
            }
            Ok(Sym::OLabel(n.to_ascii_lowercase()))
        }
        _ => Err("this name is not renamed".into()),
    }
}

/// The text that spells `sym` at one occurrence: `<name>` or a number for a
/// label (after its `o`), `name` inside a parameter's brackets. `typed` keeps
/// the case the user wrote (names are case-insensitive).
fn spelling(new: &Sym, typed: &str) -> String {
    let t = typed.trim();
    let t = t.strip_prefix('#').unwrap_or(t);
    match new {
        Sym::OLabel(k) if k.chars().all(|c| c.is_ascii_digit()) => k.clone(),
        Sym::OLabel(_) => {
            let n = t.strip_prefix(['o', 'O']).unwrap_or(t);
            let n = n
                .strip_prefix('<')
                .and_then(|n| n.strip_suffix('>'))
                .unwrap_or(n);
            format!("<{n}>")
        }
        _ => t
            .strip_prefix('<')
            .and_then(|n| n.strip_suffix('>'))
            .unwrap_or(t)
            .to_string(),
    }
}

/// The edits that rename every occurrence of `old` in the file to `typed`
/// (checked with [`new_symbol`]). Only the name changes: the `o`, the `#<`
/// and `>`, blanks and comments stay as written. Refused when the new name
/// is already used in the file, which would merge two names into one.
pub fn rename_edits(
    program: &Program,
    old: &Sym,
    typed: &str,
) -> Result<Vec<crate::TextEdit>, String> {
    let new = new_symbol(old, typed)?;
    if &new == old {
        return Ok(Vec::new());
    }
    if occurrences(program).iter().any(|o| o.sym == new) {
        return Err(format!("`{}` is already used in this file", new.display()));
    }
    let text = spelling(&new, typed);
    let mut edits = Vec::new();
    match old {
        Sym::OLabel(key) => {
            for item in &program.items {
                let ItemKind::OWord(ow) = &item.kind else {
                    continue;
                };
                if label_key(program, ow).as_deref() == Some(key.as_str()) {
                    edits.push(crate::TextEdit {
                        span: ow.label_span,
                        new_text: text.clone(),
                    });
                }
            }
        }
        Sym::Var(_) => {
            for (i, node) in program.exprs.iter().enumerate() {
                if !matches!(node.expr, Expr::Named { .. }) {
                    continue;
                }
                if var_of(program, ExprId(i as u32)).as_ref() != Some(old) {
                    continue;
                }
                // Between the brackets of `#<name>`.
                let src = program.slice(node.span);
                let (Some(a), Some(b)) = (
                    src.iter().position(|c| *c == b'<'),
                    src.iter().rposition(|c| *c == b'>'),
                ) else {
                    continue;
                };
                if b <= a {
                    continue;
                }
                edits.push(crate::TextEdit {
                    span: Span::new(node.span.start + a as u32 + 1, node.span.start + b as u32),
                    new_text: text.clone(),
                });
            }
        }
        _ => return Err("this name is not renamed".into()),
    }
    edits.sort_by_key(|e| e.span.start);
    edits.dedup_by_key(|e| e.span.start);
    Ok(edits)
}

/// The file name a LinuxCNC `o<name> call` loads: `name.ngc`, lower case as
/// LinuxCNC folds it. None for numbered labels, which are not looked up by file.
pub fn subroutine_file_name(sym: &Sym) -> Option<String> {
    match sym {
        Sym::OLabel(k) if !k.chars().all(|c| c.is_ascii_digit()) => Some(format!("{k}.ngc")),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::{parse, ParseOptions};

    fn prog(dialect: Dialect, text: &str) -> Program {
        parse(ParseOptions::new(dialect), text.as_bytes().to_vec())
    }

    #[test]
    fn ngc_sub_call_and_variables() {
        let text = "o<drill> sub\n#<depth> = 5\nG1 Z-#<depth>\no<drill> endsub\no<drill> call\n#1 = 2\nG0 X#1\nM2\n";
        let p = prog(Dialect::Rs274ngc, text);
        let call = text.rfind("o<drill> call").unwrap() as u32 + 3;
        let occ = occurrence_at(&p, call).unwrap();
        assert_eq!(occ.sym, Sym::OLabel("drill".into()));
        assert!(occ.call);
        let def = definition(&p, &occ.sym).unwrap();
        assert_eq!(def.start, 0);
        assert_eq!(references(&p, &occ.sym).len(), 3);
        let use_depth = text.find("-#<depth>").unwrap() as u32 + 2;
        let v = occurrence_at(&p, use_depth).unwrap();
        assert_eq!(v.sym, Sym::Var("#<depth>".into()));
        assert_eq!(
            definition(&p, &v.sym).map(|s| s.start),
            Some(text.find("#<depth> =").unwrap() as u32)
        );
        let x1 = text.find("X#1").unwrap() as u32 + 2;
        assert_eq!(occurrence_at(&p, x1).unwrap().sym, Sym::Var("#1".into()));
        assert_eq!(
            names(&p),
            vec![
                Sym::OLabel("drill".into()),
                Sym::Var("#<depth>".into()),
                Sym::Var("#1".into())
            ]
        );
    }

    #[test]
    fn fanuc_program_calls_and_goto() {
        let text = "O0001;\nM98 P1234;\nGOTO 20;\nN20 M30;\nO1234;\nG65 P1234 A1.;\nM99;\n";
        let p = prog(Dialect::Fanuc, text);
        let m98 = text.find("P1234").unwrap() as u32 + 1;
        let occ = occurrence_at(&p, m98).unwrap();
        assert_eq!(occ.sym, Sym::Program("1234".into()));
        assert_eq!(
            definition(&p, &occ.sym).map(|s| s.start),
            Some(text.find("O1234").unwrap() as u32)
        );
        let g = text.find("GOTO 20").unwrap() as u32 + 5;
        let occ = occurrence_at(&p, g).unwrap();
        assert_eq!(occ.sym, Sym::Seq(20));
        assert_eq!(
            definition(&p, &occ.sym).map(|s| s.start),
            Some(text.find("N20").unwrap() as u32)
        );
        assert_eq!(references(&p, &Sym::Program("1234".into())).len(), 3);
        // Packed repeat count without L; with L the whole P is the program.
        let p = prog(Dialect::Fanuc, "M98 P50010;\nM98 P50010 L2;\n");
        assert_eq!(
            occurrence_at(&p, 5).map(|o| o.sym),
            Some(Sym::Program("10".into()))
        );
        assert_eq!(
            occurrence_at(&p, 17).map(|o| o.sym),
            Some(Sym::Program("50010".into()))
        );
    }

    #[test]
    fn rename_named_parameters_and_labels() {
        let text = "o<drill> sub\n#<Depth> = 5\nG1 Z-#< depth >\no<drill> endsub\no<drill> call\n#<other> = 1\n#100 = 2\nM2\n";
        let p = prog(Dialect::Rs274ngc, text);
        let apply = |edits: Vec<crate::TextEdit>| {
            String::from_utf8(crate::fixes::apply_edits(text.as_bytes(), &edits)).unwrap()
        };
        let depth = Sym::Var("#<depth>".into());
        assert_eq!(
            apply(rename_edits(&p, &depth, "#<cut_depth>").unwrap()),
            text.replace("#<Depth>", "#<cut_depth>")
                .replace("#< depth >", "#<cut_depth>")
        );
        let drill = Sym::OLabel("drill".into());
        assert_eq!(
            apply(rename_edits(&p, &drill, "o<Peck>").unwrap()),
            text.replace("o<drill>", "o<Peck>")
        );
        // Merging two names, a global, a numbered cell: refused.
        assert!(rename_edits(&p, &depth, "other").is_err());
        assert!(rename_edits(&p, &depth, "#<_g>").is_err());
        let at = text.find("#100").unwrap() as u32 + 1;
        let cell = occurrence_at(&p, at).unwrap();
        assert!(rename_refusal(&cell).is_some_and(|r| r.contains("memory cells")));
        let at = text.find("#< depth").unwrap() as u32 + 3;
        assert_eq!(rename_refusal(&occurrence_at(&p, at).unwrap()), None);
        assert_eq!(subroutine_file_name(&drill).as_deref(), Some("drill.ngc"));
    }

    #[test]
    fn servoworks_named_program_call() {
        let text = "M98 PMoveXY\nM30\nOMoveXY\nG1 X1\nM99\n";
        let p = prog(Dialect::Servoworks, text);
        let occ = occurrence_at(&p, 6).unwrap();
        assert_eq!(occ.sym, Sym::Program("MOVEXY".into()));
        assert_eq!(
            definition(&p, &occ.sym).map(|s| s.start),
            Some(text.find("OMoveXY").unwrap() as u32)
        );
    }
}
