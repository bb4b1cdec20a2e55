//! Canonical output against the LinuxCNC `rs274` goldens in
//! `../shared/oracle/examples/rs274` (read when present).

use std::path::{Path, PathBuf};

use analyzer::{Dialect, Settings};
use runtime::{run, NoResolver, RunInput};

/// LinuxCNC's sample tool table, the one the goldens were made with.
const SAMPLE_TBL: &str = "T1 P1 D0.125000 Z+0.511000 ;1/8 end mill\nT2 P2 D0.062500 Z+0.100000 ;1/16 end mill\nT3 P3 D0.201000 Z+1.273000 ;#7 tap drill\nT99999 P99999 Z+0.100000 ;big tool number\n";

fn examples() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/oracle/examples/rs274");
    if p.is_dir() {
        return Some(p);
    }
    let p = Path::new("/work/shared/oracle/examples/rs274");
    p.is_dir().then(|| p.to_path_buf())
}

/// Drops rs274's output counter exactly like `run_rs274.sh` does.
fn strip_counter(line: &str) -> String {
    let t = line.trim_start();
    let digits = t.bytes().take_while(u8::is_ascii_digit).count();
    if digits > 0 && t[digits..].starts_with(" N") {
        return t[digits..].to_string();
    }
    line.to_string()
}

pub fn canon_of(text: &str, var: Option<&str>) -> (Vec<String>, Vec<analyzer::Diagnostic>) {
    let settings = Settings::new(Dialect::Rs274ngc);
    let a = analyzer::analyze(text.as_bytes().to_vec(), &settings);
    let machine = analyzer::config::MachineConfig::default();
    let input = RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 1_000_000,
        motion_budget: u64::MAX,
        emit_canon: true,
        tool_table: Some(SAMPLE_TBL),
        var_file: var,
    };
    let out = run(&input);
    (out.canon, out.diagnostics)
}

fn check(name: &str) {
    let Some(dir) = examples() else { return };
    let ngc = std::fs::read_to_string(dir.join(format!("{name}.ngc"))).expect("ngc");
    let golden = std::fs::read_to_string(dir.join(format!("{name}.canon"))).expect("canon");
    let var = std::fs::read_to_string(dir.join(format!("{name}.var"))).ok();
    let expected: Vec<String> = golden.lines().map(strip_counter).collect();
    let (got, diags) = canon_of(&ngc, var.as_deref());
    if got != expected {
        let mut msg = String::new();
        for i in 0..got.len().max(expected.len()) {
            let g = got.get(i).map(String::as_str).unwrap_or("<none>");
            let e = expected.get(i).map(String::as_str).unwrap_or("<none>");
            msg.push_str(&format!(
                "{} {i:3} got {g}\n          want {e}\n",
                if g == e { " " } else { "!" }
            ));
        }
        panic!("{name}: canon differs (diagnostics {diags:?})\n{msg}");
    }
}

#[test]
fn t1_basic() {
    check("t1");
}

#[test]
fn t2_inch_planes() {
    check("t2_inch_planes");
}

#[test]
fn t3_misc() {
    check("t3_misc");
}

#[test]
fn t4_var() {
    check("t4_var");
}

#[test]
fn pr_print_msg() {
    check("pr");
}

#[test]
fn t5_advanced() {
    check("t5_adv");
}

#[test]
fn err_no_ijk() {
    check("err_no_ijk");
}

/// Our own programs with goldens from `rs274` (see tests/data/interp_canon/README.md).
fn check_local(name: &str) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/interp_canon");
    let ngc = std::fs::read_to_string(dir.join(format!("{name}.ngc"))).expect("ngc");
    let golden = std::fs::read_to_string(dir.join(format!("{name}.canon"))).expect("canon");
    let tbl = std::fs::read_to_string(dir.join(format!("{name}.tbl"))).expect("tbl");
    let settings = Settings::new(Dialect::Rs274ngc);
    let a = analyzer::analyze(ngc.as_bytes().to_vec(), &settings);
    let machine = analyzer::config::MachineConfig::default();
    let input = RunInput {
        program: &a.program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 1_000_000,
        motion_budget: u64::MAX,
        emit_canon: true,
        tool_table: Some(&tbl),
        var_file: None,
    };
    let out = run(&input);
    let expected: Vec<&str> = golden.lines().collect();
    let got: Vec<&str> = out.canon.iter().map(String::as_str).collect();
    assert_eq!(got, expected, "{name}: {:?}", out.diagnostics);
}

#[test]
fn local_o_words() {
    check_local("o_words");
}

#[test]
fn local_cycles_offsets() {
    check_local("cycles_offsets");
}

#[test]
fn local_comp_tlo_modes() {
    check_local("comp_tlo_modes");
}

#[test]
fn local_g28_g52_g43_1() {
    check_local("g28_g52_g43_1");
}

#[test]
fn local_comp_convex_concave() {
    check_local("comp_convex_concave");
}

#[test]
fn local_comp_arcs() {
    check_local("comp_arcs");
}

#[test]
fn local_g76_threading() {
    check_local("g76");
}

#[test]
fn local_taps_polar_rotation_formats() {
    check_local("taps_polar");
}

#[test]
fn local_m98_subs() {
    check_local("msubs");
}
