//! The values expressions of the main file took during a run, per block: what
//! an editor shows on hover (`#101` = 3 on its fifth pass). Collected only when
//! a host asks for it ([`super::run_checkpointed_recording`]) and bounded by
//! [`ValueLimits`], so a plain run pays one branch per evaluated expression.
//!
//! Each series is keyed by its block and its byte span relative to the block's
//! start, so a rerun can keep the series of blocks an edit did not touch.

use std::collections::BTreeMap;

use super::expr::Val;

/// Bounds of a [`ValueRecord`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ValueLimits {
    /// Values kept per series, from the first execution on (the last value and
    /// the count are kept beyond them).
    pub per_series: usize,
    /// Series per block (one per expression, variable read or assignment).
    pub per_block: usize,
    /// Blocks tracked: the first blocks that evaluate an expression.
    pub blocks: usize,
    /// A block is tracked only while fewer series than this are recorded, so
    /// the record holds at most `series + per_block` series.
    pub series: usize,
}

impl Default for ValueLimits {
    fn default() -> Self {
        // About 20 MB at most: a series is under 200 bytes.
        ValueLimits {
            per_series: 8,
            per_block: 32,
            blocks: 50_000,
            series: 100_000,
        }
    }
}

/// The values one expression (or variable read, or assignment target) took,
/// one per evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueSeries {
    /// Byte offsets relative to the block's start.
    pub start: u32,
    pub end: u32,
    /// The first values, in order (`None` is FANUC's vacant).
    pub first: Vec<Val>,
    pub last: Val,
    /// Evaluations in all.
    pub count: u64,
}

/// Value series per block of the main file.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueRecord {
    limits: ValueLimits,
    blocks: BTreeMap<u32, Vec<ValueSeries>>,
    series: usize,
    /// Some value was not recorded because a limit was reached.
    pub truncated: bool,
}

impl ValueRecord {
    pub fn new(limits: ValueLimits) -> ValueRecord {
        ValueRecord {
            limits,
            blocks: BTreeMap::new(),
            series: 0,
            truncated: false,
        }
    }

    pub fn limits(&self) -> ValueLimits {
        self.limits
    }

    /// The series of block `bi`, in the order they were first evaluated.
    pub fn block(&self, bi: u32) -> &[ValueSeries] {
        self.blocks.get(&bi).map_or(&[], Vec::as_slice)
    }

    /// The series of the expression at `start..end` (relative to the start of block `bi`).
    pub fn at(&self, bi: u32, start: u32, end: u32) -> Option<&ValueSeries> {
        self.block(bi)
            .iter()
            .find(|s| s.start == start && s.end == end)
    }

    /// Blocks with at least one series.
    pub fn len(&self) -> usize {
        self.blocks.len()
    }

    pub fn is_empty(&self) -> bool {
        self.blocks.is_empty()
    }

    pub(super) fn record(&mut self, bi: u32, start: u32, end: u32, v: Val) {
        let l = self.limits;
        let admit = self.blocks.len() < l.blocks && self.series < l.series;
        let list = match self.blocks.get_mut(&bi) {
            Some(list) => list,
            None if admit => self.blocks.entry(bi).or_default(),
            None => {
                self.truncated = true;
                return;
            }
        };
        if let Some(s) = list.iter_mut().find(|s| s.start == start && s.end == end) {
            if s.first.len() < l.per_series {
                s.first.push(v);
            }
            s.last = v;
            s.count += 1;
            return;
        }
        if list.len() >= l.per_block {
            self.truncated = true;
            return;
        }
        self.series += 1;
        list.push(ValueSeries {
            start,
            end,
            first: if l.per_series > 0 {
                vec![v]
            } else {
                Vec::new()
            },
            last: v,
            count: 1,
        });
    }

    /// Removes and returns the series of blocks `bi` and later (a rerun runs
    /// them again, or takes them over shifted once the runs meet). Only for
    /// records that were not truncated (a rerun of a truncated one is a full run).
    pub(super) fn split_off(&mut self, bi: u32) -> ValueRecord {
        let tail = self.blocks.split_off(&bi);
        let moved: usize = tail.values().map(Vec::len).sum();
        self.series -= moved.min(self.series);
        ValueRecord {
            limits: self.limits,
            blocks: tail,
            series: moved,
            truncated: self.truncated,
        }
    }

    /// Takes over `tail`'s series of blocks `from` and later (previous
    /// numbering), moved by `shift` blocks, then drops the blocks a full run
    /// would not have tracked (it admits blocks in order, each after the
    /// blocks before it are complete: the run is single-pass).
    pub(super) fn splice(&mut self, tail: ValueRecord, from: u32, shift: i64) {
        self.truncated |= tail.truncated;
        for (bi, list) in tail.blocks.into_iter().filter(|(b, _)| *b >= from) {
            let Ok(moved) = u32::try_from(i64::from(bi) + shift) else {
                continue;
            };
            self.series += list.len();
            self.blocks.insert(moved, list);
        }
        let (mut n, mut total, mut cut) = (0, 0, None);
        for (b, list) in &self.blocks {
            if n >= self.limits.blocks || total >= self.limits.series {
                cut = Some(*b);
                break;
            }
            n += 1;
            total += list.len();
        }
        if let Some(c) = cut {
            self.blocks.split_off(&c);
            self.series = total;
            self.truncated = true;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_keep_the_first_values_the_last_and_the_count() {
        let mut r = ValueRecord::new(ValueLimits {
            per_series: 2,
            per_block: 4,
            blocks: 1,
            series: 10,
        });
        for v in [1.0, 2.0, 3.0] {
            r.record(4, 0, 2, Some(v));
        }
        r.record(5, 0, 2, Some(9.0));
        let s = r.at(4, 0, 2).expect("recorded");
        assert_eq!(s.first, vec![Some(1.0), Some(2.0)]);
        assert_eq!((s.last, s.count), (Some(3.0), 3));
        assert!(r.block(5).is_empty() && r.truncated);
    }

    #[test]
    fn split_and_splice_shift_blocks() {
        let mut r = ValueRecord::new(ValueLimits::default());
        r.record(1, 0, 1, Some(1.0));
        r.record(7, 0, 1, Some(7.0));
        let tail = r.split_off(5);
        assert_eq!(r.len(), 1);
        r.splice(tail, 6, 2);
        assert_eq!(r.block(9)[0].last, Some(7.0));
        assert!(r.block(7).is_empty());
    }
}
