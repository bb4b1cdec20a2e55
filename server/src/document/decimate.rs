//! The toolpath a client draws, bounded: simplified to the view's tolerance
//! and capped in size.
//!
//! Consecutive motions of one kind, feed and tool that join end to start form
//! a *run*, whose points make one polyline. Each run is simplified on its own
//! (Douglas–Peucker), so a rapid/feed change, a feed change or a tool change
//! is never smoothed over: the preview draws those differently. The
//! simplification is made once per run of the interpreter: every point gets
//! its Douglas–Peucker *significance*, the largest tolerance at which the
//! algorithm keeps it (the smaller of its distance from the chord it split
//! and the significance of that chord's own split point). A request at any
//! tolerance then keeps the points above it in one pass, and the size cap is
//! met by raising the tolerance to the significance of the last point that
//! fits.

use serde::Serialize;

use super::run::{Segment, SegmentKind};

/// Points simplified together at most; the ends of such a stretch are always
/// kept. Bounds the algorithm's quadratic worst case on one long run.
const STRETCH: usize = 4096;
/// What a segment's own fields cost in the size cap, in points (its kind,
/// line, feed and tool take about as many bytes as three points).
pub const SEGMENT_COST: usize = 3;
/// Default cap on the toolpath of one answer, in points (at most about 4 MB
/// of JSON: 3.7 MB measured at the cap, BENCHMARKS.md).
pub const DEFAULT_MAX_POINTS: usize = 100_000;
/// The smallest cap a client may set.
pub const MIN_MAX_POINTS: usize = 1_000;
/// The default tolerance is the part's extent (the longest side of the
/// toolpath's bounding box) divided by this.
pub const DEFAULT_VIEW_SIZE: f64 = 2000.0;
/// Output coordinates are rounded to this grid (mm) when points are dropped:
/// a tenth of a micrometre, far below any tolerance a view asks for, and
/// it halves the bytes of computed coordinates.
const GRID: f64 = 1e-4;

#[derive(Debug, Clone, Copy, PartialEq)]
struct Key {
    kind: SegmentKind,
    feed: f64,
    tool: u32,
}

#[derive(Debug, Clone)]
struct Run {
    key: Key,
    /// Its points: `points[first..end]`.
    first: u32,
    end: u32,
    /// Its motions: `motion_start[motions.0..motions.1]`.
    motions: (u32, u32),
    /// Points always kept (the ends of the run and of its stretches).
    fixed: u32,
}

/// A run's toolpath with the significance of every point.
#[derive(Debug, Clone, Default)]
pub struct Path {
    points: Vec<[f64; 3]>,
    /// The 0-based line of the motion each point ends (a run's first point:
    /// its first motion's line).
    lines: Vec<u32>,
    sig: Vec<f64>,
    runs: Vec<Run>,
    /// Where each motion's points start in `points`.
    motion_start: Vec<u32>,
    /// Points of the toolpath sent one segment per motion, whole.
    motion_points: usize,
    /// Exact path length (arcs by their true length).
    pub distance: f64,
    /// Bounding box of every point (`None` without motion).
    pub bounds: Option<([f64; 3], [f64; 3])>,
}

/// How a request wants the toolpath.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Request {
    /// Largest distance (mm) of a dropped point from the drawn polyline;
    /// `None`: the extent over [`DEFAULT_VIEW_SIZE`]; `Some(0)`: every point,
    /// one segment per motion, as long as that fits the cap.
    pub tolerance: Option<f64>,
    /// Cap on the points sent, a segment counting [`SEGMENT_COST`] more.
    pub max_points: usize,
}

impl Request {
    /// Every point, one segment per motion, no cap (`partscope run --html`,
    /// whose page has its own size limit).
    pub const EXACT: Request = Request {
        tolerance: Some(0.0),
        max_points: usize::MAX,
    };
}

/// What the answer says about the decimation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Decimation {
    /// The tolerance used (mm): every dropped point lies within it of the
    /// drawn polyline (to the 0.1 µm the coordinates are rounded to).
    pub tolerance_mm: f64,
    /// The tolerance asked for (or the default), before the cap raised it.
    /// A toolpath that loses no point at it is sent whole, one segment per
    /// motion, when that fits the cap.
    pub requested_tolerance_mm: f64,
    pub max_points: usize,
    pub motions: usize,
    /// Points of the whole toolpath sent one segment per motion.
    pub points_in: usize,
    pub points_out: usize,
    pub points_dropped: usize,
    pub segments_out: usize,
    /// Points were dropped or motions merged into one segment.
    pub decimated: bool,
    /// The cap applied: it raised the tolerance, or cut the toolpath.
    pub capped: bool,
    /// The toolpath sent stops before the motion of this 0-based line (the
    /// cap cut it); `null` when the whole toolpath is sent.
    pub truncated_at_line: Option<u32>,
}

