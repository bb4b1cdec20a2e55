//! `partscope run --html`: one self-contained page holding the toolpath viewer
//! of the VS Code preview (`editors/vscode/media`, built into the binary, so
//! there is one viewer) and a dry-run result in the shape `partscope/dryRun`
//! returns. The page loads nothing: its stylesheet, script and data are inline,
//! and its Content-Security-Policy forbids every fetch.

use std::io::{self, Write};

use serde::Serialize;

const HTML: &str = include_str!("../../editors/vscode/media/preview.html");
const JS: &str = include_str!("../../editors/vscode/media/preview.js");
const CSS: &str = include_str!("../../editors/vscode/media/preview.css");

/// Inline style and script only; no source is allowed for anything else, so
/// the page cannot reach the network even if the data held a URL.
const CSP: &str = "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; \
                   img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'\">";

/// The element the viewer reads its data from (`preview.js`, `boot`).
const DATA_OPEN: &str = "<script type=\"application/json\" id=\"partscope-data\">";

/// What the viewer shows: the result and the title of its toolbar.
#[derive(Serialize)]
struct Payload<'a, T: Serialize> {
    title: &'a str,
    data: &'a T,
}

/// `template` with its one `from` replaced by `to`: the page is made from
/// `preview.html` as it is, so a changed template fails loudly here (and in
/// the tests) instead of yielding a page that fetches its script.
fn replace_once(template: &str, from: &str, to: &str) -> io::Result<String> {
    let at = find_once(template, from)?;
    Ok(format!(
        "{}{to}{}",
        &template[..at],
        &template[at + from.len()..]
    ))
}

/// Where `template` holds `what`, which must be there exactly once.
fn find_once(template: &str, what: &str) -> io::Result<usize> {
    let mut found = template.match_indices(what).map(|(at, _)| at);
    match (found.next(), found.next()) {
        (Some(at), None) => Ok(at),
        _ => Err(io::Error::other(format!(
            "preview.html does not hold `{what}` exactly once"
        ))),
    }
}

