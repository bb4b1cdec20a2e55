//! Streaming runs (`run_streaming` + `StreamPlan`) give the same diagnostics and
//! cycle-time totals as the buffered path (`run_with_snapshots` + `plan_run`),
//! across chunk boundaries, with cutter compensation holding moves back, and on
//! both sides of the servo-simulation limit; so does `RunPlan` on an observed run.

use std::fmt::Write as _;
use std::sync::Arc;

use analyzer::syntax::{parse, ParseOptions, Program};
use analyzer::{Dialect, Settings};
use runtime::dryrun::{self, StreamPlan};
use runtime::machine::MachineProfile;
use runtime::plan::Totals;

fn program(dialect: Dialect, text: &str) -> Program {
    parse(
        ParseOptions::new(dialect),
        Arc::<[u8]>::from(text.as_bytes()),
    )
}

fn input<'a>(
    program: &'a Program,
    settings: &'a Settings,
    machine: &'a analyzer::config::MachineConfig,
) -> runtime::RunInput<'a> {
    runtime::RunInput {
        program,
        settings,
        machine,
        resolver: &runtime::NoResolver,
        step_budget: 10_000_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    }
}

/// (buffered totals, streamed totals, buffered motions, streamed motions); the
/// program is streamed once.
fn both(dialect: Dialect, text: &str) -> (Totals, Totals, usize, usize) {
    let p = program(dialect, text);
    let settings = Settings::new(dialect);
    let machine = analyzer::config::MachineConfig::default();
    let profile = MachineProfile::default_for(dialect);
    let buffered = runtime::run_with_snapshots(&input(&p, &settings, &machine), false);
    let dry = dryrun::plan_run(&buffered, &profile);
    let mut streamed_motions = 0;
    let mut passes = 0;
    let (streamed, totals) = dryrun::stream_totals(&profile, |sink| {
        passes += 1;
        runtime::run_streaming(&input(&p, &settings, &machine), &mut |m, e| {
            streamed_motions += m.len();
            sink(m, e)
        })
    });
    assert!(streamed.motions.is_empty() && streamed.events.is_empty());
    // Past the servo-simulation limit the kept chunks are planned again.
    assert_eq!(passes, 1);
    assert_eq!(
        format!("{:?}", buffered.diagnostics),
        format!("{:?}", streamed.diagnostics)
    );
    (dry.totals, totals, buffered.motions.len(), streamed_motions)
}

/// The plain `StreamPlan` says when a servo-simulated run needs a closed-form pass.
#[test]
fn stream_plan_asks_for_closed_form_beyond_servo_limit() {
    let dialect = Dialect::Rs274ngc;
    let settings = Settings::new(dialect);
    let machine = analyzer::config::MachineConfig::default();
    let profile = MachineProfile::default_for(dialect);
    assert!(profile.servo_simulation);
    let run = |text: &str, replay: usize| {
        let p = program(dialect, text);
        let mut plan = StreamPlan::new(&profile).with_replay_bytes(replay);
        runtime::run_streaming(&input(&p, &settings, &machine), &mut |m, e| plan.push(m, e));
        plan.finish()
    };
    // Three passes at 1 mm/min take more than four hours of naive motion time:
    // without the chunks kept the run must be streamed again.
    assert_eq!(run(&job(3, 1.0), 0), None);
    // With them (the default), the plan is closed-form from the start, as
    // `plan_run` makes it.
    let p = program(dialect, &job(3, 1.0));
    let buffered = runtime::run_with_snapshots(&input(&p, &settings, &machine), false);
    let want = dryrun::plan_run(&buffered, &profile).totals;
    assert!(want.cutting_s > dryrun::SERVO_SIMULATION_LIMIT_S);
    assert_eq!(run(&job(3, 1.0), dryrun::REPLAY_BYTES), Some(want));
    let short = run(&job(3, 1500.0), 0);
    assert!(
        short.as_ref().is_some_and(|t| t.cutting_s > 0.0),
        "{short:?}"
    );
}

/// A profile of zig-zag passes with tool changes, dwells, spindle stops and a
/// cutter-compensated contour every few hundred lines; `passes` sets the length.
fn job(passes: usize, feed: f64) -> String {
    let mut s =
        String::from("G21 G17 G90 G94 G40 G49 G80 G64 P0.01\nT1 M6\nS8000 M3\nG0 X0 Y0 Z5\n");
    for p in 0..passes {
        let _ = writeln!(s, "G1 Z-1 F{feed}");
        for k in 0..40 {
            let x = if k % 2 == 0 { 30.0 } else { 0.0 };
            let _ = writeln!(s, "X{x} Y{:.3}", p as f64 * 2.0 + k as f64 * 0.05);
        }
        if p % 25 == 7 {
            // Compensated square with an arc: the interpreter holds the last move back.
            s.push_str("G41 D0 G1 X5 Y5\nX20\nG3 X25 Y10 R5\nG1 Y20\nG40 X30 Y30\n");
        }
        if p % 50 == 13 {
            s.push_str("G4 P0.5\nM5\nT2 M6\nS9000 M3\n");
        }
        s.push_str("G0 Z5\n");
    }
    s.push_str("G0 Z50\nM5\nM30\n");
    s
}

#[test]
fn streamed_totals_equal_buffered_across_chunks() {
    // About 12 000 motions: three chunk boundaries, some inside compensated contours.
    let (buffered, streamed, nb, ns) = both(Dialect::Rs274ngc, &job(300, 1500.0));
    assert!(nb > 3 * 4096, "{nb} motions");
    assert_eq!(nb, ns);
    assert_eq!(buffered, streamed);
    // Six `G4 P0.5` dwells reach the planner through the event stream.
    assert_eq!(buffered.dwell_s, 3.0, "{buffered:?}");
}

