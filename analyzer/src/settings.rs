//! Analysis settings and the `partscope.toml` configuration format.
//!
//! Parsing configuration text is pure; finding and reading the file is the
//! host's job.

use serde::Deserialize;

use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::{Dialect, Variant};
use crate::rules::RuleMeta;
use crate::syntax::{CommentKind, ItemKind, Program};

/// The contents of a `partscope.toml`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    pub dialect: Option<String>,
    /// Variant or profile: `S-100M`, `S-120M`, `S-140M`, `linuxcnc`, `emc2`, `30i`.
    pub variant: Option<String>,
    #[serde(default)]
    pub rules: RulesConfig,
    /// The machine profile; interpreted by the runtime (axes, limits,
    /// `circle_error_allowance`, `arc_radius_tolerance`, …).
    #[serde(default)]
    pub machine: toml::Table,
    /// LinuxCNC files for the `rs274ngc` dialect (paths relative to the config file).
    pub ini: Option<String>,
    pub tool_table: Option<String>,
    pub var_file: Option<String>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RulesConfig {
    /// Rules to enable (codes, code prefixes like `S`, or `ALL`); off-by-default
    /// rules must be selected here.
    #[serde(default)]
    pub select: Vec<String>,
    #[serde(default)]
    pub ignore: Vec<String>,
    /// Lowest severity that makes `partscope check` exit 1 (default `warning`).
    pub fail_level: Option<String>,
    /// Custom G/M codes the control defines as macro calls (e.g. `["G100", "M150"]`).
    #[serde(default)]
    pub custom_codes: Vec<String>,
}

impl Config {
    pub fn from_toml(text: &str) -> Result<Config, String> {
        toml::from_str(text).map_err(|e| e.to_string())
    }
}

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
    /// Diagnostics of one code reported per file; the rest become one
    /// "… and N more" (see [`crate::limit_diagnostics`]).
    pub max_per_code: usize,
    /// Diagnostics reported per file, all codes together.
    pub max_per_file: usize,
}

/// Default of [`Settings::max_per_code`].
pub const DEFAULT_MAX_PER_CODE: usize = 1000;
/// Default of [`Settings::max_per_file`].
pub const DEFAULT_MAX_PER_FILE: usize = 20_000;

impl Settings {
    pub fn new(dialect: Dialect) -> Settings {
        Settings {
            dialect,
            variant: dialect.default_variant(),
            select: Vec::new(),
            ignore: Vec::new(),
            custom_codes: Vec::new(),
            axes: vec!['X', 'Y', 'Z', 'A', 'B', 'C'],
            integer_machine_unit: false,
            max_per_code: DEFAULT_MAX_PER_CODE,
            max_per_file: DEFAULT_MAX_PER_FILE,
        }
    }

    /// Settings from a config, with an optional dialect override.
    pub fn from_config(
        config: &Config,
        dialect_override: Option<Dialect>,
    ) -> Result<Settings, String> {
        let dialect = match (dialect_override, &config.dialect) {
            (Some(d), _) => d,
            (None, Some(s)) => Dialect::parse(s)
                .ok_or_else(|| format!("unknown dialect `{s}` (servoworks, rs274ngc, fanuc)"))?,
            (None, None) => Dialect::Rs274ngc,
        };
        let mut s = Settings::new(dialect);
        if let Some(v) = &config.variant {
            let v = Variant::parse(v).ok_or_else(|| format!("unknown variant `{v}`"))?;
            if v.dialect() == dialect {
                s.variant = v;
            }
        }
        s.select = config.rules.select.clone();
        s.ignore = config.rules.ignore.clone();
        s.custom_codes = config
            .rules
            .custom_codes
            .iter()
            .map(|c| c.to_ascii_uppercase())
            .collect();
        if let Some(toml::Value::Array(axes)) = config.machine.get("axes") {
            let letters: Vec<char> = axes
                .iter()
                .filter_map(|a| match a {
                    toml::Value::String(s) => s.chars().next(),
                    toml::Value::Table(t) => t
                        .get("letter")
                        .and_then(|l| l.as_str())
                        .and_then(|s| s.chars().next()),
                    _ => None,
                })
                .map(|c| c.to_ascii_uppercase())
                .collect();
            if !letters.is_empty() {
                s.axes = letters;
            }
        }
        if let Some(v) = config
            .machine
            .get("integer_machine_unit")
            .and_then(|v| v.as_bool())
        {
            s.integer_machine_unit = v;
        }
        Ok(s)
    }

    fn matches(pattern: &str, code: &str, name: &str) -> bool {
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
    /// (block index, code) pairs.
    block: Vec<(usize, String)>,
    file: Vec<String>,
}

impl Suppressions {
    pub fn collect(program: &Program) -> Suppressions {
        let mut s = Suppressions::default();
        // Directive comments are rare, and every directive holds a `:`
        // (`partscope:`): only the blocks with a `:` in their text are read, found
        // with a byte search instead of a walk over every item of the file.
        let text = &program.text[..];
        let mut from = 0usize;
        while let Some(at) = text.get(from..).and_then(|t| memchr::memchr(b':', t)) {
            let at = from + at;
            let Some(bi) = u32::try_from(at).ok().and_then(|a| program.block_at(a)) else {
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
                .map_or(text.len(), |b| b.span.start as usize);
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
                        self.block.extend(codes.into_iter().map(|c| (bi, c)))
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
                    Directive::Allow(codes) => s.block.extend(codes.into_iter().map(|c| (bi, c))),
                    Directive::AllowFile(codes) => s.file.extend(codes),
                    Directive::Dialect(_) => {}
                }
            }
        }
        s
    }

    pub fn is_suppressed(&self, program: &Program, d: &Diagnostic) -> bool {
        let m = |c: &String| c.eq_ignore_ascii_case(d.code) || c.eq_ignore_ascii_case("all");
        if self.file.iter().any(m) {
            return true;
        }
        if self.block.is_empty() {
            return false;
        }
        let Some(bi) = program.block_at(d.span.start) else {
            return false;
        };
        self.block.iter().any(|(b, c)| *b == bi && m(c))
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
    if let Some(d) = dialect_directive(text) {
        return Some(d);
    }
    match path_ext.map(|e| e.to_ascii_lowercase()).as_deref() {
        Some("ngc") => return Some(Dialect::Rs274ngc),
        Some("dat" | "sw") => return Some(Dialect::Servoworks),
        Some("fnc") => return Some(Dialect::Fanuc),
        _ => {}
    }
    let head = &text[..text.len().min(64 * 1024)];
    let up = String::from_utf8_lossy(head).to_ascii_uppercase();
    if up.contains(" SUB") && up.contains("O<") || up.contains("#<") || up.contains("ENDSUB") {
        return Some(Dialect::Rs274ngc);
    }
    if up.contains("WHILE[") || up.contains("WHILE [") || up.contains("GOTO") || up.contains(";\n")
    {
        return Some(Dialect::Fanuc);
    }
    None
}

/// Severity threshold helper for exit codes.
pub fn fail_level(config: &Config) -> Severity {
    config
        .rules
        .fail_level
        .as_deref()
        .and_then(Severity::parse)
        .unwrap_or(Severity::Warning)
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
        let s = Settings::from_config(&c, None).unwrap();
        assert_eq!(s.dialect, Dialect::Servoworks);
        assert_eq!(s.variant, Variant::S100M);
        assert_eq!(
            c.machine
                .get("circle_error_allowance")
                .and_then(|v| v.as_float()),
            Some(0.01)
        );
        assert!(!s.code_enabled("L008"));
        assert!(Config::from_toml("dialekt = 1").is_err());
    }
}
