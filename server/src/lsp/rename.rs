//! Rename (`textDocument/prepareRename`, `textDocument/rename`) of local named
//! parameters `#<name>` and RS274/NGC o-word labels. A named subroutine is
//! renamed everywhere it is called: this document, the other open documents,
//! the `.ngc` files beside them and in the subroutine path, and its own file
//! `name.ngc`, which is renamed too when the client can rename files. What is
//! renamed and how is [`crate::ide::rename`]; this module finds the files and
//! converts the edits.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use ropey::Rope;
use tower_lsp_server::ls_types::{
    DocumentChangeOperation, DocumentChanges, OneOf, OptionalVersionedTextDocumentIdentifier,
    Range, RenameFile, ResourceOp, TextDocumentEdit, TextEdit, Uri, WorkspaceEdit,
};

use super::dry_run::CancelFlag;
use super::goto::{external_file, parse_rope, OtherDoc};
use super::position::span_to_range;
use super::snapshot::Snapshot;
use super::workspace;
use crate::ide::rename as ide;

/// At most this many workspace files are read to find the calls of a subroutine.
const MAX_FILES: usize = 2000;

/// The range of the name under `offset`, or why it cannot be renamed (None:
/// nothing there).
pub fn prepare(snap: &Snapshot, offset: u32) -> Option<Result<Range, String>> {
    Some(ide::prepare(snap.program(), offset)?.map(|span| span_to_range(&snap.rope, span)))
}

/// `.ngc` files directly in the folders where LinuxCNC would look for a
/// subroutine file (the document's, the subroutine path), inside the workspace.
fn library_files(snap: &Snapshot, roots: &[PathBuf]) -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = Vec::new();
    if let Some(dir) = snap.path.as_deref().and_then(Path::parent) {
        dirs.push(dir.to_path_buf());
    }
    let subs = workspace::subroutine_path(&snap.doc.machine, snap.doc.config_path.as_deref());
    dirs.extend(subs.iter().filter_map(|p| workspace::confine(p, roots)));
    dirs.extend(roots.iter().cloned());
    let mut files = Vec::new();
    for d in dirs {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            let ngc = p
                .extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| x.eq_ignore_ascii_case("ngc"));
            if ngc && p.is_file() {
                if let Some(c) = workspace::confine(&p, roots) {
                    files.push(c);
                }
            }
            if files.len() >= MAX_FILES {
                return files;
            }
        }
    }
    files.sort();
    files.dedup();
    files
}

/// The workspace edit that renames the name under `offset` to `new_name`.
/// `Err` carries the message shown to the user.
pub fn rename(
    snap: &Snapshot,
    offset: u32,
    new_name: &str,
    others: &[OtherDoc],
    roots: &[PathBuf],
    rename_files: bool,
    cancel: &CancelFlag,
) -> Result<Option<WorkspaceEdit>, String> {
    let Some(plan) = ide::rename(snap.program(), offset, new_name)? else {
        return Ok(None);
    };
    // (uri, version of an open document, rope, edits), this document first.
    let mut docs: Vec<(Uri, Option<i32>, Rope, Vec<analyzer::TextEdit>)> = Vec::new();
    docs.push((
        snap.uri.clone(),
        Some(snap.version),
        snap.rope.clone(),
        plan.edits.clone(),
    ));
    let mut file_rename: Option<(Uri, Uri)> = None;
    // Only a named subroutine is called from other files (by its file name).
    if let Some(sub) = &plan.subroutine {
        let mut seen: Vec<Uri> = vec![snap.uri.clone()];
        let mut add = |uri: Uri, version: Option<i32>, rope: Rope| -> Result<(), String> {
            if seen.contains(&uri) {
                return Ok(());
            }
            seen.push(uri.clone());
            let other = parse_rope(snap, &rope);
            if let Some(edits) = plan
                .edits_in(&other)
                .map_err(|e| format!("{}: {e}", uri.as_str()))?
            {
                docs.push((uri, version, rope, edits));
            }
            Ok(())
        };
        for d in others {
            add(d.uri.clone(), d.version, d.rope.clone())?;
        }
        let sub_file = external_file(snap, &plan.sym, roots).or_else(|| {
            // Renaming from inside the subroutine's own file.
            let p = snap.path.as_deref()?;
            let name = p.file_name()?.to_str()?;
            name.eq_ignore_ascii_case(&sub.old).then(|| p.to_path_buf())
        });
        let mut files = library_files(snap, roots);
        files.extend(sub_file.iter().cloned());
        for path in files {
            if cancel.is_cancelled() {
                return Ok(None);
            }
            let Some(uri) = Uri::from_file_path(&path) else {
                continue;
            };
            if let Some((_, text)) = workspace::read_confined(&path, roots) {
                add(uri, None, Rope::from_str(&text))?;
            }
        }
        if let (Some(path), Some(new_file)) = (sub_file, sub.new.as_deref()) {
            let target = path.with_file_name(new_file);
            if target.exists() && !target.eq(&path) {
                return Err(format!(
                    "`{}` exists already: the subroutine's file cannot take its new name",
                    target.display()
                ));
            }
            if rename_files {
                if let (Some(a), Some(b)) =
                    (Uri::from_file_path(&path), Uri::from_file_path(&target))
                {
                    file_rename = Some((a, b));
                }
            }
        }
    }
    let lsp_edits = |rope: &Rope, edits: &[analyzer::TextEdit]| -> Vec<TextEdit> {
        edits
            .iter()
            .map(|e| TextEdit {
                range: span_to_range(rope, e.span),
                new_text: e.new_text.clone(),
            })
            .collect()
    };
    let docs: Vec<_> = docs.into_iter().filter(|d| !d.3.is_empty()).collect();
    if !rename_files {
        let changes: HashMap<Uri, Vec<TextEdit>> = docs
            .iter()
            .map(|(uri, _, rope, edits)| (uri.clone(), lsp_edits(rope, edits)))
            .collect();
        return Ok(Some(WorkspaceEdit {
            changes: Some(changes),
            ..Default::default()
        }));
    }
    // Text edits first, on the old file names; then the file's rename.
    let mut ops: Vec<DocumentChangeOperation> = docs
        .iter()
        .map(|(uri, version, rope, edits)| {
            DocumentChangeOperation::Edit(TextDocumentEdit {
                text_document: OptionalVersionedTextDocumentIdentifier {
                    uri: uri.clone(),
                    version: *version,
                },
                edits: lsp_edits(rope, edits)
                    .into_iter()
                    .map(OneOf::Left)
                    .collect(),
            })
        })
        .collect();
    if let Some((old_uri, new_uri)) = file_rename {
        ops.push(DocumentChangeOperation::Op(ResourceOp::Rename(
            RenameFile {
                old_uri,
                new_uri,
                options: None,
                annotation_id: None,
            },
        )));
    }
    Ok(Some(WorkspaceEdit {
        document_changes: Some(DocumentChanges::Operations(ops)),
        ..Default::default()
    }))
}
