//! Where the time goes: the planner's split of motion time by cause, computed
//! by hand from the machine limits on small programs.
//!
//! The generic trapezoid model runs in closed form, so a move from `u` up to
//! `v` and down to `w` at acceleration `a` takes (v − u)/a + (v − w)/a plus the
//! cruise at `v`. A ramp from `u` to the peak `p` below the target speed `v`
//! costs (p − u)/a · (1 − (p + u)/2v) more than running its distance at `v`;
//! that is the time charged to acceleration or to the corner.

mod common;

use analyzer::Dialect;
use common::run_with;
use runtime::dryrun;
use runtime::machine::{MachineProfile, PlannerModel};
use runtime::plan::{plan, Causes, Event, PathMode, Segment};

/// X, Y, Z at 100 mm/s and 1000 mm/s², TRAJ 100 mm/s, trapezoid model.
fn machine() -> MachineProfile {
    MachineProfile {
        planner: PlannerModel::Trapezoid,
        ..MachineProfile::default_for(Dialect::Fanuc)
    }
}

fn f(mm_per_min: f64) -> f64 {
    mm_per_min / 60.0
}

fn causes(profile: &MachineProfile, segs: Vec<Segment>) -> (f64, Causes) {
    let r = plan(profile, segs.into_iter().map(Event::Motion));
    let mut by_element = Causes::default();
    for t in &r.timings {
        by_element.add(&t.causes);
    }
    // The totals are the sum of the elements', and they add up to the motion time.
    assert_close(by_element.total_s(), r.totals.causes.total_s());
    assert_close(r.totals.causes.total_s(), r.totals.motion_s);
    (r.totals.motion_s, r.totals.causes)
}

fn assert_close(got: f64, want: f64) {
    assert!((got - want).abs() < 1e-9, "got {got} s, want {want} s");
}

/// The time a ramp from `u` to the peak `p` adds over running at `v`.
fn ramp_loss(u: f64, p: f64, v: f64, a: f64) -> f64 {
    (p - u) / a * (1.0 - (p + u) / (2.0 * v))
}

#[test]
fn a_long_move_reaching_feed_spends_its_ramps_on_acceleration() {
    // G1 X50 F3000: 50 mm/s reached after 0.05 s and 1.25 mm; 1 s at feed
    // for the 50 mm, the two ramps 0.025 s each on top.
    let (t, c) = causes(
        &machine(),
        vec![Segment::line(
            [0.0; 3],
            [50.0, 0.0, 0.0],
            f(3000.0),
            PathMode::ExactStop,
        )],
    );
    assert_close(t, 1.05);
    assert_close(c.feed_s, 1.0);
    assert_close(c.accel_s, 0.05);
    assert_eq!(c.corner_s, 0.0);
    assert_eq!(
        c.axis_cap_s + c.traj_cap_s + c.curve_cap_s + c.servo_cap_s,
        0.0
    );
}

