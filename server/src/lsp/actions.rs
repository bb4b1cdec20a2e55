//! Code actions: the quick fixes the analyzer attached to diagnostics, and,
//! when the client asks for `source.fixAll` (VS Code's `codeActionsOnSave`),
//! one action applying every fix that does not touch another
//! (`analyzer::fixes::compatible_edits`; asking again applies the rest).

use std::collections::HashMap;

use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Range, TextEdit, WorkspaceEdit,
};

use super::position::{range_to_offsets, span_to_range};
use super::snapshot::Snapshot;

/// The `source.fixAll` action, when any fix applies.
pub fn fix_all(snap: &Snapshot) -> Option<CodeActionOrCommand> {
    let edits = analyzer::fixes::compatible_edits(snap.diagnostics());
    if edits.is_empty() {
        return None;
    }
    let edits: Vec<TextEdit> = edits
        .into_iter()
        .map(|e| TextEdit {
            range: span_to_range(&snap.rope, e.span),
            new_text: e.new_text,
        })
        .collect();
    Some(CodeActionOrCommand::CodeAction(CodeAction {
        title: format!("Apply {} fix(es) that do not overlap", edits.len()),
        kind: Some(CodeActionKind::SOURCE_FIX_ALL),
        edit: Some(WorkspaceEdit {
            changes: Some(HashMap::from([(snap.uri.clone(), edits)])),
            ..Default::default()
        }),
        ..Default::default()
    }))
}

pub fn code_actions(snap: &Snapshot, range: Range) -> Vec<CodeActionOrCommand> {
    let (a, b) = range_to_offsets(&snap.rope, range);
    let (a, b) = (a as u32, b as u32);
    let mut out = Vec::new();
    for d in snap
        .diagnostics()
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
