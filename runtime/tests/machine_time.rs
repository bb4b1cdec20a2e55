//! Machine time beyond motion: auxiliary times from the profile and the
//! dialects' G0 paths, computed by hand from the shipped example profiles
//! (examples/machines) and compared with the planner to the nanosecond.
//!
//! Every move below is long enough to reach its speed (d ≥ v²/a), so a move
//! from rest to rest takes d/v + v/a, and a dog-leg G0 as long as its slowest
//! axis takes. A linear G0 runs at F = L·minᵢ(vᵢ/dᵢ) with A = L·minᵢ(aᵢ/dᵢ), so
//! it takes 1/minᵢ(vᵢ/dᵢ) + minᵢ(vᵢ/dᵢ)/minᵢ(aᵢ/dᵢ).

mod common;

use analyzer::Dialect;
use common::run_with;
use runtime::dryrun::{self, profile_from_table};
use runtime::machine::{MachineProfile, RapidPositioning};
use runtime::plan::{self, Totals};

const VMC: &str = include_str!("../../examples/machines/vmc.toml");
const ROUTER: &str = include_str!("../../examples/machines/router.toml");

/// A profile file with `extra` lines added to its `[machine]` table, replacing
/// the file's own lines of the same keys.
fn machine_text(file: &str, extra: &str) -> String {
    let key = |l: &str| l.split('=').next().map(|k| k.trim().to_string());
    let given: Vec<String> = extra.lines().filter_map(key).collect();
    let kept: Vec<&str> = file
        .lines()
        .filter(|l| !(l.contains('=') && key(l).is_some_and(|k| given.contains(&k))))
        .collect();
    kept.join("\n")
        .replacen("[machine]\n", &format!("[machine]\n{extra}\n"), 1)
}

/// Runs and plans `program` on a profile file, as `partscope run --machine` does.
fn plan_on(dialect: Dialect, program: &str, file: &str, extra: &str) -> Totals {
    let text = machine_text(file, extra);
    let table = analyzer::config::MachineConfig::from_toml(&text).expect("profile");
    let profile = profile_from_table(&table, dialect);
    let out = run_with(dialect, program, &text, &[], None);
    assert!(
        out.diagnostics.is_empty(),
        "{:?}",
        out.diagnostics
            .iter()
            .map(|d| (d.code, &d.message))
            .collect::<Vec<_>>()
    );
    dryrun::plan_run(&out, &profile).totals
}

fn assert_s(got: f64, want: f64) {
    assert!((got - want).abs() < 1e-9, "got {got} s, want {want} s");
}

const FANUC_PROGRAM: &str = "O1000;
G21 G90 G17 G40 G49 G80;
T1;
M6;
S8000 M3;
M8;
G0 X100. Y120.;
Z-50.;
G1 Z-60. F1200.;
G0 Z0.;
M9;
M5;
M30;
";

/// The FANUC VMC (LRP = 0, dog-leg G0) by hand.
#[test]
fn fanuc_vmc_program_timed_by_hand() {
    let t = plan_on(Dialect::Fanuc, FANUC_PROGRAM, VMC, "");
    let (vx, vy, vz) = (400.0, 300.0, 250.0);
    let (ax, ay, az) = (2000.0, 3000.0, 2500.0);
    let rapid_xy = f64::max(100.0 / vx + vx / ax, 120.0 / vy + vy / ay);
    let rapid_z_down = 50.0 / vz + vz / az;
    let feed = 1200.0 / 60.0;
    let cut = 10.0 / feed + feed / az;
    let rapid_z_up = 60.0 / vz + vz / az;
    let (tool_change, ramp, per_1000rpm, coolant, in_position) = (4.0, 0.2, 0.25, 0.1, 0.02);
    let spindle = ramp + per_1000rpm * 8000.0 / 1000.0;
    let stops = 4.0;

    assert_s(t.rapid_s, rapid_xy + rapid_z_down + rapid_z_up);
    assert_s(t.cutting_s, cut);
    assert_s(t.tool_change_s, tool_change);
    assert_s(t.aux.spindle_s, 2.0 * spindle);
    assert_s(t.aux.coolant_s, 2.0 * coolant);
    assert_s(t.aux.in_position_s, stops * in_position);
    assert_s(t.aux.tool_select_s, 0.0);
    assert_s(
        t.cycle_time_s,
        rapid_xy
            + rapid_z_down
            + cut
            + rapid_z_up
            + tool_change
            + 2.0 * spindle
            + 2.0 * coolant
            + stops * in_position,
    );
    assert_eq!(t.aux.tool_changes, 1);
    assert_s(t.aux.total_s(), t.tool_change_s + t.other_s);
}

