//! ServoWorks exponential interpolation G02.3/G03.3 (servoworks.md D§3.6,
//! manual §6.3.5): the rotary axis A turns exponentially with the travel of X,
//! for tapered grooves of constant helix angle.
//!
//! With I the taper angle, J the helix angle, R the exponential constant and
//! K = tan J / tan I, the rotation θ (radians) and X are tied by
//! X(θ) = R·(e^(θ/K) − 1) / tan I, so moving X from x₁ to x₂ turns A by
//! Δθ = K·[ln(x₂·tan I/R + 1) − ln(x₁·tan I/R + 1)], positive for G02.3 and
//! negative for G03.3. The digest's reading is followed where the manual is
//! silent: x₁ and x₂ are the program X coordinates of the block's start and
//! end (the curve starts at X = 0), Y and Z move linearly with X, and the
//! feed varies linearly with X from F to Q along ds = √(dX² + dA²)
//! (millimetres and degrees together, as under G310).

use std::f64::consts::PI;

/// One exponential move in the curve's own terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExpCurve {
    /// Program X at the start and the end of the move.
    pub x1: f64,
    pub x2: f64,
    pub tan_i: f64,
    /// K = tan J / tan I.
    pub k: f64,
    pub r: f64,
    /// +1 for G02.3, −1 for G03.3.
    pub sign: f64,
}

/// Length, time and the bound of the integration error of an exponential move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExpMeasure {
    /// ∫ √(dX² + dA²), mm and degrees.
    pub length: f64,
    /// ∫ ds / f(x), minutes.
    pub minutes: f64,
    /// Bound on the error of `length` (Richardson estimate of the Simpson rule).
    pub length_error: f64,
}

impl ExpCurve {
    /// The curve of a block with taper `i_deg`, helix `j_deg` and constant `r`
    /// moving X from `x1` to `x2`; `None` when the equations are undefined
    /// (I or J outside (0°, 90°), R = 0, or x·tan I/R + 1 ≤ 0 on the way,
    /// SW045), so the caller can fall back to a straight move.
    pub fn new(i_deg: f64, j_deg: f64, r: f64, x1: f64, x2: f64, ccw: bool) -> Option<ExpCurve> {
        let open = |a: f64| a > 0.0 && a < 90.0;
        if !open(i_deg) || !open(j_deg) || r == 0.0 || !r.is_finite() {
            return None;
        }
        let tan_i = i_deg.to_radians().tan();
        let k = j_deg.to_radians().tan() / tan_i;
        let c = ExpCurve {
            x1,
            x2,
            tan_i,
            k,
            r,
            sign: if ccw { -1.0 } else { 1.0 },
        };
        // The argument of ln is linear in x: positive at both ends means positive between.
        let ok = |x: f64| x.is_finite() && c.arg(x) > 0.0 && c.arg(x).is_finite();
        (ok(x1) && ok(x2) && c.a_travel().is_finite()).then_some(c)
    }

    fn arg(&self, x: f64) -> f64 {
        x * self.tan_i / self.r + 1.0
    }

    /// Rotation of A (degrees) from the start of the move to program X = `x`.
    pub fn a_at(&self, x: f64) -> f64 {
        self.sign * self.k * (self.arg(x).ln() - self.arg(self.x1).ln()) * 180.0 / PI
    }

    /// Rotation of A over the whole move, degrees.
    pub fn a_travel(&self) -> f64 {
        self.a_at(self.x2)
    }

    /// |dA/dx|, degrees per mm.
    fn slope(&self, x: f64) -> f64 {
        (180.0 / PI) * self.k * self.tan_i / (x * self.tan_i + self.r).abs()
    }