#[test]
fn a_chain_of_short_segments_never_reaches_feed() {
    // Ten collinear 0.1 mm moves at F6000 (100 mm/s) in G64, a = 1000 mm/s².
    // The look-ahead lets the newest move enter at most at sqrt(a·L) (it may
    // still be followed by a stop), so the junction speeds are the lower of
    // sqrt(2a·x) from the start and sqrt(a·0.1 + 2a·(0.9 − x)) from the end:
    // up from rest over four moves, one move across the crossing, down to
    // 10 mm/s over four, and the last move over its own small peak to rest.
    let a = 1000.0;
    let segs: Vec<Segment> = (0..10)
        .map(|i| {
            let x = i as f64 * 0.1;
            Segment::line(
                [x, 0.0, 0.0],
                [x + 0.1, 0.0, 0.0],
                f(6000.0),
                PathMode::blend(0.01),
            )
        })
        .collect();
    let up = (2.0 * a * 0.4f64).sqrt();
    let down = (a * 0.1 + 2.0 * a * 0.4f64).sqrt();
    let across = ((up * up + down * down + 2.0 * a * 0.1) / 2.0).sqrt();
    let last_in = (a * 0.1f64).sqrt();
    let last_peak = ((last_in * last_in + 2.0 * a * 0.1) / 2.0).sqrt();
    let total = up / a
        + (across - up) / a
        + (across - down) / a
        + (down - last_in) / a
        + (last_peak - last_in) / a
        + last_peak / a;
    let p = machine();
    let r = plan(&p, segs.iter().copied().map(Event::Motion));
    let (t, c) = causes(&p, segs);
    assert_close(t, total);
    // 1 mm at 100 mm/s is 0.01 s; every other second is acceleration.
    assert_close(c.feed_s, 0.01);
    assert_close(c.accel_s, total - 0.01);
    assert_eq!(c.corner_s, 0.0);
    let n = r.totals.cause_counts;
    assert_eq!(n.short, 10);
    assert_close(n.short_s, total);
    assert_close(n.short_max_mm, 0.1);
    assert_close(n.short_feed_min, 100.0);
    assert_close(n.short_feed_max, 100.0);
}

#[test]
fn a_blended_corner_charges_the_ramps_to_it() {
    // X10 then Y10 at F3000 (50 mm/s) in G64 P0.01: the 90° corner's speed is
    // sqrt(a·r) with the largest arc within the tolerance, r = P·sin45°/(1 − sin45°).
    let (a, v) = (1000.0, 50.0);
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let vc = (a * 0.01 * s / (1.0 - s)).sqrt();
    let (t, c) = causes(
        &machine(),
        vec![
            Segment::line([0.0; 3], [10.0, 0.0, 0.0], f(3000.0), PathMode::blend(0.01)),
            Segment::line(
                [10.0, 0.0, 0.0],
                [10.0, 10.0, 0.0],
                f(3000.0),
                PathMode::blend(0.01),
            ),
        ],
    );
    // Each move: up from rest (acceleration) and down to or up from the corner.
    let accel = 2.0 * ramp_loss(0.0, v, v, a);
    let corner = 2.0 * ramp_loss(vc, v, v, a);
    assert_close(c.feed_s, 0.4);
    assert_close(c.accel_s, accel);
    assert_close(c.corner_s, corner);
    assert_close(t, 0.4 + accel + corner);
}

#[test]
fn an_exact_stop_corner_is_a_corner_and_the_program_end_is_not() {
    // G61.1-style stops between two 10 mm moves at F3000: every ramp runs to
    // rest; the two at the corner are the corner's, start and end acceleration.
    let (t, c) = causes(
        &machine(),
        vec![
            Segment::line([0.0; 3], [10.0, 0.0, 0.0], f(3000.0), PathMode::ExactStop),
            Segment::line(
                [10.0, 0.0, 0.0],
                [10.0, 10.0, 0.0],
                f(3000.0),
                PathMode::ExactStop,
            ),
        ],
    );
    assert_close(t, 2.0 * (10.0 / 50.0 + 50.0 / 1000.0));
    assert_close(c.feed_s, 0.4);
    assert_close(c.accel_s, 0.05);
    assert_close(c.corner_s, 0.05);
}

#[test]
fn a_feed_above_the_traj_cap_is_charged_to_the_cap() {
    // TRAJ 80 mm/s, G1 X100 F12000 (200 mm/s): 0.5 s at feed, 1.25 − 0.5 s
    // for the cap, v/a = 0.08 s of ramps.
    let p = MachineProfile {
        traj_max_velocity: 80.0,
        ..machine()
    };
    let (t, c) = causes(
        &p,
        vec![Segment::line(
            [0.0; 3],
            [100.0, 0.0, 0.0],
            f(12000.0),
            PathMode::ExactStop,
        )],
    );
    assert_close(t, 1.33);
    assert_close(c.feed_s, 0.5);
    assert_close(c.traj_cap_s, 0.75);
    assert_close(c.accel_s, 0.08);
    assert_eq!(c.axis_cap_s, 0.0);
}

