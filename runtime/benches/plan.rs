//! Planner throughput on CAM-like input: one million short G64 segments (a 3D
//! surfacing raster of 0.05–0.5 mm moves), streamed through the `linuxcnc` model.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use runtime::machine::MachineProfile;
use runtime::plan::{Event, PathMode, Planner, Segment};

const N: usize = 1_000_000;

/// Deterministic surfacing path: rows along X with a wavy Z, short steps.
fn segments() -> impl Iterator<Item = Segment> {
    let mut p = [0.0f64, 0.0, 0.0];
    let mut state = 0x2545_f491_4f6c_dd1du64;
    (0..N).map(move |i| {
        // xorshift: step lengths vary like CAM output does.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let step = 0.05 + (state % 1000) as f64 * 0.00045;
        let row = i / 2000;
        let dir = if row % 2 == 0 { 1.0 } else { -1.0 };
        let mut q = p;
        if i % 2000 == 0 {
            q[1] += 0.3;
        } else {
            q[0] += dir * step;
        }
        q[2] = 0.2 * (q[0] * 0.7).sin() * (q[1] * 0.3).cos();
        let s = Segment::line(p, q, 50.0, PathMode::blend(0.01)).with_block(i as u32);
        p = q;
        s
    })
}

fn bench(c: &mut Criterion) {
    let profile = MachineProfile::default();
    let mut g = c.benchmark_group("plan");
    g.sample_size(10);
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("linuxcnc_1M_short_segments", |b| {
        b.iter(|| {
            let mut planner = Planner::new(&profile);
            let mut n = 0usize;
            for s in segments() {
                planner.push(Event::Motion(s), &mut |_| n += 1);
            }
            let totals = planner.finish(&mut |_| n += 1);
            (n, totals.motion_s)
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
