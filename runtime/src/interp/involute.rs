//! Involute interpolation G02.2/G03.2 (FANUC, fanuc.md §3.1): the tool follows
//! the involute of a base circle of radius R centred at start + (I, J).
//!
//! A point at distance ρ from the centre has the unwinding angle
//! φ = √((ρ/R)² − 1), and the involute's length between two unwinding angles
//! is R·|φ₂² − φ₁²|/2. The curve is the one through the start point; the
//! programmed end point may lie off it within parameter No. 5610 (the checks
//! report more), and the motion ends there.

/// One involute move in its plane's coordinates (mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InvoluteCurve {
    pub center: [f64; 2],
    pub base_radius: f64,
    /// +1 when the base angle grows with φ, −1 when it falls.
    pub sense: f64,
    /// Base angle where the involute leaves the circle (radians).
    pub alpha: f64,
    pub phi_start: f64,
    pub phi_end: f64,
}

impl InvoluteCurve {
    /// The involute from `start` toward `end` about `center` with base radius
    /// `r`, turning counter-clockwise for G03.2 (`ccw`); `None` when a point
    /// lies inside the base circle or the radius is not positive (PS0242).
    pub fn new(
        start: [f64; 2],
        end: [f64; 2],
        center: [f64; 2],
        r: f64,
        ccw: bool,
    ) -> Option<InvoluteCurve> {
        if r <= 0.0 || !r.is_finite() {
            return None;
        }
        let rho = |p: [f64; 2]| (p[0] - center[0]).hypot(p[1] - center[1]);
        let (rs, re) = (rho(start), rho(end));
        let tol = 1e-6;
        if !(rs >= r - tol && re >= r - tol) {
            return None;
        }
        let phi = |rr: f64| ((rr / r).powi(2) - 1.0).max(0.0).sqrt();
        let (ps, pe) = (phi(rs), phi(re));
        // Outward the involute unwinds with the turn, inward against it.
        let dir = if ccw { 1.0 } else { -1.0 };
        let sense = if re >= rs { dir } else { -dir };
        let ang = (start[1] - center[1]).atan2(start[0] - center[0]);
        if !(ps.is_finite() && pe.is_finite() && ang.is_finite() && (pe * pe).is_finite()) {
            return None;
        }
        Some(InvoluteCurve {
            center,
            base_radius: r,
            sense,
            alpha: ang - sense * (ps - ps.atan()),
            phi_start: ps,
            phi_end: pe,
        })
    }

    /// Path length, mm.
    pub fn length(&self) -> f64 {
        self.base_radius * (self.phi_end.powi(2) - self.phi_start.powi(2)).abs() / 2.0
    }

    /// The point at unwinding angle `phi`.
    pub fn point(&self, phi: f64) -> [f64; 2] {
        let t = self.alpha + self.sense * phi;
        let (s, c) = t.sin_cos();
        let r = self.base_radius;
        [
            self.center[0] + r * (c + self.sense * phi * s),
            self.center[1] + r * (s - self.sense * phi * c),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// fanuc.md §8.6 (N203 in the XY plane): from (−1, 0) about (0, 0) with
    /// R 1 to (1, 9.425): φ = 9.4250 rad, length R·φ²/2 = 44.41 mm; at 3π the
    /// involute through the start passes (1.00209, 9.42478).
    #[test]
    fn fanuc_8_6_numbers() {
        let c =
            InvoluteCurve::new([-1.0, 0.0], [1.0, 9.425], [0.0, 0.0], 1.0, false).expect("outside");
        assert_eq!(c.phi_start, 0.0);
        assert_eq!(format!("{:.4}", c.phi_end), "9.4250");
        // 9.425²/2 = 44.4153; the digest's 44.41 is (3π)²/2 = 44.4132, the same
        // to its two decimals within 0.01.
        assert!((c.length() - 44.41).abs() < 0.01, "{}", c.length());
        assert_eq!(c.length(), 9.425f64.powi(2) / 2.0);
        let p = c.point(3.0 * std::f64::consts::PI);
        assert_eq!(format!("{:.5} {:.5}", p[0], p[1]), "1.00000 9.42478");
        let p0 = c.point(0.0);
        assert!((p0[0] + 1.0).abs() < 1e-12 && p0[1].abs() < 1e-12);
    }

    #[test]
    fn points_inside_the_base_circle_have_no_involute() {
        assert_eq!(
            InvoluteCurve::new([0.5, 0.0], [3.0, 0.0], [0.0, 0.0], 1.0, true),
            None
        );
        assert_eq!(
            InvoluteCurve::new([1.0, 0.0], [3.0, 0.0], [0.0, 0.0], 0.0, true),
            None
        );
    }

    /// Every sampled point is φ·R from the circle along the tangent: its
    /// distance from the centre is R·√(1 + φ²).
    #[test]
    fn sampled_points_lie_on_the_involute() {
        let c = InvoluteCurve::new([2.0, 0.0], [0.0, 5.0], [0.0, 0.0], 1.0, true).expect("outside");
        for k in 0..=10 {
            let phi = c.phi_start + (c.phi_end - c.phi_start) * k as f64 / 10.0;
            let p = c.point(phi);
            let want = (1.0 + phi * phi).sqrt();
            assert!((p[0].hypot(p[1]) - want).abs() < 1e-12);
        }
        let s = c.point(c.phi_start);
        assert!((s[0] - 2.0).abs() < 1e-12 && s[1].abs() < 1e-12);
    }
}