#[test]
fn streamed_totals_equal_buffered_beyond_servo_limit() {
    // At 1 mm/min the naive motion time passes the four-hour servo-simulation limit
    // part-way through: the streamed planner must switch to closed form like plan_run.
    let (buffered, streamed, nb, ns) = both(Dialect::Rs274ngc, &job(3, 1.0));
    assert_eq!(nb, ns);
    assert!(buffered.cutting_s > dryrun::SERVO_SIMULATION_LIMIT_S);
    assert_eq!(buffered, streamed);
}

#[test]
fn streamed_totals_equal_buffered_fanuc() {
    let text = format!("%\nO1000\n{}%\n", job(120, 2000.0).replace("G64 P0.01", ""));
    let (buffered, streamed, nb, ns) = both(Dialect::Fanuc, &text);
    assert_eq!(nb, ns);
    assert_eq!(buffered, streamed);
}

/// The streamed per-block figures (`StreamPlan::with_blocks`) are the buffered
/// ones (`block_times`): times on the program clock, causes, dwell, auxiliary
/// time and lengths, across chunk boundaries and G64 chains the planner joins.
#[test]
fn streamed_blocks_equal_buffered_blocks() {
    let mut text = String::from("G21 G90 G64 P0.01 Q0.01\nM6 T1\nG0 X0 Y0 Z1\nG1 Z0 F600\n");
    for i in 0..6000 {
        let x = (i % 100) as f64 * 0.05;
        let y = (i / 100) as f64 * 0.5;
        writeln!(text, "G1 X{x:.3} Y{y:.3} F1800").unwrap();
        if i % 1500 == 0 {
            text.push_str("G4 P0.5\n");
        }
    }
    text.push_str("G0 Z5\nM2\n");
    let dialect = Dialect::Rs274ngc;
    let p = program(dialect, &text);
    let settings = Settings::new(dialect);
    let machine = analyzer::config::MachineConfig::from_toml("tool_change_time = 3.0").unwrap();
    let profile = dryrun::profile_from_table(&machine, dialect);
    let buffered = runtime::run_with_snapshots(&input(&p, &settings, &machine), false);
    let dry = dryrun::plan_run(&buffered, &profile);
    let mut plan = StreamPlan::new(&profile).with_blocks();
    runtime::run_streaming(&input(&p, &settings, &machine), &mut |m, e| plan.push(m, e));
    let (totals, blocks) = plan.finish_with_blocks().unwrap();
    assert_eq!(totals, dry.totals);
    let want = dryrun::block_times(&buffered, &dry);
    assert_eq!(blocks.len(), want.len());
    for (a, b) in blocks.iter().zip(&want) {
        let same = |x: f64, y: f64| (x - y).abs() <= 1e-9 * (1.0 + y.abs());
        assert_eq!((a.file, a.line), (b.file, b.line));
        assert!(
            same(a.start_s, b.start_s) && same(a.end_s, b.end_s) && same(a.time_s, b.time_s),
            "{a:?}\n{b:?}"
        );
        assert!(
            same(a.length_mm, b.length_mm) && same(a.dwell_s, b.dwell_s),
            "{a:?}\n{b:?}"
        );
        assert!(same(a.aux_s, b.aux_s) && same(a.causes.total_s(), b.causes.total_s()));
    }
    let sum: f64 = want.iter().map(|b| b.time_s).sum();
    assert!(
        (sum - dry.totals.cycle_time_s).abs() < 1e-6,
        "{sum} {}",
        dry.totals.cycle_time_s
    );
}

/// The language server's path: `RunPlan` fed by an observed checkpointed run
/// (motions kept in the output) gives exactly `plan_run`'s plan: totals, every
/// motion's and event's time and the per-block table, across chunk boundaries
/// and compensated contours; past the servo-simulation limit it says so.
#[test]
fn observed_run_plan_is_plan_run() {
    let dialect = Dialect::Rs274ngc;
    let settings = Settings::new(dialect);
    let machine = analyzer::config::MachineConfig::default();
    let profile = MachineProfile::default_for(dialect);
    for (passes, feed, over) in [(300, 3000.0, false), (3, 1.0, true)] {
        let p = program(dialect, &job(passes, feed));
        let mut plan = dryrun::RunPlan::new(&profile);
        let mut chunks = 0;
        let out = runtime::run_checkpointed_observed(
            &input(&p, &settings, &machine),
            true,
            None,
            &mut |m, e| {
                chunks += 1;
                plan.push(m, e, &|| false);
            },
        );
        assert_eq!(plan.over_limit(), over, "{passes} passes at F{feed}");
        let want = dryrun::plan_run(&out, &profile);
        if over {
            assert!(want.totals.cutting_s > dryrun::SERVO_SIMULATION_LIMIT_S);
            assert!(plan.finish(&out.events).is_none());
            continue;
        }
        assert!(
            out.motions.len() > 3 * 4096,
            "{} motions",
            out.motions.len()
        );
        assert!(chunks > 3, "{chunks} chunks");
        let got = plan.finish(&out.events).unwrap();
        assert_eq!(got.totals, want.totals);
        assert_eq!(got.motion_times, want.motion_times);
        assert_eq!(got.event_times, want.event_times);
        assert_eq!(got.event_seconds, want.event_seconds);
        assert_eq!(format!("{:?}", got.blocks), format!("{:?}", want.blocks));
        assert_eq!(want.totals.dwell_s, 3.0, "{:?}", want.totals);
    }
}
