//! Planner behaviour: closed-form profiles, the hand-checked LinuxCNC 2.9 values of
//! the oracle's EXPECTED.md (segments built by hand), streaming, and the `.ini` reader.

use runtime::machine::{Axis, AxisKind, MachineProfile, PlannerModel};
use runtime::plan::profile::{scurve_ramp_time, trapezoid};
use runtime::plan::{plan, Event, PathMode, Planner, Segment};

const G61: PathMode = PathMode::ExactPath;
const G64: PathMode = PathMode::blend(0.0);

/// The oracle's default machine: XYZ, 100 mm/s and 1000 mm/s² per axis, TRAJ 100 mm/s.
fn lcnc_machine() -> MachineProfile {
    MachineProfile::default_for(analyzer::Dialect::Rs274ngc)
}

fn motion(profile: &MachineProfile, segs: Vec<Segment>) -> f64 {
    plan(profile, segs.into_iter().map(Event::Motion))
        .totals
        .motion_s
}

fn assert_ms(actual: f64, expected: f64) {
    assert!(
        (actual - expected).abs() <= 0.0005 + 1e-9,
        "got {actual:.4} s, expected {expected:.3} s"
    );
}

/// Feed in mm/min → mm/s.
fn f(mm_per_min: f64) -> f64 {
    mm_per_min / 60.0
}

#[test]
fn trapezoid_closed_form() {
    // 50 mm at 50 mm/s, 1000 mm/s²: L/v + v/a.
    let p = trapezoid(50.0, 0.0, 50.0, 0.0, 1000.0);
    assert!((p.time - 1.05).abs() < 1e-12);
    assert_eq!(p.v_peak, 50.0);
    assert_eq!(p.v_end, 0.0);
    // 1 mm cannot reach 100 mm/s: triangle, 2·sqrt(L/a).
    let t = trapezoid(1.0, 0.0, 100.0, 0.0, 1000.0);
    assert!((t.time - 2.0 * (1.0f64 / 1000.0).sqrt()).abs() < 1e-12);
    assert!((t.v_peak - 1000.0f64.sqrt()).abs() < 1e-9);
    // Entering at cruise speed and leaving at cruise speed: L/v.
    let c = trapezoid(10.0, 20.0, 20.0, 20.0, 1000.0);
    assert!((c.time - 0.5).abs() < 1e-12);
    // Exit cap above what the length allows: full acceleration, sqrt(2aL).
    let a = trapezoid(0.2, 0.0, 100.0, 100.0, 1000.0);
    assert!((a.v_end - 20.0).abs() < 1e-9);
    assert!((a.time - 0.02).abs() < 1e-12);
}

#[test]
fn scurve_ramp_closed_form() {
    // Long ramp: dv/a + a/j.
    assert!((scurve_ramp_time(100.0, 1000.0, 10_000.0) - 0.2).abs() < 1e-12);
    // Short ramp never reaches a: 2·sqrt(dv/j).
    assert!((scurve_ramp_time(10.0, 1000.0, 10_000.0) - 2.0 * 0.001f64.sqrt()).abs() < 1e-12);
}

#[test]
fn expected_md_straight_moves() {
    let m = lcnc_machine();
    // prog2s: G61; G0 X100; G1 X50 F3000.
    let t = motion(
        &m,
        vec![
            Segment::rapid([0.0; 3], [100.0, 0.0, 0.0], G61),
            Segment::line([100.0, 0.0, 0.0], [50.0, 0.0, 0.0], f(3000.0), G61),
        ],
    );
    assert_ms(t, 2.150);
    // s4_x1: G1 X50 F3000.
    let t = motion(
        &m,
        vec![Segment::line([0.0; 3], [50.0, 0.0, 0.0], f(3000.0), G61)],
    );
    assert_ms(t, 1.050);
    // s1_xx: out and back (a reversal stops without the corner penalty).
    let t = motion(
        &m,
        vec![
            Segment::line([0.0; 3], [50.0, 0.0, 0.0], f(3000.0), G61),
            Segment::line([50.0, 0.0, 0.0], [0.0; 3], f(3000.0), G61),
        ],
    );
    assert_ms(t, 2.100);
    // t1_diag: G0 X100 Y100, TRAJ caps 100 mm/s, axis-limited acceleration 1414 mm/s².
    let t = motion(&m, vec![Segment::rapid([0.0; 3], [100.0, 100.0, 0.0], G61)]);
    assert_ms(t, 1.485);
    // t2_short: G1 X1 F6000: triangle of 63.2 ms, rounded up to the servo period.
    let t = motion(
        &m,
        vec![Segment::line([0.0; 3], [1.0, 0.0, 0.0], f(6000.0), G61)],
    );
    assert_ms(t, 0.064);
    // z1: G0 Z10.
    let t = motion(&m, vec![Segment::rapid([0.0; 3], [0.0, 0.0, 10.0], G61)]);
    assert_ms(t, 0.200);
}

