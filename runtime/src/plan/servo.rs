//! Servo-period execution of planner elements, following the per-cycle update of
//! LinuxCNC 2.9's trajectory planner: the trapezoidal velocity update with its
//! half-cycle correction, linear velocity ramps on short tangent elements, and
//! "split cycles" that hand the rest of a period to the next element.
//!
//! The cost is one small step per servo period of machine time (a ten-hour job is
//! 36 million steps), independent of how many elements there are.

/// Per-element execution state.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Run {
    pub progress: f64,
    pub currentvel: f64,
    pub cycle_time: f64,
    pub splitting: bool,
    pub term_vel: f64,
    pub active: bool,
    pub ramp: bool,
    pub remove: bool,
    pub peak: f64,
    /// The last update was limited by the deceleration towards the final speed.
    pub on_final_decel: bool,
    /// A parabolic blend into the next element has started (latched).
    pub blending_next: bool,
}

/// What one cycle update needs to know about an element.
#[derive(Debug, Clone, Copy)]
pub(super) struct View {
    pub target: f64,
    /// Real target speed (feed, overrides, caps).
    pub v_target: f64,
    /// Optimised final speed (`finalvel`).
    pub finalvel: f64,
    /// True when the element ends tangentially (may keep speed into the next one).
    pub tangent: bool,
    /// True for an exact stop or exact path end (not a parabolic blend).
    pub stop: bool,
    pub accel: f64,
}

const POS_EPS: f64 = 1e-12;
const TIME_EPS: f64 = 1e-12;
const VEL_EPS: f64 = 1e-8;

fn saturate(x: f64, max: f64) -> f64 {
    x.clamp(-max, max)
}

/// `tpGetRealFinalVel`.
pub(super) fn final_vel(v: &View, next_target: Option<f64>) -> f64 {
    if !v.tangent {
        return 0.0;
    }
    v.finalvel.min(v.v_target).min(next_target.unwrap_or(0.0))
}

/// One servo update of an element (`tpUpdateCycle`): velocity and progress, then
/// the end-of-element check that may schedule a split cycle.
pub(super) fn update_cycle(r: &mut Run, v: &View, next_target: Option<f64>, cycle: f64) {
    let vf = final_vel(v, next_target);
    let dx = v.target - r.progress;
    let mut acc_vel: Option<(f64, f64)> = None;
    if r.ramp && v.tangent && vf >= VEL_EPS {
        // Linear velocity ramp to the final speed over the remaining distance.
        let v_avg = (r.currentvel + vf) / 2.0;
        let mut dt = 1e-16;
        if v_avg > VEL_EPS {
            dt = (dx / v_avg).max(1e-16);
        }
        let acc = saturate((vf - r.currentvel) / dt, v.accel);
        acc_vel = Some((acc, vf));
    }
    let (acc, vel_desired) = acc_vel.unwrap_or_else(|| {
        // Trapezoid: the highest speed from which the final speed is still reachable,
        // accounting for the one-period delay of the update.
        let a = v.accel;
        let d1 = vf * vf;
        let d2 = a * (2.0 * dx - r.currentvel * r.cycle_time);
        let half = a * r.cycle_time * 0.5;
        let d3 = half * half;
        let disc = d1 + d2 + d3;
        if cruising(disc, d3, half, v.v_target, r.currentvel) {
            // The root would exceed the target speed, which caps it, and the speed
            // does not fall, so the root is not needed: the deceleration flag it
            // feeds is only raised when the speed falls.
            let dt = r.cycle_time.max(TIME_EPS);
            return (saturate((v.v_target - r.currentvel) / dt, a), f64::NAN);
        }
        let mut maxnewvel = -half;
        if disc > d3 {
            maxnewvel += disc.sqrt();
        }
        let newvel = saturate(maxnewvel, v.v_target);
        let dt = r.cycle_time.max(TIME_EPS);
        (saturate((newvel - r.currentvel) / dt, a), maxnewvel)
    });
    // tcUpdateDistFromAccel
    let mut v_next = r.currentvel + acc * r.cycle_time;
    if v_next < 0.0 {
        v_next = 0.0;
        if v.target - r.progress < r.currentvel * r.cycle_time {
            r.progress = v.target;
        }
    } else {
        r.progress += (v_next + r.currentvel) * 0.5 * r.cycle_time;
        r.progress = r.progress.clamp(0.0, v.target);
    }
    r.currentvel = v_next;
    r.peak = r.peak.max(v_next);
    r.on_final_decel = (vel_desired - v_next).abs() < VEL_EPS && acc < 0.0;
    check_end(r, v, next_target, cycle);
}

