//! Analysis settings and the `partscope.toml` configuration format.
//!
//! Parsing configuration text is pure; finding and reading the file is the
//! host's job.

use crate::diagnostic::Diagnostic;
use crate::dialect::{Dialect, Variant};
use crate::rules::RuleMeta;
use crate::span::Span;
use crate::syntax::{CommentKind, ItemKind, Program};

pub use crate::config::{fail_level, Config};

/// Everything the analysis of one file needs to know besides its text.
#[derive(Debug, Clone)]
pub struct Settings {
    pub dialect: Dialect,
    pub variant: Variant,
    pub select: Vec<String>,
    pub ignore: Vec<String>,
    pub custom_codes: Vec<String>,
    /// Axis letters the machine has (upper case).
    pub axes: Vec<char>,
    /// ServoWorks "Integer Programming with Machine Unit Enable".
    pub integer_machine_unit: bool,
    /// FANUC sequence-number digits: 5, or 8 with the 8-digit sequence number option.
    pub sequence_number_digits: u8,
    /// FANUC program-number digits: 4, or 8 with the 8-digit program number option;
    /// `None` (not configured): a program head beyond 4 digits is taken as the
    /// option's and said once, as information.
    pub program_number_digits: Option<u8>,
    /// FANUC: the last common variable of the #100 range: 199 (standard) or 499
    /// (the additional common variables option); `None` (not configured): a use of
    /// #200–#499 is taken as the option's and said once, as information.
    pub common_variables_end: Option<u16>,
    /// Diagnostics of one code reported per file; the rest become one
    /// "… and N more" (see [`crate::limit_diagnostics`]).
    pub max_per_code: usize,
    /// Diagnostics reported per file, all codes together.
    pub max_per_file: usize,
    /// Runtime errors the interpreter reports and recovers from per file; at this
    /// many it stops the run with one F004.
    pub max_runtime_errors: usize,
    /// The stem of the program's file name (`z_touch` for `z_touch.ngc`), when the
    /// program has one: LinuxCNC finds a subroutine file by the subroutine's name.
    pub file_stem: Option<String>,
}

/// Default of [`Settings::max_per_code`].
pub const DEFAULT_MAX_PER_CODE: usize = 1000;
/// Default of [`Settings::max_per_file`].
pub const DEFAULT_MAX_PER_FILE: usize = 20_000;
/// Default of [`Settings::max_runtime_errors`].
pub const DEFAULT_MAX_RUNTIME_ERRORS: usize = 100;

impl Settings {
    /// How the parser reads text for these settings (dialect and variant).
    pub fn parse_options(&self) -> crate::syntax::ParseOptions {
        crate::syntax::ParseOptions {
            dialect: self.dialect,
            variant: self.variant,
        }
    }

    pub fn new(dialect: Dialect) -> Settings {
        Settings {
            dialect,
            variant: dialect.default_variant(),
            select: Vec::new(),
            ignore: Vec::new(),
            custom_codes: Vec::new(),
            axes: vec!['X', 'Y', 'Z', 'A', 'B', 'C'],
            integer_machine_unit: false,
            sequence_number_digits: 5,
            program_number_digits: None,
            common_variables_end: None,
            max_per_code: DEFAULT_MAX_PER_CODE,
            max_per_file: DEFAULT_MAX_PER_FILE,
            max_runtime_errors: DEFAULT_MAX_RUNTIME_ERRORS,
            file_stem: None,
        }
    }

    /// Settings from a config, with an optional dialect override. The config's
    /// values were checked when it was read ([`Config::load`]).
    pub fn from_config(config: &Config, dialect_override: Option<Dialect>) -> Settings {
        let dialect = dialect_override
            .or(config.dialect)
            .unwrap_or(Dialect::Rs274ngc);
        let mut s = Settings::new(dialect);
        if let Some(v) = config.variant.filter(|v| v.dialect() == dialect) {
            s.variant = v;
        }
        let rules = &config.rules;
        s.select = rules.select.clone().unwrap_or_default();
        s.ignore = rules.ignore.clone().unwrap_or_default();
        if let Some(n) = rules.max_runtime_errors {
            s.max_runtime_errors = n;
        }
        s.custom_codes = rules
            .custom_codes
            .iter()
            .flatten()
            .map(|c| c.to_ascii_uppercase())
            .collect();
        let m = &config.machine;
        if let Some(letters) = m.axis_letters() {
            s.axes = letters;
        }
        if let Some(v) = m.integer_machine_unit {
            s.integer_machine_unit = v;
        }
        // FANUC options that widen the number formats (spec fanuc.md §1.5, §1.6).
        if let Some(n) = m.sequence_number_digits {
            s.sequence_number_digits = n;
        }
        s.program_number_digits = m.program_number_digits;
        s.common_variables_end = m.common_variables;
        s
    }

