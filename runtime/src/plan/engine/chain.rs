//! The `linuxcnc` model's naive-CAM detector: LinuxCNC's canonical layer joins
//! consecutive G64 P… straight moves into one while every intermediate point stays
//! within the tolerance of the straight line from the first start to the newest
//! end, up to 100 points.
//!
//! Checking every held-back point for every new move costs O(chain length) per move,
//! O(n²) per chain. [`Chain::linkable`] gives exactly the answer of that check, but
//! usually proves it in O(1): it keeps an upper bound of the points' distance from
//! the current line, moves the bound by how far the line moves, and only when the
//! bound no longer proves the answer runs the point-by-point check (which then
//! tightens the bound again).

use super::super::{dot3, norm3, sub3, PathMode, Segment};

/// Relative rounding margin of the bound. The point-by-point check and the bound's
/// own arithmetic err by a few units in the last place of the coordinates
/// (about 1e-15 relative); a margin a million times larger keeps the proof sound
/// while costing nothing measurable against real tolerances (0.001 mm and up).
const MARGIN: f64 = 1e-9;

/// Held-back straight moves.
#[derive(Debug, Default)]
pub(super) struct Chain {
    /// The first and the newest held-back move.
    first: Option<Segment>,
    last: Option<Segment>,
    /// End points (XYZ) of the held-back moves, in order; one per move.
    ends: Vec<[f64; 3]>,
    /// Largest absolute XYZ coordinate of the first start and of `ends`: scales the
    /// rounding margin.
    scale: f64,
    /// An upper bound of the exact distance of every point of `ends` from the
    /// segment from the first start to the newest end; NaN when unknown.
    bound: f64,
    /// Length of that segment when the last answer was yes (NaN otherwise): the
    /// next check's old segment, so its square root is not taken twice.
    len: f64,
    /// How many answers the bound proved (the tests check it does its work).
    #[cfg(test)]
    proofs: usize,
}

fn xyz(p: &[f64; 6]) -> [f64; 3] {
    [p[0], p[1], p[2]]
}

fn max_abs(p: &[f64; 3]) -> f64 {
    p[0].abs().max(p[1].abs()).max(p[2].abs())
}

impl Chain {
    pub(super) fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Holds `seg` back. A move that starts a chain needs no check; any other must
    /// have passed [`Chain::linkable`] just before, which left the bound for the line
    /// ending at `seg`'s end.
    pub(super) fn push(&mut self, seg: Segment) {
        let end = xyz(&seg.end);
        if self.first.is_none() {
            self.first = Some(seg);
            self.scale = max_abs(&xyz(&seg.start));
            // A single point lies on its own line.
            self.bound = 0.0;
            self.len = f64::NAN;
        }
        self.scale = self.scale.max(max_abs(&end));
        self.ends.push(end);
        self.last = Some(seg);
    }

    /// The first and the newest held-back move; the chain is empty afterwards.
    pub(super) fn take(&mut self) -> Option<(Segment, Segment)> {
        let first = self.first.take();
        let last = self.last.take();
        self.ends.clear();
        self.bound = f64::NAN;
        self.len = f64::NAN;
        first.zip(last)
    }

    /// Whether `seg` may join the chain: same mode and feed, at most 100 points,
    /// and every held-back end within the tolerance of the segment from the first
    /// start to `seg`'s end. When it may, the bound is moved to that segment, since
    /// the engine pushes `seg` next.
    pub(super) fn linkable(&mut self, seg: &Segment) -> bool {
        let (Some(first), Some(last)) = (&self.first, &self.last) else {
            return false;
        };
        if self.ends.len() > 100 || seg.mode != last.mode || seg.feed != last.feed {
            return false;
        }
        let PathMode::Blend {
            naive: tolerance, ..
        } = seg.mode
        else {
            return false;
        };
        let b = xyz(&first.start);
        let e = xyz(&seg.end);
        if b == e {
            return false;
        }
        let m = sub3(&e, &b);
        let mm = dot3(&m, &m);
        let l = mm.sqrt();
        if let Some(bound) = self.proven_bound(&b, &e, &m, l, tolerance) {
            self.bound = bound;
            self.len = l;
            #[cfg(test)]
            {
                self.proofs += 1;
            }
            return true;
        }
        // The point-by-point check, with the same arithmetic as LinuxCNC's detector
        // (its answer is the reference); it also measures the new bound.
        let within = Within::new(tolerance);
        let mut worst: f64 = 0.0;
        for pt in &self.ends {
            let t0 = (dot3(&m, &sub3(pt, &b)) / mm).clamp(0.0, 1.0);
            let q = [b[0] + t0 * m[0], b[1] + t0 * m[1], b[2] + t0 * m[2]];
            let r = sub3(pt, &q);
            let squared = dot3(&r, &r);
            if !within.test(squared) {
                self.bound = f64::NAN;
                self.len = f64::NAN;
                return false;
            }
            worst = worst.max(squared);
        }
        let scale = self.scale.max(max_abs(&e));
        // The square root is monotonic, so the largest distance is the root of the
        // largest square.
        self.bound = worst.sqrt() + MARGIN * (1.0 + scale);
        self.len = l;
        true
    }

