//! Arc centre computation and the per-dialect radius checks.
//!
//! All coordinates are 2-D points in the active plane (first, second axis),
//! in millimetres.

use std::f64::consts::FRAC_PI_2;

use nalgebra::Vector2;

/// How an arc was specified.
#[derive(Debug, Clone, Copy)]
pub enum ArcSpec {
    /// Signed radius (negative: more than a half circle).
    R(f64),
    /// Centre given by offsets from the start (or absolute under G90.1).
    Center([f64; 2]),
}

/// The outcome of solving an arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcSolution {
    pub center: [f64; 2],
    pub radius: f64,
    /// Whether the centre or radius was corrected within a tolerance
    /// (ServoWorks circle error allowance).
    pub corrected: bool,
    /// The mismatch that was found (R format: half chord − |R|; IJK: |r1 − r2|).
    pub mismatch: f64,
}

/// Why an arc is rejected.
#[derive(Debug, Clone, PartialEq)]
pub enum ArcError {
    /// Start equals end with the R format.
    SameEndR,
    /// Radius too small to reach the end point: (half chord − |R|).
    RadiusTooSmall(f64),
    /// End radius differs from start radius: (r1, r2).
    RadiusMismatch(f64, f64),
    /// Zero radius.
    ZeroRadius,
}

