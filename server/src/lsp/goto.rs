//! Go-to-definition and references as LSP locations: `ide::goto` finds the
//! symbol and its spans in each program; this module finds the other files
//! (the subprogram file the dry run would load, the open documents), reads
//! them only inside the workspace folders and converts spans to ranges.

use std::path::PathBuf;

use analyzer::syntax::{parse, Program};
use ropey::Rope;
use tower_lsp_server::ls_types::{Location, Position, Range, Uri};

use super::dry_run::CancelFlag;
use super::nav::Sym;
use super::position::span_to_range;
use super::snapshot::Snapshot;
use super::workspace;
use crate::ide::goto::{self as ide_goto, Definition};

/// Another document the references search looks at.
pub struct OtherDoc {
    pub uri: Uri,
    /// The open document's version (edits name it).
    pub version: Option<i32>,
    pub rope: Rope,
}

pub(super) fn parse_rope(snap: &Snapshot, rope: &Rope) -> Program {
    let settings = &snap.doc.settings;
    parse(settings.parse_options(), super::position::rope_bytes(rope))
}

/// The file that defines a subprogram/program the document calls but does not define.
pub(super) fn external_file(snap: &Snapshot, sym: &Sym, roots: &[PathBuf]) -> Option<PathBuf> {
    let key = match sym {
        Sym::OLabel(k) | Sym::Program(k) => k,
        _ => return None,
    };
    // The file the dry run would load for the call.
    crate::resolve::FsResolver::for_workspace(
        Some(snap.path.as_deref()?),
        roots,
        snap.doc.settings.dialect,
        &snap.doc.machine,
        snap.doc.config_path.as_deref(),
        crate::resolve::SizeLimit::bytes(u64::MAX, "the `maxRunFileSize` setting"),
    )
    .locate(key)
}

/// Where the symbol under `offset` is defined.
pub fn definition(
    snap: &Snapshot,
    offset: u32,
    roots: &[PathBuf],
    open: &dyn Fn(&Uri) -> Option<Rope>,
) -> Option<Location> {
    let sym = match ide_goto::definition(&super::analysis(snap), offset)? {
        Definition::Here(span) => {
            return Some(Location {
                uri: snap.uri.clone(),
                range: span_to_range(&snap.rope, span),
            })
        }
        Definition::Elsewhere(sym) => sym,
    };
    let path = external_file(snap, &sym, roots)?;
    let uri = Uri::from_file_path(&path)?;
    // The open editor's text wins over the file on disk.
    let rope = match open(&uri) {
        Some(r) => r,
        None => Rope::from_str(&workspace::read_confined(&path, roots)?.1),
    };
    let other = parse_rope(snap, &rope);
    let range = match ide_goto::definition_in(&other, &sym) {
        Some(span) => span_to_range(&rope, span),
        None => Range::new(Position::new(0, 0), Position::new(0, 0)),
    };
    Some(Location { uri, range })
}

/// Every occurrence of the symbol under `offset`: in this document, in the
/// other open documents (for programs and subprograms) and in the file that
/// defines it.
pub fn references(
    snap: &Snapshot,
    offset: u32,
    include_declaration: bool,
    others: &[OtherDoc],
    roots: &[PathBuf],
    cancel: &CancelFlag,
) -> Vec<Location> {
    let Some(refs) = ide_goto::references(&super::analysis(snap), offset, include_declaration)
    else {
        return Vec::new();
    };
    let mut out: Vec<Location> = refs
        .spans
        .iter()
        .map(|&span| Location {
            uri: snap.uri.clone(),
            range: span_to_range(&snap.rope, span),
        })
        .collect();
    if !refs.crosses_files() {
        return out;
    }
    let mut docs: Vec<(Uri, Rope)> = others
        .iter()
        .filter(|d| d.uri != snap.uri)
        .map(|d| (d.uri.clone(), d.rope.clone()))
        .collect();
    if let Some(path) = external_file(snap, &refs.sym, roots) {
        if let Some(uri) = Uri::from_file_path(&path)
            .filter(|u| *u != snap.uri && !docs.iter().any(|(d, _)| d == u))
        {
            if let Some((_, text)) = workspace::read_confined(&path, roots) {
                docs.push((uri, Rope::from_str(&text)));
            }
        }
    }
    for (uri, rope) in docs {
        if cancel.is_cancelled() {
            return Vec::new();
        }
        let other = parse_rope(snap, &rope);
        for span in ide_goto::references_in(&other, &refs.sym, include_declaration) {
            out.push(Location {
                uri: uri.clone(),
                range: span_to_range(&rope, span),
            });
        }
    }
    out
}
