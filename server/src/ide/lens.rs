//! The cycle-time lens and the inlay hints of block times and tool changes,
//! read off the document's dry run.

use super::{Analysis, RunReport};
use crate::document::run::Breakdown;

/// A block's own time: milliseconds below ten seconds, then `m:ss.s`.
pub fn block_seconds(s: f64) -> String {
    if s < 10.0 {
        format!("{s:.3} s")
    } else if s < 60.0 {
        format!("{s:.2} s")
    } else {
        format_duration(s)
    }
}

/// `m:ss.s`, or `h:mm:ss` from an hour on.
pub fn format_duration(s: f64) -> String {
    if !s.is_finite() || s < 0.0 {
        return "–".into();
    }
    let s = (s * 10.0).round() / 10.0;
    if s >= 3600.0 {
        let t = s.round() as u64;
        return format!("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60);
    }
    let m = (s / 60.0).floor();
    format!("{}:{:04.1}", m as u64, s - m * 60.0)
}

/// The title of the cycle-time lens on the first line: the run's times, or
/// why there is no run (`skipped`). `None` when the run has no times (the
/// machine table is not a planner profile) or there is neither.
pub fn cycle_time_title(run: Option<&RunReport>, skipped: Option<String>) -> Option<String> {
    let Some(r) = run else {
        return skipped;
    };
    let t = r.timing?;
    let times = format!(
        "(cutting {}, rapid {}, tool change {})",
        format_duration(t.cutting_s),
        format_duration(t.rapid_s),
        format_duration(t.tool_change_s)
    );
    Some(match &r.stopped {
        // The run covers only part of the program: say where it stopped.
        Some(s) => format!(
            "Cycle time {} partial {times}: {}",
            format_duration(t.cycle_time_s),
            s.describe()
        ),
        None if r.skipped_calls => format!(
            "Cycle time {} partial {times}: a called program was not run",
            format_duration(t.cycle_time_s)
        ),
        None => format!("Cycle time {} {times}", format_duration(t.cycle_time_s)),
    })
}

/// What the block-time hints show (the `blockTimes` setting).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockTimes {
    /// The block's own time.
    Block,
    /// The program time when the block ends.
    Cumulative,
    /// None: only the tool changes.
    Off,
}

/// One inlay hint: a label at the end of a line's content.
#[derive(Debug, Clone, PartialEq)]
pub struct InlayHint {
    /// The byte offset where the line's content ends.
    pub offset: usize,
    pub label: String,
    pub tooltip: Option<String>,
}

/// The hints of the lines `first..=last`: each tool change's program time,
/// then (unless `mode` is off) each timed block's time with its causes as
/// the tooltip, in line order, a tool change before a block time.
pub fn inlay_hints(a: &Analysis<'_>, first: u32, last: u32, mode: BlockTimes) -> Vec<InlayHint> {
    let Some(report) = a.run.as_deref() else {
        return Vec::new();
    };
    let in_range = |line: u32| first <= line && line <= last;
    let end_of_line = |line: u32| a.line_content_end(line as usize);
    let mut hints: Vec<(u32, u8, InlayHint)> = report
        .tool_changes
        .iter()
        .filter(|(line, _)| in_range(*line))
        .filter_map(|(line, t)| {
            let t = (*t)?;
            let hint = InlayHint {
                offset: end_of_line(*line)?,
                label: format!("tool change at {}", format_duration(t)),
                tooltip: None,
            };
            Some((*line, 0, hint))
        })
        .collect();
    if mode != BlockTimes::Off {
        for b in report.blocks.iter().filter(|b| in_range(b.line)) {
            if b.time_s <= 0.0 {
                continue;
            }
            let Some(offset) = end_of_line(b.line) else {
                continue;
            };
            let label = match mode {
                BlockTimes::Cumulative => format!("ends at {}", format_duration(b.end_s)),
                _ => block_seconds(b.time_s),
            };
            let tooltip = format!(
                "{}; ends at {}",
                Breakdown::of_block(b),
                format_duration(b.end_s)
            );
            hints.push((
                b.line,
                1,
                InlayHint {
                    offset,
                    label,
                    tooltip: Some(tooltip),
                },
            ));
        }
    }
    hints.sort_by_key(|(line, order, _)| (*line, *order));
    hints.into_iter().map(|(_, _, h)| h).collect()
}

#[cfg(test)]
mod tests {
    use super::format_duration;

    #[test]
    fn durations_read_like_a_clock() {
        assert_eq!(format_duration(13.04), "0:13.0");
        assert_eq!(format_duration(59.96), "1:00.0");
        assert_eq!(format_duration(754.25), "12:34.3");
        assert_eq!(format_duration(3725.4), "1:02:05");
        assert_eq!(format_duration(f64::NAN), "–");
    }
}