fn hypot(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The centre of the R-format arc from `s` to `e` with radius `r` (signed)
/// when |R| ≥ half chord (`half` is clamped to |R|).
pub fn r_center(s: [f64; 2], e: [f64; 2], r: f64, cw: bool) -> [f64; 2] {
    let abs_r = r.abs();
    let (s, e) = (Vector2::from(s), Vector2::from(e));
    let mid = (s + e) / 2.0;
    // LinuxCNC snaps a chord within 1e-12 of the diameter to a half circle.
    let to_end = mid - e;
    let mut half = to_end.x.hypot(to_end.y);
    if abs_r > 0.0 && half / abs_r > 1.0 - 1e-12 {
        half = abs_r;
    }
    let chord = e - s;
    let base = chord.y.atan2(chord.x);
    // LinuxCNC adds the long-double π/2 (`M_PI_2l`); the low part of π/2
    // reproduces that rounding in double arithmetic.
    const PI_2_LO: f64 = 6.123_233_995_736_766e-17;
    let theta = if (cw && r > 0.0) || (!cw && r < 0.0) {
        (base - FRAC_PI_2) - PI_2_LO
    } else {
        (base + FRAC_PI_2) + PI_2_LO
    };
    let offset = if abs_r > 0.0 {
        abs_r * (half / abs_r).asin().cos()
    } else {
        0.0
    };
    // The centre lies `offset` from the chord's middle, along the chord's normal
    // on the side the sign of R and the direction choose.
    (mid + Vector2::new(theta.cos(), theta.sin()) * offset).into()
}

/// LinuxCNC 2.9 checks (`profile linuxcnc`) or the 2007 EMC2 checks (`emc2`).
/// Coordinates are in program units (`inch` selects the tolerance set).
pub fn solve_ngc(
    s: [f64; 2],
    e: [f64; 2],
    spec: ArcSpec,
    cw: bool,
    inch: bool,
    emc2: bool,
) -> Result<ArcSolution, ArcError> {
    // LinuxCNC's constants, per program unit.
    let radius_tol = if inch { 0.00005 } else { 0.00005 * 25.4 };
    let emc2_tol = if inch { 0.0002 } else { 0.002 };
    let spiral_abs = if inch {
        2.0 * 0.001 * std::f64::consts::SQRT_2
    } else {
        2.0 * 0.01 * std::f64::consts::SQRT_2
    };
    match spec {
        ArcSpec::R(r) => {
            if s == e {
                return Err(ArcError::SameEndR);
            }
            let half = hypot(s, e) / 2.0;
            let tol = if emc2 { emc2_tol } else { radius_tol };
            if half - r.abs() > tol {
                return Err(ArcError::RadiusTooSmall(half - r.abs()));
            }
            Ok(ArcSolution {
                center: r_center(s, e, r, cw),
                radius: r.abs(),
                corrected: false,
                mismatch: (half - r.abs()).max(0.0),
            })
        }
        ArcSpec::Center(c) => {
            let r1 = hypot(s, c);
            let r2 = hypot(e, c);
            if !emc2 && (r1 < radius_tol || r2 < radius_tol) {
                return Err(ArcError::ZeroRadius);
            }
            let abs_err = (r1 - r2).abs();
            if emc2 {
                if abs_err > emc2_tol {
                    return Err(ArcError::RadiusMismatch(r1, r2));
                }
            } else {
                let rel = abs_err / r1.max(r2);
                if abs_err > spiral_abs * 100.0 || (rel > 0.001 && abs_err > spiral_abs) {
                    return Err(ArcError::RadiusMismatch(r1, r2));
                }
            }
            Ok(ArcSolution {
                center: c,
                radius: r1,
                corrected: false,
                mismatch: abs_err,
            })
        }
    }
}

/// FANUC: R format never fails by a small margin (the control makes a half
/// circle when |R| is slightly short); IJK end-radius difference above
/// `tolerance` (parameter 3410) is alarm PS0020.
pub fn solve_fanuc(
    s: [f64; 2],
    e: [f64; 2],
    spec: ArcSpec,
    cw: bool,
    tolerance: f64,
) -> Result<ArcSolution, ArcError> {
    match spec {
        ArcSpec::R(r) => {
            if s == e {
                return Err(ArcError::SameEndR);
            }
            let half = hypot(s, e) / 2.0;
            if half - r.abs() > tolerance.max(1e-9) {
                return Err(ArcError::RadiusTooSmall(half - r.abs()));
            }
            let corrected = half > r.abs();
            let radius = r.abs().max(half);
            Ok(ArcSolution {
                center: r_center(s, e, if r < 0.0 { -radius } else { radius }, cw),
                radius,
                corrected,
                mismatch: (half - r.abs()).max(0.0),
            })
        }
        ArcSpec::Center(c) => {
            let r1 = hypot(s, c);
            let r2 = hypot(e, c);
            if (r1 - r2).abs() > tolerance {
                return Err(ArcError::RadiusMismatch(r1, r2));
            }
            Ok(ArcSolution {
                center: c,
                radius: r1,
                corrected: false,
                mismatch: (r1 - r2).abs(),
            })
        }
    }
}

/// ServoWorks circle error allowance (§6.3.3): `allowance` is the larger of
/// the configured allowance and the machine-unit bound.
pub fn solve_servoworks(
    s: [f64; 2],
    e: [f64; 2],
    spec: ArcSpec,
    cw: bool,
    allowance: f64,
) -> Result<ArcSolution, ArcError> {
    match spec {
        ArcSpec::R(r) => {
            if s == e {
                return Err(ArcError::SameEndR);
            }
            let h = hypot(s, e) / 2.0;
            if r.abs() >= h {
                return Ok(ArcSolution {
                    center: r_center(s, e, r, cw),
                    radius: r.abs(),
                    corrected: false,
                    mismatch: 0.0,
                });
            }
            let d = h - r.abs();
            if d <= allowance {
                // Tolerated: a half circle about the chord's midpoint.
                let mid = [(s[0] + e[0]) / 2.0, (s[1] + e[1]) / 2.0];
                return Ok(ArcSolution {
                    center: mid,
                    radius: h,
                    corrected: true,
                    mismatch: d,
                });
            }
            Err(ArcError::RadiusTooSmall(d))
        }
        ArcSpec::Center(c) => {
            let r1 = hypot(s, c);
            let r2 = hypot(e, c);
            let delta = (r1 - r2).abs();
            if delta == 0.0 {
                return Ok(ArcSolution {
                    center: c,
                    radius: r1,
                    corrected: false,
                    mismatch: 0.0,
                });
            }
            if delta > allowance {
                return Err(ArcError::RadiusMismatch(r1, r2));
            }
            let r = (r1 + r2) / 2.0;
            Ok(ArcSolution {
                center: bisector_center(s, e, r, c),
                radius: r,
                corrected: true,
                mismatch: delta,
            })
        }
    }
}

/// The point at distance `r` from both `s` and `e` nearest to `hint`.
pub fn bisector_center(s: [f64; 2], e: [f64; 2], r: f64, hint: [f64; 2]) -> [f64; 2] {
    let mid = [(s[0] + e[0]) / 2.0, (s[1] + e[1]) / 2.0];
    let h = hypot(s, e) / 2.0;
    if h == 0.0 {
        return hint;
    }
    let off = (r * r - h * h).max(0.0).sqrt();
    let n = [-(e[1] - s[1]) / (2.0 * h), (e[0] - s[0]) / (2.0 * h)];
    let c1 = [mid[0] + off * n[0], mid[1] + off * n[1]];
    let c2 = [mid[0] - off * n[0], mid[1] - off * n[1]];
    if hypot(c1, hint) <= hypot(c2, hint) {
        c1
    } else {
        c2
    }
}

/// The swept angle (radians, positive) of an arc, `turns` extra full turns.
pub fn sweep(s: [f64; 2], e: [f64; 2], c: [f64; 2], cw: bool, turns: i32) -> f64 {
    let a0 = (s[1] - c[1]).atan2(s[0] - c[0]);
    let a1 = (e[1] - c[1]).atan2(e[0] - c[0]);
    let mut d = if cw { a0 - a1 } else { a1 - a0 };
    // Distinct ends are never a full circle, however small the angle (`R1e12`).
    let zero = if hypot(s, e) > 1e-6 { 0.0 } else { 1e-12 };
    while d <= zero {
        d += std::f64::consts::TAU;
    }
    while d > std::f64::consts::TAU + 1e-12 {
        d -= std::f64::consts::TAU;
    }
    d + std::f64::consts::TAU * f64::from(turns.max(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn servoworks_examples() {
        let s = [0.0, 0.0];
        let e = [100.0, 0.0];
        let a = solve_servoworks(s, e, ArcSpec::R(49.0), true, 1.5).unwrap();
        assert_eq!(a.center, [50.0, 0.0]);
        assert_eq!(a.radius, 50.0);
        assert!(solve_servoworks(s, e, ArcSpec::R(49.0), true, 0.5).is_err());
        let b = solve_servoworks(s, e, ArcSpec::Center([49.0, 0.0]), true, 2.5).unwrap();
        assert!((b.center[0] - 50.0).abs() < 1e-12 && b.center[1].abs() < 1e-12);
        let c = solve_servoworks(s, e, ArcSpec::Center([0.0, -100.0]), true, 50.0).unwrap();
        assert!((c.radius - 120.710_678).abs() < 1e-6);
        assert!((c.center[0] - 50.0).abs() < 1e-9);
        assert!((c.center[1] + 109.868).abs() < 1e-3);
    }
}
