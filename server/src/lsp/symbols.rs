//! Document symbols and folding ranges as LSP values: `ide::symbols` with
//! spans converted to ranges.

use ropey::Rope;
#[allow(deprecated)]
use tower_lsp_server::ls_types::{DocumentSymbol, FoldingRange, FoldingRangeKind, SymbolKind};

use super::position::span_to_range;
use super::snapshot::Snapshot;
use crate::ide::symbols::{self as ide_symbols, RegionKind, Symbol};

#[allow(deprecated)]
fn convert(rope: &Rope, s: Symbol) -> DocumentSymbol {
    let children: Vec<DocumentSymbol> = s.children.into_iter().map(|c| convert(rope, c)).collect();
    DocumentSymbol {
        name: s.name,
        detail: Some(s.kind.detail().into()),
        kind: match s.kind {
            RegionKind::Program => SymbolKind::MODULE,
            RegionKind::Sub => SymbolKind::FUNCTION,
            RegionKind::Control => SymbolKind::NAMESPACE,
            RegionKind::Tool => SymbolKind::EVENT,
        },
        tags: None,
        deprecated: None,
        range: span_to_range(rope, s.span),
        selection_range: span_to_range(rope, s.selection),
        children: (!children.is_empty()).then_some(children),
    }
}

pub fn document_symbols(snap: &Snapshot) -> Vec<DocumentSymbol> {
    ide_symbols::document_symbols(snap.program())
        .into_iter()
        .map(|s| convert(&snap.rope, s))
        .collect()
}

pub fn folding_ranges(snap: &Snapshot) -> Vec<FoldingRange> {
    ide_symbols::folding_ranges(&super::analysis(snap))
        .into_iter()
        .map(|f| FoldingRange {
            start_line: f.start_line,
            start_character: None,
            end_line: f.end_line,
            end_character: None,
            kind: Some(FoldingRangeKind::Region),
            collapsed_text: Some(f.name),
        })
        .collect()
}
