//! Times parsing, interpreting and planning a file (developer aid for large programs).
//! Usage: run_time FILE [dialect] [values | plan [REPEAT]]
//! With `values` the run records expression values as the language server asks it to.
//! With `plan` the run is then planned REPEAT times (default 3) with the dialect's
//! default profile, printing the cycle time and its bits so two builds can be compared.
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else { return };
    let dialect = args
        .get(2)
        .and_then(|d| analyzer::Dialect::parse(d))
        .unwrap_or(analyzer::Dialect::Rs274ngc);
    let mode = args.get(3).map(String::as_str);
    let text = std::fs::read(path).unwrap_or_default();
    let settings = analyzer::Settings::new(dialect);
    let t0 = std::time::Instant::now();
    let opts = analyzer::syntax::ParseOptions::new(dialect);
    let program = analyzer::syntax::parse(opts, text);
    let t1 = std::time::Instant::now();
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
    let out = if mode == Some("values") {
        runtime::run_checkpointed_recording(&input, true, Some(runtime::ValueLimits::default()))
    } else {
        runtime::run(&input)
    };
    let t2 = std::time::Instant::now();
    println!(
        "blocks {} motions {} events {} diagnostics {} recorded blocks {} parse {:?} run {:?}",
        program.blocks.len(),
        out.motions.len(),
        out.events.len(),
        out.diagnostics.len(),
        out.values.as_ref().map_or(0, |v| v.len()),
        t1 - t0,
        t2 - t1
    );
    if mode != Some("plan") {
        return;
    }
    let repeat: usize = args.get(4).and_then(|r| r.parse().ok()).unwrap_or(3);
    let profile = runtime::machine::MachineProfile::default_for(dialect);
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
