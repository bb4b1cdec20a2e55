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

fn set_split(r: &mut Run, split_time: f64, v_f: f64) {
    if r.splitting && split_time > 0.0 {
        return;
    }
    r.splitting = true;
    r.cycle_time = split_time;
    r.term_vel = v_f;
}
