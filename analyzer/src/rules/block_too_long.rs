//! W011: lines longer than the control reads.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;

use super::util::is_emc2;
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Flags physical lines longer than the control accepts: 85 characters on ServoWorks;
    /// on LinuxCNC 2.9 more than 252 characters before the line end (251 when the line ends
    /// with CR LF), and more than 256 in the 2007 `emc2` profile.
    ///
    /// ## Why is this bad?
    /// ServoWorks limits a block to 85 characters; LinuxCNC reads lines into a fixed buffer
    /// and stops with `Command too long`. Long lines usually come from generated comments
    /// or joined blocks.
    ///
    /// ## Example
    /// ```servoworks
    /// G01 X10.0 Y10.0 Z10.0 F1000.0 (this comment makes the line longer than 85 characters.)
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// (this comment now has a line of its own)
    /// G01 X10.0 Y10.0 Z10.0 F1000.0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks and RS274/NGC, error. FANUC does not state a block length limit.
    ///
    /// Implements: SW001, NGC001
    pub static BLOCK_TOO_LONG = {
        code: "W011",
        name: "block-too-long",
        summary: "Line longer than the control accepts",
        implements: &["SW001", "NGC001"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct BlockTooLong;

impl Rule for BlockTooLong {
    fn meta(&self) -> &'static RuleMeta {
        &BLOCK_TOO_LONG
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let d = cx.program.dialect;
        if d == Dialect::Fanuc {
            return;
        }
        let text = &cx.program.text;
        // Runs of plain blocks: whole lines of at most 80 bytes each, so no
        // line inside one is too long; the scan jumps over them.
        let p = cx.program;
        let runs: Vec<(usize, usize)> = cx
            .segments()
            .iter()
            .filter(|s| s.plain)
            .filter_map(|s| Some((p.blocks.get(s.first)?, p.blocks.get(s.last())?)))
            .map(|(a, z)| (a.span.start as usize, z.end().end as usize))
            .collect();
        let mut next_run = 0;
        let mut start = 0usize;
        while start < text.len() {
            while runs.get(next_run).is_some_and(|r| r.0 < start) {
                next_run += 1;
            }
            if let Some(&(_, z)) = runs.get(next_run).filter(|r| r.0 == start && r.1 > start) {
                next_run += 1;
                start = z;
                continue;
            }
            let nl = text[start..]
                .iter()
                .position(|b| *b == b'\n' || *b == b'\r')
                .map(|i| start + i);
            let end = nl.unwrap_or(text.len());
            let crlf =
                nl.is_some_and(|i| text.get(i) == Some(&b'\r') && text.get(i + 1) == Some(&b'\n'));
            let len = text[start..end]
                .iter()
                .filter(|b| (**b & 0xC0) != 0x80)
                .count();
            let limit = line_limit(d, cx.settings, crlf);
            if len > limit {
                let msg = match d {
                    Dialect::Servoworks => format!("Line is {len} characters long; ServoWorks blocks are limited to 85. Split the line or shorten its comment."),
                    _ => format!("Command too long: the line has {len} characters and LinuxCNC reads at most {limit}{}. Split it into several lines.", if crlf { " with a CR LF ending" } else { "" }),
                };
                out.push(BLOCK_TOO_LONG.error(Span::new(start as u32, end as u32), msg));
            }
            start = match nl {
                Some(i) if crlf => i + 2,
                Some(i) => i + 1,
                None => text.len(),
            };
        }
    }
}

/// Characters a line may hold: ServoWorks blocks, LinuxCNC's read buffer (less the
/// CR of a CR LF ending), the 2007 `emc2` profile's.
fn line_limit(dialect: Dialect, settings: &crate::Settings, crlf: bool) -> usize {
    match dialect {
        Dialect::Servoworks => 85,
        _ if is_emc2(settings) => 256,
        _ if crlf => 251,
        _ => 252,
    }
}

/// Whether applying `edits` leaves every line they touch within the dialect's line
/// limit (or no longer than it was): a fix must not make a block too long (W011).
/// An edit outside the text `program` holds (another window of the file) is
/// taken as it is.
pub fn edits_keep_line_length(
    program: &crate::syntax::Program,
    settings: &crate::Settings,
    edits: &[crate::TextEdit],
) -> bool {
    let text = &program.text[..];
    // The stricter CR LF limit: the edit does not know the line's ending.
    let limit = line_limit(program.dialect, settings, true);
    edits.iter().all(|e| {
        let (Some(s), Some(t)) = (
            e.span.start.checked_sub(program.base),
            e.span.end.checked_sub(program.base),
        ) else {
            return true;
        };
        let (s, t) = (s as usize, t as usize);
        if s > t || t > text.len() || e.new_text.contains('\n') {
            return true;
        }
        let start = text[..s]
            .iter()
            .rposition(|b| *b == b'\n')
            .map_or(0, |i| i + 1);
        let end = text[t..]
            .iter()
            .position(|b| *b == b'\n' || *b == b'\r')
            .map_or(text.len(), |i| t + i);
        let chars = |b: &[u8]| b.iter().filter(|c| (**c & 0xC0) != 0x80).count();
        let before = chars(&text[start..end]);
        let after = before - chars(&text[s..t]) + e.new_text.chars().count();
        after <= limit.max(before)
    })
}
