//! Output formats of `partscope check`: human (miette), JSON, SARIF 2.1.0,
//! GitHub workflow commands.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;

use analyzer::{Diagnostic, LineIndex, Severity};
use serde_json::{json, Value};

use super::Format;

/// The diagnostics of one checked file.
pub struct FileReport {
    pub path: PathBuf,
    pub text: Arc<[u8]>,
    pub diagnostics: Vec<Diagnostic>,
    pub io_error: bool,
    /// Files the interpreter opened (subprograms): `FileId(i)` is `extra_files[i - 1]`.
    pub extra_files: Vec<(PathBuf, Arc<[u8]>)>,
    /// The dialect the file was read in, and why (`None` for a file not read).
    pub dialect: Option<(analyzer::Dialect, String)>,
    /// For a file too large to hold (`cli::stream`), `text` holds only the
    /// lines the report shows, and this says where they are in the file.
    pub sparse: Option<Sparse>,
}

/// Some lines of a file, in file order: whole lines, each piece starting at a
/// line start.
#[derive(Debug, Default, Clone)]
pub struct Sparse {
    pub text: Vec<u8>,
    /// Where each piece starts: (file offset, offset in `text`, file line,
    /// line in `text`), both lines 0-based.
    pieces: Vec<(u32, u32, u32, u32)>,
    text_lines: u32,
}

impl Sparse {
    /// Adds the lines `bytes`, which start at file offset `file` on 0-based line `line`.
    pub fn push(&mut self, file: u32, line: u32, bytes: &[u8]) {
        if bytes.is_empty() {
            return;
        }
        self.pieces
            .push((file, self.text.len() as u32, line, self.text_lines));
        self.text.extend_from_slice(bytes);
        self.text_lines += analyzer::span::line_breaks(bytes);
    }

    /// The index of the piece holding file offset `at` (or the last before it).
    fn piece(&self, at: u32) -> Option<usize> {
        self.pieces.partition_point(|p| p.0 <= at).checked_sub(1)
    }

    /// The offset in `text` of file offset `at` (positions between pieces go
    /// to the end of the piece before).
    pub fn to_text(&self, at: u32) -> u32 {
        let Some((i, &(file, text, _, _))) =
            self.piece(at).and_then(|i| Some((i, self.pieces.get(i)?)))
        else {
            return 0;
        };
        let next = self
            .pieces
            .get(i + 1)
            .map_or(self.text.len() as u32, |p| p.1);
        (text + (at - file)).min(next)
    }

    /// The file line of line `text_line` of `text`, in the piece of file offset `at`.
    fn file_line(&self, at: u32, text_line: u32) -> u32 {
        match self.piece(at).and_then(|i| self.pieces.get(i)) {
            Some(&(_, _, line, tl)) => text_line.saturating_sub(tl) + line,
            None => text_line,
        }
    }
}

impl FileReport {
    /// The offset in `text` of a main-file offset.
    pub fn text_offset(&self, at: u32) -> u32 {
        match &self.sparse {
            Some(s) => s.to_text(at),
            None => at,
        }
    }
}

/// The report's dialect name and reason, for the JSON outputs.
pub fn dialect_fields(r: &FileReport) -> (Option<&'static str>, Option<&str>) {
    match &r.dialect {
        Some((d, why)) => (Some(d.as_str()), Some(why.as_str())),
        None => (None, None),
    }
}

/// Reads the subprogram files a run opened, for showing their diagnostics; a file
/// that vanished since shows without source text.
pub fn read_extra_files(files: &[String]) -> Vec<(PathBuf, Arc<[u8]>)> {
    files
        .iter()
        .map(|p| {
            (
                PathBuf::from(p),
                std::fs::read(p)
                    .map(Arc::from)
                    .unwrap_or_else(|_| Arc::from(&b""[..])),
            )
        })
        .collect()
}

/// A diagnostic with resolved 1-based positions.
pub struct Located<'a> {
    pub path: String,
    pub text: &'a [u8],
    pub line: u32,
    pub column: u32,
    pub end_line: u32,
    pub end_column: u32,
    pub d: &'a Diagnostic,
    /// Index of the report the diagnostic belongs to.
    pub report: usize,
}

