//! Completion: G/M codes of the dialect (with docs), the parameters of the G
//! code of the current block, subprogram/program names and variables seen in
//! the file. The context is read from the text left of the cursor.

use analyzer::dialect::CodeKind;
use analyzer::rules::context::collect_codes;
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, MarkupContent,
    MarkupKind, Range, TextEdit,
};

use super::hover::code_markdown;
use super::keywords::{self, KwKind};
use super::nav::{self, Sym};
use super::position::offset_to_position;
use super::snapshot::Snapshot;

fn doc(md: String) -> Option<Documentation> {
    Some(Documentation::MarkupContent(MarkupContent {
        kind: MarkupKind::Markdown,
        value: md,
    }))
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

pub fn complete(snap: &Snapshot, offset: usize) -> Vec<CompletionItem> {
    let rope = &snap.rope;
    let offset = offset.min(rope.len_bytes());
    let line = rope.byte_to_line(offset);
    let line_start = rope.line_to_byte(line);
    let before = rope.byte_slice(line_start..offset).to_string();
    let pre = prefix(&before);
    let replace = Range::new(
        offset_to_position(rope, offset - pre.len()),
        offset_to_position(rope, offset),
    );
    let edit = |text: String| {
        Some(CompletionTextEdit::Edit(TextEdit {
            range: replace,
            new_text: text,
        }))
    };
    let settings = &snap.doc.settings;
    let program = snap.program();
    let mut out = Vec::new();

    let upper = pre.to_ascii_uppercase();
    // Variables: `#`, `#<`, `#<na`, `#1`.
    if upper.starts_with('#') {
        for sym in nav::names(program) {
            if let Sym::Var(v) = sym {
                out.push(CompletionItem {
                    label: v.clone(),
                    kind: Some(CompletionItemKind::VARIABLE),
                    filter_text: Some(v.clone()),
                    text_edit: edit(v),
                    ..Default::default()
                });
            }
        }
        return out;
    }
    // Subprogram labels: `o<`.
    if upper.starts_with("O<") {
        for sym in nav::names(program) {
            if let Sym::OLabel(l) = &sym {
                let text = format!("o<{l}>");
                out.push(CompletionItem {
                    label: text.clone(),
                    kind: Some(CompletionItemKind::FUNCTION),
                    detail: Some("subprogram".into()),
                    text_edit: edit(text),
                    ..Default::default()
                });
            }
        }
        // Subroutine files next to the document (`drill.ngc` → `o<drill>`).
        for name in ngc_files_beside(snap) {
            let text = format!("o<{name}>");
            if out.iter().any(|i| i.label == text) {
                continue;
            }
            out.push(CompletionItem {
                label: text.clone(),
                kind: Some(CompletionItemKind::FILE),
                detail: Some(format!("subprogram file {name}.ngc")),
                text_edit: edit(text),
                ..Default::default()
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
                let text = format!("P{p}");
                out.push(CompletionItem {
                    label: text.clone(),
                    kind: Some(CompletionItemKind::MODULE),
                    detail: Some("program".into()),
                    text_edit: edit(text),
                    ..Default::default()
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
                out.push(CompletionItem {
                    label: name.clone(),
                    kind: Some(if info.kind == CodeKind::Misc {
                        CompletionItemKind::EVENT
                    } else {
                        CompletionItemKind::FUNCTION
                    }),
                    detail: Some(info.summary.to_string()),
                    documentation: doc(code_markdown(info, settings.variant)),
                    // Sort G1 before G10 by number, not by text.
                    sort_text: Some(format!("{letter}{:08}", info.num.0)),
                    filter_text: Some(name.clone()),
                    text_edit: edit(name),
                    ..Default::default()
                });
            }
        }
        if !pre.is_empty() && pre.len() > 1 {
            // `GOTO`, `GT`, `MOD`: a keyword, not a code.
            keyword_items(settings.dialect, &before, pre, &mut out, &edit);
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
                        label: p.letter.to_string(),
                        kind: Some(CompletionItemKind::PROPERTY),
                        detail: Some(format!("{}: {}{req}", info.name(), p.doc)),
                        documentation: doc(format!(
                            "**{}** in **{}**: {}{req}",
                            p.letter,
                            info.name(),
                            p.doc
                        )),
                        sort_text: Some(format!("0{}", p.letter)),
                        text_edit: edit(p.letter.to_string()),
                        ..Default::default()
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
                label: a.letter.to_string(),
                kind: Some(CompletionItemKind::KEYWORD),
                detail: Some(a.doc.to_string()),
                sort_text: Some(format!("1{}", a.letter)),
                text_edit: edit(a.letter.to_string()),
                ..Default::default()
            });
        }
    }
    keyword_items(settings.dialect, &before, pre, &mut out, &edit);
    out
}

/// Macro statements, operators, functions and (after an O label) O-word
/// keywords of the dialect that start with the word being typed.
fn keyword_items(
    dialect: analyzer::Dialect,
    before: &str,
    pre: &str,
    out: &mut Vec<CompletionItem>,
    edit: &dyn Fn(String) -> Option<CompletionTextEdit>,
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
        out.push(CompletionItem {
            label: k.name.to_string(),
            kind: Some(match k.kind {
                KwKind::Function => CompletionItemKind::FUNCTION,
                KwKind::Operator => CompletionItemKind::OPERATOR,
                KwKind::Statement | KwKind::OWord => CompletionItemKind::KEYWORD,
            }),
            detail: Some(k.syntax.to_string()),
            documentation: doc(keywords::markdown(k)),
            sort_text: Some(format!("2{}", k.name)),
            filter_text: Some(k.name.to_string()),
            text_edit: edit(k.name.to_string()),
            ..Default::default()
        });
    }
}

/// Stems of the `.ngc` files in the document's folder (inside the workspace).
fn ngc_files_beside(snap: &Snapshot) -> Vec<String> {
    let Some(dir) = snap.path.as_deref().and_then(|p| p.parent()) else {
        return Vec::new();
    };
    if super::workspace::confine(dir, &snap.roots).is_none() {
        return Vec::new();
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut names: Vec<String> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.extension().is_some_and(|e| e.eq_ignore_ascii_case("ngc"))
                && p != snap.path.as_deref().unwrap_or(p)
        })
        .filter_map(|p| p.file_stem().and_then(|s| s.to_str()).map(str::to_string))
        .collect();
    names.sort();
    names
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