    /// Whether a `select`/`ignore` pattern (a code, a code prefix, a rule name or
    /// `ALL`) names the rule `code`/`name`.
    pub fn matches(pattern: &str, code: &str, name: &str) -> bool {
        let p = pattern.trim();
        p.eq_ignore_ascii_case("ALL")
            || code.starts_with(&p.to_ascii_uppercase())
            || p.eq_ignore_ascii_case(name)
    }

    /// Whether a rule runs under these settings.
    pub fn rule_enabled(&self, meta: &RuleMeta) -> bool {
        if self
            .ignore
            .iter()
            .any(|p| Self::matches(p, meta.code, meta.name))
        {
            return false;
        }
        if self.select.is_empty() {
            return meta.default_enabled;
        }
        let explicit = self.select.iter().any(|p| {
            let p = p.trim();
            !p.eq_ignore_ascii_case("ALL") && Self::matches(p, meta.code, meta.name)
        });
        explicit
            || (meta.default_enabled
                && self
                    .select
                    .iter()
                    .any(|p| Self::matches(p, meta.code, meta.name)))
    }

    /// Whether a diagnostic code passes select/ignore (for codes without metadata).
    pub fn code_enabled(&self, code: &str) -> bool {
        if self.ignore.iter().any(|p| Self::matches(p, code, "")) {
            return false;
        }
        self.select.is_empty() || self.select.iter().any(|p| Self::matches(p, code, ""))
    }
}

/// `(partscope: allow CODE, CODE)` suppresses those codes in its block;
/// `(partscope: allow-file CODE)` anywhere suppresses them in the file; and
/// `(partscope: dialect=NAME)` on the first line chooses the dialect.
#[derive(Debug, Default, Clone)]
pub struct Suppressions {
    /// (the file offsets a block owns, code) pairs: from the block's start to
    /// the next block's, as [`Program::block_at`] assigns offsets to blocks.
    block: Vec<(Span, String)>,
    file: Vec<String>,
}

/// The offsets block `bi` owns ([`Program::block_at`]).
fn owned_range(program: &Program, bi: usize) -> Span {
    // Offsets before the first block belong to it.
    let start = match bi {
        0 => program.base,
        _ => program.blocks.get(bi).map_or(0, |b| b.span.start),
    };
    let end = program
        .blocks
        .get(bi + 1)
        .map_or(u32::MAX, |b| b.span.start);
    Span::new(start, end)
}

impl Suppressions {
    /// Moves the block directives with `f` (a host that collected them from
    /// a stand-in for the file maps them back to the file's offsets).
    pub fn map_spans(&mut self, f: impl Fn(Span) -> Span) {
        for (s, _) in &mut self.block {
            *s = f(*s);
        }
    }

    /// Adds another part of the same file's directives.
    pub fn extend(&mut self, other: Suppressions) {
        self.block.extend(other.block);
        self.file.extend(other.file);
    }

    pub fn collect(program: &Program) -> Suppressions {
        let mut s = Suppressions::default();
        // Directive comments are rare, and every directive holds a `:`
        // (`partscope:`): only the blocks with a `:` in their text are read, found
        // with a byte search instead of a walk over every item of the file.
        let text = &program.text[..];
        let base = program.base as usize;
        let mut from = 0usize;
        while let Some(at) = text.get(from..).and_then(|t| memchr::memchr(b':', t)) {
            let at = from + at;
            let Some(bi) = u32::try_from(at + base)
                .ok()
                .and_then(|a| program.block_at(a))
            else {
                break;
            };
            let Some(block) = program.blocks.get(bi) else {
                break;
            };
            s.collect_block(program, bi, block);
            // The next block, or the next byte when the block ends before `at` (text
            // between blocks, which owns no items).
            let next = program
                .blocks
                .get(bi + 1)
                .map_or(text.len(), |b| (b.span.start as usize).saturating_sub(base));
            from = next.max(at + 1);
        }
        s
    }