    /// A bound of every held-back end's distance from the segment `b`→`e` that
    /// proves all of them within `tolerance` even after rounding, or `None`.
    ///
    /// The old segment runs from `b` to the newest end `k`, of length `lk`; the new
    /// one from `b` along the unit vector `u` for a length `l ≥ lk`. Mapping the old
    /// segment's point at distance `s` from `b` to the new one's at the same
    /// distance moves it by `s·|u − u_k| ≤ |lk·u − (k − b)|` =: Δ, so no point's
    /// distance grows by more than Δ.
    fn proven_bound(
        &self,
        b: &[f64; 3],
        e: &[f64; 3],
        m: &[f64; 3],
        l: f64,
        tolerance: f64,
    ) -> Option<f64> {
        // NaN (unknown, or a non-finite coordinate) fails every comparison below.
        let bound = self.bound;
        let k = self.ends.last()?;
        let scale = self.scale.max(max_abs(e));
        let eps = MARGIN * (1.0 + scale);
        let bk = sub3(k, b);
        // The old segment's length, measured by the last check when there was one.
        let lk = if self.len.is_nan() {
            norm3(&bk)
        } else {
            self.len
        };
        // A shorter new segment (or one too short to divide by safely) would need
        // the clamped mapping; the point-by-point check decides instead.
        if !(l >= lk + eps && l > eps) {
            return None;
        }
        let f = lk / l;
        let shifted = [f * m[0], f * m[1], f * m[2]];
        let delta = norm3(&sub3(&shifted, &bk));
        // One margin for the rounding of Δ and of this sum, one for the rounding of
        // the point-by-point distances the bound stands in for.
        let next = bound + delta + eps;
        (next + eps <= tolerance).then_some(next)
    }
}

/// `sqrt(squared) <= tolerance` exactly as the rounded square root compares, without
/// taking the root unless the square is within a hair of the tolerance's square.
struct Within {
    tolerance: f64,
    /// Squares at or below `lo` pass and above `hi` fail; between, the root decides.
    lo: f64,
    hi: f64,
}

impl Within {
    fn new(tolerance: f64) -> Within {
        let t2 = tolerance * tolerance;
        // Both limits sit 2^-40 (relative) inside the band where rounding of the
        // square or of the root could matter (2^-52); a square that underflows or
        // overflows (or a tolerance that is not positive) leaves the band open, so
        // the root decides every time.
        let (lo, hi) = if tolerance > 0.0 && t2.is_normal() {
            (
                t2 * (1.0 - 1.0 / (1u64 << 40) as f64),
                t2 * (1.0 + 1.0 / (1u64 << 40) as f64),
            )
        } else {
            (f64::NEG_INFINITY, f64::INFINITY)
        };
        Within { tolerance, lo, hi }
    }