/// Runs, at once, the periods in which an element holds its target speed and is
/// not yet near its end (no deceleration, no split): returns how many periods it
/// advanced, at most `max`. Each is exactly what [`update_cycle`] does in such a
/// period (the same addition to `progress`), so the state is bit for bit the same;
/// a long move then costs one addition per period instead of one update.
///
/// Every condition such a period depends on (the trapezoid update keeps the
/// speed, `check_end` changes nothing) holds for all remaining distances above a
/// threshold, since rounded arithmetic is monotone. The thresholds are solved for
/// and then checked with the very predicates the update uses; when a check fails
/// nothing is skipped.
pub(super) fn cruise(r: &mut Run, v: &View, next_target: Option<f64>, cycle: f64, max: u64) -> u64 {
    let cv = r.currentvel;
    // The update keeps the speed only when it already is the target speed (the
    // trapezoid's acceleration is then 0) and the linear ramp is not in use.
    let vf = final_vel(v, next_target);
    let ramp = r.ramp && v.tangent && vf >= VEL_EPS;
    if max == 0 || ramp || r.splitting || r.remove || cv.to_bits() != v.v_target.to_bits() {
        return 0;
    }
    if !(cv > 0.0 && cv.is_finite() && r.cycle_time.to_bits() == cycle.to_bits() && v.accel > 0.0) {
        return 0;
    }
    let ct = r.cycle_time;
    let a = v.accel;
    let half = a * ct * 0.5;
    let d3 = half * half;
    let keeps_speed = |dx: f64| {
        let disc = vf * vf + a * (2.0 * dx - cv * ct) + d3;
        cruising(disc, d3, half, v.v_target, cv)
    };
    let v_avg = (cv + vf) / 2.0;
    let end_is_far =
        |dx: f64| dx > POS_EPS && (v.stop || far_from_end(dx, v_avg, cv, vf, a, cycle));
    let need = v.v_target + half;
    let pre = ((need * need * (1.0 + MARGIN) - vf * vf - d3) / a + cv * ct) / 2.0;
    let post = if v.stop {
        2.0 * POS_EPS
    } else {
        (cycle * v_avg * (1.0 + MARGIN)).max((vf - cv).abs() * v_avg / (a * (1.0 - MARGIN)))
    };
    let (Some(pre), Some(post)) = (
        verified_threshold(pre, keeps_speed),
        verified_threshold(post, end_is_far),
    ) else {
        return 0;
    };
    // The same expression as the update's, with `v_next == currentvel`.
    let step = (cv + cv) * 0.5 * ct;
    let mut n = 0;
    while n < max && v.target - r.progress >= pre && v.target - (r.progress + step) >= post {
        r.progress += step;
        n += 1;
    }
    if n > 0 {
        r.peak = r.peak.max(cv);
        r.on_final_decel = false;
    }
    n
}

/// A remaining distance at and above which `holds` is true (it is monotone), found
/// a little above the solved `guess` and checked; `None` when the check fails.
fn verified_threshold(guess: f64, holds: impl Fn(f64) -> bool) -> Option<f64> {
    let t = guess.max(POS_EPS) * (1.0 + 1e-9) + 2.0 * POS_EPS;
    (t.is_finite() && holds(t)).then_some(t)
}

/// `tpCheckEndCondition`.
fn check_end(r: &mut Run, v: &View, next_target: Option<f64>, cycle: f64) {
    r.cycle_time = cycle;
    let dx = v.target - r.progress;
    if dx <= POS_EPS {
        r.progress = v.target;
        set_split(r, 0.0, r.currentvel);
        if v.stop {
            r.remove = true;
        }
        return;
    }
    if v.stop {
        return;
    }
    let mut v_f = final_vel(v, next_target);
    let v_avg = (r.currentvel + v_f) / 2.0;
    if far_from_end(dx, v_avg, r.currentvel, v_f, v.accel, cycle) {
        return;
    }
    let mut dt = TIME_EPS / 2.0;
    if v_avg > VEL_EPS {
        dt = dt.max(dx / v_avg);
    } else if dx > v_avg * cycle && dx > POS_EPS {
        return;
    }
    let a_f = (v_f - r.currentvel) / dt;
    let a_max = v.accel;
    let a = saturate(a_f, a_max);
    if a != a_f {
        let disc = (r.currentvel / a).powi(2) + 2.0 / a * dx;
        if disc < 0.0 {
            return;
        }
        dt = if disc < TIME_EPS * TIME_EPS {
            -r.currentvel / a
        } else if a > 0.0 {
            -r.currentvel / a + disc.sqrt()
        } else {
            -r.currentvel / a - disc.sqrt()
        };
        v_f = r.currentvel + dt * a;
    }
    if dt < TIME_EPS {
        r.progress = v.target;
        set_split(r, 0.0, v_f);
    } else if dt < cycle {
        set_split(r, dt, v_f);
    }
}

