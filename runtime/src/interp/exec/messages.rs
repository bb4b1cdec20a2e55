//! Comments and messages: plain comments in canonical output, `(MSG, …)`,
//! `(DEBUG, …)`, `(PRINT, …)` and `(ABORT, …)` with their parameter substitution,
//! and rs274's wording of interpreter errors for canonical output.

use super::params::predefined;
use super::*;
use crate::rules::macro_alarm::MACRO_ALARM;

impl Interp<'_, '_> {
    pub(super) fn exec_comment(
        &mut self,
        p: &Program,
        k: CommentKind,
        s: Span,
    ) -> Result<(), Diagnostic> {
        let text = p.str_of(s).into_owned();
        if text.starts_with(';') {
            return Ok(());
        }
        let inner = text
            .trim_start_matches('(')
            .trim_end_matches(')')
            .to_string();
        let after_comma = |t: &str| {
            t.split_once(',')
                .map(|(_, r)| r.to_string())
                .unwrap_or_default()
        };
        match k {
            CommentKind::Plain | CommentKind::Partscope if self.ngc() => {
                self.canon_comment(inner.trim_start())
            }
            CommentKind::Msg => {
                let m = after_comma(&inner);
                canon!(self, "MESSAGE(\"{m}\")");
                self.event(EventKind::Message(m));
            }
            CommentKind::Debug | CommentKind::Print => {
                let m = self.substitute(&after_comma(&inner));
                if k == CommentKind::Print {
                    if let Some(c) = self.canon.as_mut() {
                        c.raw(m);
                    }
                } else if !self.ngc() || self.read_param(5599) > 0.0 {
                    // #5599 = 0 silences (DEBUG,) in LinuxCNC.
                    canon!(self, "MESSAGE(\"{m}\")");
                }
            }
            CommentKind::Abort => {
                let m = self.substitute(&after_comma(&inner));
                return Err(self.err(&MACRO_ALARM, s, format!("abort: {m}")));
            }
            _ => {}
        }
        Ok(())
    }

    /// Replaces `#n` and `#<name>` in a message with `%f`-formatted values.
    pub(super) fn substitute(&self, text: &str) -> String {
        let b = text.as_bytes();
        let mut out = String::new();
        let mut i = 0;
        // LinuxCNC's `%d`, `%f` (4 decimals) and `%.Nf` set the format of the
        // parameters that follow (a bare `%lf` stays as text); the default is 6 decimals.
        let mut decimals = 6usize;
        while i < b.len() {
            if b[i] == b'%' {
                let rest = &text[i + 1..];
                let (spec_len, d) = if rest.starts_with('d') {
                    (1, Some(0))
                } else if rest.starts_with('f') {
                    (1, Some(4))
                } else if let Some(r) = rest.strip_prefix('.') {
                    let digits = r.bytes().take_while(u8::is_ascii_digit).count();
                    let after = &r[digits..];
                    let tail = if after.starts_with("lf") {
                        2
                    } else if after.starts_with('f') {
                        1
                    } else {
                        0
                    };
                    if digits > 0 && tail > 0 {
                        (
                            1 + digits + tail,
                            r[..digits].parse::<usize>().ok().map(|n| n.min(20)),
                        )
                    } else {
                        (0, None)
                    }
                } else {
                    (0, None)
                };
                if let Some(d) = d {
                    decimals = d;
                    i += 1 + spec_len;
                    continue;
                }
            }
            if b[i] == b'#' {
                if b.get(i + 1) == Some(&b'<') {
                    if let Some(end) = text[i..].find('>') {
                        let name = expr::named_key(&text[i + 2..i + end]);
                        let locals = self
                            .frames
                            .last()
                            .map(|f| &f.named_locals)
                            .unwrap_or(&self.main_locals);
                        let v = locals
                            .get(&name)
                            .copied()
                            .or_else(|| self.st.named.get(&name).copied())
                            .or_else(|| predefined(&self.st, &name));
                        match v {
                            Some(v) => out.push_str(&format!("{v:.decimals$}")),
                            None => out.push_str("######"),
                        }
                        i += end + 1;
                        continue;
                    }
                } else {
                    let mut j = i + 1;
                    while j < b.len() && b[j].is_ascii_digit() {
                        j += 1;
                    }
                    if j > i + 1 {
                        // LinuxCNC has 5602 numbered parameters and prints those
                        // beyond as hashes.
                        match text[i + 1..j].parse::<usize>() {
                            Ok(n) if !self.ngc() || n < 5602 => {
                                let v = self.read_param(n as i64);
                                out.push_str(&format!("{v:.decimals$}"));
                            }
                            _ => out.push_str("######"),
                        }
                        i = j;
                        continue;
                    }
                }
            }
            let ch = text[i..].chars().next().unwrap_or(' ');
            out.push(ch);
            i += ch.len_utf8();
        }
        out
    }
}