#[test]
fn expected_md_g61_corners_cost_acceleration() {
    let m = lcnc_machine();
    // s3_xy: 90° corner in G61: both moves lose 10 % of their acceleration.
    let t = motion(
        &m,
        vec![
            Segment::line([0.0; 3], [50.0, 0.0, 0.0], f(3000.0), G61),
            Segment::line([50.0, 0.0, 0.0], [50.0, 50.0, 0.0], f(3000.0), G61),
        ],
    );
    assert_ms(t, 2.112);
    let square = |mode| {
        let p = [
            [0.0, 0.0, 0.0],
            [50.0, 0.0, 0.0],
            [50.0, 50.0, 0.0],
            [0.0, 50.0, 0.0],
        ];
        (0..4)
            .map(|i| Segment::line(p[i], p[(i + 1) % 4], f(3000.0), mode))
            .collect::<Vec<_>>()
    };
    assert_ms(motion(&m, square(G61)), 4.224);
    // t3_square_g64: blended corners.
    assert_ms(motion(&m, square(G64)), 3.994);
}

#[test]
fn expected_md_arcs_use_half_acceleration() {
    let m = lcnc_machine();
    let circle = |feed: f64| {
        vec![
            Segment::rapid([0.0; 3], [10.0, 0.0, 0.0], G61),
            Segment::arc(
                [10.0, 0.0, 0.0],
                [0.0; 3],
                [0.0, 0.0, 1.0],
                -std::f64::consts::TAU,
                0.0,
                f(feed),
                G61,
            ),
        ]
    };
    assert_ms(motion(&m, circle(600.0)), 6.504);
    assert_ms(motion(&m, circle(3000.0)), 1.557);
}

#[test]
fn expected_md_dwell_is_not_motion() {
    let m = lcnc_machine();
    let ev = vec![
        Event::Motion(Segment::line([0.0; 3], [10.0, 0.0, 0.0], f(6000.0), G61)),
        Event::Dwell {
            seconds: 0.5,
            block: 2,
        },
        Event::Motion(Segment::line([10.0, 0.0, 0.0], [0.0; 3], f(6000.0), G61)),
    ];
    let r = plan(&m, ev);
    assert_ms(r.totals.motion_s, 0.400);
    assert_ms(r.totals.dwell_s, 0.5);
    assert_ms(r.totals.cycle_time_s, 0.900);
}

#[test]
fn expected_md_polygon_g64() {
    let m = lcnc_machine();
    let round4 = |v: f64| (v * 10_000.0).round() / 10_000.0;
    let mut segs = vec![Segment::rapid([0.0; 3], [20.0, 0.0, 0.0], G64)];
    let mut prev = [20.0, 0.0, 0.0];
    for i in 1..=360 {
        let a = (i as f64).to_radians();
        let p = [round4(20.0 * a.cos()), round4(20.0 * a.sin()), 0.0];
        segs.push(Segment::line(prev, p, f(3000.0), G64));
        prev = p;
    }
    // Measured 2.921 s.
    let t = motion(&m, segs);
    assert!((t - 2.921).abs() <= 0.0015, "polygon: {t:.4} s");
}

#[test]
fn expected_md_traj_velocity_caps_feed_but_not_acceleration() {
    let mut m = lcnc_machine();
    m.traj_max_velocity = 20.0;
    m.traj_max_acceleration = 100.0;
    let t = motion(
        &m,
        vec![Segment::line([0.0; 3], [50.0, 0.0, 0.0], f(3000.0), G61)],
    );
    assert_ms(t, 2.520);
}

#[test]
fn expected_md_sample_axis_mm_machine() {
    let mut m = lcnc_machine();
    m.axes = vec![
        Axis::linear('X', 30.48, 508.0),
        Axis::linear('Y', 30.48, 508.0),
        Axis::linear('Z', 30.48, 508.0),
    ];
    m.traj_max_velocity = 30.48;
    let t = motion(
        &m,
        vec![
            Segment::rapid([0.0; 3], [100.0, 0.0, 0.0], G61),
            Segment::line([100.0, 0.0, 0.0], [50.0, 0.0, 0.0], f(3000.0), G61),
        ],
    );
    assert_ms(t, 5.042);
}

