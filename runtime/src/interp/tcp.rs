//! ServoWorks tool centre point control G43.2 (servoworks.md D§5.5, manual
//! §6.3.18; S-140M). The program gives the tool tip; the machine's linear
//! axes carry the tool base point, L = arm length + tool length behind the tip
//! along the tool, tilted by Axis 5 (B, from −Z) and turned by Axis 4 (C, in
//! the XY plane from +X):
//! X′ = X − L·sin θb·cos θc, Y′ = Y − L·sin θb·sin θc, Z′ = Z + L·cos θb.
//! The feed stays along the tip path, so motions keep the tip; the base point
//! is what the travel limits see.

use nalgebra::Vector3;

/// The tool base point for the tip `tip` (mm) at angles `b_deg`, `c_deg`.
pub fn base_point(tip: [f64; 3], b_deg: f64, c_deg: f64, length: f64) -> [f64; 3] {
    (Vector3::from(tip) - tool_arm(b_deg, c_deg, length)).into()
}

/// The vector from the tool base point to the tip: `length` along the tool
/// axis, which Axis 5 tilts from −Z and Axis 4 turns about Z. Each component
/// is the length times the direction's factors in that order, as the
/// manual's formula writes it.
pub fn tool_arm(b_deg: f64, c_deg: f64, length: f64) -> Vector3<f64> {
    let (sb, cb) = b_deg.to_radians().sin_cos();
    let (sc, cc) = c_deg.to_radians().sin_cos();
    Vector3::new(length * sb * cc, length * sb * sc, -(length * cb))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TV-37: arm 80 + tool length 20 = 100; the tip at the origin with
    /// θc = 45°, θb = −45° puts the base at (50, 50, 70.711); θb = 0 at (0, 0, 100).
    #[test]
    fn tv37_base_point() {
        let p = base_point([0.0; 3], -45.0, 45.0, 100.0);
        let s: Vec<String> = p.iter().map(|v| format!("{v:.3}")).collect();
        assert_eq!(s, ["50.000", "50.000", "70.711"]);
        assert_eq!(base_point([0.0; 3], 0.0, 45.0, 100.0), [0.0, 0.0, 100.0]);
    }
}