    /// The directives of the comments of block `bi`.
    fn collect_block(&mut self, program: &Program, bi: usize, block: &crate::syntax::Block) {
        for item in program.items_of(block) {
            if !matches!(item.kind, ItemKind::Comment(CommentKind::Partscope)) {
                continue;
            }
            let text = program.str_of(item.span).into_owned();
            for directive in parse_directives(&text) {
                match directive {
                    Directive::Allow(codes) => {
                        let range = owned_range(program, bi);
                        self.block.extend(codes.into_iter().map(|c| (range, c)))
                    }
                    Directive::AllowFile(codes) => self.file.extend(codes),
                    Directive::Dialect(_) => {}
                }
            }
        }
    }

    /// The item-by-item scan `collect` replaces, kept to test that both agree.
    #[cfg(test)]
    fn collect_by_items(program: &Program) -> Suppressions {
        let mut s = Suppressions::default();
        for (k, item) in program.items.iter().enumerate() {
            if !matches!(item.kind, ItemKind::Comment(CommentKind::Partscope)) {
                continue;
            }
            let k = k as u32;
            let bi = program.blocks.partition_point(|b| b.items.0 <= k);
            let Some(bi) = bi
                .checked_sub(1)
                .filter(|&bi| program.blocks.get(bi).is_some_and(|b| k < b.items.1))
            else {
                continue;
            };
            let text = program.str_of(item.span).into_owned();
            for directive in parse_directives(&text) {
                match directive {
                    Directive::Allow(codes) => {
                        let range = owned_range(program, bi);
                        s.block.extend(codes.into_iter().map(|c| (range, c)))
                    }
                    Directive::AllowFile(codes) => s.file.extend(codes),
                    Directive::Dialect(_) => {}
                }
            }
        }
        s
    }

    pub fn is_suppressed(&self, d: &Diagnostic) -> bool {
        let m = |c: &String| c.eq_ignore_ascii_case(d.code) || c.eq_ignore_ascii_case("all");
        if self.file.iter().any(m) {
            return true;
        }
        let at = d.span.start;
        self.block
            .iter()
            .any(|(r, c)| r.start <= at && at < r.end && m(c))
    }
}

#[derive(Debug, PartialEq)]
pub enum Directive {
    Allow(Vec<String>),
    AllowFile(Vec<String>),
    Dialect(String),
}

/// Reads `partscope:` directives from a comment's text.
pub fn parse_directives(comment: &str) -> Vec<Directive> {
    let body = comment
        .trim_start_matches(['(', ';'])
        .trim_end_matches(')')
        .trim();
    let Some(rest) = body
        .get(10..)
        .filter(|_| body.len() >= 10 && body[..10].eq_ignore_ascii_case("partscope:"))
    else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let rest = rest.trim();
    let lower = rest.to_ascii_lowercase();
    let codes_after = |prefix: usize| -> Vec<String> {
        rest[prefix..]
            .split([',', ' ', '\t'])
            .map(|c| c.trim().to_ascii_uppercase())
            .filter(|c| !c.is_empty())
            .collect()
    };
    if lower.starts_with("allow-file") {
        out.push(Directive::AllowFile(codes_after(10)));
    } else if lower.starts_with("allow") {
        out.push(Directive::Allow(codes_after(5)));
    } else if let Some(d) = lower.strip_prefix("dialect") {
        let d = d.trim_start().trim_start_matches(['=', ':']).trim();
        out.push(Directive::Dialect(
            d.split_whitespace().next().unwrap_or("").to_string(),
        ));
    }
    out
}