#[test]
fn totals_split_rapid_cutting_and_tools() {
    let m = lcnc_machine();
    let ev = vec![
        Event::Motion(Segment::rapid([0.0; 3], [100.0, 0.0, 0.0], G61).with_tool(1)),
        Event::ToolChange { tool: 2, block: 1 },
        Event::Motion(
            Segment::line([100.0, 0.0, 0.0], [50.0, 0.0, 0.0], f(3000.0), G61).with_tool(2),
        ),
    ];
    let mut m2 = m.clone();
    m2.tool_change_time = 4.0;
    let r = plan(&m2, ev);
    assert_ms(r.totals.rapid_s, 1.100);
    assert_ms(r.totals.cutting_s, 1.050);
    assert_ms(r.totals.tool_change_s, 4.0);
    assert_ms(r.totals.cycle_time_s, 6.150);
    assert_ms(r.totals.per_tool[&1].rapid_s, 1.100);
    assert_ms(r.totals.per_tool[&2].cutting_s, 1.050);
    assert!((r.totals.distance_mm - 150.0).abs() < 1e-9);
    assert_eq!(r.timings.len(), 2);
    assert_ms(r.timings[1].start_s, 1.100);
}

#[test]
fn streaming_keeps_a_bounded_window() {
    // Timings come out while events are still being pushed.
    let m = lcnc_machine();
    let mut planner = Planner::new(&m);
    let mut seen = 0usize;
    let mut x = 0.0;
    for i in 0..1000 {
        let y = if i % 2 == 0 { 0.5 } else { 0.0 };
        let seg = Segment::line([x, 0.5 - y, 0.0], [x + 0.5, y, 0.0], f(3000.0), G64);
        x += 0.5;
        planner.push(Event::Motion(seg), &mut |_| seen += 1);
    }
    assert!(seen > 900, "only {seen} timings before finish");
    let mut rest = 0usize;
    let totals = planner.finish(&mut |_| rest += 1);
    assert!(rest <= m.lookahead as usize + 2);
    assert!(totals.motion_s > 0.0);
}

#[test]
fn generic_models_are_slower_with_jerk() {
    let mut m = lcnc_machine();
    m.planner = PlannerModel::Trapezoid;
    let segs = || vec![Segment::line([0.0; 3], [50.0, 0.0, 0.0], f(3000.0), G61)];
    let trap = motion(&m, segs());
    assert!((trap - 1.05).abs() < 1e-9, "trapezoid {trap}");
    m.planner = PlannerModel::Scurve;
    for a in &mut m.axes {
        a.jerk = 10_000.0;
    }
    // 50 mm/s < a²/j, so each ramp never reaches full acceleration and lasts
    // 2·sqrt(dv/j) instead of dv/a; half of the difference is lost per ramp.
    let s = motion(&m, segs());
    let expected = 1.05 + (2.0 * (50.0f64 / 10_000.0).sqrt() - 0.05);
    assert!((s - expected).abs() < 1e-9, "scurve {s}");
}

/// The INI measure_cycle_time.sh generates for its default machine.
const ORACLE_INI: &str = "\
[EMC]
VERSION = 1.1
MACHINE = cycle-time-sim
DEBUG = 0

[TRAJ]
COORDINATES = XYZ
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
DEFAULT_LINEAR_VELOCITY = 10.0
MAX_LINEAR_VELOCITY = 100
MAX_LINEAR_ACCELERATION = 1000

[KINS]
JOINTS = 3
KINEMATICS = trivkins coordinates=XYZ

[EMCMOT]
EMCMOT = motmod
COMM_TIMEOUT = 1.0
SERVO_PERIOD = 1000000

[RS274NGC]
PARAMETER_FILE = /tmp/lcnc_cycle.x/sim.var

[AXIS_X]
MIN_LIMIT = -100000
MAX_LIMIT = 100000
MAX_VELOCITY = 100
MAX_ACCELERATION = 1000

[JOINT_0]
TYPE = LINEAR
MIN_LIMIT = -100000
MAX_LIMIT = 100000
MAX_VELOCITY = 100
MAX_ACCELERATION = 1000
FERROR = 1e9
MIN_FERROR = 1e9
HOME = 0