/// rs274's wording of an interpreter error, from our message: known messages map
/// to its text; otherwise the part before the first explanation, capitalised.
/// rs274's words for a `#` it cannot read in `line`, the first one from the left: a name
/// that is no function (`#foo`), a `<name` without `>`, or nothing it can read as a number
/// (`#]`). `None` when every `#` reads (the block failed for another reason).
pub(super) fn rs274_parameter_message(line: &str) -> Option<String> {
    // rs274 reads a letter after `#` as a unary function; the first letter picks the
    // candidates, and a letter no function starts with has its own message.
    const FUNCTIONS: [&str; 14] = [
        "abs", "acos", "asin", "atan", "cos", "exists", "exp", "fix", "fup", "ln", "round", "sin",
        "sqrt", "tan",
    ];
    const FIRST: &[u8] = b"aceflrst";
    let text = line.to_ascii_lowercase();
    let b = text.as_bytes();
    let mut i = 0;
    let mut comment = false;
    while i < b.len() {
        let c = b[i];
        i += 1;
        match c {
            b'(' => comment = true,
            b')' => comment = false,
            b';' if !comment => return None,
            b'#' if !comment => {
                let mut j = i;
                while j < b.len() && (b[j] == b' ' || b[j] == b'\t') {
                    j += 1;
                }
                match b.get(j) {
                    Some(b'<') => {
                        if !b[j..].contains(&b'>') {
                            return Some("Named parameter not terminated".to_string());
                        }
                    }
                    Some(c) if c.is_ascii_alphabetic() => {
                        let word: String = b[j..]
                            .iter()
                            .take_while(|c| c.is_ascii_alphabetic())
                            .map(|&c| c as char)
                            .collect();
                        if !FUNCTIONS.iter().any(|f| word.starts_with(f)) {
                            return Some(if FIRST.contains(c) {
                                format!("Unknown word starting with {}", *c as char)
                            } else {
                                "Unknown word where unary operation could be".to_string()
                            });
                        }
                    }
                    Some(c)
                        if c.is_ascii_digit() || matches!(c, b'[' | b'+' | b'-' | b'.' | b'#') => {}
                    _ => {
                        return Some("bad number format (conversion failed) parsing ''".to_string())
                    }
                }
            }
            _ => {}
        }
    }
    None
}

pub(super) fn rs274_message(msg: &str) -> String {
    const KNOWN: &[(&str, &str)] = &[
        (
            "cannot feed with zero feed rate",
            "Cannot do g1 with zero feed rate",
        ),
        (
            "R, I, J and K words all missing",
            "R i j k words all missing for arc",
        ),
        ("SQRT of a negative", "Negative argument to sqrt"),
        (
            "Start point too close to probe point",
            "Start point too close to probe point",
        ),
        ("argument to sqrt out of range", "Negative argument to sqrt"),
        (
            "argument to ln out of range",
            "Zero or negative argument to ln",
        ),
        (
            "Arc with both a radius R",
            "Mixed radius ijk format for arc",
        ),
        ("bad character '", ""),
        (
            "length of cutter compensation entry move",
            "Length of cutter compensation entry move is not greater than the tool radius",
        ),
        (
            "zero degree inside corner",
            "Zero degree inside corner is invalid for cutter compensation",
        ),
    ];
    if msg.starts_with("parameter number #") && msg.contains("out of range") {
        return "Parameter number out of range".to_string();
    }
    if msg.starts_with("M72 restores a modal state that no M70") {
        return "Cannot restore context from invalid stack frame - missing M70/M73?".to_string();
    }
    if msg.contains("is the first move after G40") {
        return "The move just after exiting cutter compensation mode must be straight, not an arc"
            .to_string();
    }
    for (ours, theirs) in KNOWN {
        if msg.starts_with(ours) {
            if theirs.is_empty() {
                break;
            }
            return (*theirs).to_string();
        }
    }
    // Our own wording starts in lower case and explains after a colon; messages
    // already in rs274's words start with a capital and are kept whole.
    let head = if msg.starts_with(|c: char| c.is_ascii_lowercase()) {
        msg.split(": ").next().unwrap_or(msg)
    } else {
        msg
    };
    let mut c = head.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}
