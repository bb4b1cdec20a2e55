//! Helpers shared by the interpreter tests.
#![allow(dead_code)]

use std::collections::HashMap;

use analyzer::{Dialect, FileId, Settings};
use runtime::{run, Motion, MotionKind, ResolvedFile, Resolver, RunInput, RunOutput};

/// Resolves names from an in-memory map (`name` → text), case-insensitively.
pub struct MapResolver(pub HashMap<String, String>);

impl Resolver for MapResolver {
    fn resolve(&self, name: &str, _from: FileId) -> Option<ResolvedFile> {
        let key = name.to_ascii_lowercase();
        self.0.get(&key).map(|t| ResolvedFile {
            path: format!("{name}.dat"),
            text: t.as_bytes().to_vec().into(),
        })
    }
}

pub fn run_with(
    dialect: Dialect,
    text: &str,
    machine: &str,
    files: &[(&str, &str)],
    tools: Option<&str>,
) -> RunOutput {
    run_full(dialect, text, machine, files, tools, None)
}

/// `run_with` plus a LinuxCNC `.var` file.
pub fn run_full(
    dialect: Dialect,
    text: &str,
    machine: &str,
    files: &[(&str, &str)],
    tools: Option<&str>,
    var_file: Option<&str>,
) -> RunOutput {
    run_full_sel(dialect, text, machine, files, tools, var_file, None)
}

/// `run_full` with one extra rule selected (rules that are off by default).
pub fn run_full_sel(
    dialect: Dialect,
    text: &str,
    machine: &str,
    files: &[(&str, &str)],
    tools: Option<&str>,
    var_file: Option<&str>,
    select: Option<&str>,
) -> RunOutput {
    let mut settings = Settings::new(dialect);
    if let Some(code) = select {
        settings.select = vec!["ALL".into(), code.into()];
    }
    let a = analyzer::analyze(text.as_bytes().to_vec(), &settings);
    let machine = analyzer::config::MachineConfig::from_toml(machine).expect("machine toml");
    let resolver = MapResolver(
        files
            .iter()
            .map(|(n, t)| (n.to_ascii_lowercase(), t.to_string()))
            .collect(),
    );
    let input = RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &resolver,
        step_budget: 100_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: tools,
        var_file,
    };
    run(&input)
}

pub fn run_sw(text: &str, machine: &str) -> RunOutput {
    run_with(Dialect::Servoworks, text, machine, &[], None)
}

pub fn run_fanuc(text: &str, machine: &str) -> RunOutput {
    run_with(Dialect::Fanuc, text, machine, &[], None)
}

pub fn run_ngc(text: &str) -> RunOutput {
    run_with(Dialect::Rs274ngc, text, "", &[], None)
}

pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[track_caller]
pub fn assert_pt(got: [f64; 6], want: &[f64], tol: f64) {
    for (i, w) in want.iter().enumerate() {
        assert!(
            close(got[i], *w, tol),
            "axis {i}: got {got:?}, want {want:?}"
        );
    }
}

/// Codes of the diagnostics.
pub fn codes(out: &RunOutput) -> Vec<&'static str> {
    out.diagnostics.iter().map(|d| d.code).collect()
}

/// Ends of the motions (XYZ).
pub fn ends(out: &RunOutput) -> Vec<[f64; 3]> {
    out.motions
        .iter()
        .map(|m| [m.end[0], m.end[1], m.end[2]])
        .collect()
}

pub fn is_rapid(m: &Motion) -> bool {
    matches!(m.kind, MotionKind::Rapid)
}

pub fn is_feed(m: &Motion) -> bool {
    matches!(m.kind, MotionKind::Feed)
}

/// Length of a motion (arcs: in-plane sweep × radius, combined with the helix rise).
pub fn length(m: &Motion) -> f64 {
    match m.kind {
        MotionKind::Arc {
            center,
            normal,
            turns,
            radius,
        } => {
            let n = if normal[2] != 0.0 {
                2
            } else if normal[1] != 0.0 {
                1
            } else {
                0
            };
            let (a, b) = match n {
                2 => (0, 1),
                1 => (2, 0),
                _ => (1, 2),
            };
            let sign = normal[n].signum();
            let a0 = (m.start[b] - center[b]).atan2(m.start[a] - center[a]);
            let a1 = (m.end[b] - center[b]).atan2(m.end[a] - center[a]);
            let mut d = (a1 - a0) * sign;
            while d <= 1e-9 {
                d += std::f64::consts::TAU;
            }
            d += std::f64::consts::TAU * turns as f64;
            (d * radius).hypot(m.end[n] - m.start[n])
        }
        _ => {
            let d: f64 = (0..3).map(|i| (m.end[i] - m.start[i]).powi(2)).sum();
            d.sqrt()
        }
    }
}
