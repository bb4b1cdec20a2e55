//! A host stops a run through `Resolver::cancelled` (the language server's
//! `$/cancelRequest`): the interpreter polls it every `CANCEL_POLL_STEPS`
//! blocks and the planner every 1024 events.

use std::cell::Cell;
use std::sync::Arc;

use analyzer::syntax::{parse, ParseOptions};
use analyzer::{Dialect, FileId, Settings};
use runtime::{ResolvedFile, Resolver, CANCEL_POLL_STEPS};

/// Says "stop" from its `after`-th poll on, and counts the polls.
struct StopAfter {
    after: u32,
    polls: Cell<u32>,
}

impl Resolver for StopAfter {
    fn resolve(&self, _: &str, _: FileId) -> Option<ResolvedFile> {
        None
    }

    fn cancelled(&self) -> bool {
        self.polls.set(self.polls.get() + 1);
        self.polls.get() >= self.after
    }
}

/// One block before the loop, then three per pass: the `while`, the move
/// and the `endwhile`.
const ENDLESS: &str = "G91 F100\no100 while [1 GT 0]\nG1 X1\no100 endwhile\nM2\n";

fn run(resolver: &dyn Resolver, step_budget: u64) -> runtime::RunOutput {
    let settings = Settings::new(Dialect::Rs274ngc);
    let program = parse(
        ParseOptions::new(Dialect::Rs274ngc),
        Arc::<[u8]>::from(ENDLESS.as_bytes()),
    );
    let machine = analyzer::config::MachineConfig::default();
    runtime::run(&runtime::RunInput {
        program: &program,
        settings: &settings,
        machine: &machine,
        resolver,
        step_budget,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    })
}

#[test]
fn a_cancelled_run_stops_at_the_next_poll() {
    let stop = StopAfter {
        after: 3,
        polls: Cell::new(0),
    };
    let out = run(&stop, 1_000_000);
    assert_eq!(stop.polls.get(), 3);
    // Blocks 1..=3072 executed before the third poll stopped block 3072's
    // successor: 1 setup block, then one move per three blocks.
    assert_eq!(CANCEL_POLL_STEPS, 1024);
    assert_eq!(out.motions.len(), (3 * 1024 - 1) / 3);
    // Stopping is not the step budget running out.
    assert!(
        out.diagnostics.iter().all(|d| d.code != "F004"),
        "{:?}",
        out.diagnostics
    );
}

#[test]
fn a_host_that_never_cancels_runs_to_the_budget() {
    let never = StopAfter {
        after: u32::MAX,
        polls: Cell::new(0),
    };
    let out = run(&never, 30_000);
    assert_eq!(never.polls.get(), 30_000 / 1024);
    assert!(
        out.diagnostics.iter().any(|d| d.code == "F004"),
        "{:?}",
        out.diagnostics
    );
}

#[test]
fn the_planner_stops_when_asked_and_plans_in_full_otherwise() {
    let out = run(&runtime::NoResolver, 30_000);
    let profile = runtime::machine::MachineProfile::default_for(Dialect::Rs274ngc);
    assert!(runtime::dryrun::plan_run_until(&out, &profile, &|| true).is_none());
    let full = runtime::dryrun::plan_run(&out, &profile);
    let again = runtime::dryrun::plan_run_until(&out, &profile, &|| false)
        .expect("a plan that was not stopped");
    assert_eq!(again.totals.cycle_time_s, full.totals.cycle_time_s);
    assert!(full.totals.cycle_time_s > 0.0);
}
