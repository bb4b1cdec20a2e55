//! ServoWorks G310/G311: how a feed is shared between linear and rotary axes
//! (servoworks.md D§3.9, manual §6.3.46).
//!
//! Under G310 (the default) F is the speed along the combined distance of all
//! moving axes, millimetres and degrees alike: axis i moves at F·Δi / √(Σ Δ²).
//! Under G311 F is the speed along the linear axes only, and rotary axes get
//! the same scale factor. Motions carry their feed along XYZ (the planner's
//! path), so a G310 move that also turns rotary axes is given the XYZ share
//! of F; moves of linear or rotary axes alone are the same in both modes.

/// The XYZ path feed of a G310 straight move from `start` to `end` (X Y Z A B C)
/// at the programmed feed `f`: f · √(ΣΔxyz²) / √(ΣΔall²). Returns `f` when only
/// linear or only rotary axes move.
pub fn g310_linear_feed(f: f64, start: &[f64; 6], end: &[f64; 6]) -> f64 {
    let sq = |r: std::ops::Range<usize>| -> f64 { r.map(|i| (end[i] - start[i]).powi(2)).sum() };
    let (lin, rot) = (sq(0..3), sq(3..6));
    if lin == 0.0 || rot == 0.0 || !(lin + rot).is_finite() {
        return f;
    }
    f * (lin / (lin + rot)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TV-42's block `G91 G01 X30.0 Y40.0 A50.0 F3000`: 50 mm of XY in a
    /// combined 70.711 gives an XY feed of 2121.3 mm/min, so X runs at
    /// 1272.8 mm/min, Y at 1697.1 and A at 2121.3 deg/min.
    #[test]
    fn tv42_axis_speeds() {
        let f = g310_linear_feed(3000.0, &[0.0; 6], &[30.0, 40.0, 0.0, 50.0, 0.0, 0.0]);
        let want = 3000.0 * 50.0 / 5000f64.sqrt();
        assert!((f - want).abs() < 1e-9, "{f}");
        assert_eq!(format!("{:.1}", f * 30.0 / 50.0), "1272.8");
        assert_eq!(format!("{:.1}", f * 40.0 / 50.0), "1697.1");
        assert_eq!(format!("{:.1}", f * 50.0 / 50.0), "2121.3");
    }

    #[test]
    fn single_kind_moves_keep_the_feed() {
        let z = [0.0; 6];
        assert_eq!(
            g310_linear_feed(100.0, &z, &[1.0, 2.0, 3.0, 0.0, 0.0, 0.0]),
            100.0
        );
        assert_eq!(
            g310_linear_feed(100.0, &z, &[0.0, 0.0, 0.0, 9.0, 0.0, 0.0]),
            100.0
        );
        assert_eq!(g310_linear_feed(100.0, &z, &z), 100.0);
    }
}