/// The dialect a file names in a `(partscope: dialect=…)` comment on its first
/// non-blank line.
pub fn dialect_directive(text: &[u8]) -> Option<Dialect> {
    // The first line that is neither blank nor a `%` tape mark.
    let line = text
        .split(|b| *b == b'\n')
        .map(|l| l.trim_ascii())
        .find(|l| !l.is_empty() && *l != b"%")?;
    let line = String::from_utf8_lossy(line);
    let start = line.find(['(', ';'])?;
    parse_directives(&line[start..])
        .into_iter()
        .find_map(|d| match d {
            Directive::Dialect(name) => Dialect::parse(&name),
            _ => None,
        })
}

/// Guesses the dialect from a file's extension and content, when neither a
/// config nor a directive says.
pub fn sniff_dialect(path_ext: Option<&str>, text: &[u8]) -> Option<Dialect> {
    sniff_dialect_why(path_ext, text).map(|(d, _)| d)
}

/// [`sniff_dialect_why`] for a file name: when neither the extension nor the
/// content decides, a FANUC-style program-number name (`O8502`, `O1234.NC`)
/// does. Both hosts sniff through this.
pub fn sniff_file_dialect_why(file_name: Option<&str>, text: &[u8]) -> Option<(Dialect, String)> {
    let (stem, ext) = match file_name.and_then(|n| n.rsplit_once('.')) {
        Some((stem, ext)) if !stem.is_empty() => (Some(stem), Some(ext)),
        _ => (file_name, None),
    };
    sniff_dialect_why(ext, text).or_else(|| {
        let stem = stem?;
        program_number(stem.to_ascii_uppercase().as_bytes())
            .filter(|_| stem.starts_with(['O', 'o']))
            .map(|_| {
                (
                    Dialect::Fanuc,
                    format!("the program-number file name `{stem}`"),
                )
            })
    })
}

/// [`sniff_dialect`] with the evidence that decided it, in words a user can
/// check ("program number O1000 on line 2"), so a wrong guess is visible.
pub fn sniff_dialect_why(path_ext: Option<&str>, text: &[u8]) -> Option<(Dialect, String)> {
    if let Some(d) = dialect_directive(text) {
        return Some((d, "the first-line `(partscope: dialect=…)` comment".into()));
    }
    let ext = path_ext.map(|e| e.to_ascii_lowercase());
    let by_ext = match ext.as_deref() {
        Some("ngc") => Some(Dialect::Rs274ngc),
        Some("dat" | "sw") => Some(Dialect::Servoworks),
        Some("fnc") => Some(Dialect::Fanuc),
        _ => None,
    };
    if let (Some(d), Some(e)) = (by_ext, ext.as_deref()) {
        return Some((d, format!("the `.{e}` extension")));
    }
    content_dialect(&text[..text.len().min(64 * 1024)])
}

/// The dialect that the text's own syntax proves. RS274/NGC O-word and named
/// parameter syntax exists in no FANUC program; FANUC macro statements, GOTO,
/// G65/G66 calls, `;` block ends and an `O` program number on a line of its
/// own (rs274 rejects an O-word without a keyword) exist in no LinuxCNC one.
fn content_dialect(head: &[u8]) -> Option<(Dialect, String)> {
    let mut fanuc: Option<String> = None;
    let mut percent_line = None;
    for (i, raw) in head.split(|b| *b == b'\n').enumerate() {
        let n = i + 1;
        let line = raw.trim_ascii();
        if line == b"%" {
            percent_line.get_or_insert(n);
            continue;
        }
        let code = code_of_line(line);
        let words = code.split(|b| *b == b' ').filter(|w| !w.is_empty());
        let first = code.split(|b| *b == b' ').find(|w| !w.is_empty());
        if let Some(e) = ngc_evidence(&code, first) {
            return Some((Dialect::Rs274ngc, format!("{e} on line {n}")));
        }
        if semicolon_comment(line) {
            return Some((
                Dialect::Rs274ngc,
                format!("a `;` comment on line {n} (FANUC ends the block at `;` and reads the text after it as words)"),
            ));
        }
        if fanuc.is_some() {
            continue;
        }
        let mut it = words.peekable();
        // A leading N number does not change what the block is.
        if it.peek().is_some_and(|w| is_word(w, b'N')) {
            it.next();
        }
        let lead = it.next().unwrap_or_default();
        if lead == b"WHILE" || lead.starts_with(b"WHILE[") {
            fanuc = Some(format!("a `WHILE` statement on line {n}"));
        } else if lead == b"IF" || lead.starts_with(b"IF[") {
            fanuc = Some(format!("an `IF` statement on line {n}"));
        } else if contains(&code, b"GOTO") {
            fanuc = Some(format!("a `GOTO` on line {n}"));
        } else if macro_call(&code) {
            fanuc = Some(format!("a G65/G66 macro call on line {n}"));
        } else if line.ends_with(b";") && code.len() > 1 {
            fanuc = Some(format!("blocks ending in `;` (line {n})"));
        } else if let Some(head) = program_number(without_sequence_number(&code)) {
            fanuc = Some(match percent_line {
                Some(p) => format!("the `%` line {p} and program number {head} on line {n}"),
                None => format!("program number {head} on line {n}"),
            });
        }
    }
    fanuc.map(|e| (Dialect::Fanuc, e))
}

