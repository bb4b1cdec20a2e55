//! The source scan of the rule-code tests (`analyzer/tests/rule_codes.rs`,
//! `runtime/tests/rule_codes.rs`): a tokenizer of Rust source that tells string
//! literals from comments, char literals and lifetimes, the code-shaped literals a
//! file writes outside `declare_rule!` and `#[cfg(test)]` items, and the rules it
//! declares.

use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    Punct(char),
    /// A string literal's text between its quotes (escapes left as written), its
    /// line, and whether it is a byte string.
    Str(String, usize, bool),
}

/// The tokens of Rust source, comments dropped. Only what the scans need: identifiers
/// (numbers read as identifiers), punctuation, and string literals told apart from
/// char literals and lifetimes.
fn tokens(src: &str) -> Vec<Tok> {
    let s: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    let at = |k: usize| s.get(k).copied().unwrap_or('\0');
    while i < s.len() {
        let c = s[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && at(i + 1) == '/' {
            while i < s.len() && s[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < s.len() {
                if s[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if s[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    line += usize::from(s[i] == '\n');
                    i += 1;
                }
            }
        } else if let Some((start, hashes, byte)) = string_start(&s, i) {
            let first = line;
            let mut j = start;
            let mut text = String::new();
            while let Some(&d) = s.get(j) {
                if hashes.is_none() && d == '\\' {
                    text.push(d);
                    text.push(at(j + 1));
                    line += usize::from(at(j + 1) == '\n');
                    j += 2;
                    continue;
                }
                let n = hashes.unwrap_or(0);
                if d == '"' && (1..=n).all(|k| at(j + k) == '#') {
                    j += 1 + n;
                    break;
                }
                line += usize::from(d == '\n');
                text.push(d);
                j += 1;
            }
            out.push(Tok::Str(text, first, byte));
            i = j;
        } else if c == '\'' {
            // A char literal ('x', '\n', '\u{7f}', b'x' starts at the b) or a lifetime.
            if at(i + 1) == '\\' {
                let mut j = i + 3;
                while j < s.len() && s[j] != '\'' {
                    j += 1;
                }
                i = j + 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                i += 1;
            }
        } else if c.is_alphanumeric() || c == '_' {
            let mut j = i;
            while j < s.len() && (s[j].is_alphanumeric() || s[j] == '_') {
                j += 1;
            }
            let word: String = s[i..j].iter().collect();
            // b'x': the b is the prefix of the char literal that follows.
            if word == "b" && at(j) == '\'' {
                i = j;
                continue;
            }
            out.push(Tok::Ident(word));
            i = j;
        } else {
            out.push(Tok::Punct(c));
            i += 1;
        }
    }
    out
}

/// Where a string literal starting at `i` has its text: (first char of the text,
/// `Some(hashes)` for a raw string, byte string).
fn string_start(s: &[char], i: usize) -> Option<(usize, Option<usize>, bool)> {
    let mut j = i;
    let byte = s.get(j) == Some(&'b') || s.get(j) == Some(&'c');
    if byte {
        j += 1;
    }
    if s.get(j) == Some(&'"') {
        return Some((j + 1, None, byte));
    }
    if s.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let mut n = 0;
    while s.get(j) == Some(&'#') {
        n += 1;
        j += 1;
    }
    (s.get(j) == Some(&'"')).then_some((j + 1, Some(n), byte))
}

/// The index after the group that opens at `open` (`{`, `(` or `[`).
fn skip_group(t: &[Tok], open: usize) -> usize {
    let mut depth = 0usize;
    for (k, tok) in t.iter().enumerate().skip(open) {
        match tok {
            Tok::Punct('{' | '(' | '[') => depth += 1,
            Tok::Punct('}' | ')' | ']') => {
                depth -= 1;
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
    }
    t.len()
}

/// The index after the item that starts at `i` (its attributes, then up to its `;`
/// or through its `{…}` body).
fn skip_item(t: &[Tok], mut i: usize) -> usize {
    while i < t.len() {
        match t[i] {
            Tok::Punct('#') => i = skip_group(t, i + 1),
            Tok::Punct('(' | '[') => i = skip_group(t, i),
            Tok::Punct(';') => return i + 1,
            Tok::Punct('{') => return skip_group(t, i),
            _ => i += 1,
        }
    }
    i
}

fn is(t: &[Tok], i: usize, want: &[&str]) -> bool {
    want.iter().enumerate().all(|(k, w)| match t.get(i + k) {
        Some(Tok::Ident(s)) => s == w,
        Some(Tok::Punct(c)) => w.len() == 1 && w.starts_with(*c),
        _ => false,
    })
}

/// Whether a literal's text has the shape of a rule code: a capital letter and
/// three digits (`G004`, `L015`, `X003`).
pub fn code_shaped(text: &str) -> bool {
    let b = text.as_bytes();
    b.len() == 4 && b[0].is_ascii_uppercase() && b[1..].iter().all(u8::is_ascii_digit)
}

/// One source file read for the scans.
pub struct Scan {
    /// Code-shaped `&str` literals outside `declare_rule!` and `#[cfg(test)]` items:
    /// (line, text).
    pub code_literals: Vec<(usize, String)>,
    /// The rules the file declares: (static, code, origin).
    pub declared: Vec<(String, String, String)>,
}

pub fn scan(src: &str) -> Scan {
    let t = tokens(src);
    let mut scan = Scan {
        code_literals: Vec::new(),
        declared: Vec::new(),
    };
    let mut i = 0;
    while i < t.len() {
        if is(&t, i, &["declare_rule", "!"]) && !is(&t, i.saturating_sub(1), &["macro_rules"]) {
            let end = skip_group(&t, i + 2);
            scan.declared.push(declared_rule(&t[i..end]));
            i = end;
        } else if is(&t, i, &["#", "[", "cfg", "(", "test", ")", "]"]) {
            // Tests assert the codes users see, as literals.
            i = skip_item(&t, i + 7);
        } else {
            if let Tok::Str(text, line, false) = &t[i] {
                if code_shaped(text) {
                    scan.code_literals.push((*line, text.clone()));
                }
            }
            i += 1;
        }
    }
    scan
}

/// (static, code, origin) of one `declare_rule! { … }`.
fn declared_rule(t: &[Tok]) -> (String, String, String) {
    let mut rule = (String::new(), String::new(), String::new());
    for k in 0..t.len() {
        if is(t, k, &["static"]) {
            if let Some(Tok::Ident(s)) = t.get(k + 1) {
                rule.0 = s.clone();
            }
        }
        if is(t, k, &["code", ":"]) {
            if let Some(Tok::Str(s, ..)) = t.get(k + 2) {
                rule.1 = s.clone();
            }
        }
        if is(t, k, &["origin", ":"]) {
            if let Some(Tok::Ident(s)) = t.get(k + 2) {
                rule.2 = s.clone();
            }
        }
    }
    rule
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("read src")
        .map(|e| e.expect("dir entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Every `.rs` file under `crate_dir/src`, scanned: (its path under `src`, the scan).
pub fn sources(crate_dir: &str) -> Vec<(String, Scan)> {
    let src = Path::new(crate_dir).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    assert!(
        files.len() > 50,
        "found only {} files under {src:?}",
        files.len()
    );
    files
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p).expect("read source");
            let name = p
                .strip_prefix(&src)
                .expect("under src")
                .to_string_lossy()
                .replace('\\', "/");
            (name, scan(&text))
        })
        .collect()
}
