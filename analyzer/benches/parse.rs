//! Parse throughput on a generated ~1M-line CAM-style program.
//!
//! The program is generated in memory, deterministically (a fixed-seed LCG),
//! in the shape of 3D surfacing output: mostly `X… Z…` blocks of a few
//! tenths of a millimetre, with a feed change every few hundred blocks and
//! periodic row changes. Run with `cargo bench -p analyzer --bench parse`.

use std::fmt::Write as _;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

use analyzer::dialect::Dialect;
use analyzer::syntax::{parse, parse_lean, ParseOptions, Program};
use analyzer::Settings;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

const LINES: usize = 1_000_000;

/// A tiny deterministic generator so the benchmark input never changes.
struct Lcg(u64);

impl Lcg {
    fn next_f64(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn surface_z(x: f64, y: f64) -> f64 {
    -2.0 + 1.5 * (x / 17.0).sin() * (y / 11.0).cos() + 0.4 * ((x + y) / 5.0).sin()
}

/// Generates a surfacing program of about `lines` lines for `dialect`.
fn surfacing(dialect: Dialect, lines: usize) -> Vec<u8> {
    let mut s = String::with_capacity(lines * 20);
    let mut rng = Lcg(0x5eed);
    match dialect {
        Dialect::Servoworks => s.push_str("%\nG90 G17 G21 G40 G49 G80\nT03 M6\nG43 H3 Z50.\n"),
        Dialect::Rs274ngc => s.push_str("G21 G17 G90 G94 G40 G49 G80 G64 P0.01\nT3 M6\nG43 H3\n"),
        Dialect::Fanuc => {
            s.push_str("%\nO1000 (SURFACING)\nG21 G17 G90 G94 G40 G49 G80\nT3 M6\nG43 H3 Z50.\n")
        }
    }
    s.push_str("S12000 M3\nG0 X0. Y0. Z5.\nG1 Z-2. F800.\n");
    let (mut x, mut y, mut dir) = (0.0f64, 0.0f64, 1.0f64);
    let mut n = 0usize;
    while n < lines {
        x += dir * (0.08 + 0.12 * rng.next_f64());
        if !(0.0..=120.0).contains(&x) {
            x = x.clamp(0.0, 120.0);
            y += 0.25;
            dir = -dir;
            let _ = writeln!(s, "Y{:.4} Z{:.4}", y, surface_z(x, y));
        } else if n.is_multiple_of(500) {
            let _ = writeln!(s, "G1 X{:.4} Y{:.4} Z{:.4} F2000.", x, y, surface_z(x, y));
        } else {
            let _ = writeln!(s, "X{:.4} Z{:.4}", x, surface_z(x, y));
        }
        n += 1;
    }
    s.push_str("G0 Z50.\nM5\nM30\n");
    if dialect != Dialect::Rs274ngc {
        s.push_str("%\n");
    }
    s.into_bytes()
}

/// Ten samples of a 20 MB parse take a few seconds; criterion's defaults (100
/// samples, 5 s) would stretch each benchmark to minutes on a shared machine.
fn short(group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
}

/// One criterion group timing `parse` on the surfacing program of every dialect.
fn parse_group(c: &mut Criterion, name: &str, parse: fn(ParseOptions, Arc<[u8]>) -> Program) {
    let mut group = c.benchmark_group(name);
    short(&mut group);
    for dialect in Dialect::ALL {
        let text: Arc<[u8]> = surfacing(dialect, LINES).into();
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_function(dialect.as_str(), |b| {
            b.iter(|| {
                let program = parse(ParseOptions::new(dialect), text.clone());
                black_box(program.blocks.len())
            })
        });
    }
    group.finish();
}

fn bench_parse(c: &mut Criterion) {
    parse_group(c, "parse_1M_lines", parse);
    // Without tokens, as the command line parses.
    parse_group(c, "parse_lean_1M_lines", parse_lean);

    // Parse and static rules, as `analyze` runs them.
    let mut group = c.benchmark_group("analyze_1M_lines");
    short(&mut group);
    for dialect in Dialect::ALL {
        let text: Arc<[u8]> = surfacing(dialect, LINES).into();
        let settings = Settings::new(dialect);
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_function(dialect.as_str(), |b| {
            b.iter(|| black_box(analyzer::analyze(text.clone(), &settings).diagnostics.len()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_parse);
criterion_main!(benches);
