//! Completion: G/M codes of the dialect (with docs), the parameters of the G
//! code of the current block, subprogram/program names and variables seen in
//! the file. The context is read from the text left of the cursor.

use analyzer::dialect::CodeKind;
use analyzer::names::{self as nav, Sym};
use analyzer::rules::context::collect_codes;
use analyzer::Span;

use super::hover::code_markdown;
use super::keywords::{self, KwKind};
use super::Analysis;

/// What an item is, for the client's icon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ItemKind {
    Variable,
    /// A subprogram defined in the document, a G code, a function.
    Function,
    /// A subprogram file beside the document.
    File,
    /// A program number (`M98 P…`).
    Module,
    /// An M code.
    Event,
    /// A parameter of a G code of the block.
    Property,
    /// An address letter, a statement, an O-word keyword.
    Keyword,
    Operator,
}

/// One completion item; accepting it replaces `replace` (the word being
/// typed) with `text`.
#[derive(Debug, Clone, PartialEq)]
pub struct CompletionItem {
    pub label: String,
    pub kind: ItemKind,
    pub detail: Option<String>,
    /// Markdown.
    pub documentation: Option<String>,
    pub sort_text: Option<String>,
    pub filter_text: Option<String>,
    pub replace: Span,
    pub text: String,
}

impl CompletionItem {
    fn new(label: String, kind: ItemKind, replace: Span) -> CompletionItem {
        CompletionItem {
            text: label.clone(),
            label,
            kind,
            detail: None,
            documentation: None,
            sort_text: None,
            filter_text: None,
            replace,
        }
    }
}

/// The word being typed: the run of word characters ending at the cursor.
fn prefix(line_before: &str) -> &str {
    let start = line_before
        .char_indices()
        .rev()
        .take_while(|(_, c)| c.is_ascii_alphanumeric() || matches!(c, '.' | '#' | '<' | '_'))
        .last()
        .map(|(i, _)| i)
        .unwrap_or(line_before.len());
    &line_before[start..]
}

