//! Signature help: the words a G code of the current block takes, with the
//! one being typed highlighted.

use analyzer::dialect::CodeInfo;
use analyzer::rules::context::collect_codes;
use tower_lsp_server::ls_types::{
    Documentation, MarkupContent, MarkupKind, ParameterInformation, ParameterLabel, SignatureHelp,
    SignatureInformation,
};

use super::snapshot::Snapshot;

fn signature(info: &CodeInfo) -> SignatureInformation {
    let mut label = info.name();
    let mut params = Vec::new();
    for p in info.params {
        label.push(' ');
        let start = label.encode_utf16().count() as u32;
        if p.required {
            label.push(p.letter);
        } else {
            label.push_str(&format!("[{}]", p.letter));
        }
        let end = label.encode_utf16().count() as u32;
        let (s, e) = if p.required {
            (start, end)
        } else {
            (start + 1, end - 1)
        };
        params.push(ParameterInformation {
            label: ParameterLabel::LabelOffsets([s, e]),
            documentation: Some(Documentation::String(p.doc.to_string())),
        });
    }
    SignatureInformation {
        label,
        documentation: Some(Documentation::MarkupContent(MarkupContent {
            kind: MarkupKind::Markdown,
            value: format!("{}\n\n{}", info.summary, info.doc),
        })),
        parameters: Some(params),
        active_parameter: None,
    }
}

pub fn signature_help(snap: &Snapshot, offset: u32) -> Option<SignatureHelp> {
    let program = snap.program();
    let bi = program.block_at(offset.saturating_sub(1))?;
    let block = &program.blocks[bi];
    if block.full_span().end < offset {
        return None;
    }
    let mut codes = Vec::new();
    collect_codes(program, block, &mut codes);
    let infos: Vec<&CodeInfo> = codes
        .iter()
        .filter_map(|c| c.info)
        .filter(|i| !i.params.is_empty())
        .collect();
    if infos.is_empty() {
        return None;
    }
    // The word the cursor is in or just after.
    let letter = program
        .words(block)
        .filter(|(it, _)| it.span.start < offset)
        .last()
        .filter(|(it, _)| it.span.end >= offset)
        .map(|(_, w)| w.letter as char);
    let active_sig = 0;
    let active_param = letter
        .and_then(|l| infos[0].params.iter().position(|p| p.letter == l))
        .map(|i| i as u32);
    Some(SignatureHelp {
        signatures: infos.iter().map(|i| signature(i)).collect(),
        active_signature: Some(active_sig),
        active_parameter: active_param,
    })
}