fn escape_text(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Writes the page for `result` (a `partscope/dryRun` result) with `title`
/// (the program's name) to `out`.
pub fn write(out: &mut impl Write, result: &impl Serialize, title: &str) -> io::Result<()> {
    let mut page = replace_once(HTML, "<!-- partscope:csp -->", CSP)?;
    page = replace_once(
        &page,
        "<title>Partscope toolpath</title>",
        &format!("<title>{} — Partscope toolpath</title>", escape_text(title)),
    )?;
    page = replace_once(
        &page,
        "<link rel=\"stylesheet\" href=\"preview.css\">",
        &format!("<style>\n{CSS}</style>"),
    )?;
    // Clicking a segment asks the editor to show its line; a page has no editor.
    page = replace_once(&page, " · click: go to line", "")?;
    // The script element becomes the data block and the inline script.
    let script = "<script src=\"preview.js\"></script>";
    let at = find_once(&page, script)?;
    let (head, tail) = (&page[..at], &page[at + script.len()..]);
    out.write_all(head.as_bytes())?;
    out.write_all(DATA_OPEN.as_bytes())?;
    let mut json = ScriptSafe {
        out: &mut *out,
        held: Vec::new(),
    };
    serde_json::to_writer(
        &mut json,
        &Payload {
            title,
            data: result,
        },
    )?;
    json.finish()?;
    out.write_all(b"</script>\n<script>\n")?;
    out.write_all(JS.as_bytes())?;
    out.write_all(b"</script>")?;
    out.write_all(tail.as_bytes())
}

/// How many of `segments`, from the first, take at most `max_bytes` as JSON.
pub fn segments_within(segments: &[impl Serialize], max_bytes: u64) -> usize {
    let mut size = Count(0);
    for (i, s) in segments.iter().enumerate() {
        // One byte more for the comma between segments.
        size.0 += 1;
        if serde_json::to_writer(&mut size, s).is_err() || size.0 > max_bytes {
            return i;
        }
    }
    segments.len()
}

/// Counts the bytes written to it.
struct Count(u64);

impl Write for Count {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0 += buf.len() as u64;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// Passes JSON on with `<`, `>` and `&` written as `\u003c`, `\u003e` and
/// `\u0026`, and U+2028/U+2029 as `\u2028`/`\u2029`: inside a `<script>`
/// element no `</script>` or `<!--` can then end or bend the data block, and
/// the text parses as JavaScript too. JSON has these characters only inside
/// strings, where the escapes mean the same characters.
struct ScriptSafe<W: Write> {
    out: W,
    /// The start of a UTF-8 sequence that may be U+2028/U+2029, cut by the
    /// end of a write.
    held: Vec<u8>,
}

impl<W: Write> ScriptSafe<W> {
    fn finish(mut self) -> io::Result<()> {
        let held = std::mem::take(&mut self.held);
        self.out.write_all(&held)
    }
}

impl<W: Write> Write for ScriptSafe<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let mut bytes = std::mem::take(&mut self.held);
        bytes.extend_from_slice(buf);
        let mut start = 0;
        let mut i = 0;
        while i < bytes.len() {
            let escape: Option<(&[u8], usize)> = match bytes[i] {
                b'<' => Some((b"\\u003c", 1)),
                b'>' => Some((b"\\u003e", 1)),
                b'&' => Some((b"\\u0026", 1)),
                0xE2 => match bytes.get(i + 1..i + 3) {
                    Some([0x80, 0xA8]) => Some((b"\\u2028", 3)),
                    Some([0x80, 0xA9]) => Some((b"\\u2029", 3)),
                    Some(_) => None,
                    // Cut short: decide once the next write brings the rest.
                    None => {
                        self.out.write_all(&bytes[start..i])?;
                        self.held = bytes[i..].to_vec();
                        return Ok(buf.len());
                    }
                },
                _ => None,
            };
            match escape {
                Some((with, len)) => {
                    self.out.write_all(&bytes[start..i])?;
                    self.out.write_all(with)?;
                    i += len;
                    start = i;
                }
                None => i += 1,
            }
        }
        self.out.write_all(&bytes[start..])?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn page(data: &serde_json::Value, title: &str) -> String {
        let mut out = Vec::new();
        write(&mut out, data, title).unwrap();
        String::from_utf8(out).unwrap()
    }

    /// The JSON between the data block's tags.
    fn data_block(page: &str) -> &str {
        let start = page.find(DATA_OPEN).unwrap() + DATA_OPEN.len();
        let len = page[start..].find("</script>").unwrap();
        &page[start..start + len]
    }

    #[test]
    fn viewer_files_cannot_end_their_elements() {
        let js = JS.to_ascii_lowercase();
        assert!(!js.contains("</script") && !js.contains("<!--"));
        assert!(!CSS.to_ascii_lowercase().contains("</style"));
    }

    #[test]
    fn page_inlines_the_viewer_and_fetches_nothing() {
        let p = page(&serde_json::json!({"toolpath": {"segments": []}}), "a.ngc");
        assert!(p.contains(CSP));
        assert!(p.contains(JS) && p.contains(CSS));
        assert!(p.contains("<title>a.ngc — Partscope toolpath</title>"));
        for external in [
            "src=\"preview.js\"",
            "href=\"preview.css\"",
            "click: go to line",
        ] {
            assert!(!p.contains(external), "{external}");
        }
        assert_eq!(
            data_block(&p),
            r#"{"title":"a.ngc","data":{"toolpath":{"segments":[]}}}"#
        );
    }

    #[test]
    fn hostile_strings_stay_inside_the_data_block() {
        let hostile = "</script><script>alert(1)</script><!-- & \u{2028}\u{2029}";
        let data = serde_json::json!({ "stopped_at": { "reason": hostile } });
        let title = "<b>x</b>.ngc";
        let p = page(&data, title);
        let block = data_block(&p);
        assert!(
            !block.contains(['<', '>', '&', '\u{2028}', '\u{2029}']),
            "{block}"
        );
        let back: serde_json::Value = serde_json::from_str(block).unwrap();
        assert_eq!(back["data"]["stopped_at"]["reason"], hostile);
        assert_eq!(back["title"], title);
        assert!(p.contains("<title>&lt;b&gt;x&lt;/b&gt;.ngc — Partscope toolpath</title>"));
    }

    #[test]
    fn segments_within_counts_their_json() {
        let segs = vec![serde_json::json!([1, 2]); 4];
        // `[1,2]` is 5 bytes, and each takes one more for its comma.
        assert_eq!(segments_within(&segs, 23), 3);
        assert_eq!(segments_within(&segs, 24), 4);
        assert_eq!(segments_within(&segs, 5), 0);
    }

    #[test]
    fn a_line_separator_cut_between_writes_is_escaped() {
        let text = "a\u{2028}b\u{2029}c\u{e9}\u{20ac}".as_bytes();
        for cut in 0..=text.len() {
            let mut out = Vec::new();
            let mut w = ScriptSafe {
                out: &mut out,
                held: Vec::new(),
            };
            w.write_all(&text[..cut]).unwrap();
            w.write_all(&text[cut..]).unwrap();
            w.finish().unwrap();
            assert_eq!(
                String::from_utf8(out).unwrap(),
                "a\\u2028b\\u2029c\u{e9}\u{20ac}",
                "cut at {cut}"
            );
        }
    }
}