    fn test(&self, squared: f64) -> bool {
        if squared <= self.lo {
            true
        } else if squared > self.hi {
            false
        } else {
            squared.sqrt() <= self.tolerance
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The detector as LinuxCNC states it: every held-back end against the segment.
    fn reference(chain: &[Segment], seg: &Segment) -> bool {
        let Some(first) = chain.first() else {
            return false;
        };
        let last = &chain[chain.len() - 1];
        if chain.len() > 100 || seg.mode != last.mode || seg.feed != last.feed {
            return false;
        }
        let PathMode::Blend {
            naive: tolerance, ..
        } = seg.mode
        else {
            return false;
        };
        let b = xyz(&first.start);
        let e = xyz(&seg.end);
        if b == e {
            return false;
        }
        let m = sub3(&e, &b);
        let mm = dot3(&m, &m);
        chain.iter().all(|p| {
            let pt = xyz(&p.end);
            let t0 = (dot3(&m, &sub3(&pt, &b)) / mm).clamp(0.0, 1.0);
            let q = [b[0] + t0 * m[0], b[1] + t0 * m[1], b[2] + t0 * m[2]];
            norm3(&sub3(&pt, &q)) <= tolerance
        })
    }

    /// A small deterministic generator (xorshift64*), so failures reproduce.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Feeds a path of moves to a `Chain` and to the reference the way the engine
    /// does, and returns how many decisions were made and how many the bound proved.
    fn compare(points: &[[f64; 3]], tolerance: f64, feeds: &[f64]) -> (usize, usize) {
        let mode = PathMode::blend(tolerance);
        let mut chain = Chain::default();
        let mut held: Vec<Segment> = Vec::new();
        let mut decisions = 0;
        for (i, w) in points.windows(2).enumerate() {
            let seg = Segment::line(w[0], w[1], feeds[i % feeds.len()], mode);
            if !held.is_empty() {
                let want = reference(&held, &seg);
                assert_eq!(
                    chain.linkable(&seg),
                    want,
                    "move {i} of {} at tolerance {tolerance}",
                    points.len() - 1
                );
                decisions += 1;
                if !want {
                    let (f, l) = chain.take().expect("a held chain");
                    assert_eq!((f.end, l.end), (held[0].end, held[held.len() - 1].end));
                    held.clear();
                }
            }
            chain.push(seg);
            held.push(seg);
        }
        (decisions, chain.proofs)
    }

    #[test]
    fn the_bound_never_changes_the_answer() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut decisions, mut proofs) = (0, 0);
        for case in 0..400 {
            // Raster passes over a curved surface (what CAM output looks like),
            // with noise near the tolerance, steps of 0.01-0.3 mm, offsets far from
            // the origin, and an occasional reversal or repeated point.
            let tolerance = [0.001, 0.005, 0.01, 0.05][case % 4];
            let origin = [
                rng.next() * 2000.0 - 1000.0,
                rng.next() * 100.0,
                -rng.next() * 50.0,
            ];
            let curvature = rng.next() * 0.02;
            let noise = tolerance * [0.0, 0.3, 1.0, 3.0][(case / 4) % 4];
            let step = 0.01 + rng.next() * 0.29;
            let mut pts = Vec::new();
            let mut x: f64 = 0.0;
            for j in 0..600 {
                x += if rng.next() < 0.01 { -step } else { step };
                let z = curvature * x * x + noise * (rng.next() - 0.5);
                let y = if j % 97 == 96 { 0.5 } else { 0.0 };
                pts.push([origin[0] + x, origin[1] + y, origin[2] + z]);
                if rng.next() < 0.005 {
                    pts.push(*pts.last().expect("a point"));
                }
            }
            let (d, p) = compare(&pts, tolerance, &[1.0, 1.0, 1.0, 1.0, 1.0, 2.0]);
            decisions += d;
            proofs += p;
        }
        // Both ways of answering are exercised.
        assert!(decisions > 200_000, "{decisions} decisions");
        assert!(
            proofs > decisions / 10 && proofs < decisions * 9 / 10,
            "{proofs} of {decisions} proved"
        );
    }

    #[test]
    fn collinear_moves_chain_up_to_the_limit() {
        let pts: Vec<[f64; 3]> = (0..300).map(|i| [i as f64 * 0.1, 0.0, 0.0]).collect();
        let (decisions, proofs) = compare(&pts, 0.01, &[1.0]);
        assert_eq!(decisions, 298);
        // On a straight line the bound proves every join; the two refusals at the
        // 101-point limit need no proof.
        assert_eq!(proofs, 298 - 2);
        // The 102nd move starts a new chain: 101 points is the most one holds.
        let mut chain = Chain::default();
        let mode = PathMode::blend(0.01);
        let mut joined = 0;
        for w in pts.windows(2) {
            let seg = Segment::line(w[0], w[1], 1.0, mode);
            if !chain.is_empty() && !chain.linkable(&seg) {
                break;
            }
            chain.push(seg);
            joined += 1;
        }
        assert_eq!(joined, 101);
    }

    #[test]
    fn squares_compare_as_their_rounded_roots() {
        let mut rng = Rng(7);
        for tolerance in [1e-3, 0.01, 0.0125, 0.1, 1.0, 3.7, 1e-160, 1e160, 0.0, -0.01] {
            let within = Within::new(tolerance);
            let t2 = tolerance * tolerance;
            for k in -2000..2000 {
                // Squares within a few thousand units in the last place of the
                // tolerance's square, then random ones around it.
                let near = t2 * (1.0 + k as f64 * f64::EPSILON);
                let far = t2 * (0.5 + rng.next());
                for sq in [near, far, near.next_up(), near.next_down()] {
                    assert_eq!(
                        within.test(sq),
                        sq.sqrt() <= tolerance,
                        "{sq:e} against {tolerance:e}"
                    );
                }
            }
            assert!(!within.test(f64::NAN));
            assert_eq!(within.test(f64::INFINITY), f64::INFINITY <= tolerance);
        }
    }

    #[test]
    fn non_finite_points_break_the_chain() {
        let mode = PathMode::blend(0.01);
        let mut chain = Chain::default();
        chain.push(Segment::line([0.0; 3], [1.0, 0.0, 0.0], 1.0, mode));
        let bad = Segment::line([1.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0], 1.0, mode);
        assert!(!chain.linkable(&bad));
        let far = Segment::line([1.0, 0.0, 0.0], [f64::INFINITY, 0.0, 0.0], 1.0, mode);
        assert!(!chain.linkable(&far));
    }
}
