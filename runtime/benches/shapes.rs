//! The benchmark matrix in process: every CAM program shape of
//! `scripts/gen_programs.py` (the shapes `scripts/bench_matrix.sh` times with the
//! CLI) in every dialect where it applies, through what `partscope check` does
//! (parse, static rules, interpreter) and what `partscope run --format json`
//! does (the same with the interpreter's motions into the streaming planner), on
//! one thread: the CLI runs the static rules (and the planner) on a second one.
//!
//!     cargo bench -p runtime --bench shapes
//!     PARTSCOPE_BENCH_LINES=500000 cargo bench -p runtime --bench shapes -- 'check/arcs'
//!
//! The programs are generated when the bench starts (Python 3); 20 000 lines
//! each unless `PARTSCOPE_BENCH_LINES` says otherwise. Throughput is in bytes of
//! program text, so shapes of different line lengths compare.

use std::path::Path;
use std::process::Command;
use std::sync::Arc;

use analyzer::{Dialect, Settings};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use runtime::dryrun;
use runtime::machine::MachineProfile;

const SHAPES: [&str; 6] = ["g1xyz", "surfacing", "arcs", "drilling", "fusion", "macro"];
const DIALECTS: [(&str, Dialect); 3] = [
    ("rs274ngc", Dialect::Rs274ngc),
    ("fanuc", Dialect::Fanuc),
    ("servoworks", Dialect::Servoworks),
];

/// The generated program, or `None` (with a note) when the generator cannot run
/// or does not write this shape for this dialect (Fusion output is FANUC and
/// RS274/NGC only).
fn program(shape: &str, dialect: &str, lines: usize) -> Option<Arc<[u8]>> {
    if shape == "fusion" && dialect == "servoworks" {
        return None;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/gen_programs.py");
    let out = Command::new("python3")
        .arg(script)
        .args([shape, "--dialect", dialect, "--lines", &lines.to_string()])
        .output();
    match out {
        Ok(o) if o.status.success() => Some(Arc::from(o.stdout)),
        Ok(o) => {
            eprintln!("{shape} {dialect}: {}", String::from_utf8_lossy(&o.stderr));
            None
        }
        Err(e) => {
            eprintln!("{shape} {dialect}: python3: {e}");
            None
        }
    }
}

/// What `check` and `run` give the interpreter besides the program.
fn input<'a>(
    parsed: &'a analyzer::Parsed,
    settings: &'a Settings,
    machine: &'a analyzer::config::MachineConfig,
) -> runtime::RunInput<'a> {
    let blocks = parsed.program.blocks.len();
    runtime::RunInput {
        program: &parsed.program,
        settings,
        machine,
        resolver: &runtime::NoResolver,
        step_budget: runtime::default_step_budget(blocks),
        motion_budget: runtime::default_motion_budget(blocks),
        emit_canon: false,
        tool_table: None,
        var_file: None,
    }
}

fn bench(c: &mut Criterion) {
    let lines = std::env::var("PARTSCOPE_BENCH_LINES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_000);
    let machine = analyzer::config::MachineConfig::default();
    let mut check = c.benchmark_group("check");
    check.sample_size(10);
    let mut programs = Vec::new();
    for shape in SHAPES {
        for (name, dialect) in DIALECTS {
            if let Some(text) = program(shape, name, lines) {
                programs.push((shape, name, dialect, text));
            }
        }
    }
    for (shape, name, dialect, text) in &programs {
        let settings = Settings::new(*dialect);
        check.throughput(Throughput::Bytes(text.len() as u64));
        check.bench_with_input(BenchmarkId::new(*shape, name), text, |b, text| {
            b.iter(|| {
                let parsed = analyzer::parse_text_lean(text.clone(), &settings);
                let statics = analyzer::lint(&parsed, &settings);
                let out =
                    runtime::run_streaming(&input(&parsed, &settings, &machine), &mut |_, _| {});
                let found = analyzer::finish(&parsed.program, &settings, out.diagnostics);
                analyzer::merge(statics, found, &settings).len()
            })
        });
    }
    check.finish();
    let mut run = c.benchmark_group("run");
    run.sample_size(10);
    for (shape, name, dialect, text) in &programs {
        let settings = Settings::new(*dialect);
        let profile = MachineProfile::default_for(*dialect);
        run.throughput(Throughput::Bytes(text.len() as u64));
        run.bench_with_input(BenchmarkId::new(*shape, name), text, |b, text| {
            b.iter(|| {
                let parsed = analyzer::parse_text_lean(text.clone(), &settings);
                let statics = analyzer::lint(&parsed, &settings);
                let (_, totals) = dryrun::stream_totals(&profile, |sink| {
                    runtime::run_streaming(&input(&parsed, &settings, &machine), sink)
                });
                (statics.len(), totals.cycle_time_s)
            })
        });
    }
    run.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