/// LRP = 1 (linear interpolation positioning): the same G0 X100. Y120. runs on a
/// line whose speed Y limits and whose acceleration X limits, so it is slower
/// than the dog-leg, whose slowest axis (Y) needs 0.5 s.
#[test]
fn fanuc_lrp_1_is_linear_positioning() {
    let program = "G21 G90;\nG0 X100. Y120.;\nM30;\n";
    let dogleg = plan_on(Dialect::Fanuc, program, VMC, "");
    let linear = plan_on(Dialect::Fanuc, program, VMC, "lrp = 1");
    let (vx, vy, ax, ay) = (400.0, 300.0, 2000.0, 3000.0);
    let (dx, dy) = (100.0, 120.0);
    let v_per_l = f64::min(vx / dx, vy / dy);
    let a_per_l = f64::min(ax / dx, ay / dy);
    assert_s(linear.rapid_s, 1.0 / v_per_l + v_per_l / a_per_l);
    assert_s(
        dogleg.rapid_s,
        f64::max(dx / vx + vx / ax, dy / vy + vy / ay),
    );
    // The dog-leg's path is longer than the line it replaces.
    assert_s(linear.distance_mm, (dx * dx + dy * dy).sqrt());
    assert!(dogleg.distance_mm > linear.distance_mm + 1.0);
    assert!(dogleg.distance_mm < dx + dy);
}

const SERVOWORKS_PROGRAM: &str = "G21 G90 G17 G40 G49 G80
T1
S18000 M03
M08
G00 X300. Y200.
G00 Z-30.
G01 Z-40. F600.
G04 P1500
G00 Z0.
M09
M05
M30
";

/// The ServoWorks router (G00 without linear interpolation) by hand; the T word
/// itself changes the tool, G04 P is in milliseconds.
#[test]
fn servoworks_router_program_timed_by_hand() {
    let t = plan_on(Dialect::Servoworks, SERVOWORKS_PROGRAM, ROUTER, "");
    let (vx, vy, vz) = (500.0, 400.0, 250.0);
    let (ax, ay, az) = (2500.0, 1500.0, 2500.0);
    let rapid_xy = f64::max(300.0 / vx + vx / ax, 200.0 / vy + vy / ay);
    let rapid_z_down = 30.0 / vz + vz / az;
    let feed = 600.0 / 60.0;
    let cut = 10.0 / feed + feed / az;
    let dwell = 1500.0 / 1000.0;
    let rapid_z_up = 40.0 / vz + vz / az;
    let (tool_change, ramp, per_1000rpm, coolant) = (8.0, 0.5, 0.25, 0.1);
    let spindle = ramp + per_1000rpm * 18000.0 / 1000.0;

    assert_s(t.rapid_s, rapid_xy + rapid_z_down + rapid_z_up);
    assert_s(t.cutting_s, cut);
    assert_s(t.dwell_s, dwell);
    assert_s(t.tool_change_s, tool_change);
    assert_s(t.aux.spindle_s, 2.0 * spindle);
    assert_s(t.aux.coolant_s, 2.0 * coolant);
    assert_s(
        t.cycle_time_s,
        rapid_xy
            + rapid_z_down
            + cut
            + dwell
            + rapid_z_up
            + tool_change
            + 2.0 * spindle
            + 2.0 * coolant,
    );
}

/// *G00 Perform Linear Interpolation* enabled: X limits the line's speed, Y
/// (the gantry) its acceleration.
#[test]
fn servoworks_g00_linear_interpolation() {
    let program = "G21 G90\nG00 X300. Y200.\nM30\n";
    let linear = plan_on(
        Dialect::Servoworks,
        program,
        ROUTER,
        "g00_linear_interpolation = true",
    );
    let (vx, vy, ax, ay) = (500.0, 400.0, 2500.0, 1500.0);
    let (dx, dy) = (300.0, 200.0);
    let v_per_l = f64::min(vx / dx, vy / dy);
    let a_per_l = f64::min(ax / dx, ay / dy);
    assert_s(linear.rapid_s, 1.0 / v_per_l + v_per_l / a_per_l);
    let dogleg = plan_on(Dialect::Servoworks, program, ROUTER, "");
    assert_s(
        dogleg.rapid_s,
        f64::max(dx / vx + vx / ax, dy / vy + vy / ay),
    );
}