/// The items at `offset`. `files_beside` lists the stems of the `.ngc` files
/// beside the document (`drill.ngc` → `o<drill>`), asked only after `o<`.
pub fn complete(
    a: &Analysis<'_>,
    offset: usize,
    files_beside: &dyn Fn() -> Vec<String>,
) -> Vec<CompletionItem> {
    let offset = offset.min(a.program.text.len());
    let (_, before) = a.line_before(offset);
    let pre = prefix(&before);
    let replace = Span::new((offset - pre.len()) as u32, offset as u32);
    let item = |label: String, kind| CompletionItem::new(label, kind, replace);
    let settings = a.settings;
    let program = a.program;
    let mut out = Vec::new();

    let upper = pre.to_ascii_uppercase();
    // Variables: `#`, `#<`, `#<na`, `#1`.
    if upper.starts_with('#') {
        for sym in nav::names(program) {
            if let Sym::Var(v) = sym {
                out.push(CompletionItem {
                    filter_text: Some(v.clone()),
                    ..item(v, ItemKind::Variable)
                });
            }
        }
        return out;
    }
    // Subprogram labels: `o<`.
    if upper.starts_with("O<") {
        for sym in nav::names(program) {
            if let Sym::OLabel(l) = &sym {
                out.push(CompletionItem {
                    detail: Some("subprogram".into()),
                    ..item(format!("o<{l}>"), ItemKind::Function)
                });
            }
        }
        // Subroutine files next to the document (`drill.ngc` → `o<drill>`).
        for name in files_beside() {
            let text = format!("o<{name}>");
            if out.iter().any(|i| i.label == text) {
                continue;
            }
            out.push(CompletionItem {
                detail: Some(format!("subprogram file {name}.ngc")),
                ..item(text, ItemKind::File)
            });
        }
        return out;
    }
    // Program names after `M98 P` / `G65 P`.
    if upper.starts_with('P')
        && (before.to_ascii_uppercase().contains("M98")
            || before.to_ascii_uppercase().contains("G65"))
    {
        for sym in nav::names(program) {
            if let Sym::Program(p) = &sym {
                out.push(CompletionItem {
                    detail: Some("program".into()),
                    ..item(format!("P{p}"), ItemKind::Module)
                });
            }
        }
        if !out.is_empty() {
            return out;
        }
    }
    // G and M codes.
    if let Some(letter @ ('G' | 'M')) = upper.chars().next() {
        if upper[1..].chars().all(|c| c.is_ascii_digit() || c == '.') {
            for info in settings
                .dialect
                .codes()
                .iter()
                .filter(|c| c.letter == letter && c.on_variant(settings.variant))
            {
                // As the dialect's manual writes it (`G01` in FANUC, `G1` in RS274/NGC).
                let name = info.display_name(settings.dialect);
                let kind = if info.kind == CodeKind::Misc {
                    ItemKind::Event
                } else {
                    ItemKind::Function
                };
                out.push(CompletionItem {
                    detail: Some(info.summary.to_string()),
                    documentation: Some(code_markdown(info, settings.variant)),
                    // Sort G1 before G10 by number, not by text.
                    sort_text: Some(format!("{letter}{:08}", info.num.0)),
                    filter_text: Some(name.clone()),
                    ..item(name, kind)
                });
            }
        }
        if !pre.is_empty() && pre.len() > 1 {
            // `GOTO`, `GT`, `MOD`: a keyword, not a code.
            keyword_items(settings.dialect, &before, pre, &mut out, &item);
            return out;
        }
    }
    // Parameters of the G codes of the current block that are not written yet.
    if pre.len() <= 1 {
        let offset32 = offset as u32;
        if let Some(bi) = program
            .block_at(offset32.saturating_sub(1))
            .filter(|&bi| program.blocks[bi].full_span().end >= offset32)
        {
            let block = &program.blocks[bi];
            let mut codes = Vec::new();
            collect_codes(program, block, &mut codes);
            let written: Vec<u8> = program.words(block).map(|(_, w)| w.letter).collect();
            for c in &codes {
                let Some(info) = c.info else { continue };
                for p in info.params {
                    if written.contains(&(p.letter as u8))
                        || !p.letter.to_string().starts_with(&upper)
                    {
                        continue;
                    }
                    let req = if p.required { " (required)" } else { "" };
                    out.push(CompletionItem {
                        detail: Some(format!("{}: {}{req}", info.name(), p.doc)),
                        documentation: Some(format!(
                            "**{}** in **{}**: {}{req}",
                            p.letter,
                            info.name(),
                            p.doc
                        )),
                        sort_text: Some(format!("0{}", p.letter)),
                        ..item(p.letter.to_string(), ItemKind::Property)
                    });
                }
            }
        }
    }
    // Address letters of the dialect, when nothing more specific applies.
    if out.is_empty() && pre.len() <= 1 {
        for a in settings.dialect.addresses() {
            if !a.letter.to_string().starts_with(&upper) || a.letter == '#' {
                continue;
            }
            out.push(CompletionItem {
                detail: Some(a.doc.to_string()),
                sort_text: Some(format!("1{}", a.letter)),
                ..item(a.letter.to_string(), ItemKind::Keyword)
            });
        }
    }
    keyword_items(settings.dialect, &before, pre, &mut out, &item);
    out
}

/// Macro statements, operators, functions and (after an O label) O-word
/// keywords of the dialect that start with the word being typed.
fn keyword_items(
    dialect: analyzer::Dialect,
    before: &str,
    pre: &str,
    out: &mut Vec<CompletionItem>,
    item: &dyn Fn(String, ItemKind) -> CompletionItem,
) {
    if pre.is_empty() || !pre.chars().all(|c| c.is_ascii_alphabetic()) {
        return;
    }
    // `o100 wh`, `o<name> ca`: the keyword slot of an O-word line.
    let head = before[..before.len() - pre.len()].trim();
    let oword_slot =
        head.len() > 1 && head.starts_with(['o', 'O']) && !head.contains(char::is_whitespace);
    for k in keywords::all(dialect) {
        if (k.kind == KwKind::OWord) != oword_slot
            || !k
                .name
                .to_ascii_uppercase()
                .starts_with(&pre.to_ascii_uppercase())
        {
            continue;
        }
        let kind = match k.kind {
            KwKind::Function => ItemKind::Function,
            KwKind::Operator => ItemKind::Operator,
            KwKind::Statement | KwKind::OWord => ItemKind::Keyword,
        };
        out.push(CompletionItem {
            detail: Some(k.syntax.to_string()),
            documentation: Some(keywords::markdown(k)),
            sort_text: Some(format!("2{}", k.name)),
            filter_text: Some(k.name.to_string()),
            ..item(k.name.to_string(), kind)
        });
    }
}

#[cfg(test)]
mod tests {
    use super::prefix;

    #[test]
    fn prefix_is_the_word_being_typed() {
        assert_eq!(prefix("G1 X1 G8"), "G8");
        assert_eq!(prefix("G1 #<de"), "#<de");
        assert_eq!(prefix("o<dr"), "o<dr");
        assert_eq!(prefix("G1 "), "");
        assert_eq!(prefix("(é) M"), "M");
    }
}