[AXIS_Y]
MIN_LIMIT = -100000
MAX_LIMIT = 100000
MAX_VELOCITY = 50
MAX_ACCELERATION = 500

[JOINT_1]
TYPE = LINEAR
MAX_VELOCITY = 50
MAX_ACCELERATION = 500

[AXIS_Z]
MAX_VELOCITY = 20
MAX_ACCELERATION = 200

[JOINT_2]
TYPE = LINEAR
MAX_VELOCITY = 20
MAX_ACCELERATION = 200

[EMCIO]
EMCIO = io
CYCLE_TIME = 0.001
TOOL_TABLE = tool.tbl
";

#[test]
fn reads_oracle_ini() {
    let (p, extras) = MachineProfile::from_linuxcnc_ini(ORACLE_INI).expect("ini");
    assert_eq!(p.axes.len(), 3);
    assert_eq!(p.traj_max_velocity, 100.0);
    assert_eq!(p.traj_max_acceleration, 1000.0);
    assert_eq!(p.servo_period, 0.001);
    let y = p.axis('Y').expect("Y");
    assert_eq!((y.max_velocity, y.max_acceleration), (50.0, 500.0));
    let x = p.axis('x').expect("X");
    assert_eq!((x.min_travel, x.max_travel), (-100000.0, 100000.0));
    assert_eq!(p.axis('Z').expect("Z").max_velocity, 20.0);
    assert_eq!(extras.tool_table.as_deref(), Some("tool.tbl"));
    assert_eq!(
        extras.parameter_file.as_deref(),
        Some("/tmp/lcnc_cycle.x/sim.var")
    );
    assert_eq!(p.planner, PlannerModel::Linuxcnc);
}

#[test]
fn reads_inch_ini_with_joint_fallback_and_rotary() {
    let ini = "\
[TRAJ]
COORDINATES = X Y Z A
LINEAR_UNITS = inch
MAX_VELOCITY = 1.2
[JOINT_0]
MAX_VELOCITY = 1.2
MAX_ACCELERATION = 20.0
MIN_LIMIT = -10
MAX_LIMIT = 10
[JOINT_3]
MAX_VELOCITY = 90
MAX_ACCELERATION = 900
[TRAJ]
ARC_BLEND_OPTIMIZATION_DEPTH = 30
ARC_BLEND_KINK_RATIO = 0.2
";
    let (p, extras) = MachineProfile::from_linuxcnc_ini(ini).expect("ini");
    let x = p.axis('X').expect("X");
    assert!((x.max_velocity - 30.48).abs() < 1e-9);
    assert!((x.max_acceleration - 508.0).abs() < 1e-9);
    assert!((x.min_travel + 254.0).abs() < 1e-9);
    assert!((p.traj_max_velocity - 30.48).abs() < 1e-9);
    let a = p.axis('A').expect("A");
    assert_eq!(a.kind, AxisKind::Rotary);
    assert_eq!((a.max_velocity, a.max_acceleration), (90.0, 900.0));
    assert_eq!(p.lookahead, 30);
    assert_eq!(p.tangent_kink_ratio, 0.2);
    assert_eq!(extras.linear_units.as_deref(), Some("inch"));
    assert_eq!(extras.tool_table, None);
}

#[test]
fn bad_ini_number_is_an_error() {
    let err = MachineProfile::from_linuxcnc_ini("[AXIS_X]\nMAX_VELOCITY = fast\n");
    assert!(err.is_err());
}

#[test]
fn profile_toml_overrides_defaults() {
    let text = "
[machine]
traj_max_velocity = 250.0
tool_change_time = 6.5
planner = \"scurve\"
[[machine.axes]]
letter = \"X\"
max_velocity = 250.0
max_acceleration = 3000.0
";
    let p = MachineProfile::from_toml(text, analyzer::Dialect::Fanuc).expect("toml");
    assert_eq!(p.traj_max_velocity, 250.0);
    assert_eq!(p.tool_change_time, 6.5);
    assert_eq!(p.planner, PlannerModel::Scurve);
    assert_eq!(p.axes.len(), 1);
    assert_eq!(p.axes[0].max_acceleration, 3000.0);
    // Unstated fields keep FANUC's defaults (AI contour control: 40 blocks).
    assert_eq!(p.lookahead, 40);
    assert!(MachineProfile::from_toml("[machine]\nbogus = 1\n", analyzer::Dialect::Fanuc).is_err());
}

