//! Flow-sensitive rule: its metadata and its check, which the interpreter runs
//! once before the first block (`Interp::spec_input_files`).

use analyzer::declare_rule;
use analyzer::{Severity, Span};

use super::check::Sink;

declare_rule! {
    /// ## What it does
    /// Checks the LinuxCNC parameter (`.var`) file the run reads: every line must be `number value`, with increasing numbers. The example program runs with a file holding `5221 1.0` then `5220 1.0`.
    ///
    /// ## Why is this bad?
    /// LinuxCNC refuses a parameter file that is out of order or cannot be read.
    ///
    /// ## Example
    /// ```gcode
    /// G0 X1
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```gcode
    /// G0 X1
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC (the file the host reads). Error.
    ///
    /// Implements: NGC429
    pub static VAR_FILE = {
        code: "X011",
        name: "var-file",
        summary: "Malformed or out-of-order parameter file",
        implements: &["NGC429"],
        origin: Runtime,
        default_enabled: true,
    }
}

/// Reports the problems of the LinuxCNC `.var` file the host read.
pub(crate) fn check(text: &str, out: &mut Sink<'_>) {
    for (line, msg) in problems(text) {
        out.diag(
            &VAR_FILE,
            Severity::Error,
            Span::default(),
            format!("parameter file line {line}: {msg}"),
        );
    }
}

/// Problems of a LinuxCNC `.var` file: (1-based line, message).
fn problems(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut last: Option<u64> = None;
    for (k, line) in text.lines().enumerate() {
        let mut it = line.split_whitespace();
        let Some(n) = it.next() else { continue };
        let (Ok(n), Some(Ok(_))) = (n.parse::<u64>(), it.next().map(|v| v.parse::<f64>())) else {
            out.push((
                k + 1,
                format!(
                    "`{}` is not `number value`: LinuxCNC cannot read the parameter file",
                    line.trim()
                ),
            ));
            continue;
        };
        if last.is_some_and(|l| n <= l) {
            out.push((k + 1, format!("parameter {n} is out of order (after {}): LinuxCNC requires increasing numbers", last.unwrap_or(0))));
        }
        last = Some(n);
    }
    out
}
