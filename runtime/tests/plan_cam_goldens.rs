//! Cycle time of CAM-shaped programs against LinuxCNC 2.9 measurements
//! (`tests/cycle_time/cam/goldens.tsv`, written by `tests/cycle_time/cam/regenerate.sh`
//! from the programs of `scripts/gen_cam_programs.py`).
//!
//! Unlike `plan_goldens`, these programs go through the real interpreter (planes,
//! G64 Q, block delete, M6 and spindle words), then the planner.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;

use analyzer::Dialect;
use common::run_with;
use runtime::dryrun::planner_events;
use runtime::machine::{Axis, MachineProfile};
use runtime::plan::{plan, Event};

/// The validation data; `CAM_GOLDENS_DIR` points the test at another set laid out
/// the same way (for investigating new programs before they become goldens).
fn root() -> PathBuf {
    match std::env::var("CAM_GOLDENS_DIR") {
        Ok(d) => PathBuf::from(d),
        Err(_) => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/cycle_time/cam"),
    }
}

/// The machines of `cam/regenerate.sh`: the profile, and the machine TOML the
/// interpreter reads. LinuxCNC starts with block delete on (`bdoff`: switched off).
fn machine(name: &str) -> (MachineProfile, &'static str) {
    let mut p = MachineProfile::default_for(Dialect::Rs274ngc);
    let (vel, acc, y, z) = match name {
        "m60" | "m60bdoff" => (60.0, 800.0, (60.0, 800.0), (60.0, 800.0)),
        "mixed" => (100.0, 1000.0, (50.0, 500.0), (20.0, 200.0)),
        other => panic!("unknown machine {other}"),
    };
    p.axes = vec![
        Axis::linear('X', vel, acc),
        Axis::linear('Y', y.0, y.1),
        Axis::linear('Z', z.0, z.1),
    ];
    p.traj_max_velocity = vel;
    p.traj_max_acceleration = acc;
    let toml = if name == "m60bdoff" {
        "block_skip = false"
    } else {
        "block_skip = true"
    };
    (p, toml)
}

struct Row {
    class: String,
    program: String,
    machine: String,
    lcnc: f64,
    ours: f64,
    naive: f64,
}

fn evaluate() -> Vec<Row> {
    let goldens = std::fs::read_to_string(root().join("goldens.tsv")).expect("goldens.tsv");
    let only = std::env::var("CAM_ONLY").unwrap_or_default();
    let mut rows = Vec::new();
    for line in goldens.lines().skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        let (program, mname, lcnc) = (f[0], f[1], f[2].parse::<f64>().expect("motion_s"));
        if !program.contains(only.as_str()) {
            continue;
        }
        let text = std::fs::read_to_string(root().join("programs").join(format!("{program}.ngc")))
            .expect("program");
        let (profile, toml) = machine(mname);
        let out = run_with(Dialect::Rs274ngc, &text, toml, &[], None);
        assert!(
            out.stopped.is_none(),
            "{program}: the interpreter stopped: {:?}",
            out.stopped
        );
        let events = planner_events(&out);
        let naive: f64 = events
            .iter()
            .filter_map(|e| match e {
                Event::Motion(s) => Some(*s),
                _ => None,
            })
            .map(|s| {
                // Distance over feed, the feed capped at the machine's speed.
                let v = if matches!(s.kind, runtime::plan::SegmentKind::Rapid) {
                    profile.traj_max_velocity
                } else {
                    s.feed.min(profile.traj_max_velocity)
                };
                if v > 0.0 {
                    s.length / v
                } else {
                    0.0
                }
            })
            .sum();
        let res = plan(&profile, events);
        if std::env::var("CAM_DEBUG").as_deref() == Ok(program) {
            for t in &res.timings {
                println!(
                    "  blk {} blend {} len {:.4} v0 {:.2} vp {:.2} ve {:.2} dt {:.4}",
                    t.block,
                    t.blend,
                    t.length,
                    t.entry_speed,
                    t.peak_speed,
                    t.exit_speed,
                    t.end_s - t.start_s
                );
            }
        }
        let ours = res.totals.motion_s;
        rows.push(Row {
            class: program.split("__").next().unwrap_or(program).to_string(),
            program: program.to_string(),
            machine: mname.to_string(),
            lcnc,
            ours,
            naive,
        });
    }
    rows
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        0.0
    } else {
        v[v.len() / 2]
    }
}

fn max(v: &[f64]) -> f64 {
    v.iter().cloned().fold(0.0, f64::max)
}

/// The model names the LinuxCNC the goldens were measured with.
#[test]
fn the_model_names_the_oracle() {
    let oracle = std::fs::read_to_string(root().join("oracle.txt")).expect("oracle.txt");
    assert_eq!(
        runtime::machine::model_reference(runtime::machine::PlannerModel::Linuxcnc),
        Some(oracle.trim())
    );
}

#[test]
fn cam_goldens_match_linuxcnc() {
    let rows = evaluate();
    println!("program\tmachine\tlinuxcnc\tours\terr_%\tnaive\tnaive_err_%");
    for r in &rows {
        println!(
            "{}\t{}\t{:.4}\t{:.4}\t{:+.2}\t{:.4}\t{:+.1}",
            r.program,
            r.machine,
            r.lcnc,
            r.ours,
            (r.ours - r.lcnc) / r.lcnc * 100.0,
            r.naive,
            (r.naive - r.lcnc) / r.lcnc * 100.0
        );
    }
    let rel = |r: &Row, v: f64| (v - r.lcnc).abs() / r.lcnc * 100.0;
    let mut classes: BTreeMap<&str, Vec<&Row>> = BTreeMap::new();
    for r in &rows {
        classes.entry(r.class.as_str()).or_default().push(r);
    }
    println!("| class | runs | median abs err | max abs err | naive median | naive max |");
    println!("|---|---|---|---|---|---|");
    let line = |name: &str, rs: &[&Row]| {
        let ours: Vec<f64> = rs.iter().map(|r| rel(r, r.ours)).collect();
        let naive: Vec<f64> = rs.iter().map(|r| rel(r, r.naive)).collect();
        println!(
            "| {name} | {} | {:.2} % | {:.2} % | {:.1} % | {:.1} % |",
            rs.len(),
            median(ours.clone()),
            max(&ours),
            median(naive.clone()),
            max(&naive)
        );
    };
    for (c, rs) in &classes {
        line(c, rs);
    }
    let all: Vec<&Row> = rows.iter().collect();
    line("all", &all);
    if !std::env::var("CAM_ONLY").unwrap_or_default().is_empty()
        || std::env::var("CAM_GOLDENS_DIR").is_ok()
    {
        return;
    }
    assert!(
        rows.len() >= 200,
        "expected the full set, got {}",
        rows.len()
    );
    let ours: Vec<f64> = rows.iter().map(|r| rel(r, r.ours)).collect();
    // What a user quoting from the estimate relies on (issue #19's hold-out targets).
    assert!(median(ours.clone()) <= 1.0, "median {:.2} %", median(ours));
    for r in &rows {
        assert!(
            rel(r, r.ours) <= 3.0,
            "{} on {}: ours {:.4} s, LinuxCNC {:.4} s",
            r.program,
            r.machine,
            r.ours,
            r.lcnc
        );
    }
}