#[test]
fn a_feed_above_the_axis_limit_is_charged_to_the_axis() {
    // TRAJ 1000 mm/s, X at 100 mm/s: G1 X100 F12000 runs at 100 mm/s.
    let p = MachineProfile {
        traj_max_velocity: 1000.0,
        ..machine()
    };
    let (t, c) = causes(
        &p,
        vec![Segment::line(
            [0.0; 3],
            [100.0, 0.0, 0.0],
            f(12000.0),
            PathMode::ExactStop,
        )],
    );
    assert_close(t, 1.1);
    assert_close(c.feed_s, 0.5);
    assert_close(c.axis_cap_s, 0.5);
    assert_close(c.accel_s, 0.1);
    assert_eq!(c.traj_cap_s, 0.0);
}

#[test]
fn the_feed_override_moves_the_programmed_feed() {
    // F1500 at 200 %: 50 mm/s, as F3000 at 100 %.
    let p = MachineProfile {
        feed_override: 2.0,
        ..machine()
    };
    let (t, c) = causes(
        &p,
        vec![Segment::line(
            [0.0; 3],
            [50.0, 0.0, 0.0],
            f(1500.0),
            PathMode::ExactStop,
        )],
    );
    assert_close(t, 1.05);
    assert_close(c.feed_s, 1.0);
    assert_close(c.accel_s, 0.05);
}

#[test]
fn blocks_carry_their_causes_dwell_and_auxiliary_time() {
    // A rapid, a cut, a dwell and a tool change, each on its own line.
    let program = "G21 G90 G94 G61.1\nG0 X10\nG1 X60 F3000\nG4 P2\nM6 T2\nM2\n";
    let table = analyzer::config::MachineConfig::from_toml("tool_change_time = 5.0").expect("toml");
    let profile = MachineProfile {
        planner: PlannerModel::Trapezoid,
        ..dryrun::profile_from_table(&table, Dialect::Rs274ngc)
    };
    let out = run_with(
        Dialect::Rs274ngc,
        program,
        "tool_change_time = 5.0",
        &[],
        None,
    );
    let dry = dryrun::plan_run(&out, &profile);
    let blocks = dryrun::block_times(&out, &dry);
    let line = |l: u32| {
        blocks
            .iter()
            .find(|b| b.line == l)
            .unwrap_or_else(|| panic!("no block on line {}", l + 1))
    };
    // G0 X10 at 100 mm/s, a = 1000: a triangle of 2·sqrt(10/1000) s.
    let rapid = 2.0 * 0.01f64.sqrt();
    assert_close(line(1).causes.rapid_s, rapid);
    assert_close(line(1).time_s, rapid);
    assert_close(line(2).causes.feed_s, 1.0);
    assert_close(line(2).causes.accel_s, 0.05);
    assert_close(line(2).time_s, 1.05);
    assert_close(line(3).dwell_s, 2.0);
    assert_close(line(3).start_s, rapid + 1.05);
    assert_close(line(3).end_s, rapid + 1.05 + 2.0);
    assert_close(line(4).aux_s, 5.0);
    // The tool change follows the dwell.
    assert_close(line(4).start_s, rapid + 1.05 + 2.0);
    assert_close(line(4).end_s, dry.totals.cycle_time_s);
    let sum: f64 = blocks.iter().map(|b| b.time_s).sum();
    assert_close(sum, dry.totals.cycle_time_s);
}