/// A line upper-cased, without `( )` comments, with blanks folded to one.
fn code_of_line(line: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(line.len());
    let mut depth = 0u32;
    for &b in line {
        match b {
            b'(' => depth += 1,
            b')' if depth > 0 => depth -= 1,
            _ if depth > 0 => {}
            b' ' | b'\t' | b'\r' => {
                if out.last().is_some_and(|l| *l != b' ') {
                    out.push(b' ');
                }
            }
            _ => out.push(b.to_ascii_uppercase()),
        }
    }
    while out.last() == Some(&b' ') {
        out.pop();
    }
    out
}

/// `G65 P…`/`G66 P…`, or a call by name (`G65 "PROBECONFIG"`, `G65 <NAME>`,
/// written by controls of the FANUC family).
fn macro_call(code: &[u8]) -> bool {
    code.windows(3).enumerate().any(|(i, w)| {
        (w == b"G65" || w == b"G66")
            && code
                .get(i.wrapping_sub(1))
                .is_none_or(|b| !b.is_ascii_alphanumeric())
            && {
                let rest = &code[i + 3..];
                let rest = rest.strip_prefix(b" ").unwrap_or(rest);
                matches!(rest.first(), Some(b'P' | b'"' | b'<'))
            }
    })
}

/// The block without a leading `N` sequence number (`N0 O9999` is a program head).
fn without_sequence_number(code: &[u8]) -> &[u8] {
    match code.split_first() {
        Some((b'N', rest)) => {
            let digits = rest.iter().take_while(|b| b.is_ascii_digit()).count();
            if digits > 0 {
                rest[digits..].trim_ascii_start()
            } else {
                code
            }
        }
        _ => code,
    }
}

fn contains(hay: &[u8], needle: &[u8]) -> bool {
    hay.windows(needle.len()).any(|w| w == needle)
}

/// `X12` style word: the letter, then digits.
fn is_word(w: &[u8], letter: u8) -> bool {
    w.len() > 1 && w[0] == letter && w[1..].iter().all(u8::is_ascii_digit)
}

/// What in a line only RS274/NGC writes: `o<name>`, `#<name>`, or a numbered
/// O-word followed by its keyword (`o100 sub`, `O110 if [...]`).
fn ngc_evidence(code: &[u8], first: Option<&[u8]>) -> Option<&'static str> {
    if contains(code, b"#<") {
        return Some("a named parameter `#<…>`");
    }
    let first = first?;
    if first.starts_with(b"O<") {
        return Some("an O-word `o<…>`");
    }
    const KEYWORDS: &[&[u8]] = &[
        b"SUB",
        b"ENDSUB",
        b"CALL",
        b"IF",
        b"ELSEIF",
        b"ELSE",
        b"ENDIF",
        b"WHILE",
        b"ENDWHILE",
        b"DO",
        b"REPEAT",
        b"ENDREPEAT",
        b"RETURN",
        b"BREAK",
        b"CONTINUE",
    ];
    if is_word(first, b'O') {
        let rest = &code[first.len()..];
        let rest = rest.strip_prefix(b" ").unwrap_or(rest);
        let kw: &[u8] = rest
            .split(|b| !b.is_ascii_alphabetic())
            .next()
            .unwrap_or_default();
        if KEYWORDS.contains(&kw) {
            return Some("a numbered O-word with its keyword");
        }
    }
    None
}

