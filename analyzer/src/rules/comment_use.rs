//! W019: RS274/NGC comments that do not do what they look like.

use crate::declare_rule;
use crate::diagnostic::{Diagnostic, Severity};
use crate::dialect::Dialect;
use crate::syntax::{CommentKind, ItemKind};

use super::util::is_emc2;
use super::{BlockCx, Interest, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks RS274/NGC comments: an active comment (`MSG`, `DEBUG`, `PRINT`, `LOG`, …)
    /// followed by another comment on the same line, which disables it; a comment that
    /// looks like an active comment but lacks the exact `KEYWORD,` form, such as
    /// `(MSG hello)`; an unknown `%` format in `DEBUG`/`PRINT`/`LOG`; a comment on an
    /// O-word line.
    ///
    /// ## Why is this bad?
    /// Only the last comment of a line is used, so `(MSG,x)(note)` shows nothing. A
    /// message written without the comma is an ordinary comment and is never shown. An
    /// unknown format is printed literally. Comments on O-word lines are undefined
    /// behaviour in the LinuxCNC documentation.
    ///
    /// ## Example
    /// ```ngc
    /// (MSG change the tool)
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// (MSG, change the tool)
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: warning for a malformed active comment and an unknown format (`linuxcnc`);
    /// info for a disabled active comment and an O-line comment (`linuxcnc`; LinuxCNC's own
    /// examples use them, and they work in 2.9).
    ///
    /// Implements: NGC023, NGC032, NGC034, NGC112, NGC711
    pub static COMMENT_USE = {
        code: "W019",
        name: "comment-use",
        summary: "Comment that does not do what it looks like",
        implements: &["NGC023", "NGC032", "NGC034", "NGC112", "NGC711"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct CommentUse;

const KEYWORDS: &[&str] = &[
    "msg",
    "debug",
    "print",
    "logopen",
    "logappend",
    "logclose",
    "log",
    "abort",
    "probeopen",
    "probeclose",
];

/// Whether a `%` format in a DEBUG/PRINT/LOG text is one LinuxCNC knows.
fn bad_format(text: &str) -> Option<String> {
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let rest = &text[i + 1..];
            let ok = rest.starts_with('d')
                || rest.starts_with('f')
                || rest.starts_with("lf")
                || (rest.starts_with('.')
                    && rest.as_bytes().get(1).is_some_and(|c| c.is_ascii_digit())
                    && rest.as_bytes().get(2) == Some(&b'f'));
            if !ok {
                return Some(
                    text[i..]
                        .chars()
                        .take_while(|c| !c.is_whitespace())
                        .take(4)
                        .collect(),
                );
            }
        }
        i += 1;
    }
    None
}

impl Rule for CommentUse {
    fn meta(&self) -> &'static RuleMeta {
        &COMMENT_USE
    }

    /// Every report is about a comment.
    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::OTHER
    }

    fn check_block(&self, cx: &BlockCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        let modern = !is_emc2(cx.settings);
        let items = cx.items();
        let comments: Vec<_> = items
            .iter()
            .filter_map(|i| {
                if let ItemKind::Comment(k) = i.kind {
                    Some((i, k))
                } else {
                    None
                }
            })
            .collect();
        for (n, (item, kind)) in comments.iter().enumerate() {
            let text = p.str_of(item.span).into_owned();
            let active = !matches!(kind, CommentKind::Plain | CommentKind::Partscope);
            if active && n + 1 < comments.len() {
                out.push(
                    COMMENT_USE.diagnostic(Severity::Info, item.span, "Only the last comment of a line is used: this active comment is disabled by the comment after it. Move the other comment to its own line.")
                        .with_related(comments[n + 1].0.span, "later comment"),
                );
            }
            if *kind == CommentKind::Plain {
                // Only parenthesised comments: a `;` comment is often commented-out code.
                let raw = text.strip_prefix('(').unwrap_or("").trim_start();
                let body = raw.to_ascii_lowercase();
                let kw = KEYWORDS.iter().find(|k| {
                    // The keyword is ASCII, so after a match its length is a char boundary.
                    let Some(after) = body.strip_prefix(*k) else {
                        return false;
                    };
                    let upper = raw
                        .get(..k.len())
                        .is_some_and(|w| w.bytes().all(|b| b.is_ascii_uppercase()));
                    // `(MSG ,x)` (a blank before the comma), or `(MSG text)` in capitals;
                    // prose such as `(abort the run here)` is left alone.
                    after.trim_start_matches([' ', '\t']).starts_with(',')
                        && after.starts_with([' ', '\t'])
                        || upper && after.starts_with([' ', '\t', ')'])
                });
                if let Some(kw) =
                    kw.filter(|k| !matches!(**k, "logclose" | "probeopen" | "probeclose"))
                {
                    out.push(COMMENT_USE.warning(
                        item.span,
                        format!("This looks like a `{}` comment but is an ordinary one: the keyword must be followed directly by a comma, as in `({},text)`.", kw.to_uppercase(), kw.to_uppercase()),
                    ));
                }
            }
            if modern
                && matches!(
                    kind,
                    CommentKind::Debug | CommentKind::Print | CommentKind::Log | CommentKind::Abort
                )
            {
                if let Some(f) = bad_format(&text) {
                    out.push(COMMENT_USE.warning(
                        item.span,
                        format!("Unknown format `{f}`: LinuxCNC knows %d, %f, %lf and %.Nf and prints anything else literally."),
                    ));
                }
            }
        }
        if modern && items.iter().any(|i| matches!(i.kind, ItemKind::OWord(_))) {
            if let Some((c, _)) = comments.first() {
                out.push(COMMENT_USE.info(c.span, "A comment on an O-word line is undefined behaviour in LinuxCNC. Put the comment on its own line."));
            }
        }
    }
}
