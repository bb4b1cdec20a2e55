//! Output stays bounded on hostile cycle data (regressions found by fuzzing).

use std::sync::Arc;

use analyzer::syntax::{parse, ParseOptions};
use analyzer::{Dialect, Settings};

#[test]
fn peck_cycle_with_zero_q_is_reported_and_bounded() {
    // Found by the `interpret` fuzz target: Q0. made every hole 100 000 pecks and the
    // run ran out of memory. Now the hole is drilled in one peck and C002 reports Q.
    let text = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/robustness/crashes/interp-g83-q0-pecks.nc"
    ))
    .unwrap();
    let settings = Settings::new(Dialect::Servoworks);
    let program = parse(
        ParseOptions::new(Dialect::Servoworks),
        Arc::<[u8]>::from(text),
    );
    let machine = analyzer::config::MachineConfig::default();
    let out = runtime::run(&runtime::RunInput {
        program: &program,
        settings: &settings,
        machine: &machine,
        resolver: &runtime::NoResolver,
        step_budget: 10_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    });
    assert!(out.motions.len() < 200, "{} motions", out.motions.len());
    assert!(
        out.diagnostics.iter().any(|d| d.code == "C002"),
        "{:?}",
        out.diagnostics
    );
    // The first hole (Q2 from R2 to Z-10.55) still pecks: 7 feeds to the bottom.
    let first_hole_feeds = out
        .motions
        .iter()
        .take_while(|m| m.start[0].abs() < 1e-9)
        .filter(|m| m.kind == runtime::MotionKind::Feed)
        .count();
    assert_eq!(first_hole_feeds, 7);
}
