//! Signature help: the words a G code of the current block takes, with the
//! one being typed highlighted.

use std::ops::Range;

use analyzer::dialect::CodeInfo;
use analyzer::rules::context::collect_codes;

use super::Analysis;

/// One parameter: where its letter is in the signature's label (bytes).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Parameter {
    pub label: Range<usize>,
    pub doc: String,
}

/// One G code's words: `G81 X Y Z R [L]`, required letters bare, optional
/// ones in brackets.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Signature {
    pub label: String,
    /// Markdown.
    pub documentation: String,
    pub parameters: Vec<Parameter>,
}

/// The signatures of the block's G codes that take words, and which
/// parameter of the first the cursor is on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SignatureHelp {
    pub signatures: Vec<Signature>,
    pub active_parameter: Option<u32>,
}

fn signature(info: &CodeInfo) -> Signature {
    let mut label = info.name();
    let mut parameters = Vec::new();
    for p in info.params {
        label.push(' ');
        let start = label.len();
        if p.required {
            label.push(p.letter);
        } else {
            label.push_str(&format!("[{}]", p.letter));
        }
        let end = label.len();
        let range = if p.required {
            start..end
        } else {
            start + 1..end - 1
        };
        parameters.push(Parameter {
            label: range,
            doc: p.doc.to_string(),
        });
    }
    Signature {
        label,
        documentation: format!("{}\n\n{}", info.summary, info.doc),
        parameters,
    }
}

pub fn signature_help(a: &Analysis<'_>, offset: u32) -> Option<SignatureHelp> {
    let program = a.program;
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
    let active_parameter = letter
        .and_then(|l| infos[0].params.iter().position(|p| p.letter == l))
        .map(|i| i as u32);
    Some(SignatureHelp {
        signatures: infos.iter().map(|i| signature(i)).collect(),
        active_parameter,
    })
}