/// Relative margin of the shortcuts below: far above the rounding of the few
/// operations they stand in for (2^-52 each), far below anything that matters.
const MARGIN: f64 = 1.0 / (1u64 << 40) as f64;

/// Whether the trapezoid update's `-half + sqrt(disc)` is certain to round to at
/// least `v_target` (so the target speed is the new speed) while the speed is not
/// above it: the common cruising period, which then needs no square root.
fn cruising(disc: f64, d3: f64, half: f64, v_target: f64, currentvel: f64) -> bool {
    let need = v_target + half;
    // `need² (1 + m)` under the discriminant puts its root `(1 + m/2)` above
    // `need`, which no rounding of the root or of the subtraction undoes. NaN or
    // infinite terms fail a comparison and take the full update.
    currentvel <= v_target
        && half >= 0.0
        && v_target >= 0.0
        && disc > d3
        && disc >= need * need * (1.0 + MARGIN)
}

/// Whether `check_end` is certain to change nothing: the element ends more than
/// one period ahead (`dx / v_avg ≥ cycle`, so no split) and reaching the final
/// speed over that time needs less than the acceleration limit (so no
/// saturation), decided with multiplications instead of its two divisions.
fn far_from_end(dx: f64, v_avg: f64, currentvel: f64, v_f: f64, accel: f64, cycle: f64) -> bool {
    v_avg > VEL_EPS
        && cycle >= TIME_EPS
        && dx >= cycle * v_avg * (1.0 + MARGIN)
        && (v_f - currentvel).abs() * v_avg <= accel * dx * (1.0 - MARGIN)
}

