//! Where the time goes, in words: the planner's split of the cycle time
//! ([`super::Causes`]) as the lines `partscope run` prints and the editor
//! shows.

use super::Totals;

/// One part of the cycle time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// JSON key (`feed_s`, …).
    pub key: &'static str,
    /// Plain-words label.
    pub label: &'static str,
    pub seconds: f64,
}

/// The cycle time by cause, in a fixed order: motion causes, then dwell and
/// auxiliary time. The parts sum to the cycle time.
pub fn parts(t: &Totals) -> [Part; 10] {
    let c = &t.causes;
    let part = |key, label, seconds| Part {
        key,
        label,
        seconds,
    };
    [
        part("feed_s", "cutting at programmed feed", c.feed_s),
        part("accel_s", "limited by acceleration", c.accel_s),
        part("corner_s", "limited by corners and blending", c.corner_s),
        part("axis_cap_s", "limited by axis velocity", c.axis_cap_s),
        part(
            "traj_cap_s",
            "limited by the TRAJ velocity cap",
            c.traj_cap_s,
        ),
        part("curve_cap_s", "limited by arc acceleration", c.curve_cap_s),
        part("servo_cap_s", "limited by the servo period", c.servo_cap_s),
        part("rapid_s", "rapids", c.rapid_s),
        part("dwell_s", "dwell", t.dwell_s),
        part("auxiliary_s", "auxiliary", t.tool_change_s + t.other_s),
    ]
}

/// `1,842`.
pub fn thousands(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::with_capacity(s.len() + s.len() / 3);
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

/// The smallest 1, 2 or 5 times a power of ten above `x`: "shorter than" it is true
/// of every value up to `x`.
fn round_above(x: f64) -> f64 {
    if !(x > 0.0 && x.is_finite()) {
        return 0.0;
    }
    let mut p = 10f64.powf(x.log10().floor());
    loop {
        for m in [1.0, 2.0, 5.0] {
            let v = m * p;
            if v > x * (1.0 + 1e-9) {
                return v;
            }
        }
        p *= 10.0;
    }
}

/// A length in mm without trailing zeros (`0.05`, `2`).
fn mm(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// A feed in mm/s as an F word in mm/min.
fn feed_word(mm_per_s: f64) -> String {
    let f = mm_per_s * 60.0;
    if f >= 10.0 {
        format!("F{f:.0}")
    } else {
        format!("F{}", mm(f))
    }
}

fn percent(part: f64, whole: f64) -> String {
    let p = 100.0 * part / whole;
    if p > 0.0 && p < 0.05 {
        "< 0.1 %".to_string()
    } else if p >= 10.0 {
        format!("{p:.0} %")
    } else {
        format!("{p:.1} %")
    }
}

/// One or several.
fn plural(n: u64, one: &str, many: &str) -> String {
    if n == 1 {
        format!("1 {one}")
    } else {
        format!("{} {many}", thousands(n))
    }
}

/// The causes that cost the most cutting time, largest first (at most four),
/// each a sentence such as "1,842 segments shorter than 0.05 mm never reach
/// F2000: 41 % of cutting time". `traj_max_velocity` (mm/s) names the cap.
pub fn top_causes(t: &Totals, traj_max_velocity: f64) -> Vec<String> {
    let cut = t.cutting_s;
    if !(cut > 0.0 && cut.is_finite()) {
        return Vec::new();
    }
    let c = &t.causes;
    let n = &t.cause_counts;
    let mut lines: Vec<(f64, String)> = Vec::new();
    if n.short > 0 {
        let feed = if n.short_feed_max - n.short_feed_min <= 1e-9 * n.short_feed_max {
            feed_word(n.short_feed_max)
        } else {
            format!(
                "their feed ({}–{})",
                feed_word(n.short_feed_min),
                feed_word(n.short_feed_max)
            )
        };
        let what = plural(n.short, "segment", "segments");
        let verb = if n.short == 1 {
            "never reaches"
        } else {
            "never reach"
        };
        lines.push((
            n.short_s,
            format!(
                "{what} shorter than {} mm {verb} {feed}: {} of cutting time",
                mm(round_above(n.short_max_mm)),
                percent(n.short_s, cut)
            ),
        ));
    }
    let mut add = |s: f64, who: String| {
        if s > 0.0 {
            lines.push((
                s,
                format!("{who} cost {:.3} s: {} of cutting time", s, percent(s, cut)),
            ));
        }
    };
    add(
        c.accel_s,
        format!(
            "ramps at the acceleration limit ({}, at starts, stops and short moves)",
            plural(n.accel, "move", "moves")
        ),
    );
    add(
        c.corner_s,
        format!(
            "{} slowed by corners (blending, exact stops)",
            plural(n.corner, "move", "moves")
        ),
    );
    add(
        c.traj_cap_s,
        format!(
            "{} programmed above the TRAJ velocity cap of {}",
            plural(n.traj_cap, "move", "moves"),
            feed_word(traj_max_velocity)
        ),
    );
    add(
        c.axis_cap_s,
        format!(
            "{} programmed faster than an axis allows",
            plural(n.axis_cap, "move", "moves")
        ),
    );
    add(
        c.curve_cap_s,
        format!(
            "{} slowed by their centripetal acceleration",
            plural(n.curve_cap, "arc", "arcs")
        ),
    );
    add(
        c.servo_cap_s,
        format!(
            "{} too short for a servo period at their feed",
            plural(n.servo_cap, "move", "moves")
        ),
    );
    lines.sort_by(|a, b| b.0.total_cmp(&a.0));
    lines.into_iter().take(4).map(|(_, s)| s).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{CauseCounts, Causes};

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(thousands(1842), "1,842");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1_000_000), "1,000,000");
        assert_eq!(round_above(0.0493), 0.05);
        assert_eq!(round_above(0.1), 0.2);
        assert_eq!(round_above(3.0), 5.0);
        assert_eq!(mm(0.05), "0.05");
        assert_eq!(feed_word(2000.0 / 60.0), "F2000");
    }

    #[test]
    fn short_segments_lead_when_they_take_the_most_time() {
        let t = Totals {
            cutting_s: 100.0,
            causes: Causes {
                feed_s: 50.0,
                accel_s: 30.0,
                corner_s: 20.0,
                ..Causes::default()
            },
            cause_counts: CauseCounts {
                accel: 1900,
                corner: 12,
                short: 1842,
                short_s: 41.0,
                short_max_mm: 0.0493,
                short_feed_min: 2000.0 / 60.0,
                short_feed_max: 2000.0 / 60.0,
                ..CauseCounts::default()
            },
            ..Totals::default()
        };
        assert_eq!(
            top_causes(&t, 100.0),
            vec![
                "1,842 segments shorter than 0.05 mm never reach F2000: 41 % of cutting time",
                "ramps at the acceleration limit (1,900 moves, at starts, stops and short moves) cost 30.000 s: 30 % of cutting time",
                "12 moves slowed by corners (blending, exact stops) cost 20.000 s: 20 % of cutting time",
            ]
        );
    }
}
