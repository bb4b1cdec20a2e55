//! Document formatting (`textDocument/formatting`): `analyzer::format` with
//! its options read from the request's `partscope.*` properties, then the
//! client's `format` settings, then the defaults (block numbers kept, one
//! blank between words, upper case).
//!
//! Keys: `numbers` = `keep` | `renumber` | `add` | `remove`, `start` (10),
//! `step` (10), `spacing` = `keep` | `one` | `none`, `uppercase` (true).

use std::collections::HashMap;

use analyzer::format::{format_edits, FormatOptions, Numbers, Spacing};
use serde_json::Value;
use tower_lsp_server::ls_types::{FormattingProperty, TextEdit};

use super::position::span_to_range;
use super::snapshot::Snapshot;

/// One option's value: the request's `partscope.KEY` property, else the
/// client's `format.KEY`.
fn option(
    key: &str,
    defaults: Option<&Value>,
    props: &HashMap<String, FormattingProperty>,
) -> Option<Value> {
    match props.get(&format!("partscope.{key}")) {
        Some(FormattingProperty::Bool(b)) => return Some(Value::Bool(*b)),
        Some(FormattingProperty::Number(n)) => return Some(Value::from(*n)),
        Some(FormattingProperty::String(s)) => return Some(Value::String(s.clone())),
        None => {}
    }
    defaults.and_then(|d| d.get(key)).cloned()
}

/// Reads the options; an unknown value is an error naming the valid ones.
pub fn options(
    defaults: Option<&Value>,
    props: &HashMap<String, FormattingProperty>,
) -> Result<FormatOptions, String> {
    let get = |k: &str| option(k, defaults, props);
    let number = |k: &str, dflt: u32| -> Result<u32, String> {
        match get(k) {
            None => Ok(dflt),
            Some(v) => v
                .as_u64()
                .and_then(|n| u32::try_from(n).ok())
                .filter(|n| k != "step" || *n > 0)
                .ok_or_else(|| {
                    format!(
                        "format `{k}` must be a whole number{}, not {v}",
                        if k == "step" { " above 0" } else { "" }
                    )
                }),
        }
    };
    let text = |k: &str, dflt: &str| -> Result<String, String> {
        match get(k) {
            None => Ok(dflt.to_string()),
            Some(Value::String(s)) => Ok(s.to_ascii_lowercase()),
            Some(v) => Err(format!("format `{k}` must be a string, not {v}")),
        }
    };
    let (start, step) = (number("start", 10)?, number("step", 10)?);
    let numbers = match text("numbers", "keep")?.as_str() {
        "keep" => Numbers::Keep,
        "renumber" => Numbers::Renumber { start, step },
        "add" => Numbers::Add { start, step },
        "remove" => Numbers::Remove,
        other => {
            return Err(format!(
                "format `numbers` is keep, renumber, add or remove, not `{other}`"
            ))
        }
    };
    let spacing = match text("spacing", "one")?.as_str() {
        "keep" => Spacing::Keep,
        "one" => Spacing::One,
        "none" => Spacing::None,
        other => {
            return Err(format!(
                "format `spacing` is keep, one or none, not `{other}`"
            ))
        }
    };
    let uppercase = match get("uppercase") {
        None => true,
        Some(Value::Bool(b)) => b,
        Some(v) => return Err(format!("format `uppercase` is true or false, not {v}")),
    };
    Ok(FormatOptions {
        numbers,
        spacing,
        uppercase,
    })
}

pub fn format(
    snap: &Snapshot,
    defaults: Option<&Value>,
    props: &HashMap<String, FormattingProperty>,
) -> Result<Vec<TextEdit>, String> {
    let opts = options(defaults, props)?;
    let edits = format_edits(snap.program(), &opts)?;
    Ok(edits
        .into_iter()
        .map(|e| TextEdit {
            range: span_to_range(&snap.rope, e.span),
            new_text: e.new_text,
        })
        .collect())
}