    /// Path length and time at a feed running linearly in X from `f_start` to
    /// `f_end` (per minute), by composite Simpson integration over X, doubling
    /// the panels until the Richardson error estimate of the length is below
    /// 1e-9 of it (at most 2^14 panels, so a near-singular curve costs at most
    /// about 33 000 evaluations; `length_error` then says how far off it may be).
    pub fn measure(&self, f_start: f64, f_end: f64) -> ExpMeasure {
        let (a, b) = (self.x1, self.x2);
        let span = b - a;
        let ds = |x: f64| (1.0 + self.slope(x).powi(2)).sqrt();
        let feed = |x: f64| {
            let t = if span != 0.0 { (x - a) / span } else { 0.0 };
            f_start + (f_end - f_start) * t
        };
        let simpson = |n: usize| -> (f64, f64) {
            let h = span / n as f64;
            let (mut l, mut t) = (0.0, 0.0);
            for k in 0..=n {
                let x = a + h * k as f64;
                let w = if k == 0 || k == n {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                let s = ds(x);
                l += w * s;
                t += w * s / feed(x);
            }
            (l * h.abs() / 3.0, t * h.abs() / 3.0)
        };
        let mut n = 8;
        let mut prev = simpson(n);
        loop {
            n *= 2;
            let next = simpson(n);
            let err = (next.0 - prev.0).abs() / 15.0;
            if err <= 1e-9 * next.0.abs() || n >= 1 << 14 {
                return ExpMeasure {
                    length: next.0,
                    minutes: next.1,
                    length_error: err,
                };
            }
            prev = next;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TV-25: `G02.3 X30.5 … I10.0 J30.0 R1.0 F20 Q10` from X0 A0:
    /// K = tan 30°/tan 10° = 3.274316, Δθ = K·ln(30.5·tan 10° + 1) = 6.066818 rad,
    /// A +347.603° (G03.3: −347.603°), length 349.296, 21.978 min.
    #[test]
    fn tv25_digest_numbers() {
        let c = ExpCurve::new(10.0, 30.0, 1.0, 0.0, 30.5, false).expect("defined");
        assert_eq!(format!("{:.6}", c.k), "3.274316");
        assert_eq!(format!("{:.6}", c.a_travel().to_radians()), "6.066818");
        assert_eq!(format!("{:.3}", c.a_travel()), "347.603");
        let ccw = ExpCurve::new(10.0, 30.0, 1.0, 0.0, 30.5, true).expect("defined");
        assert_eq!(format!("{:.3}", ccw.a_travel()), "-347.603");
        let m = c.measure(20.0, 10.0);
        assert_eq!(format!("{:.3}", m.length), "349.296");
        assert_eq!(format!("{:.3}", m.minutes), "21.978");
        assert!(m.length_error < 1e-6, "{}", m.length_error);
        assert_eq!(ccw.measure(20.0, 10.0), m);
    }

    /// Moving X from x₁ to x₂ turns A by the difference of the two logarithms,
    /// so two moves in a row turn A as one.
    #[test]
    fn split_moves_add_up() {
        let whole = ExpCurve::new(10.0, 30.0, 1.0, 0.0, 30.5, false).expect("defined");
        let a = ExpCurve::new(10.0, 30.0, 1.0, 0.0, 12.0, false).expect("defined");
        let b = ExpCurve::new(10.0, 30.0, 1.0, 12.0, 30.5, false).expect("defined");
        assert!((a.a_travel() + b.a_travel() - whole.a_travel()).abs() < 1e-9);
        let l = a.measure(5.0, 5.0).length + b.measure(5.0, 5.0).length;
        assert!((l - whole.measure(5.0, 5.0).length).abs() < 1e-6);
    }

    /// Overflowing inputs have no curve; a start next to the singularity
    /// (x·tan I/R + 1 → 0) still measures to a finite length with its bound.
    #[test]
    fn extreme_inputs_are_bounded() {
        assert_eq!(ExpCurve::new(89.9, 89.9, 1e-300, 0.0, 1e300, false), None);
        let x0 = -1.0 / 10f64.to_radians().tan() + 1e-9;
        let c = ExpCurve::new(10.0, 30.0, 1.0, x0, 1.0, false).expect("defined");
        let m = c.measure(10.0, 10.0);
        assert!(m.length.is_finite() && m.minutes.is_finite() && m.length_error.is_finite());
        assert!(m.length > c.a_travel().abs());
    }

    #[test]
    fn degenerate_inputs_have_no_curve() {
        assert_eq!(ExpCurve::new(0.0, 30.0, 1.0, 0.0, 1.0, false), None);
        assert_eq!(ExpCurve::new(10.0, 0.0, 1.0, 0.0, 1.0, false), None);
        assert_eq!(ExpCurve::new(10.0, 90.0, 1.0, 0.0, 1.0, false), None);
        assert_eq!(ExpCurve::new(10.0, 30.0, 0.0, 0.0, 1.0, false), None);
        // x·tan 10°/1 + 1 ≤ 0 at x = −10.
        assert_eq!(ExpCurve::new(10.0, 30.0, 1.0, 0.0, -10.0, false), None);
        assert_eq!(ExpCurve::new(10.0, 30.0, 1.0, f64::NAN, 1.0, false), None);
    }
}
