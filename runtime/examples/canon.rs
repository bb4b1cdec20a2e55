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
    let dir = std::path::Path::new(path)
        .parent()
        .map(|p| p.to_path_buf())
        .unwrap_or_default();
    let resolver = DirResolver(dir);
    let a = analyzer::analyze(text, &settings);
    let machine = analyzer::config::MachineConfig::default();
    let input = runtime::RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &resolver,
        step_budget: 10_000_000,
        motion_budget: u64::MAX,
        emit_canon: true,
        tool_table: tbl.as_deref(),
        var_file: var.as_deref(),
    };
    let out = runtime::run(&input);
    let _ = &resolver;
    for l in out.canon {
        println!("{l}");
    }
    for d in out.diagnostics {
        eprintln!("{} {}", d.code, d.message);
    }
}

/// Finds `name.ngc` next to the main file.
struct DirResolver(std::path::PathBuf);

impl runtime::Resolver for DirResolver {
    fn resolve(&self, name: &str, _from: analyzer::FileId) -> Option<runtime::ResolvedFile> {
        let p = self.0.join(format!("{name}.ngc"));
        let text = std::fs::read(&p).ok()?;
        Some(runtime::ResolvedFile {
            path: p.display().to_string(),
            text: text.into(),
        })
    }
}