#[test]
fn block_processing_time_is_a_minimum_per_move() {
    let mut m = lcnc_machine();
    m.block_processing_time = 0.5;
    let t = motion(
        &m,
        vec![Segment::line([0.0; 3], [1.0, 0.0, 0.0], f(6000.0), G61)],
    );
    assert_ms(t, 0.5);
    let t = motion(
        &m,
        vec![Segment::line([0.0; 3], [50.0, 0.0, 0.0], f(3000.0), G61)],
    );
    assert_ms(t, 1.050);
}

#[test]
fn closed_form_execution_reproduces_expected_md() {
    let mut m = lcnc_machine();
    m.servo_simulation = false;
    let line = |a: [f64; 3], b: [f64; 3], feed: f64, mode| Segment::line(a, b, f(feed), mode);
    assert_ms(
        motion(&m, vec![line([0.0; 3], [50.0, 0.0, 0.0], 3000.0, G61)]),
        1.050,
    );
    assert_ms(
        motion(&m, vec![line([0.0; 3], [1.0, 0.0, 0.0], 6000.0, G61)]),
        0.064,
    );
    assert_ms(
        motion(
            &m,
            vec![
                line([0.0; 3], [50.0, 0.0, 0.0], 3000.0, G61),
                line([50.0, 0.0, 0.0], [50.0, 50.0, 0.0], 3000.0, G61),
            ],
        ),
        2.112,
    );
    let p = [
        [0.0, 0.0, 0.0],
        [50.0, 0.0, 0.0],
        [50.0, 50.0, 0.0],
        [0.0, 50.0, 0.0],
    ];
    let square: Vec<Segment> = (0..4)
        .map(|i| line(p[i], p[(i + 1) % 4], 3000.0, G64))
        .collect();
    assert_ms(motion(&m, square), 3.994);
    let circle = vec![
        Segment::rapid([0.0; 3], [10.0, 0.0, 0.0], G61),
        Segment::arc(
            [10.0, 0.0, 0.0],
            [0.0; 3],
            [0.0, 0.0, 1.0],
            -std::f64::consts::TAU,
            0.0,
            f(600.0),
            G61,
        ),
    ];
    assert_ms(motion(&m, circle), 6.504);
}

#[test]
fn naive_cam_joins_nearly_straight_g64p_moves() {
    let m = lcnc_machine();
    let pts = [
        [0.0, 0.0, 0.0],
        [1.0, 0.004, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.003, 0.0],
    ];
    let segs = |tol: f64| -> Vec<Event> {
        (0..3)
            .map(|i| {
                Event::Motion(
                    Segment::line(pts[i], pts[i + 1], f(3000.0), PathMode::blend(tol))
                        .with_block(i as u32),
                )
            })
            .collect()
    };
    // P0.01: all points lie within 0.01 mm of the chord, so one straight move.
    let joined = plan(&m, segs(0.01));
    assert_eq!(joined.timings.len(), 1);
    assert_eq!(joined.timings[0].block, 2);
    let chord = (9.0f64 + 0.003 * 0.003).sqrt();
    assert!((joined.timings[0].length - chord).abs() < 1e-12);
    // Without P nothing is joined: two blend arcs, and the middle move is so short
    // after both blends trimmed it that the second blend swallows its rest.
    let apart = plan(&m, segs(0.0));
    let kinds: Vec<(u32, bool)> = apart.timings.iter().map(|t| (t.block, t.blend)).collect();
    assert_eq!(kinds, vec![(0, false), (0, true), (1, true), (2, false)]);
    // P0.001 is tighter than the 0.004 mm bump: no joining either.
    assert!(plan(&m, segs(0.001)).timings.len() > 1);
}

#[test]
fn absurdly_slow_feed_finishes_quickly() {
    // 1 m at 0.001 mm/min would be 60 million seconds: planned in closed form.
    let m = lcnc_machine();
    let t = motion(
        &m,
        vec![Segment::line([0.0; 3], [1000.0, 0.0, 0.0], f(0.001), G61)],
    );
    assert!((t - 6.0e7).abs() / 6.0e7 < 1e-6, "{t}");
}

