//! Flow-sensitive rule: its metadata and its check, which the interpreter runs
//! once before the first block (`Interp::spec_input_files`).

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::Sink;

declare_rule! {
    /// ## What it does
    /// Checks the LinuxCNC tool table the run reads: a line without T or P, or with a value that is not a number, is an error; a pocket used twice is a warning (the last line wins). The example program runs with a table holding `T1 P1` and `T2 P1`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC cannot load a malformed line, and a duplicated pocket silently hides a tool.
    ///
    /// ## Example
    /// ```gcode
    /// T1 M6
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// T1 M6
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC (the table the host reads). Error; warning for duplicate pockets.
    ///
    /// Implements: NGC430, NGC432
    pub static TOOL_TABLE = {
        code: "T008",
        name: "tool-table",
        summary: "Malformed tool table line or duplicate pocket",
        implements: &["NGC430", "NGC432"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// Reports the problems of the LinuxCNC tool table the host read.
pub(crate) fn check(text: &str, out: &mut Sink<'_>) {
    for (line, msg) in problems(text) {
        out.diag(
            &TOOL_TABLE,
            if msg.1 {
                Severity::Error
            } else {
                Severity::Warning
            },
            Span::default(),
            format!("tool table line {line}: {}", msg.0),
        );
    }
}

/// Problems of a LinuxCNC tool table: (1-based line, (message, is error)).
fn problems(text: &str) -> Vec<(usize, (String, bool))> {
    let mut out = Vec::new();
    let mut pockets: Vec<(i64, usize)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let body = line.split(';').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let mut t = None;
        let mut p = None;
        for word in body.split_whitespace() {
            let mut chars = word.chars();
            let letter = chars.next().map(|c| c.to_ascii_uppercase());
            let value = chars.as_str().parse::<f64>();
            match (letter, value) {
                (Some('T'), Ok(v)) => t = Some(v),
                (Some('P'), Ok(v)) => p = Some(v as i64),
                (
                    Some(
                        'T' | 'P' | 'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | 'U' | 'V' | 'W' | 'D' | 'I'
                        | 'J' | 'Q',
                    ),
                    Err(_),
                )
                | (None, _) => {
                    out.push((
                        k + 1,
                        (
                            format!("`{word}` is not a number: LinuxCNC cannot load this line"),
                            true,
                        ),
                    ));
                }
                (Some(c), _) if !"TPXYZABCUVWDIJQ".contains(c) => {
                    out.push((
                        k + 1,
                        (
                            format!("unknown entry `{word}`: LinuxCNC cannot load this line"),
                            true,
                        ),
                    ));
                }
                _ => {}
            }
        }
        if t.is_none() || p.is_none() {
            out.push((
                k + 1,
                (
                    format!("a tool line needs both T (tool number) and P (pocket): `{body}`"),
                    true,
                ),
            ));
        }
        if let Some(p) = p {
            if let Some((_, first)) = pockets.iter().find(|(q, _)| *q == p) {
                out.push((
                    k + 1,
                    (
                        format!("pocket P{p} is already used on line {first}: the last line wins"),
                        false,
                    ),
                ));
            } else {
                pockets.push((p, k + 1));
            }
        }
    }
    out
}
