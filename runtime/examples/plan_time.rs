//! Times the planner on a file's run (developer aid for large programs): the
//! interpreter once, then `dryrun::plan_run` with the dialect's default profile
//! REPEAT times, printing the cycle time and its bits so runs of two builds can
//! be compared.
//! Usage: plan_time FILE [dialect] [REPEAT]
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else { return };
    let dialect = args
        .get(2)
        .and_then(|d| analyzer::Dialect::parse(d))
        .unwrap_or(analyzer::Dialect::Rs274ngc);
    let repeat: usize = args.get(3).and_then(|r| r.parse().ok()).unwrap_or(3);
    let text = std::fs::read(path).unwrap_or_default();
    let settings = analyzer::Settings::new(dialect);
    let program = analyzer::syntax::parse_lean(analyzer::syntax::ParseOptions::new(dialect), text);
    let machine = analyzer::config::MachineConfig::default();
    let input = runtime::RunInput {
        program: &program,
        settings: &settings,
        machine: &machine,
        resolver: &runtime::NoResolver,
        step_budget: 100_000_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    };
    let t0 = std::time::Instant::now();
    let out = runtime::run(&input);
    let t1 = std::time::Instant::now();
    let profile = runtime::machine::MachineProfile::default_for(dialect);
    println!(
        "motions {} events {} run {:?}",
        out.motions.len(),
        out.events.len(),
        t1 - t0
    );
    for _ in 0..repeat {
        let t = std::time::Instant::now();
        let plan = runtime::dryrun::plan_run(&out, &profile);
        let elapsed = t.elapsed();
        let blocks: f64 = plan.blocks.iter().map(|b| b.time_s).sum();
        println!(
            "plan {elapsed:?}: cycle {} ({:#x}) motion {:#x} blocks {} ({:#x})",
            plan.totals.cycle_time_s,
            plan.totals.cycle_time_s.to_bits(),
            plan.totals.motion_s.to_bits(),
            plan.blocks.len(),
            blocks.to_bits()
        );
    }
}
