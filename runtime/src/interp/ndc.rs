//! ServoWorks normal direction control G40.1/G41.1/G42.1 (servoworks.md
//! D§5.3, manual §6.3.16): a rotary axis keeps the tool normal to the XY
//! direction of motion.
//!
//! The tool angle is the direction of motion − 90° under G41.1 (tool on the
//! left) and + 90° under G42.1, counter-clockwise from +X. At the start of
//! each line or arc the axis turns in place, the shorter way, at the Rotation
//! Feedrate, unless the turn from its actual angle is smaller than the Angle
//! Limit (skipped turns therefore add up until they reach the limit) or the
//! block is shorter than the Length Limit. Along an arc the axis turns with
//! the direction of motion, by the arc's sweep.

use analyzer::config::{MachineConfig, NdcAxis};

use super::types::{Motion, MotionKind};

/// The Normal Direction Control screen's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NdcConfig {
    /// The rotary axis (3 = A, 4 = B, 5 = C).
    pub axis: usize,
    /// Rotation Feedrate, degrees per minute.
    pub rotation_feed: f64,
    /// Angle Limit, degrees.
    pub angle_limit: f64,
    /// Length Limit, mm.
    pub length_limit: f64,
}

impl NdcConfig {
    /// Keys `ndc_axis` ("A", "B" or "C"; default C), `ndc_rotation_feed`
    /// (deg/min, default 1000 as in the manual's screenshot), `ndc_angle_limit`
    /// and `ndc_length_limit` (default 0: every corner turns).
    pub fn read(m: &MachineConfig) -> NdcConfig {
        NdcConfig {
            axis: match m.ndc_axis {
                Some(NdcAxis::A) => 3,
                Some(NdcAxis::B) => 4,
                Some(NdcAxis::C) | None => 5,
            },
            rotation_feed: m.ndc_rotation_feed.unwrap_or(1000.0),
            angle_limit: m.ndc_angle_limit.unwrap_or(0.0).abs(),
            length_limit: m.ndc_length_limit.unwrap_or(0.0).abs(),
        }
    }
}

/// The tool angle (degrees in [0, 360)) for a direction of motion.
pub fn tool_angle(direction: f64, left: bool) -> f64 {
    let a = if left {
        direction - 90.0
    } else {
        direction + 90.0
    };
    a.rem_euclid(360.0)
}

/// The shorter signed turn from angle `from` to angle `to`, in (−180, 180].
pub fn shortest(from: f64, to: f64) -> f64 {
    let d = (to - from).rem_euclid(360.0);
    if d > 180.0 {
        d - 360.0
    } else {
        d
    }
}

/// The in-place turn from the axis's actual angle to `target`, or `None`
/// when it is smaller than the angle limit (or nothing).
pub fn corner_turn(actual: f64, target: f64, angle_limit: f64) -> Option<f64> {
    let t = shortest(actual, target);
    // Angles that print the same are the same: no turn for round-off.
    (t.abs() > 1e-9 && t.abs() >= angle_limit).then_some(t)
}

/// What normal direction control does to one XY motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NdcStep {
    /// The in-place turn before the motion, degrees.
    pub turn: Option<f64>,
    /// The turn during the motion (arcs: their signed sweep), degrees.
    pub along: f64,
}

/// The step for a motion (machine frame, XY plane) with the axis at `actual`
/// degrees; `None` for motions that have no XY direction (rapids, moves along
/// Z only, other planes' arcs) or that already move the axis.
pub fn step(m: &Motion, actual: f64, left: bool, cfg: &NdcConfig) -> Option<NdcStep> {
    if m.end[cfg.axis] != m.start[cfg.axis] {
        return None;
    }
    let (dx, dy) = (m.end[0] - m.start[0], m.end[1] - m.start[1]);
    let (direction, along, length) = match m.kind {
        MotionKind::Feed => {
            if dx.hypot(dy) <= 1e-9 {
                return None;
            }
            let l = (dx * dx + dy * dy + (m.end[2] - m.start[2]).powi(2)).sqrt();
            (dy.atan2(dx).to_degrees(), 0.0, l)
        }
        MotionKind::Arc {
            center,
            normal,
            turns,
            radius,
        } if normal[0] == 0.0 && normal[1] == 0.0 && normal[2] != 0.0 => {
            let ccw = normal[2] > 0.0;
            let a0 = (m.start[1] - center[1]).atan2(m.start[0] - center[0]);
            let a1 = (m.end[1] - center[1]).atan2(m.end[0] - center[0]);
            let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
            if sweep <= 1e-12 {
                sweep += std::f64::consts::TAU;
            }
            sweep += std::f64::consts::TAU * f64::from(turns.max(0));
            let tangent = if ccw {
                a0.to_degrees() + 90.0
            } else {
                a0.to_degrees() - 90.0
            };
            let signed = if ccw { sweep } else { -sweep };
            (tangent, signed.to_degrees(), radius * sweep)
        }
        _ => return None,
    };
    if length < cfg.length_limit {
        return Some(NdcStep {
            turn: None,
            along: 0.0,
        });
    }
    Some(NdcStep {
        turn: corner_turn(actual, tool_angle(direction, left), cfg.angle_limit),
        along,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TV-40's corner turns for directions E, SE, W, N from a tool angle of 0°
    /// under G41.1, for each angle limit.
    #[test]
    fn tv40_angle_limits() {
        let dirs = [0.0, -45.0, 180.0, 90.0];
        let run = |limit: f64| -> (Vec<f64>, f64) {
            let mut actual: f64 = 0.0;
            let mut turns = Vec::new();
            for d in dirs {
                if let Some(t) = corner_turn(actual, tool_angle(d, true), limit) {
                    turns.push(t.abs());
                    actual += t;
                }
            }
            (turns, actual.rem_euclid(360.0))
        };
        assert_eq!(run(0.0), (vec![90.0, 45.0, 135.0, 90.0], 0.0));
        assert_eq!(run(46.0), (vec![90.0, 180.0, 90.0], 0.0));
        assert_eq!(run(91.0), (vec![135.0, 135.0], 90.0));
        assert_eq!(run(181.0), (vec![], 0.0));
    }

    #[test]
    fn shortest_turns() {
        assert_eq!(shortest(0.0, 270.0), -90.0);
        assert_eq!(shortest(270.0, 90.0), 180.0);
        assert_eq!(shortest(-90.0, 225.0), -45.0);
        assert_eq!(shortest(350.0, 10.0), 20.0);
        assert_eq!(tool_angle(0.0, false), 90.0);
    }
}
