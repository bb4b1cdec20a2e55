//! Cycle time of the whole pipeline (`partscope run --machine X.ini --format json`)
//! against LinuxCNC 2.9's trajectory planner measured by
//! `/work/shared/oracle/measure_cycle_time.sh` (goldens in tests/cycle_time/).

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The LinuxCNC `.ini` the oracle generated for a machine (the parts our reader uses),
/// mirroring `mkconfig.py` in measure_cycle_time.sh: rotary axes get 360 deg/s and
/// 3600 deg/s².
fn ini(coords: &str, vel: f64, acc: f64, over: &[(char, f64, f64)]) -> String {
    let mut s = format!(
        "[EMC]\nVERSION = 1.1\n[TRAJ]\nCOORDINATES = {coords}\nLINEAR_UNITS = mm\nANGULAR_UNITS = degree\n\
         DEFAULT_LINEAR_VELOCITY = {}\nMAX_LINEAR_VELOCITY = {vel}\nMAX_LINEAR_ACCELERATION = {acc}\n\
         [KINS]\nJOINTS = {}\nKINEMATICS = trivkins coordinates={coords}\n[EMCMOT]\nSERVO_PERIOD = 1000000\n[RS274NGC]\n",
        vel / 10.0,
        coords.len()
    );
    for (j, c) in coords.chars().enumerate() {
        let rotary = "ABC".contains(c);
        let (v, a) = if rotary { (360.0, 3600.0) } else { (vel, acc) };
        let (v, a) = over
            .iter()
            .find(|o| o.0 == c)
            .map(|o| (o.1, o.2))
            .unwrap_or((v, a));
        let (lo, hi, kind) = if rotary {
            ("-1e9", "1e9", "ANGULAR")
        } else {
            ("-100000", "100000", "LINEAR")
        };
        s += &format!(
            "[AXIS_{c}]\nMIN_LIMIT = {lo}\nMAX_LIMIT = {hi}\nMAX_VELOCITY = {v}\nMAX_ACCELERATION = {a}\n\
             [JOINT_{j}]\nTYPE = {kind}\nMIN_LIMIT = {lo}\nMAX_LIMIT = {hi}\nMAX_VELOCITY = {v}\nMAX_ACCELERATION = {a}\n"
        );
    }
    s
}

#[test]
fn motion_time_matches_linuxcnc_goldens() {
    let dir = std::env::temp_dir().join(format!("partscope-ct-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let machines = [
        ("m100", ini("XYZ", 100.0, 1000.0, &[])),
        ("m60", ini("XYZ", 60.0, 800.0, &[])),
        (
            "mixed",
            ini(
                "XYZ",
                100.0,
                1000.0,
                &[('Y', 50.0, 500.0), ('Z', 20.0, 200.0)],
            ),
        ),
        ("rot", ini("XYZA", 100.0, 1000.0, &[])),
        // The inch machine's INI is the one LinuxCNC ran, committed as data.
        (
            "inch",
            std::fs::read_to_string(repo().join("tests/cycle_time/machines/inch.ini")).unwrap(),
        ),
    ];
    for (name, text) in &machines {
        std::fs::write(dir.join(format!("{name}.ini")), text).unwrap();
    }
    let goldens = std::fs::read_to_string(repo().join("tests/cycle_time/goldens.tsv")).unwrap();
    let mut errors = Vec::new();
    let mut report = String::new();
    for line in goldens.lines().skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        let (prog, machine, golden): (&str, &str, f64) = (f[0], f[1], f[2].parse().unwrap());
        let out = Command::new(env!("CARGO_BIN_EXE_partscope"))
            .args(["run", "--format", "json", "--machine"])
            .arg(dir.join(format!("{machine}.ini")))
            .arg(repo().join(format!("tests/cycle_time/programs/{prog}.ngc")))
            .output()
            .unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("{prog}: {e}: {}", String::from_utf8_lossy(&out.stderr)));
        let ours = v["motion_s"].as_f64().unwrap();
        let rel = (ours - golden) / golden * 100.0;
        report +=
            &format!("{prog:28} {machine:6} golden {golden:8.3} ours {ours:8.3} {rel:+6.2}%\n");
        errors.push(rel.abs());
    }
    errors.sort_by(f64::total_cmp);
    let median = errors[errors.len() / 2];
    let max = errors[errors.len() - 1];
    println!(
        "{report}{} programs: median |error| {median:.3}%, max {max:.3}%",
        errors.len()
    );
    assert!(errors.len() >= 100, "goldens missing");
    assert!(median <= 1.0, "median |error| {median:.3}% > 1%\n{report}");
    assert!(max <= 3.0, "max |error| {max:.3}% > 3%\n{report}");
}