/// Remembers the last located offset so that many diagnostics on one long
/// line are located in linear rather than quadratic time (a 300 kB line with
/// 100 000 diagnostics once took minutes).
#[derive(Default)]
struct Columns {
    /// (line, byte offset, 0-based character column at that offset).
    last: Option<(u32, usize, u32)>,
}

impl Columns {
    /// 1-based line and 1-based character column of a byte offset.
    fn position(&mut self, index: &LineIndex, text: &[u8], offset: u32) -> (u32, u32) {
        let (line, col) = index.line_col(offset);
        let start = index.line_start(line).unwrap_or(0) as usize;
        let end = (start + col as usize).min(text.len());
        let (from, base) = match self.last {
            // Resume only at a character boundary, so the lossy count of the
            // remainder equals that of the whole prefix.
            Some((l, at, chars))
                if l == line && at <= end && text.get(at).is_none_or(|b| (*b & 0xC0) != 0x80) =>
            {
                (at, chars)
            }
            _ => (start.min(end), 0),
        };
        let chars = base + String::from_utf8_lossy(&text[from..end]).chars().count() as u32;
        self.last = Some((line, end, chars));
        (line + 1, chars + 1)
    }
}

pub fn locate(reports: &[FileReport]) -> Vec<Located<'_>> {
    let mut out = Vec::new();
    for (ri, r) in reports.iter().enumerate() {
        // A clean file needs no line index (a pass over every byte of it).
        if r.diagnostics.is_empty() {
            continue;
        }
        let mut indexes: Vec<(String, &[u8], LineIndex)> =
            Vec::with_capacity(1 + r.extra_files.len());
        let sparse = r.sparse.as_ref();
        indexes.push((
            r.path.display().to_string(),
            &r.text[..],
            LineIndex::new(&r.text),
        ));
        for (p, t) in &r.extra_files {
            indexes.push((p.display().to_string(), &t[..], LineIndex::new(t)));
        }
        let mut starts = Columns::default();
        let mut ends = Columns::default();
        let mut last_file = None;
        for d in &r.diagnostics {
            let Some((path, text, index)) = indexes.get(d.file.0 as usize) else {
                continue;
            };
            if last_file != Some(d.file) {
                starts = Columns::default();
                ends = Columns::default();
                last_file = Some(d.file);
            }
            // A sparse text holds the lines around the file's offsets.
            let (s, e) = (d.span.start, d.span.end.max(d.span.start));
            let (line, column, end_line, end_column) = match sparse.filter(|_| d.file.0 == 0) {
                Some(sp) => {
                    let (l, c) = starts.position(index, text, sp.to_text(s));
                    let (el, ec) = ends.position(index, text, sp.to_text(e));
                    (
                        sp.file_line(s, l - 1) + 1,
                        c,
                        sp.file_line(e, el - 1) + 1,
                        ec,
                    )
                }
                None => {
                    let (l, c) = starts.position(index, text, s);
                    let (el, ec) = ends.position(index, text, e);
                    (l, c, el, ec)
                }
            };
            out.push(Located {
                path: path.clone(),
                text,
                line,
                column,
                end_line,
                end_column,
                d,
                report: ri,
            });
        }
    }
    out
}

pub fn emit(format: Format, reports: &[FileReport]) -> std::io::Result<()> {
    let located = locate(reports);
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    match format {
        Format::Json => {
            let arr: Vec<Value> = located
                .iter()
                .map(|l| json_of(l, &reports[l.report]))
                .collect();
            serde_json::to_writer_pretty(&mut out, &Value::Array(arr))?;
            writeln!(out)?;
        }
        Format::Sarif => {
            serde_json::to_writer_pretty(&mut out, &sarif(&located))?;
            writeln!(out)?;
        }
        Format::Github => {
            for l in &located {
                let level = match l.d.severity {
                    Severity::Error => "error",
                    Severity::Warning => "warning",
                    _ => "notice",
                };
                writeln!(
                    out,
                    "::{level} file={},line={},col={},endLine={},endColumn={},title={}::{}",
                    escape_property(&l.path),
                    l.line,
                    l.column,
                    l.end_line,
                    l.end_column,
                    escape_property(&format!("{} {}", l.d.code, rule_name(l.d.code))),
                    escape_data(&l.d.message)
                )?;
            }
        }
        Format::Human => human(&mut out, reports, &located)?,
    }
    out.flush()
}