impl Path {
    /// An empty path with room for `motions` motions of two points each
    /// (a million-line program's vectors then never move while they fill;
    /// room that is not filled costs address space, not memory).
    pub fn with_capacity(motions: usize) -> Path {
        Path {
            points: Vec::with_capacity(2 * motions + 1),
            lines: Vec::with_capacity(2 * motions + 1),
            motion_start: Vec::with_capacity(motions),
            ..Path::default()
        }
    }

    /// Adds one motion's polyline (at least two points).
    pub fn push(
        &mut self,
        kind: SegmentKind,
        line: u32,
        feed: f64,
        tool: u32,
        points: &[[f64; 3]],
        length: f64,
    ) {
        let (Some(first), Some(_)) = (points.first(), points.get(1)) else {
            return;
        };
        self.distance += length;
        self.motion_points += points.len();
        let (lo, hi) = self
            .bounds
            .get_or_insert(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]));
        for p in points {
            for k in 0..3 {
                if p[k].is_finite() {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let key = Key { kind, feed, tool };
        let motion = self.motion_start.len() as u32;
        let joins =
            self.runs.last().is_some_and(|r| r.key == key) && self.points.last() == Some(first);
        let skip = if joins {
            // The motion starts where the run's last point is: share it.
            self.motion_start.push(self.points.len() as u32 - 1);
            1
        } else {
            self.motion_start.push(self.points.len() as u32);
            let at = self.points.len() as u32;
            self.runs.push(Run {
                key,
                first: at,
                end: at,
                motions: (motion, motion),
                fixed: 0,
            });
            0
        };
        for p in &points[skip..] {
            self.points.push(*p);
            self.lines.push(line);
        }
        if let Some(r) = self.runs.last_mut() {
            r.end = self.points.len() as u32;
            r.motions.1 = motion + 1;
        }
    }

    /// Computes every point's significance; call once after the last push.
    pub fn finish(&mut self) {
        self.finish_until(&|| false);
    }

    /// [`Path::finish`] that gives up when `stop` says so (polled once per
    /// stretch of points); `false` then, and the path is not usable.
    pub fn finish_until(&mut self, stop: &dyn Fn() -> bool) -> bool {
        if let Some((lo, hi)) = self.bounds {
            if !lo[0].is_finite() {
                self.bounds = Some(([0.0; 3], [0.0; 3]));
            } else {
                self.bounds = Some((lo, hi));
            }
        }
        self.sig = vec![0.0; self.points.len()];
        let mut stack = Vec::new();
        for r in &mut self.runs {
            let (first, end) = (r.first as usize, r.end as usize);
            let mut a = first;
            while a + 1 < end {
                if stop() {
                    return false;
                }
                let b = (a + STRETCH).min(end - 1);
                self.sig[a] = f64::INFINITY;
                self.sig[b] = f64::INFINITY;
                significance(&self.points, &mut self.sig, a, b, &mut stack);
                a = b;
            }
            self.sig[first] = f64::INFINITY;
            self.sig[end - 1] = f64::INFINITY;
            r.fixed = self.sig[first..end]
                .iter()
                .filter(|s| s.is_infinite())
                .count() as u32;
        }
        true
    }

    /// The part's extent: the longest side of the bounding box.
    pub fn extent(&self) -> f64 {
        self.bounds
            .map(|(lo, hi)| (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max))
            .unwrap_or(0.0)
    }

    /// The segments a request gets, and what was done to them.
    pub fn select(&self, req: Request) -> (Vec<Segment>, Decimation) {
        let max_points = req.max_points.max(MIN_MAX_POINTS);
        let requested = match req.tolerance {
            Some(t) if t.is_finite() && t >= 0.0 => t,
            _ => self.extent() / DEFAULT_VIEW_SIZE,
        };
        let motions = self.motion_start.len();
        let mut report = Decimation {
            tolerance_mm: requested,
            requested_tolerance_mm: requested,
            max_points,
            motions,
            points_in: self.motion_points,
            points_out: 0,
            points_dropped: 0,
            segments_out: 0,
            decimated: false,
            capped: false,
            truncated_at_line: None,
        };
        let exact_cost = self
            .motion_points
            .saturating_add(motions.saturating_mul(SEGMENT_COST));
        // A toolpath that loses no point at the tolerance goes out as before,
        // one segment per motion, if that fits.
        let loses_none = self.sig.iter().all(|s| s.is_infinite() || *s > requested);
        if (requested == 0.0 || loses_none) && exact_cost <= max_points {
            let segs = self.per_motion();
            report.points_out = self.motion_points;
            report.segments_out = segs.len();
            return (segs, report);
        }
        // Each run costs its fixed points and its fields; when they alone
        // exceed the cap, the toolpath is cut after the runs that fill half
        // of it, leaving the other half to their shapes.
        let run_cost = |r: &Run| r.fixed as usize + SEGMENT_COST;
        let total_fixed: usize = self.runs.iter().map(run_cost).sum();
        let mut kept_runs = self.runs.len();
        let mut fixed = total_fixed;
        if total_fixed > max_points {
            fixed = 0;
            kept_runs = 0;
            for r in &self.runs {
                if fixed + run_cost(r) > max_points / 2 {
                    break;
                }
                fixed += run_cost(r);
                kept_runs += 1;
            }
            report.capped = true;
            report.truncated_at_line = self
                .runs
                .get(kept_runs)
                .and_then(|r| self.lines.get(r.first as usize).copied());
        }
        let runs = &self.runs[..kept_runs];
        // The other points that the requested tolerance keeps; if more than
        // the cap leaves room for, the tolerance rises to keep only the most
        // significant ones.
        let budget = max_points - fixed;
        let mut candidates: Vec<f64> = runs
            .iter()
            .flat_map(|r| &self.sig[r.first as usize..r.end as usize])
            .copied()
            .filter(|s| s.is_finite() && *s > requested)
            .collect();
        let mut tolerance = requested;
        if candidates.len() > budget {
            let nth = candidates.len() - budget - 1;
            let (_, t, _) = candidates.select_nth_unstable_by(nth, f64::total_cmp);
            tolerance = *t;
            report.capped = true;
        }
        drop(candidates);
        report.tolerance_mm = tolerance;
        let mut segs = Vec::with_capacity(runs.len());
        for r in runs {
            let range = r.first as usize..r.end as usize;
            let keep: Vec<usize> = range.filter(|&i| self.sig[i] > tolerance).collect();
            let (m0, m1) = (r.motions.0 as usize, r.motions.1 as usize);
            let whole = keep.len() == (r.end - r.first) as usize;
            if m1 - m0 == 1 && whole {
                // One motion, every point kept: the segment of that motion.
                segs.extend(self.motion_segment(r, m0));
                continue;
            }
            let round = |p: &[f64; 3]| p.map(|v| (v / GRID).round() * GRID);
            segs.push(Segment {
                kind: r.key.kind,
                line: self.lines[r.first as usize],
                feed: r.key.feed,
                tool: r.key.tool,
                points: keep.iter().map(|&i| round(&self.points[i])).collect(),
                lines: Some(keep.iter().map(|&i| self.lines[i]).collect()),
                length: 0.0,
            });
        }
        report.points_out = segs.iter().map(|s| s.points.len()).sum();
        report.segments_out = segs.len();
        report.points_dropped = self.motion_points.saturating_sub(report.points_out);
        report.decimated = true;
        (segs, report)
    }

    /// One segment per motion, every point.
    fn per_motion(&self) -> Vec<Segment> {
        let mut out = Vec::with_capacity(self.motion_start.len());
        for r in &self.runs {
            for m in r.motions.0..r.motions.1 {
                out.extend(self.motion_segment(r, m as usize));
            }
        }
        out
    }

    fn motion_segment(&self, r: &Run, m: usize) -> Option<Segment> {
        let start = *self.motion_start.get(m)? as usize;
        let end = match self.motion_start.get(m + 1) {
            Some(&next) if (m + 1) < r.motions.1 as usize => next as usize + 1,
            _ => r.end as usize,
        };
        Some(Segment {
            kind: r.key.kind,
            line: self.lines[end - 1],
            feed: r.key.feed,
            tool: r.key.tool,
            points: self.points.get(start..end)?.to_vec(),
            lines: None,
            length: 0.0,
        })
    }
}

/// Distance of `p` from the segment `a`–`b`.
fn distance_to_segment(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if len2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// Douglas–Peucker significance of the points strictly between `a` and `b`
/// (with an explicit stack: no recursion depth to bound).
fn significance(
    points: &[[f64; 3]],
    sig: &mut [f64],
    a: usize,
    b: usize,
    stack: &mut Vec<(usize, usize, f64)>,
) {
    stack.clear();
    stack.push((a, b, f64::INFINITY));
    while let Some((a, b, cap)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (mut far, mut best) = (a + 1, -1.0);
        for (i, p) in points.iter().enumerate().take(b).skip(a + 1) {
            let d = distance_to_segment(p, &points[a], &points[b]);
            if d > best {
                best = d;
                far = i;
            }
        }
        // A point is kept only while the chord it splits is kept.
        let s = best.min(cap);
        sig[far] = s;
        stack.push((a, far, s));
        stack.push((far, b, s));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(motions: &[(SegmentKind, f64, u32, Vec<[f64; 3]>)]) -> Path {
        let mut p = Path::default();
        for (i, (kind, feed, tool, pts)) in motions.iter().enumerate() {
            p.push(*kind, i as u32, *feed, *tool, pts, 1.0);
        }
        p.finish();
        p
    }

    /// Every point of `all` is within `tol` of the polyline through `kept`.
    fn within(all: &[[f64; 3]], kept: &[[f64; 3]], tol: f64) -> Result<(), String> {
        for p in all {
            let d = kept
                .windows(2)
                .map(|w| distance_to_segment(p, &w[0], &w[1]))
                .fold(f64::INFINITY, f64::min);
            let d = if kept.len() == 1 {
                distance_to_segment(p, &kept[0], &kept[0])
            } else {
                d
            };
            if d > tol + 1e-9 {
                return Err(format!(
                    "{p:?} is {d} from the kept polyline (tolerance {tol})"
                ));
            }
        }
        Ok(())
    }

    #[test]
    fn collinear_feeds_become_one_segment_with_their_lines() {
        let f = SegmentKind::Feed;
        let p = path(&[
            (f, 100.0, 1, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
            (f, 100.0, 1, vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
            (f, 100.0, 1, vec![[2.0, 0.0, 0.0], [2.0, 1.0, 0.0]]),
        ]);
        let (segs, d) = p.select(Request {
            tolerance: Some(0.01),
            max_points: 100_000,
        });
        assert_eq!(segs.len(), 1);
        assert_eq!(
            segs[0].points,
            vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]]
        );
        assert_eq!(segs[0].lines, Some(vec![0, 1, 2]));
        assert_eq!((d.points_in, d.points_out, d.points_dropped), (6, 3, 3));
        assert!(d.decimated && !d.capped);
    }

    #[test]
    fn runs_break_at_kind_feed_and_tool_changes() {
        let (f, r) = (SegmentKind::Feed, SegmentKind::Rapid);
        let p = path(&[
            (f, 100.0, 1, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
            (f, 100.0, 1, vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
            (f, 200.0, 1, vec![[2.0, 0.0, 0.0], [3.0, 0.0, 0.0]]),
            (r, 0.0, 1, vec![[3.0, 0.0, 0.0], [4.0, 0.0, 0.0]]),
            (r, 0.0, 2, vec![[4.0, 0.0, 0.0], [5.0, 0.0, 0.0]]),
        ]);
        let (segs, _) = p.select(Request {
            tolerance: None,
            max_points: 100_000,
        });
        let shape: Vec<(SegmentKind, f64, u32, usize)> = segs
            .iter()
            .map(|s| (s.kind, s.feed, s.tool, s.points.len()))
            .collect();
        assert_eq!(
            shape,
            vec![
                (f, 100.0, 1, 2),
                (f, 200.0, 1, 2),
                (r, 0.0, 1, 2),
                (r, 0.0, 2, 2)
            ]
        );
        // The one-motion runs go out as before, without `lines`.
        assert_eq!(segs[1].lines, None);
        assert_eq!(segs[1].line, 2);
    }

    #[test]
    fn tolerance_zero_sends_every_motion_whole() {
        let f = SegmentKind::Feed;
        let p = path(&[
            (f, 100.0, 1, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
            (f, 100.0, 1, vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
        ]);
        let (segs, d) = p.select(Request::EXACT);
        assert_eq!(segs.len(), 2);
        assert_eq!(segs[1].points, vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
        assert_eq!((segs[0].line, segs[1].line), (0, 1));
        assert!(!d.decimated);
        assert_eq!(d.points_dropped, 0);
    }

    /// A deterministic generator for the property tests (no dependency).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn every_dropped_point_is_within_the_tolerance_of_the_kept_polyline() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for case in 0..300 {
            // Random walks of feeds with occasional rapids and feed changes,
            // some long enough to cross a stretch boundary.
            let n = if case % 50 == 0 {
                9000
            } else {
                2 + (rng.next() * 400.0) as usize
            };
            let mut at = [0.0; 3];
            let mut motions = Vec::new();
            for _ in 0..n {
                let step = [rng.next() - 0.3, rng.next() - 0.5, (rng.next() - 0.5) * 0.2];
                let next = [at[0] + step[0], at[1] + step[1], at[2] + step[2]];
                let kind = if rng.next() < 0.05 {
                    SegmentKind::Rapid
                } else {
                    SegmentKind::Feed
                };
                let feed = if rng.next() < 0.02 { 500.0 } else { 1000.0 };
                motions.push((kind, feed, 1, vec![at, next]));
                at = next;
            }
            let p = path(&motions);
            let tol = [0.0, 0.001, 0.05, 0.3, 2.0][case % 5];
            let max_points = if case % 3 == 0 { 1_000 } else { 100_000 };
            let (segs, d) = p.select(Request {
                tolerance: Some(tol),
                max_points,
            });
            assert!(d.tolerance_mm >= tol);
            if !d.decimated {
                assert_eq!(d.points_out, d.points_in);
                continue;
            }
            // Decimated: each run of the input is one segment, in order.
            assert!(segs.len() <= p.runs.len());
            assert_eq!(segs.len() < p.runs.len(), d.truncated_at_line.is_some());
            let cost: usize = segs.iter().map(|s| s.points.len() + SEGMENT_COST).sum();
            assert!(cost <= max_points, "case {case}: {cost} > {max_points}");
            for (r, s) in p.runs.iter().zip(&segs) {
                let all = &p.points[r.first as usize..r.end as usize];
                let near = |a: &[f64; 3], b: &[f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() <= GRID);
                assert!(
                    near(&all[0], &s.points[0])
                        && near(&all[all.len() - 1], &s.points[s.points.len() - 1])
                );
                within(all, &s.points, d.tolerance_mm + GRID)
                    .unwrap_or_else(|e| panic!("case {case}: {e}"));
            }
        }
    }

    #[test]
    fn the_cap_raises_the_tolerance_then_cuts() {
        let f = SegmentKind::Feed;
        // A zigzag of 20 000 points in one run: no point is negligible at a
        // fine tolerance, so the cap decides.
        let pts: Vec<[f64; 3]> = (0..20_000)
            .map(|i| {
                [
                    i as f64 * 0.01,
                    if i % 2 == 0 {
                        0.0
                    } else {
                        0.5 + (i % 7) as f64 * 0.1
                    },
                    0.0,
                ]
            })
            .collect();
        let motions: Vec<_> = pts.windows(2).map(|w| (f, 100.0, 1, w.to_vec())).collect();
        let p = path(&motions);
        let (segs, d) = p.select(Request {
            tolerance: Some(0.001),
            max_points: 5_000,
        });
        assert!(d.capped && d.truncated_at_line.is_none());
        assert!(d.tolerance_mm > 0.001);
        assert_eq!(segs.len(), 1);
        assert!(d.points_out + SEGMENT_COST <= 5_000, "{d:?}");
        assert!(d.points_out > 4_000, "{d:?}");
        // 20 000 separate runs (alternating kinds) cannot fit: cut at half the cap.
        let motions: Vec<_> = pts
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                (
                    if i % 2 == 0 { f } else { SegmentKind::Rapid },
                    100.0,
                    1,
                    w.to_vec(),
                )
            })
            .collect();
        let p = path(&motions);
        let (segs, d) = p.select(Request {
            tolerance: None,
            max_points: 5_000,
        });
        // Each one-motion run costs 2 points + 3: 500 runs fill half of 5 000.
        assert_eq!(segs.len(), 500);
        assert_eq!(d.truncated_at_line, Some(500));
        assert!(d.capped);
    }
}
