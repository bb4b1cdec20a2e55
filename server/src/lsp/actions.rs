//! Code actions: the quick fixes the analyzer attached to diagnostics.

use std::collections::HashMap;

use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Range, TextEdit, WorkspaceEdit,
};

use super::position::{range_to_offsets, span_to_range};
use super::snapshot::Snapshot;

pub fn code_actions(snap: &Snapshot, range: Range) -> Vec<CodeActionOrCommand> {
    let (a, b) = range_to_offsets(&snap.rope, range);
    let (a, b) = (a as u32, b as u32);
    let mut out = Vec::new();
    for d in snap
        .analysis
        .diagnostics
        .iter()
        .filter(|d| d.file == analyzer::FileId(0))
    {
        // Overlap, treating empty ranges as touching.
        if d.span.end < a || d.span.start > b {
            continue;
        }
        for fix in &d.fixes {
            let edits: Vec<TextEdit> = fix
                .edits
                .iter()
                .map(|e| TextEdit {
                    range: span_to_range(&snap.rope, e.span),
                    new_text: e.new_text.clone(),
                })
                .collect();
            let changes = HashMap::from([(snap.uri.clone(), edits)]);
            out.push(CodeActionOrCommand::CodeAction(CodeAction {
                title: fix.title.clone(),
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![snap.to_lsp(d)]),
                edit: Some(WorkspaceEdit {
                    changes: Some(changes),
                    ..Default::default()
                }),
                is_preferred: Some(d.fixes.len() == 1),
                ..Default::default()
            }));
        }
    }
    out
}