fn rule_name(code: &str) -> &'static str {
    crate::rules::lookup(code).map(|r| r.name).unwrap_or("")
}

fn json_of(l: &Located<'_>, r: &FileReport) -> Value {
    let (dialect, dialect_reason) = dialect_fields(r);
    json!({
        "path": l.path,
        "line": l.line,
        "column": l.column,
        "end_line": l.end_line,
        "end_column": l.end_column,
        "code": l.d.code,
        "name": rule_name(l.d.code),
        "severity": l.d.severity.as_str(),
        "message": l.d.message,
        "dialect": dialect,
        "dialect_reason": dialect_reason,
        "fixes": l.d.fixes.iter().map(|f| json!({
            "title": f.title,
            "edits": f.edits.iter().map(|e| json!({"start": e.span.start, "end": e.span.end, "new_text": e.new_text})).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}

/// A SARIF artifact location: relative to `%SRCROOT%` (the current folder)
/// for files under it, a `file://` URI otherwise, percent-encoded (RFC 3986).
fn artifact_location(path: &str, root: Option<&std::path::Path>) -> Value {
    let p = std::path::Path::new(path);
    // A file that could not be read may not exist: made absolute without
    // resolving links, so it keeps its place under the root.
    let abs = p
        .canonicalize()
        .or_else(|_| std::path::absolute(p))
        .unwrap_or_else(|_| p.to_path_buf());
    match root.and_then(|r| abs.strip_prefix(r).ok()) {
        Some(rel) => {
            json!({"uri": encode_uri_path(&rel.to_string_lossy()), "uriBaseId": "%SRCROOT%"})
        }
        None => json!({"uri": format!("file://{}", encode_uri_path(&abs.to_string_lossy()))}),
    }
}

/// Percent-encodes a path for a URI: everything but unreserved characters and `/`.
fn encode_uri_path(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    for b in path.replace('\\', "/").bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

fn sarif(located: &[Located<'_>]) -> Value {
    let root = std::env::current_dir().and_then(|d| d.canonicalize()).ok();
    let rules: Vec<Value> = crate::rules::all()
        .iter()
        .map(|r| {
            json!({
                "id": r.code,
                "name": r.name,
                "shortDescription": {"text": r.summary},
                "fullDescription": {"text": crate::rules::clean_doc(r.doc)},
                "defaultConfiguration": {"enabled": r.default_enabled},
                "properties": {"implements": r.implements},
            })
        })
        .collect();
    let results: Vec<Value> = located
        .iter()
        .map(|l| {
            let level = match l.d.severity {
                Severity::Error => "error",
                Severity::Warning => "warning",
                _ => "note",
            };
            json!({
                "ruleId": l.d.code,
                "level": level,
                "message": {"text": l.d.message},
                "locations": [{
                    "physicalLocation": {
                        "artifactLocation": artifact_location(&l.path, root.as_deref()),
                        "region": {
                            "startLine": l.line,
                            "startColumn": l.column,
                            "endLine": l.end_line,
                            "endColumn": l.end_column,
                        }
                    }
                }],
            })
        })
        .collect();
    json!({
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {
                "name": "partscope",
                "version": env!("CARGO_PKG_VERSION"),
                "informationUri": "https://partscope.dev",
                "rules": rules,
            }},
            "results": results,
            // Columns count characters (Unicode code points), as the other formats do.
            "columnKind": "unicodeCodePoints",
            "originalUriBaseIds": {
                "%SRCROOT%": {"uri": root.as_ref().map(|r| format!("file://{}/", encode_uri_path(&r.to_string_lossy()))).unwrap_or_else(|| "file:///".into())}
            },
        }]
    })
}

fn escape_data(s: &str) -> String {
    s.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

fn escape_property(s: &str) -> String {
    escape_data(s).replace(':', "%3A").replace(',', "%2C")
}

fn human(
    out: &mut impl Write,
    reports: &[FileReport],
    located: &[Located<'_>],
) -> std::io::Result<()> {
    use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan, MietteDiagnostic};
    let color = std::io::IsTerminal::is_terminal(&std::io::stdout())
        && std::env::var_os("NO_COLOR").is_none();
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme).with_context_lines(1);
    let (mut errors, mut warnings, mut others) = (0, 0, 0);
    let plain = located.len() > 1000;
    let mut last_report = None;
    for l in located {
        if last_report != Some(l.report) {
            last_report = Some(l.report);
            if let Some((d, why)) = &reports[l.report].dialect {
                writeln!(
                    out,
                    "{}: checked as {} ({why})",
                    reports[l.report].path.display(),
                    d.as_str()
                )?;
            }
        }
        match l.d.severity {
            Severity::Error => errors += 1,
            Severity::Warning => warnings += 1,
            _ => others += 1,
        }
        if plain {
            writeln!(
                out,
                "{}:{}:{}: {} {}: {}",
                l.path,
                l.line,
                l.column,
                l.d.severity.as_str(),
                l.d.code,
                super::excerpt::visible_str(&l.d.message)
            )?;
            continue;
        }
        // Only the lines around the spans: the report reads nothing else.
        let r = &reports[l.report];
        let at = |o: u32| -> usize {
            if l.d.file.0 == 0 {
                r.text_offset(o) as usize
            } else {
                o as usize
            }
        };
        let (ps, pe) = (at(l.d.span.start), at(l.d.span.end));
        let near = |rel: &analyzer::diagnostic::Related| {
            rel.file == l.d.file
                && (rel.span.start as usize).abs_diff(l.d.span.start as usize)
                    <= super::excerpt::MAX_RELATED_DISTANCE
        };
        let (lo, hi) =
            l.d.related
                .iter()
                .filter(|r| near(r))
                .fold((ps, pe), |(a, b), r| {
                    (a.min(at(r.span.start)), b.max(at(r.span.end)))
                });
        let lo_line = if lo < ps {
            (l.line as usize).saturating_sub(1).saturating_sub(
                l.text
                    .get(lo..ps)
                    .map_or(0, |t| t.iter().filter(|b| **b == b'\n').count()),
            )
        } else {
            (l.line as usize).saturating_sub(1)
        };
        let src = super::excerpt::Excerpt::new(l.path.clone(), l.text, lo, hi, lo_line);
        let s = src.map(ps);
        let e = src.map(pe).max(s);
        let mut labels = vec![LabeledSpan::new_primary_with_span(
            Some(l.d.code.to_string()),
            (s, e - s),
        )];
        for r in l.d.related.iter().filter(|r| near(r)) {
            let rs = src.map(at(r.span.start));
            let re = src.map(at(r.span.end)).max(rs);
            labels.push(LabeledSpan::new_with_span(
                Some(super::excerpt::visible_str(&r.message).into_owned()),
                (rs, re - rs),
            ));
        }
        let severity = match l.d.severity {
            Severity::Error => miette::Severity::Error,
            Severity::Warning => miette::Severity::Warning,
            _ => miette::Severity::Advice,
        };
        let mut diag = MietteDiagnostic::new(super::excerpt::visible_str(&l.d.message))
            .with_code(format!("{}({})", l.d.code, rule_name(l.d.code)))
            .with_severity(severity)
            .with_labels(labels);
        if let Some(f) = l.d.fixes.first() {
            diag = diag.with_help(format!("fix available: {}", f.title));
        }
        let report = miette::Report::new(diag).with_source_code(src);
        let mut buf = String::new();
        if handler.render_report(&mut buf, report.as_ref()).is_ok() {
            writeln!(out, "{buf}")?;
        } else {
            writeln!(
                out,
                "{}:{}:{}: {} {}: {}",
                l.path,
                l.line,
                l.column,
                l.d.severity.as_str(),
                l.d.code,
                l.d.message
            )?;
        }
    }
    let files = reports.len();
    if errors + warnings + others == 0 {
        writeln!(
            out,
            "All checks passed ({files} file{}).",
            if files == 1 { "" } else { "s" }
        )?;
    } else {
        writeln!(
            out,
            "Found {errors} error(s), {warnings} warning(s), {others} note(s) in {files} file(s)."
        )?;
    }
    Ok(())
}