#[test]
fn the_linuxcnc_model_splits_its_servo_periods_too() {
    // G1 X50 F3000 on the LinuxCNC model, period by period: the parts still
    // add up, and the time beyond 1 s at feed is all acceleration.
    let p = MachineProfile::default_for(Dialect::Rs274ngc);
    let (t, c) = causes(
        &p,
        vec![Segment::line(
            [0.0; 3],
            [50.0, 0.0, 0.0],
            f(3000.0),
            PathMode::ExactStop,
        )],
    );
    assert_close(c.feed_s, 1.0);
    assert_close(c.accel_s, t - 1.0);
    assert!((t - 1.05).abs() < 0.002, "{t}");
}

#[test]
fn what_ifs_plan_again_with_one_change() {
    // G1 X10, G1 Y10 at F3000 with exact stops on the trapezoid machine.
    let p = machine();
    let segs = [
        Segment::line([0.0; 3], [10.0, 0.0, 0.0], f(3000.0), PathMode::ExactStop),
        Segment::line(
            [10.0, 0.0, 0.0],
            [10.0, 10.0, 0.0],
            f(3000.0),
            PathMode::ExactStop,
        ),
    ];
    let events: Vec<Event> = segs.iter().copied().map(Event::Motion).collect();
    let at = |k| dryrun::what_if(&events, &p, k);
    // As programmed: 2·(10/50 + 50/1000).
    assert_close(plan(&p, events.iter().copied()).totals.cycle_time_s, 0.5);
    // 120 %: 60 mm/s, 2·(10/60 + 60/1000).
    let feed = at(dryrun::WhatIfKind::FeedOverride);
    assert_eq!(feed.label, "feed override 120 %");
    assert_close(feed.cycle_time_s, 2.0 * (10.0 / 60.0 + 0.06));
    // 2000 mm/s²: 2·(10/50 + 50/2000).
    assert_close(
        at(dryrun::WhatIfKind::Acceleration).cycle_time_s,
        2.0 * (0.2 + 0.025),
    );
    // G64 P0.05: the corner is taken at sqrt(a·r), r = P·sin45°/(1 − sin45°),
    // instead of stopping; each move loses (50 − vc)/a·(1 − (50 + vc)/100)
    // less than before.
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let vc = (1000.0 * 0.05 * s / (1.0 - s)).sqrt();
    let corner = ramp_loss(vc, 50.0, 50.0, 1000.0);
    let blend = at(dryrun::WhatIfKind::Blend);
    assert_close(blend.cycle_time_s, 0.4 + 0.05 + 2.0 * corner);
    assert!(!dryrun::WhatIfKind::Blend.applies(Dialect::Fanuc));
}

/// On the CAM-shaped programs of `tests/cycle_time/cam/programs` (on
/// the LinuxCNC model period by period) the causes are never negative and add
/// up to the motion time, element by element and in sum.
#[test]
fn causes_add_up_on_cam_programs() {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/cycle_time/cam/programs");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("cam programs")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ngc"))
        .collect();
    files.sort();
    assert!(files.len() > 30, "{}", files.len());
    let profile = MachineProfile::default_for(Dialect::Rs274ngc);
    for path in &files {
        let text = std::fs::read_to_string(path).expect("program");
        let out = run_with(Dialect::Rs274ngc, &text, "block_skip = true", &[], None);
        let r = plan(&profile, dryrun::planner_events(&out));
        let name = path.display();
        for t in &r.timings {
            let c = &t.causes;
            let parts = [
                c.feed_s,
                c.accel_s,
                c.corner_s,
                c.axis_cap_s,
                c.traj_cap_s,
                c.curve_cap_s,
                c.servo_cap_s,
                c.rapid_s,
            ];
            assert!(parts.iter().all(|s| *s >= 0.0), "{name}: {c:?}");
        }
        let sum: f64 = r.timings.iter().map(|t| t.causes.total_s()).sum();
        let m = r.totals.motion_s;
        assert!((sum - m).abs() <= 1e-9 * m.max(1.0), "{name}: {sum} vs {m}");
        assert!(
            (r.totals.causes.total_s() - m).abs() <= 1e-9 * m.max(1.0),
            "{name}"
        );
    }
}
