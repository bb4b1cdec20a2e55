//! Closed-form velocity profiles along one segment.

/// Result of running one segment from an entry speed towards an exit-speed cap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentProfile {
    /// Time spent on the segment, s.
    pub time: f64,
    /// Speed reached at the end, ≤ the requested exit cap.
    pub v_end: f64,
    /// Highest speed on the segment.
    pub v_peak: f64,
}

/// Trapezoidal (constant acceleration `a`) profile over length `l`, entering at
/// `v0`, cruising at most at `vmax` and leaving at no more than `v_end_cap`.
///
/// The exit speed is the cap when the segment is long enough to get there from
/// `v0`, otherwise whatever full acceleration reaches. The entry speed is assumed
/// reachable (the backward pass guarantees `v0² ≤ v_end² + 2·a·l`); if it is not, the
/// segment is run as a pure deceleration and the overshoot is ignored.
pub fn trapezoid(l: f64, v0: f64, vmax: f64, v_end_cap: f64, a: f64) -> SegmentProfile {
    if l <= 0.0 {
        return SegmentProfile {
            time: 0.0,
            v_end: v0,
            v_peak: v0,
        };
    }
    let a = if a > 0.0 { a } else { 1e-9 };
    let vmax = vmax.max(1e-9);
    let v0 = v0.min(vmax).max(0.0);
    let reachable = (v0 * v0 + 2.0 * a * l).sqrt();
    let ve = v_end_cap.min(vmax).min(reachable).max(0.0);
    // Peak where the acceleration and deceleration ramps meet.
    let v_meet = ((2.0 * a * l + v0 * v0 + ve * ve) / 2.0).sqrt();
    let vp = v_meet.min(vmax).max(v0.max(ve));
    let d_acc = ((vp * vp - v0 * v0) / (2.0 * a)).max(0.0);
    let d_dec = ((vp * vp - ve * ve) / (2.0 * a)).max(0.0);
    let cruise = (l - d_acc - d_dec).max(0.0);
    let time = (vp - v0) / a + (vp - ve) / a + if vp > 0.0 { cruise / vp } else { 0.0 };
    SegmentProfile {
        time,
        v_end: ve,
        v_peak: vp,
    }
}

/// Time for a jerk-limited change of speed by `dv` with acceleration limit `a`
/// and jerk `j` (seven-segment S-curve, one acceleration phase).
pub fn scurve_ramp_time(dv: f64, a: f64, j: f64) -> f64 {
    let dv = dv.abs();
    if dv <= 0.0 {
        return 0.0;
    }
    if j <= 0.0 || !j.is_finite() {
        return dv / a;
    }
    if dv >= a * a / j {
        dv / a + a / j
    } else {
        2.0 * (dv / j).sqrt()
    }
}

/// Extra time an S-curve needs compared with the trapezoid of the same limits:
/// each acceleration or deceleration phase is stretched by the jerk ramps.
pub fn scurve_penalty(v0: f64, vp: f64, ve: f64, a: f64, j: f64) -> f64 {
    let phase = |dv: f64| -> f64 {
        let dv = dv.abs();
        if dv <= 0.0 {
            0.0
        } else {
            // The average speed during the ramp is unchanged to first order, so the
            // cost is the difference in ramp duration, halved (the distance covered
            // during the longer ramp is mostly not covered at cruise speed).
            (scurve_ramp_time(dv, a, j) - dv / a) * 0.5
        }
    };
    phase(vp - v0) + phase(vp - ve)
}