fn set_split(r: &mut Run, split_time: f64, v_f: f64) {
    if r.splitting && split_time > 0.0 {
        return;
    }
    r.splitting = true;
    r.cycle_time = split_time;
    r.term_vel = v_f;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference_update_cycle(r: &mut Run, v: &View, next_target: Option<f64>, cycle: f64) {
        let vf = final_vel(v, next_target);
        let dx = v.target - r.progress;
        let mut acc_vel: Option<(f64, f64)> = None;
        if r.ramp && v.tangent && vf >= VEL_EPS {
            // Linear velocity ramp to the final speed over the remaining distance.
            let v_avg = (r.currentvel + vf) / 2.0;
            let mut dt = 1e-16;
            if v_avg > VEL_EPS {
                dt = (dx / v_avg).max(1e-16);
            }
            let acc = saturate((vf - r.currentvel) / dt, v.accel);
            acc_vel = Some((acc, vf));
        }
        let (acc, vel_desired) = acc_vel.unwrap_or_else(|| {
            // Trapezoid: the highest speed from which the final speed is still reachable,
            // accounting for the one-period delay of the update.
            let a = v.accel;
            let d1 = vf * vf;
            let d2 = a * (2.0 * dx - r.currentvel * r.cycle_time);
            let half = a * r.cycle_time * 0.5;
            let d3 = half * half;
            let disc = d1 + d2 + d3;
            let mut maxnewvel = -half;
            if disc > d3 {
                maxnewvel += disc.sqrt();
            }
            let newvel = saturate(maxnewvel, v.v_target);
            let dt = r.cycle_time.max(TIME_EPS);
            (saturate((newvel - r.currentvel) / dt, a), maxnewvel)
        });
        // tcUpdateDistFromAccel
        let mut v_next = r.currentvel + acc * r.cycle_time;
        if v_next < 0.0 {
            v_next = 0.0;
            if v.target - r.progress < r.currentvel * r.cycle_time {
                r.progress = v.target;
            }
        } else {
            r.progress += (v_next + r.currentvel) * 0.5 * r.cycle_time;
            r.progress = r.progress.clamp(0.0, v.target);
        }
        r.currentvel = v_next;
        r.peak = r.peak.max(v_next);
        r.on_final_decel = (vel_desired - v_next).abs() < VEL_EPS && acc < 0.0;
        reference_check_end(r, v, next_target, cycle);
    }

    /// The end check before the shortcut, as the reference.
    fn reference_check_end(r: &mut Run, v: &View, next_target: Option<f64>, cycle: f64) {
        r.cycle_time = cycle;
        let dx = v.target - r.progress;
        if dx <= POS_EPS {
            r.progress = v.target;
            set_split(r, 0.0, r.currentvel);
            if v.stop {
                r.remove = true;
            }
            return;
        }
        if v.stop {
            return;
        }
        let mut v_f = final_vel(v, next_target);
        let v_avg = (r.currentvel + v_f) / 2.0;
        let mut dt = TIME_EPS / 2.0;
        if v_avg > VEL_EPS {
            dt = dt.max(dx / v_avg);
        } else if dx > v_avg * cycle && dx > POS_EPS {
            return;
        }
        let a_f = (v_f - r.currentvel) / dt;
        let a_max = v.accel;
        let a = saturate(a_f, a_max);
        if a != a_f {
            let disc = (r.currentvel / a).powi(2) + 2.0 / a * dx;
            if disc < 0.0 {
                return;
            }
            dt = if disc < TIME_EPS * TIME_EPS {
                -r.currentvel / a
            } else if a > 0.0 {
                -r.currentvel / a + disc.sqrt()
            } else {
                -r.currentvel / a - disc.sqrt()
            };
            v_f = r.currentvel + dt * a;
        }
        if dt < TIME_EPS {
            r.progress = v.target;
            set_split(r, 0.0, v_f);
        } else if dt < cycle {
            set_split(r, dt, v_f);
        }
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

        fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
            xs[(self.next() * xs.len() as f64) as usize % xs.len()]
        }
    }

    fn bits(r: &Run) -> [u64; 11] {
        [
            r.progress.to_bits(),
            r.currentvel.to_bits(),
            r.cycle_time.to_bits(),
            r.term_vel.to_bits(),
            r.peak.to_bits(),
            r.splitting as u64,
            r.active as u64,
            r.ramp as u64,
            r.remove as u64,
            r.on_final_decel as u64,
            r.blending_next as u64,
        ]
    }

    /// Elements run period by period from a random entry speed to their end, with
    /// the shortcuts and with the reference update: every state after every period
    /// is bit for bit the same, and the shortcuts are taken in most periods.
    #[test]
    fn shortcuts_change_no_bit() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let cycle = 0.001;
        let (mut periods, mut cruising_periods, mut far_periods) = (0u64, 0u64, 0u64);
        for case in 0..3000 {
            let x = rng.next();
            let v_target = rng.pick(&[0.5, 5.0, 33.333_333_333_333_336, 250.0]) * (0.5 + x);
            let v = View {
                target: rng.pick(&[1e-9, 0.05, 0.3, 2.4, 40.0]) * (0.5 + x),
                v_target,
                finalvel: rng.pick(&[0.0, v_target, v_target * x, v_target * 2.0]),
                tangent: case % 3 != 0,
                stop: case % 5 == 0,
                accel: rng.pick(&[1.0, 10.0, 500.0, 1000.0, 20000.0]) * (0.5 + x),
            };
            let next_target = rng.pick(&[None, Some(v_target), Some(v_target * x), Some(0.0)]);
            let mut a = Run {
                currentvel: rng.pick(&[0.0, v_target, v_target * x, v_target * 1.5]),
                cycle_time: cycle,
                ramp: case % 7 == 0,
                ..Run::default()
            };
            let mut b = a;
            for _ in 0..5_000 {
                let disc_case = {
                    let vf = final_vel(&v, next_target);
                    let dx = v.target - a.progress;
                    let half = v.accel * a.cycle_time * 0.5;
                    let disc =
                        vf * vf + v.accel * (2.0 * dx - a.currentvel * a.cycle_time) + half * half;
                    cruising(disc, half * half, half, v.v_target, a.currentvel)
                };
                update_cycle(&mut a, &v, next_target, cycle);
                reference_update_cycle(&mut b, &v, next_target, cycle);
                assert_eq!(bits(&a), bits(&b), "case {case}: {v:?}");
                periods += 1;
                cruising_periods += disc_case as u64;
                let dx = v.target - a.progress;
                let vf = final_vel(&v, next_target);
                far_periods += far_from_end(
                    dx,
                    (a.currentvel + vf) / 2.0,
                    a.currentvel,
                    vf,
                    v.accel,
                    cycle,
                ) as u64;
                if a.remove || a.splitting {
                    break;
                }
            }
        }
        assert!(periods > 300_000, "{periods} periods");
        assert!(
            cruising_periods > periods / 2,
            "{cruising_periods} of {periods} cruising"
        );
        assert!(
            far_periods > periods / 2,
            "{far_periods} of {periods} far from the end"
        );
    }

    /// Elements run to their end with [`cruise`] skipping what it can and with one
    /// update per period: after every skipped stretch and every update the states
    /// are bit for bit the same, the period counts agree, and most periods of the
    /// longer elements are skipped.
    #[test]
    fn cruise_changes_no_bit() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let cycle = 0.001;
        let (mut periods, mut skipped) = (0u64, 0u64);
        for case in 0..2000 {
            let x = rng.next();
            let v_target = rng.pick(&[0.5, 5.0, 33.333_333_333_333_336, 250.0]) * (0.5 + x);
            let v = View {
                target: rng.pick(&[1e-9, 0.05, 0.3, 2.4, 40.0]) * (0.5 + x),
                v_target,
                finalvel: rng.pick(&[0.0, v_target, v_target * x, v_target * 2.0]),
                tangent: case % 3 != 0,
                stop: case % 5 == 0,
                accel: rng.pick(&[1.0, 10.0, 500.0, 1000.0, 20000.0]) * (0.5 + x),
            };
            let next_target = rng.pick(&[None, Some(v_target), Some(v_target * x), Some(0.0)]);
            let mut a = Run {
                currentvel: rng.pick(&[0.0, v_target, v_target * x, v_target * 1.5]),
                cycle_time: cycle,
                ramp: case % 7 == 0,
                ..Run::default()
            };
            let mut b = a;
            let max = 200_000;
            let mut n = 0;
            while n < max && !(a.remove || a.splitting) {
                let k = cruise(&mut a, &v, next_target, cycle, max - n);
                for _ in 0..k {
                    update_cycle(&mut b, &v, next_target, cycle);
                }
                assert_eq!(bits(&a), bits(&b), "case {case} after {k} skipped: {v:?}");
                skipped += k;
                n += k;
                if n >= max {
                    break;
                }
                update_cycle(&mut a, &v, next_target, cycle);
                update_cycle(&mut b, &v, next_target, cycle);
                assert_eq!(bits(&a), bits(&b), "case {case}: {v:?}");
                n += 1;
            }
            periods += n;
            // The reference ends in the same period.
            if n < max {
                assert!(b.remove || b.splitting, "case {case}: {v:?}");
            }
        }
        assert!(periods > 1_000_000, "{periods} periods");
        assert!(skipped > periods * 3 / 4, "{skipped} of {periods} skipped");
    }

    /// Single updates from random states, including states no run reaches (speed
    /// above the target, zero or huge values).
    #[test]
    fn shortcuts_change_no_bit_from_any_state() {
        let mut rng = Rng(42);
        let cycle = 0.001;
        for case in 0..500_000 {
            let x = rng.next();
            let scale = rng.pick(&[0.0, 1e-12, 1e-6, 1.0, 1e3, 1e9]);
            let v = View {
                target: rng.next() * scale * 10.0,
                v_target: rng.next() * scale,
                finalvel: rng.next() * scale,
                tangent: case % 2 == 0,
                stop: case % 3 == 0,
                accel: (rng.next() * scale).max(1e-9),
            };
            let next_target = rng.pick(&[None, Some(x * scale)]);
            let mut a = Run {
                progress: v.target * rng.next(),
                currentvel: rng.next() * scale * 1.2,
                cycle_time: rng.pick(&[0.0, cycle, cycle * x]),
                ramp: case % 4 == 0,
                ..Run::default()
            };
            let mut b = a;
            update_cycle(&mut a, &v, next_target, cycle);
            reference_update_cycle(&mut b, &v, next_target, cycle);
            assert_eq!(bits(&a), bits(&b), "case {case}: {v:?}");
        }
    }
}
