//! Signature help as LSP values: `ide::signature` with each parameter's
//! place in its label converted from bytes to UTF-16 units.

use tower_lsp_server::ls_types::{
    Documentation, MarkupContent, MarkupKind, ParameterInformation, ParameterLabel, SignatureHelp,
    SignatureInformation,
};

use super::snapshot::Snapshot;
use crate::ide::signature as ide_signature;

fn utf16(s: &str, byte: usize) -> u32 {
    s.get(..byte).unwrap_or(s).encode_utf16().count() as u32
}

pub fn signature_help(snap: &Snapshot, offset: u32) -> Option<SignatureHelp> {
    let help = ide_signature::signature_help(&super::analysis(snap), offset)?;
    let signatures = help
        .signatures
        .into_iter()
        .map(|sig| {
            let parameters = sig
                .parameters
                .iter()
                .map(|p| ParameterInformation {
                    label: ParameterLabel::LabelOffsets([
                        utf16(&sig.label, p.label.start),
                        utf16(&sig.label, p.label.end),
                    ]),
                    documentation: Some(Documentation::String(p.doc.clone())),
                })
                .collect();
            SignatureInformation {
                label: sig.label,
                documentation: Some(Documentation::MarkupContent(MarkupContent {
                    kind: MarkupKind::Markdown,
                    value: sig.documentation,
                })),
                parameters: Some(parameters),
                active_parameter: None,
            }
        })
        .collect();
    Some(SignatureHelp {
        signatures,
        active_signature: Some(0),
        active_parameter: help.active_parameter,
    })
}