/// The switches' defaults: FANUC LRP = 0 and ServoWorks without linear
/// interpolation move axes independently; LinuxCNC always interpolates.
#[test]
fn rapid_positioning_defaults_and_manual_names() {
    let d = |dialect| MachineProfile::default_for(dialect).rapid_positioning;
    assert_eq!(d(Dialect::Fanuc), RapidPositioning::Independent);
    assert_eq!(d(Dialect::Servoworks), RapidPositioning::Independent);
    assert_eq!(d(Dialect::Rs274ngc), RapidPositioning::Linear);
    let with = |key: &str, dialect| {
        analyzer::config::MachineConfig::from_toml(key)
            .map(|t| profile_from_table(&t, dialect).rapid_positioning)
    };
    assert_eq!(
        with("lrp = 1", Dialect::Fanuc),
        Ok(RapidPositioning::Linear)
    );
    assert_eq!(
        with("g00_linear_interpolation = true", Dialect::Servoworks),
        Ok(RapidPositioning::Linear)
    );
    assert_eq!(
        with("rapid_positioning = \"independent\"", Dialect::Rs274ngc),
        Ok(RapidPositioning::Independent)
    );
    assert!(with("lrp = 2", Dialect::Fanuc).is_err());
}

/// The dog-leg is drawn as the axes move: with equal rates (100 mm/s) and
/// accelerations (1000 mm/s²) both axes cover the same distance until Y starts
/// to brake at 35 mm (0.4 s), X cruises on to 45 mm while Y stops at 40, then X
/// runs alone. Every point lies in the box of the end points, so the
/// travel-limit check of the end points covers the path.
#[test]
fn dogleg_toolpath_is_the_axes_real_path() {
    let program = "G21 G90;\nG0 X100. Y40.;\nM30;\n";
    let out = run_with(Dialect::Fanuc, program, "", &[], None);
    let profile = MachineProfile::default_for(Dialect::Fanuc);
    let tp = dryrun::toolpath_on(&out, 0.01, &profile);
    let pts = &tp.segments[0].points;
    assert_eq!(pts.first(), Some(&[0.0, 0.0, 0.0]));
    assert_eq!(pts.last(), Some(&[100.0, 40.0, 0.0]));
    let (v, a) = (100.0, 1000.0);
    let brake = 40.0 - v * v / (2.0 * a);
    let arrive_x = brake + v * (v / a);
    let near = |x: f64, y: f64| {
        pts.iter()
            .any(|p| (p[0] - x).abs() < 1e-9 && (p[1] - y).abs() < 1e-9)
    };
    assert!(near(brake, brake), "{pts:?}");
    assert!(near(arrive_x, 40.0), "{pts:?}");
    for p in pts {
        assert!((0.0..=100.0).contains(&p[0]) && (0.0..=40.0).contains(&p[1]));
        assert!(p[1] <= p[0] + 1e-9, "{p:?} left the 45° line");
    }
    // Without the profile (or with linear positioning) the line is straight.
    assert_eq!(dryrun::toolpath(&out, 0.01).segments[0].points.len(), 2);
    // The travel-limit check sees the same move: inside X 0..100, Y 0..40.
    let limited = "[[axes]]\nletter = \"X\"\nmin_travel = 0.0\nmax_travel = 100.0\n\
                   [[axes]]\nletter = \"Y\"\nmin_travel = 0.0\nmax_travel = 40.0\n";
    let out = run_with(Dialect::Fanuc, program, limited, &[], None);
    assert!(out.diagnostics.is_empty(), "{:?}", out.diagnostics);
    // Its length is what `distance_mm` reports.
    let t = dryrun::plan_run(&out, &profile).totals;
    let bent = plan::polyline_length(
        &pts.iter()
            .map(|p| [p[0], p[1], p[2], 0.0, 0.0, 0.0])
            .collect::<Vec<_>>(),
    );
    assert_s(t.distance_mm, bent);
    assert!(bent > brake * 2f64.sqrt() + (100.0 - brake) - 1e-9);
    assert!(bent < 40.0 * 2f64.sqrt() + 60.0);
}

