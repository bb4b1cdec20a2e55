//! Prints the canonical lines of an RS274/NGC file (developer aid for
//! comparing with LinuxCNC's `rs274`). Usage: canon FILE.ngc [TOOL.tbl] [VAR.var]
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        eprintln!("usage: canon FILE.ngc [TOOL.tbl] [VAR.var]");
        return;
    };
    let text = std::fs::read(path).unwrap_or_default();
    let tbl = args.get(2).and_then(|p| std::fs::read_to_string(p).ok());
    let var = args.get(3).and_then(|p| std::fs::read_to_string(p).ok());
    let settings = analyzer::Settings::new(analyzer::Dialect::Rs274ngc);
    let a = analyzer::analyze(text, &settings);
    let machine = toml::Table::new();
    let input = runtime::RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &runtime::NoResolver,
        step_budget: 10_000_000,
        emit_canon: true,
        tool_table: tbl.as_deref(),
        var_file: var.as_deref(),
    };
    let out = runtime::run(&input);
    for l in out.canon {
        println!("{l}");
    }
    for d in out.diagnostics {
        eprintln!("{} {}", d.code, d.message);
    }
}