/// Whether text after a `;` reads as prose: a word of two or more letters
/// that is no macro keyword or function (`N1 G21; mm mode`). LinuxCNC, Mach and
/// Grbl take `;` to the end of the line as a comment; on FANUC `;` ends the
/// block, so no FANUC program has prose after one (it would alarm).
fn semicolon_comment(line: &[u8]) -> bool {
    const MACRO_WORDS: &[&[u8]] = &[
        b"GOTO", b"WHILE", b"DO", b"END", b"IF", b"THEN", b"EQ", b"NE", b"GT", b"LT", b"GE", b"LE",
        b"AND", b"OR", b"XOR", b"MOD", b"POPEN", b"PCLOS", b"DPRNT", b"BPRNT",
    ];
    let mut depth = 0u32;
    let Some(at) = line.iter().position(|&b| {
        match b {
            b'(' => depth += 1,
            b')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        b == b';' && depth == 0
    }) else {
        return false;
    };
    let rest = code_of_line(&line[at + 1..]);
    rest.split(|b| !b.is_ascii_alphabetic())
        .filter(|w| w.len() >= 2)
        .any(|w| {
            !MACRO_WORDS.contains(&w)
                && crate::syntax::Func::from_name(&String::from_utf8_lossy(w)).is_none()
        })
}

/// `O1000` or `:1000` alone on its line (a comment or `;` may follow): a
/// FANUC program number. Returns it as written.
fn program_number(code: &[u8]) -> Option<String> {
    let code = code.strip_suffix(b";").unwrap_or(code).trim_ascii();
    let (letter, digits) = code.split_first()?;
    let ok = matches!(letter, b'O' | b':')
        && (1..=8).contains(&digits.len())
        && digits.iter().all(u8::is_ascii_digit);
    ok.then(|| String::from_utf8_lossy(code).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CLI and the language server both sniff through this function, so
    /// a file's dialect cannot depend on the host (the LSP soak test found a
    /// `.fnc` file checked as FANUC by `check` and as RS274/NGC by the server).
    #[test]
    fn extensions_pick_the_dialect_after_the_directive() {
        assert_eq!(sniff_dialect(Some("fnc"), b"G0 X1\n"), Some(Dialect::Fanuc));
        assert_eq!(sniff_dialect(Some("FNC"), b"G0 X1\n"), Some(Dialect::Fanuc));
        assert_eq!(
            sniff_dialect(Some("sw"), b"G0 X1\n"),
            Some(Dialect::Servoworks)
        );
        assert_eq!(sniff_dialect(Some("nc"), b"G0 X1\n"), None);
        assert_eq!(
            sniff_dialect(Some("fnc"), b"(partscope: dialect=rs274ngc)\nG0 X1\n"),
            Some(Dialect::Rs274ngc)
        );
    }

    /// A generator's program with `%`, an O number and `;` comments (a real one:
    /// `N1 G21; mm mode`) is no FANUC program, where `;` ends the block and the
    /// comment's words would be read as addresses (2 000 errors on one file).
    /// Text after `;` that is G-code, a macro statement or a `( )` comment keeps
    /// FANUC.
    #[test]
    fn prose_after_a_semicolon_is_a_comment_not_a_fanuc_block_end() {
        let why = |t: &str| sniff_dialect_why(Some("nc"), t.as_bytes());
        assert_eq!(
            why("%\nO0000(MY GCODE)\nN1 G21; mm mode\nN2 G0 X0 Y0\nM30\n%\n"),
            Some((
                Dialect::Rs274ngc,
                "a `;` comment on line 3 (FANUC ends the block at `;` and reads the text after it as words)"
                    .into()
            ))
        );
        for fanuc in [
            "%\nO1000\nG0 X1.;\nG1 X2.; (FEED)\nM30;\n%\n",
            "%\nO1000\nG0 X1.;G1 X2.;\nIF[#1EQ1]GOTO10;\n#2=SIN[#1];\nM30\n%\n",
        ] {
            assert_eq!(why(fanuc).map(|w| w.0), Some(Dialect::Fanuc), "{fanuc}");
        }
    }

    /// Content decides for files whose extension does not (`.nc`, `.tap`, …):
    /// the shapes real posts and hand-written programs have.
    #[test]
    fn content_picks_the_dialect_with_its_evidence() {
        let why = |t: &str| sniff_dialect_why(Some("nc"), t.as_bytes());
        // A FANUC post's program: `%`, `O1000 (…)`, blocks, `M30`, `%`.
        assert_eq!(
            why("%\nO1000 (PART 12)\nG90 G54 G0 X10. Y10.\nG4 P500\nM30\n%\n"),
            Some((
                Dialect::Fanuc,
                "the `%` line 1 and program number O1000 on line 2".into()
            ))
        );
        assert_eq!(
            why("O01000\nN10 G0 X0 Y0\nM30\n"),
            Some((Dialect::Fanuc, "program number O01000 on line 1".into()))
        );
        assert_eq!(
            why("#1=0\nN20 WHILE [#1 LT 3] DO1\n#1=#1+1\nEND1\nM30\n"),
            Some((Dialect::Fanuc, "a `WHILE` statement on line 2".into()))
        );
        assert_eq!(
            why("G90\nG65 P9010 A1. B2.\nM30\n"),
            Some((Dialect::Fanuc, "a G65/G66 macro call on line 2".into()))
        );
        assert_eq!(
            why("G0 X1;\nM30;\n"),
            Some((Dialect::Fanuc, "blocks ending in `;` (line 1)".into()))
        );
        // LinuxCNC: numbered O-words with keywords, named O-words and parameters.
        assert_eq!(
            why("%\no100 while [#1 lt 3]\n#1=[#1+1]\no100 endwhile\nM2\n%\n"),
            Some((
                Dialect::Rs274ngc,
                "a numbered O-word with its keyword on line 2".into()
            ))
        );
        assert_eq!(
            why("(GOTO is only a word here)\no<probe> sub\no<probe> endsub\n"),
            Some((Dialect::Rs274ngc, "an O-word `o<…>` on line 2".into()))
        );
        assert_eq!(
            why("#<depth> = 2\nG1 Z-#<depth>\n"),
            Some((
                Dialect::Rs274ngc,
                "a named parameter `#<…>` on line 1".into()
            ))
        );
        // A program head behind a sequence number, a macro call by name.
        assert_eq!(
            why("%\nN0 O9999 (CHOOSER)\nM99\n%\n"),
            Some((
                Dialect::Fanuc,
                "the `%` line 1 and program number O9999 on line 2".into()
            ))
        );
        assert_eq!(
            why("G94 G17\nG65 \"PROBECONFIG\" T#100\nM99\n"),
            Some((Dialect::Fanuc, "a G65/G66 macro call on line 2".into()))
        );
        assert_eq!(why("G0 X1\nG65.1 X2\nG1 X3 F100\nM2\n"), None);
        // Nothing that only one dialect writes: the caller's default applies.
        assert_eq!(why("%\nG21 G90\nG1 X1 F100 (O1000)\nM2\n%\n"), None);
        assert_eq!(
            sniff_dialect_why(Some("NGC"), b"O1000\n"),
            Some((Dialect::Rs274ngc, "the `.ngc` extension".into()))
        );
    }

    /// A FANUC program-number file name decides only when nothing else does.
    #[test]
    fn a_program_number_file_name_is_fanuc_evidence() {
        let plain = b"#110 = 570\nG0 X1\nM99\n";
        assert_eq!(
            sniff_file_dialect_why(Some("O8502.NC"), plain),
            Some((
                Dialect::Fanuc,
                "the program-number file name `O8502`".into()
            ))
        );
        assert_eq!(
            sniff_file_dialect_why(Some("o1234"), plain).map(|(d, _)| d),
            Some(Dialect::Fanuc)
        );
        assert_eq!(sniff_file_dialect_why(Some("OUTLINE.nc"), plain), None);
        assert_eq!(sniff_file_dialect_why(Some("O123456789.nc"), plain), None);
        assert_eq!(
            sniff_file_dialect_why(Some("O8502.ngc"), plain),
            Some((Dialect::Rs274ngc, "the `.ngc` extension".into()))
        );
        assert_eq!(
            sniff_file_dialect_why(Some("O100.nc"), b"o<probe> sub\no<probe> endsub\n")
                .map(|(d, _)| d),
            Some(Dialect::Rs274ngc)
        );
    }

    /// The byte search for `:` finds the same directives, in the same order, as
    /// the walk over every item it replaced.
    #[test]
    fn suppressions_by_search_equal_suppressions_by_items() {
        let pieces: &[&str] = &[
            "G0 X1 Y2",
            "(partscope: allow W001, W005)",
            "(PARTSCOPE: allow-file L008)",
            "(partscope allow G001)",
            "; partscope: allow P002",
            "(plain: comment)",
            "(msg, time 12:30)",
            "#<a> = 2 (partscope: allow all)",
            "o100 sub",
            ":1000",
            "N10 G1 X3 (partscope: allow W001) (partscope: allow-file S001)",
            "/ X1 (partscope: allow K001)",
            "(unclosed partscope: allow W007",
            "%",
            "",
            "X1 ; partscope: allow W001",
            "G1 X5 (: partscope: allow W002)",
            "(partscope: dialect=fanuc)",
        ];
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let (mut blocks, mut files) = (0, 0);
        for case in 0..600 {
            let mut text = String::new();
            for _ in 0..(case % 13 + 1) {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                text.push_str(pieces[(seed % pieces.len() as u64) as usize]);
                text.push_str(["\n", "\r\n", " ", "\n\n"][(seed >> 8) as usize % 4]);
            }
            for dialect in [Dialect::Rs274ngc, Dialect::Fanuc, Dialect::Servoworks] {
                let p = crate::syntax::parse(
                    crate::syntax::ParseOptions::new(dialect),
                    std::sync::Arc::<[u8]>::from(text.as_bytes()),
                );
                let (a, b) = (
                    Suppressions::collect(&p),
                    Suppressions::collect_by_items(&p),
                );
                assert_eq!(
                    (&a.block, &a.file),
                    (&b.block, &b.file),
                    "{dialect:?}: {text:?}"
                );
                blocks += a.block.len();
                files += a.file.len();
            }
        }
        // The cases do hold directives of both kinds.
        assert!(
            blocks > 1000 && files > 500,
            "{blocks} block and {files} file directives"
        );
    }

    #[test]
    fn directives_are_parsed() {
        assert_eq!(
            parse_directives("(partscope: allow G001, W001)"),
            vec![Directive::Allow(vec!["G001".into(), "W001".into()])]
        );
        assert_eq!(
            parse_directives("(PARTSCOPE: allow-file L008)"),
            vec![Directive::AllowFile(vec!["L008".into()])]
        );
        assert_eq!(
            parse_directives("; partscope: dialect=fanuc"),
            vec![Directive::Dialect("fanuc".into())]
        );
        assert!(parse_directives("(plain comment)").is_empty());
    }

    #[test]
    fn dialect_directive_reads_first_line() {
        assert_eq!(
            dialect_directive(b"\n(partscope: dialect=servoworks)\nG0 X1\n"),
            Some(Dialect::Servoworks)
        );
        assert_eq!(
            dialect_directive(b"G0 X1 (partscope: dialect=fanuc)\n"),
            Some(Dialect::Fanuc)
        );
        assert_eq!(
            dialect_directive(b"G0 X1\n(partscope: dialect=fanuc)\n"),
            None
        );
        assert_eq!(
            dialect_directive(b"%\n(partscope: dialect=fanuc)\nO1\n"),
            Some(Dialect::Fanuc)
        );
    }

    #[test]
    fn config_keys() {
        let c = Config::from_toml("dialect = \"servoworks\"\nvariant = \"S-100M\"\n[machine]\ncircle_error_allowance = 0.01\narc_radius_tolerance = 0.002\n[rules]\nignore = [\"L008\"]\n").unwrap();
        let s = Settings::from_config(&c, None);
        assert_eq!(s.dialect, Dialect::Servoworks);
        assert_eq!(s.variant, Variant::S100M);
        assert_eq!(c.machine.circle_error_allowance, Some(0.01));
        assert!(!s.code_enabled("L008"));
        assert!(Config::from_toml("dialekt = 1").is_err());
    }
}