/// M19, the pallet change code, other M codes by number, T pre-selection and
/// program stops each take their profile time; a code with no time does not
/// stop the motion.
#[test]
fn auxiliary_codes_take_their_profile_times() {
    let program = "G21 G90;\nT5;\nM19;\nM60;\nM10;\nM11;\nM0;\nM1;\nM30;\n";
    let extra = "tool_select_time = 1.5\npallet_change_time = 12.0\nm_code_time = 0.3\n\
                 m_code_times = { M10 = 0.7 }\nprogram_stop_time = 20.0";
    let t = plan_on(Dialect::Fanuc, program, VMC, extra);
    assert_s(t.aux.tool_select_s, 1.5);
    assert_s(t.aux.orient_s, 1.0);
    assert_s(t.aux.pallet_change_s, 12.0);
    assert_s(t.aux.m_code_s, 0.7 + 0.3);
    // M1 runs through: the optional-stop switch is off.
    assert_s(t.aux.program_stop_s, 20.0);
    assert_eq!(t.aux.program_stops, 1);
    assert_s(t.cycle_time_s, 1.5 + 1.0 + 12.0 + 0.7 + 0.3 + 20.0);
    // A builder's pallet code; M60 is then an ordinary M code.
    let t = plan_on(
        Dialect::Fanuc,
        "M60;\nM50;\nM30;\n",
        VMC,
        "pallet_change_m = 50\npallet_change_time = 9.0\nm_code_time = 0.25",
    );
    assert_s(t.aux.pallet_change_s, 9.0);
    assert_s(t.aux.m_code_s, 0.25);
}

/// Spindle time follows the speed change: up to S, an S change while turning, a
/// reversal through rest, the stop, and nothing for a spindle already at rest.
#[test]
fn spindle_ramps_by_the_speed_change() {
    let program = "M5;\nS2000 M3;\nS6000;\nM4;\nM5;\nM5;\nM30;\n";
    let t = plan_on(Dialect::Fanuc, program, VMC, "");
    let (ramp, per_1000rpm) = (0.2, 0.25);
    let up = ramp + per_1000rpm * 2.0;
    let faster = ramp + per_1000rpm * 4.0;
    let reverse = ramp + per_1000rpm * 12.0;
    let stop = ramp + per_1000rpm * 6.0;
    assert_s(t.aux.spindle_s, up + faster + reverse + stop);
}

/// G31 (skip) is a feed move at F, whatever the modal motion; G38.2 likewise.
#[test]
fn probe_moves_are_timed_as_feed_moves() {
    let t = plan_on(
        Dialect::Fanuc,
        "G21 G90 G0 X0.;\nG31 Z-50. F600.;\nM30;\n",
        VMC,
        "in_position_time = 0.0",
    );
    let (feed, az) = (600.0 / 60.0, 2500.0);
    assert_s(t.cutting_s, 50.0 / feed + feed / az);
    assert_s(t.rapid_s, 0.0);
    let out = run_with(
        Dialect::Rs274ngc,
        "G21 G90\nG38.2 Z-50 F600\nM2\n",
        "",
        &[],
        None,
    );
    assert!(matches!(out.motions[0].kind, runtime::MotionKind::Probe));
    let t = dryrun::plan_run(&out, &MachineProfile::default_for(Dialect::Rs274ngc)).totals;
    assert!(t.cutting_s > 50.0 / feed && t.rapid_s == 0.0, "{t:?}");
}

/// A FANUC G00 stops at its end even when it is interpolated (LRP = 1) and G64
/// is in force: two rapids round a corner as two moves from rest to rest.
#[test]
fn fanuc_rapids_stop_at_every_block_end() {
    let program = "G21 G90 G64;\nG0 X100.;\nG0 Y100.;\nM30;\n";
    let t = plan_on(
        Dialect::Fanuc,
        program,
        VMC,
        "lrp = 1\nin_position_time = 0.0",
    );
    let (vx, vy, ax, ay) = (400.0, 300.0, 2000.0, 3000.0);
    assert_s(t.rapid_s, 100.0 / vx + vx / ax + 100.0 / vy + vy / ay);
}
