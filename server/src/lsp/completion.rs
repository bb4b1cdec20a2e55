//! Completion as LSP items: `ide::completion` over the document, with the
//! `.ngc` files beside it (read here, inside the workspace), each item's
//! replaced span converted to a range.

use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionTextEdit, Documentation, MarkupContent,
    MarkupKind, TextEdit,
};

use super::position::span_to_range;
use super::snapshot::Snapshot;
use crate::ide::completion::{self as ide_completion, ItemKind};

pub fn complete(snap: &Snapshot, offset: usize) -> Vec<CompletionItem> {
    let items =
        ide_completion::complete(&super::analysis(snap), offset, &|| ngc_files_beside(snap));
    items
        .into_iter()
        .map(|i| CompletionItem {
            label: i.label,
            kind: Some(kind(i.kind)),
            detail: i.detail,
            documentation: i.documentation.map(|md| {
                Documentation::MarkupContent(MarkupContent {
                    kind: MarkupKind::Markdown,
                    value: md,
                })
            }),
            sort_text: i.sort_text,
            filter_text: i.filter_text,
            text_edit: Some(CompletionTextEdit::Edit(TextEdit {
                range: span_to_range(&snap.rope, i.replace),
                new_text: i.text,
            })),
            ..Default::default()
        })
        .collect()
}

fn kind(k: ItemKind) -> CompletionItemKind {
    match k {
        ItemKind::Variable => CompletionItemKind::VARIABLE,
        ItemKind::Function => CompletionItemKind::FUNCTION,
        ItemKind::File => CompletionItemKind::FILE,
        ItemKind::Module => CompletionItemKind::MODULE,
        ItemKind::Event => CompletionItemKind::EVENT,
        ItemKind::Property => CompletionItemKind::PROPERTY,
        ItemKind::Keyword => CompletionItemKind::KEYWORD,
        ItemKind::Operator => CompletionItemKind::OPERATOR,
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
