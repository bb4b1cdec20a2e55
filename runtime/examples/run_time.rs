//! Times parsing and interpreting a file (developer aid for large programs).
//! Usage: run_time FILE [dialect] [values]
//! With `values` the run records expression values as the language server asks it to.
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else { return };
    let dialect = args
        .get(2)
        .and_then(|d| analyzer::Dialect::parse(d))
        .unwrap_or(analyzer::Dialect::Rs274ngc);
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
    let out = if args.get(3).is_some_and(|a| a == "values") {
        runtime::run_checkpointed_recording(&input, true, Some(runtime::ValueLimits::default()))
    } else {
        runtime::run(&input)
    };
    let t2 = std::time::Instant::now();
    println!(
        "blocks {} motions {} diagnostics {} recorded blocks {} parse {:?} run {:?}",
        program.blocks.len(),
        out.motions.len(),
        out.diagnostics.len(),
        out.values.as_ref().map_or(0, |v| v.len()),
        t1 - t0,
        t2 - t1
    );
}