/// Deterministic pseudo-random numbers for the robustness test.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn random_programs_plan_to_finite_monotonic_times() {
    for (model, servo) in [
        (PlannerModel::Linuxcnc, true),
        (PlannerModel::Linuxcnc, false),
        (PlannerModel::Trapezoid, false),
        (PlannerModel::Scurve, false),
    ] {
        let mut m = lcnc_machine();
        m.planner = model;
        m.servo_simulation = servo;
        m.axes.push(Axis::rotary('A', 360.0, 3600.0));
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut p = [0.0f64; 6];
        let mut events = Vec::new();
        for i in 0..3000u32 {
            let r = rng.next();
            let mode = match (rng.next() * 4.0) as u32 {
                0 => PathMode::ExactStop,
                1 => PathMode::ExactPath,
                2 => PathMode::blend(0.0),
                _ => PathMode::blend(rng.next() * 0.1),
            };
            let scale = if rng.next() < 0.5 { 0.05 } else { 20.0 };
            let mut q = p;
            for v in q.iter_mut().take(3) {
                *v += (rng.next() - 0.5) * scale;
            }
            if rng.next() < 0.1 {
                q[3] += (rng.next() - 0.5) * 90.0;
            }
            let feed = 1.0 + rng.next() * 150.0;
            let mut seg = if r < 0.1 {
                Segment::rapid([p[0], p[1], p[2]], [q[0], q[1], q[2]], mode)
            } else if r < 0.3 {
                let c = [
                    p[0] + (rng.next() - 0.5) * scale,
                    p[1] + (rng.next() - 0.5) * scale,
                    p[2],
                ];
                let sweep = (rng.next() - 0.5) * 4.0 * std::f64::consts::PI;
                let rise = if rng.next() < 0.2 { rng.next() } else { 0.0 };
                let s = Segment::arc(
                    [p[0], p[1], p[2]],
                    c,
                    [0.0, 0.0, 1.0],
                    sweep,
                    rise,
                    feed,
                    mode,
                );
                q = [s.end[0], s.end[1], s.end[2], p[3], p[4], p[5]];
                s
            } else {
                Segment::line([p[0], p[1], p[2]], [q[0], q[1], q[2]], feed, mode)
            };
            seg.start[3] = p[3];
            seg.end[3] = q[3];
            events.push(Event::Motion(seg.with_block(i)));
            if rng.next() < 0.01 {
                events.push(Event::Dwell {
                    seconds: 0.1,
                    block: i,
                });
            }
            p = q;
        }
        let r = plan(&m, events);
        let t = &r.totals;
        assert!(
            t.motion_s.is_finite() && t.motion_s > 0.0,
            "{model:?}: {t:?}"
        );
        assert!((t.rapid_s + t.cutting_s - t.motion_s).abs() < 1e-6);
        assert!((t.cycle_time_s - t.motion_s - t.dwell_s).abs() < 1e-6);
        let mut last_end = 0.0;
        for s in &r.timings {
            assert!(
                s.start_s.is_finite() && s.end_s >= s.start_s,
                "{model:?}: {s:?}"
            );
            assert!(
                s.end_s >= last_end - 1e-9,
                "{model:?}: time went back at {s:?}"
            );
            assert!(s.peak_speed.is_finite() && s.peak_speed >= 0.0);
            last_end = s.end_s;
        }
    }
}

#[test]
fn rapid_rate_and_in_position_time_in_generic_models() {
    let mut m = MachineProfile::default_for(analyzer::Dialect::Fanuc);
    assert_eq!(m.planner, PlannerModel::Trapezoid);
    for a in &mut m.axes {
        a.rapid_rate = 50.0;
    }
    m.in_position_time = 0.25;
    let r = plan(
        &m,
        vec![
            Event::Motion(Segment::rapid(
                [0.0; 3],
                [100.0, 0.0, 0.0],
                PathMode::ExactStop,
            )),
            Event::Motion(Segment::line(
                [100.0, 0.0, 0.0],
                [50.0, 0.0, 0.0],
                f(3000.0),
                PathMode::ExactStop,
            )),
        ],
    );
    // Rapid at 50 mm/s: 100/50 + 50/1000; feed: 50/50 + 50/1000; two settles.
    assert!(
        (r.totals.motion_s - (2.05 + 1.05)).abs() < 1e-9,
        "{:?}",
        r.totals
    );
    assert!((r.totals.other_s - 0.5).abs() < 1e-12);
    assert!((r.totals.cycle_time_s - 3.6).abs() < 1e-9);
    assert!((r.timings[1].start_s - 2.3).abs() < 1e-9);
}
