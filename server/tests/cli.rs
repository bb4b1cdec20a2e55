//! End-to-end tests of `partscope check` and `partscope rule` against the built binary.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_partscope"))
}

fn tempdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("partscope-cli-{}-{}", name, std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &Path, name: &str, text: &[u8]) -> PathBuf {
    let p = dir.join(name);
    if let Some(parent) = p.parent() {
        std::fs::create_dir_all(parent).unwrap();
    }
    std::fs::write(&p, text).unwrap();
    p
}

fn check_json(args: &[&str]) -> (i32, Vec<Value>) {
    let out = bin()
        .arg("check")
        .arg("--format")
        .arg("json")
        .args(args)
        .output()
        .unwrap();
    let code = out.status.code().unwrap_or(-1);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "not JSON ({e}): {}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (code, v.as_array().cloned().unwrap_or_default())
}

fn codes(diags: &[Value]) -> Vec<(String, u64, String)> {
    diags
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap_or("").to_string(),
                d["line"].as_u64().unwrap_or(0),
                d["severity"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect()
}

#[test]
fn json_output_has_documented_fields_and_exit_1() {
    let d = tempdir("json");
    let f = write(&d, "a.ngc", "G0 X1\nG1 X1.2.3 F100 (open\nM2\n".as_bytes());
    let (code, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!(code, 1);
    let first = &diags[0];
    for key in [
        "path",
        "line",
        "column",
        "end_line",
        "end_column",
        "code",
        "name",
        "severity",
        "message",
    ] {
        assert!(first.get(key).is_some(), "missing {key} in {first}");
    }
    let c = codes(&diags);
    assert!(c.contains(&("L004".into(), 2, "error".into())), "{c:?}");
    assert!(c.contains(&("L001".into(), 2, "error".into())), "{c:?}");
    let l004 = diags.iter().find(|d| d["code"] == "L004").unwrap();
    assert_eq!(
        (l004["column"].as_u64(), l004["end_column"].as_u64()),
        (Some(5), Some(10))
    );
    assert_eq!(l004["name"], "malformed-number");
}

#[test]
fn clean_file_exits_0_and_unreadable_exits_2() {
    let d = tempdir("clean");
    let f = write(&d, "ok.ngc", b"G0 X1\nM2\n");
    let (code, diags) = check_json(&[f.to_str().unwrap()]);
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(code, 0);
    let missing = d.join("missing.ngc");
    let (code, diags) = check_json(&[missing.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert_eq!(codes(&diags)[0].0, "L000");
}

#[test]
fn binary_file_is_one_diagnostic() {
    let d = tempdir("bin");
    let mut junk = vec![0u8, 1, 2, 255, 254, 0, 7];
    junk.extend(std::iter::repeat_n(0u8, 4000));
    let f = write(&d, "junk.nc", &junk);
    let (code, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert_eq!(
        codes(&diags),
        vec![("L009".to_string(), 1, "error".to_string())]
    );
}

#[test]
fn config_is_discovered_upward_and_selects_dialect_and_rules() {
    let d = tempdir("config");
    write(
        &d,
        "partscope.toml",
        b"dialect = \"servoworks\"\n[rules]\nignore = [\"L013\"]\n",
    );
    // Lower case is ignored by ServoWorks (L008), `;` prose would be L013 but is ignored by config.
    let f = write(&d, "sub/dir/p.nc", b"G01 x10.0 F100.0\nG80; cancel\nM30\n");
    let (_, diags) = check_json(&[f.to_str().unwrap()]);
    let c: Vec<String> = codes(&diags).into_iter().map(|c| c.0).collect();
    assert!(c.contains(&"L008".to_string()), "{c:?}");
    assert!(!c.contains(&"L013".to_string()), "{c:?}");
    // --dialect overrides the config: RS274/NGC is case-insensitive.
    let (_, diags) = check_json(&["--dialect", "rs274ngc", f.to_str().unwrap()]);
    assert!(!codes(&diags).iter().any(|c| c.0 == "L008"));
}

#[test]
fn check_reads_the_linuxcnc_files_a_config_names() {
    // rs274 -t t.tbl stops at `T5 M6` with "Requested tool 5 not found in the tool
    // table"; check must see the same table through `tool_table` or the ini's
    // TOOL_TABLE, relative to the config file.
    let d = tempdir("cfgfiles");
    write(&d, "machine/t.tbl", b"T1 P1 Z0.5 D0.25\n");
    write(
        &d,
        "partscope.toml",
        b"dialect = \"rs274ngc\"\ntool_table = \"machine/t.tbl\"\n",
    );
    let f = write(&d, "p.ngc", b"G21\nT1 M6\nT5 M6\nM2\n");
    let (code, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert_eq!(
        codes(&diags),
        vec![("T001".to_string(), 3, "error".to_string())]
    );
    write(
        &d,
        "machine/mill.ini",
        b"[EMCIO]\nTOOL_TABLE = t.tbl\n[TRAJ]\nLINEAR_UNITS = mm\nMAX_LINEAR_VELOCITY = 60\n",
    );
    write(
        &d,
        "partscope.toml",
        b"dialect = \"rs274ngc\"\nini = \"machine/mill.ini\"\n",
    );
    let (_, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!(
        codes(&diags),
        vec![("T001".to_string(), 3, "error".to_string())]
    );
    // Without a table every tool number is accepted.
    write(&d, "partscope.toml", b"dialect = \"rs274ngc\"\n");
    let (code, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!((code, diags.len()), (0, 0), "{diags:?}");
}

#[test]
fn suppression_comments() {
    let d = tempdir("suppress");
    let f = write(
        &d,
        "s.ngc",
        b"G1 X1.2.3 F100 (partscope: allow L004)\nG1 X1.2.3\nM2\n",
    );
    let (_, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!(
        codes(&diags)
            .iter()
            .filter(|c| c.0 == "L004")
            .map(|c| c.1)
            .collect::<Vec<_>>(),
        vec![2]
    );
    let f = write(
        &d,
        "t.ngc",
        b"(partscope: allow-file L004)\nG1 X1.2.3 F100\nM2\n",
    );
    let (_, diags) = check_json(&[f.to_str().unwrap()]);
    assert!(!codes(&diags).iter().any(|c| c.0 == "L004"));
}

#[test]
fn directory_walk_respects_gitignore_and_extensions() {
    let d = tempdir("walk");
    std::fs::create_dir_all(d.join(".git")).unwrap();
    write(&d, ".gitignore", b"ignored/\n");
    write(&d, "a.ngc", b"G1 X1.2.3\nM2\n");
    write(&d, "ignored/b.ngc", b"G1 X1.2.3\nM2\n");
    write(&d, "notes.txt", b"G1 X1.2.3\n");
    let (_, diags) = check_json(&[d.to_str().unwrap()]);
    let paths: Vec<&str> = diags.iter().filter_map(|d| d["path"].as_str()).collect();
    assert!(!paths.is_empty());
    assert!(paths.iter().all(|p| p.ends_with("a.ngc")), "{paths:?}");
}

#[test]
fn sarif_and_github_formats() {
    let d = tempdir("sarif");
    let f = write(&d, "a.ngc", b"G1 X1.2.3 F100\nM2\n");
    let out = bin()
        .args(["check", "--format", "sarif", f.to_str().unwrap()])
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["version"], "2.1.0");
    let run = &v["runs"][0];
    assert!(run["tool"]["driver"]["rules"]
        .as_array()
        .unwrap()
        .iter()
        .any(|r| r["id"] == "L004"));
    assert_eq!(run["results"][0]["ruleId"], "L004");
    assert_eq!(
        run["results"][0]["locations"][0]["physicalLocation"]["region"]["startLine"],
        1
    );
    let out = bin()
        .args(["check", "--format", "github", f.to_str().unwrap()])
        .output()
        .unwrap();
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(s.starts_with("::error file="), "{s}");
    assert!(s.contains("line=1,col=5,endLine=1,endColumn=10"), "{s}");
}

/// A reader that closes the pipe early (`partscope rule --all | head -1`) ends the
/// output; the process exits as it would have, with no panic on standard error.
#[test]
fn output_to_a_closed_pipe_ends_quietly() {
    let dir = tempdir("closed-pipe");
    let prog = dir.join("p.ngc");
    let mut text = String::from("G21 G90\n");
    for i in 0..20000 {
        text.push_str(&format!("G1 X{i} F100\n"));
    }
    text.push_str("M2\n");
    std::fs::write(&prog, text).unwrap();
    let prog = prog.to_str().unwrap().to_string();
    for args in [
        vec!["rule", "--all"],
        vec!["rule", "--all", "--json"],
        vec!["rule", "W012"],
        vec!["check", "--select", "S", prog.as_str()],
        vec!["check", "--format", "json", prog.as_str()],
        vec!["run", "--emit", "toolpath", prog.as_str()],
        vec!["run", "--format", "json", prog.as_str()],
    ] {
        let mut child = bin()
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // Closed before the program writes anything.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(!err.contains("cannot write"), "{args:?}: {err}");
        // The exit status is the one the findings give, as with the output read.
        let read = bin().args(&args).output().unwrap();
        assert_eq!(out.status.code(), read.status.code(), "{args:?}: {err}");
    }
}

/// A call the dry run skips leaves its time out of the figures: `run` says they are
/// partial (JSON, human summary, exit status 1), as it does for a run that stopped.
#[test]
fn a_skipped_call_makes_the_run_partial() {
    let dir = tempdir("skipped-call");
    let prog = write(
        &dir,
        "p.ngc",
        b"G21 G90\nG1 X10 F600\no<not_here> call\nG1 X20\nM2\n",
    );
    let out = bin()
        .args(["run", "--format", "json"])
        .arg(&prog)
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["partial"], true, "{v}");
    assert_eq!(v["complete"], false);
    assert_eq!(v["stopped_at"], serde_json::Value::Null);
    assert_eq!(out.status.code(), Some(1));
    let out = bin().arg("run").arg(&prog).output().unwrap();
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(
        s.contains(
            "partial: a called program was not run (F002); the figures leave out what it does"
        ),
        "{s}"
    );
    // With the subroutine beside it, nothing is skipped.
    write(
        &dir,
        "not_here.ngc",
        b"o<not_here> sub\nG1 Y5\no<not_here> endsub\nM2\n",
    );
    let out = bin()
        .args(["run", "--format", "json"])
        .arg(&prog)
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["partial"], false, "{v}");
    assert_eq!(out.status.code(), Some(0));
}

#[test]
fn rule_explains_and_lists() {
    let out = bin().args(["rule", "L001"]).output().unwrap();
    assert!(out.status.success());
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(
        s.contains("## What it does") && s.contains("unclosed-comment"),
        "{s}"
    );
    let out = bin().args(["rule", "--all"]).output().unwrap();
    assert!(String::from_utf8_lossy(&out.stdout).lines().count() >= 10);
    let out = bin().args(["rule", "NOPE999"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = bin()
        .args(["check", "--format", "yaml", "x.ngc"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn run_writes_pictures_and_block_times() {
    let d = tempdir("run");
    let f = write(
        &d,
        "p.ngc",
        b"G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F600\nG1 X10 F1200\nG2 X20 Y0 I5 J0\nG0 Z5\nM2\n",
    );
    let (svg, png) = (d.join("p.svg"), d.join("p.png"));
    let out = bin()
        .args([
            "run",
            f.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = std::fs::read_to_string(&svg).unwrap();
    assert!(s.starts_with("<svg"));
    // Feed moves carry their source line; rapids are dashed.
    assert!(
        s.contains(r#"data-line="4""#) && s.contains(r#"data-line="5""#),
        "{s}"
    );
    assert!(s.contains("stroke-dasharray"));
    assert_eq!(&std::fs::read(&png).unwrap()[..8], b"\x89PNG\r\n\x1a\n");
    let out = bin()
        .args(["run", f.to_str().unwrap(), "--emit", "blocks"])
        .output()
        .unwrap();
    let csv = String::from_utf8_lossy(&out.stdout);
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("line,start_s,end_s,duration_s,length_mm,peak_feed_mm_min,time_s,feed_s,accel_s,corner_s,axis_cap_s,traj_cap_s,curve_cap_s,servo_cap_s,rapid_s,dwell_s,aux_s")
    );
    // Line 4 is the 10 mm feed move; line 5 the half circle of radius 5 (5π mm).
    let row = |n: &str| {
        csv.lines()
            .find(|l| l.starts_with(&format!("{n},")))
            .unwrap()
            .split(',')
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    assert_eq!(row("4")[4], "10.000000");
    assert_eq!(row("5")[4], format!("{:.6}", 5.0 * std::f64::consts::PI));
}

/// `run --format json` plans on a second thread as the interpreter streams; with
/// `--svg` it keeps every motion and plans afterwards. Both print the same summary,
/// also when the program passes the four-hour servo-simulation limit part-way and
/// the streamed run is planned again in closed form.
#[test]
fn streamed_run_summary_equals_buffered_summary() {
    let dir = tempdir("streamed");
    let svg = dir.join("p.svg");
    for (name, feed, over_limit) in [("fast", 1500.0, false), ("slow", 1.0, true)] {
        let mut text = String::from("G21 G17 G90 G94 G64 P0.01\nT1 M6\nS8000 M3\nG0 X0 Y0 Z5\n");
        for p in 0..3 {
            text += &format!("G1 Z-1 F{feed}\n");
            for k in 0..40 {
                let x = if k % 2 == 0 { 30 } else { 0 };
                text += &format!("X{x} Y{:.3}\n", p as f64 * 2.0 + k as f64 * 0.05);
            }
            text += "G4 P0.5\nG0 Z5\n";
        }
        text += "M5\nM30\n";
        let file = write(&dir, &format!("{name}.ngc"), text.as_bytes());
        let run = |extra: &[&std::ffi::OsStr]| -> Value {
            let out = bin()
                .args(["run", "--format", "json"])
                .args(extra)
                .arg(&file)
                .output()
                .unwrap();
            assert_eq!(out.status.code(), Some(0), "{name}");
            serde_json::from_slice(&out.stdout).unwrap()
        };
        let streamed = run(&[]);
        let buffered = run(&["--svg".as_ref(), svg.as_os_str()]);
        assert_eq!(streamed, buffered, "{name}");
        let cutting = streamed["cutting_s"].as_f64().unwrap_or(0.0);
        assert_eq!(cutting > 4.0 * 3600.0, over_limit, "{name}: {cutting}");
        assert_eq!(streamed["dwell_s"].as_f64(), Some(1.5), "{name}");
    }
}

/// A FANUC macro file (returns with M99, never ends the program) is checked
/// as its callers would run it: no dry run of its own, so its arguments are
/// not "read before assigned" and its M99 is not an endless loop. A main
/// program (it ends with M30) is still run.
#[test]
fn fanuc_macro_file_is_not_run_on_its_own() {
    let dir = tempdir("macro-file");
    let f = write(
        &dir,
        "o9100.nc",
        b"%\nO9100 (BOLT CIRCLE)\n#1=#1+1.\nG00 X#24 Y#25\nM99\n%\n",
    );
    let (code, diags) = check_json(&["--dialect", "fanuc", f.to_str().unwrap()]);
    assert_eq!(codes(&diags), vec![], "{diags:?}");
    assert_eq!(code, 0);
    let f = write(&dir, "main.nc", b"%\nO1000\nG21 G90 G01 X1.\nM30\n%\n");
    let (_, diags) = check_json(&["--dialect", "fanuc", f.to_str().unwrap()]);
    // The interpreter's zero-feed error shows the main program was run.
    assert!(codes(&diags).iter().any(|c| c.0 == "F001"), "{diags:?}");
}

/// An `o<name> sub` library file needs no M2 (LinuxCNC never reads it as a
/// main program); a file that defines a sub and then runs is still a program.
#[test]
fn ngc_subroutine_file_needs_no_program_end() {
    let dir = tempdir("ngc-sub-file");
    let f = write(&dir, "peck.ngc", b"o<peck> sub\nG0 Z1\no<peck> endsub\n");
    let (code, diags) = check_json(&[f.to_str().unwrap()]);
    assert_eq!(codes(&diags), vec![], "{diags:?}");
    assert_eq!(code, 0);
    let f = write(
        &dir,
        "main.ngc",
        b"o<peck> sub\nG0 Z1\no<peck> endsub\no<peck> call\n",
    );
    let (_, diags) = check_json(&[f.to_str().unwrap()]);
    // Run as a main program, it does need its end: P005, which also stands for the
    // interpreter's F006 at the end of the file (one diagnostic per fault).
    assert_eq!(
        codes(&diags),
        vec![("P005".into(), 4, "error".into())],
        "{diags:?}"
    );
}

/// `machine.subroutine_path` is searched by `check` and `run` as by the editor,
/// and a `--config` elsewhere in the project does not shrink what may be read.
#[test]
fn subroutine_path_and_config_elsewhere_in_the_project() {
    let dir = tempdir("sub-path");
    std::fs::create_dir_all(dir.join(".git")).unwrap();
    write(
        &dir,
        "lib/drill.ngc",
        b"o<drill> sub\nG0 Z1\no<drill> endsub\n",
    );
    let main = write(&dir, "lib/jobs/main.ngc", b"o<drill> call\nM2\n");
    let main = main.to_str().unwrap();
    // Without a search path the dry run cannot know the sub is missing.
    let (code, diags) = check_json(&[main]);
    assert_eq!(
        (code, codes(&diags)),
        (0, vec![("F002".into(), 1, "info".into())])
    );
    write(
        &dir,
        "lib/jobs/partscope.toml",
        b"[machine]\nsubroutine_path = \"nowhere\"\n",
    );
    let (code, diags) = check_json(&[main]);
    assert_eq!(
        (code, codes(&diags)),
        (1, vec![("F002".into(), 1, "error".into())])
    );
    write(
        &dir,
        "lib/jobs/partscope.toml",
        b"[machine]\nsubroutine_path = \"..\"\n",
    );
    let (code, diags) = check_json(&[main]);
    assert_eq!((code, codes(&diags)), (0, vec![]), "{diags:?}");
    let out = bin()
        .args(["run", "--format", "json", main])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    write(
        &dir,
        "src/drill.ngc",
        b"o<drill> sub\nG0 Z1\no<drill> endsub\n",
    );
    let src = write(&dir, "src/main.ngc", b"o<drill> call\nM2\n");
    let cfg = write(&dir, "ci/partscope.toml", b"dialect = \"rs274ngc\"\n");
    let (code, diags) = check_json(&["--config", cfg.to_str().unwrap(), src.to_str().unwrap()]);
    assert_eq!((code, codes(&diags)), (0, vec![]), "{diags:?}");
}

/// The JSON output names the dialect and why it was chosen.
#[test]
fn json_names_the_dialect_and_its_evidence() {
    let dir = tempdir("dialect-why");
    let f = write(
        &dir,
        "part.nc",
        b"%\nO1234 (PART)\nG90 G54 G00 X0 Y0\nG04 P500\nG1 X1.\nM30\n%\n",
    );
    let (_, diags) = check_json(&[f.to_str().unwrap()]);
    let d = diags.first().expect("the zero feed is reported");
    assert_eq!(d["dialect"], "fanuc");
    assert_eq!(
        d["dialect_reason"],
        "the `%` line 1 and program number O1234 on line 2"
    );
    let out = bin()
        .args(["run", "--format", "json", f.to_str().unwrap()])
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["dialect"], "fanuc");
    // FANUC dwell P is in milliseconds: 0.5 s, not 500 s.
    assert_eq!(v["dwell_s"], 0.5);
}

/// A FANUC control finds a called program by the O number of its head: a
/// Haas-style five-digit name and a file named for its job both resolve.
#[test]
fn fanuc_calls_find_programs_by_their_head() {
    let dir = tempdir("fanuc-heads");
    let main = write(&dir, "f2.nc", b"%\nO5\nM98 P1002\nG65 P9002 A1.\nM30\n%\n");
    let (_, diags) = check_json(&["--dialect", "fanuc", main.to_str().unwrap()]);
    assert_eq!(codes(&diags)[0], ("F002".into(), 3, "error".into()));
    write(
        &dir,
        "gauge_tool_o1002.nc",
        b"%\nO1002 (GAUGE)\nG0 X1.\nM99\n%\n",
    );
    write(&dir, "O09002.nc", b"%\nO09002\nG0 X#1\nM99\n%\n");
    let (code, diags) = check_json(&["--dialect", "fanuc", main.to_str().unwrap()]);
    assert_eq!((code, codes(&diags)), (0, vec![]), "{diags:?}");
}

/// A lathe program written for this test: T0101, G50 S, G71/G70 P Q, G28 U W.
const LATHE: &[u8] = b"%\nO3100 (SHAFT)\nG20 G18 G40\nG28 U0. W0.\nT0101\nG50 S2000\nG96 S500 M03\nG00 X1.8 Z0.1\nG71 P10 Q20 U0.02 W0.005 D0.03 F0.01\nN10 G00 X0.9\nG01 Z-0.8\nN20 X1.8\nG70 P10 Q20 F0.004\nG28 U0. W0.\nM30\n%\n";

#[test]
fn a_lathe_program_checked_as_fanuc_gets_exactly_one_diagnostic() {
    let dir = tempdir("lathe-mismatch");
    let p = write(&dir, "shaft.nc", LATHE);
    let path = p.to_str().unwrap();
    let (code, diags) = check_json(&["--dialect", "fanuc", path]);
    // A warning fails `check` at the default fail level: an unchecked program does not pass.
    assert_eq!(code, 1);
    assert_eq!(
        codes(&diags),
        vec![("P010".to_string(), 4, "warning".to_string())]
    );
    assert_eq!(
        diags[0]["message"].as_str().unwrap(),
        "This looks like a FANUC or Haas lathe program (G28 U0. W0. on line 4, T0101 on line 5, G50 S2000 on line 6, G71 P10 Q20 on line 9): Partscope checks FANUC 30i mill programs; lathe programs are not checked. No other finding and no cycle time is reported for this file."
    );
    // Without P010 the same program floods (U and W are not mill axes): what it replaces.
    let (_, flood) = check_json(&["--dialect", "fanuc", "--ignore", "P010", path]);
    assert!(flood.len() >= 5, "{flood:?}");
    assert!(flood.iter().all(|d| d["code"] != "P010"));
}

#[test]
fn run_reports_no_cycle_time_for_a_lathe_program() {
    let dir = tempdir("lathe-run");
    let p = write(&dir, "shaft.nc", LATHE);
    let out = bin()
        .args(["run", "--format", "json", "--dialect", "fanuc"])
        .arg(&p)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["cycle_time_s"], Value::Null);
    assert_eq!(v["distance_mm"], Value::Null);
    assert_eq!(v["partial"], Value::Bool(true));
    let diags = v["diagnostics"].as_array().unwrap();
    assert_eq!(
        codes(diags),
        vec![("P010".to_string(), 4, "warning".to_string())]
    );
}

/// A user M code (M100–M199) runs a program file from the machine's
/// USER_M_PATH: without `machine.user_m_codes` and without a search path the
/// file may exist on the machine, so it is information and the check goes on;
/// with the list configured, a code not in it stops LinuxCNC (rs274: "Unknown m
/// code used").
#[test]
fn user_m_code_needs_configuration_to_be_an_error() {
    let dir = tempdir("userm");
    let prog = write(&dir, "p.ngc", b"G21\nM101\nG0 X1\nG1 X2 F100\nM2\n");
    let (_, diags) = check_json(&[prog.to_str().unwrap()]);
    assert_eq!(codes(&diags), vec![("X009".into(), 2, "info".into())]);
    write(&dir, "partscope.toml", b"[machine]\nuser_m_codes = [102]\n");
    let (code, diags) = check_json(&[prog.to_str().unwrap()]);
    assert_eq!(codes(&diags), vec![("X009".into(), 2, "error".into())]);
    assert_eq!(code, 1);
    write(&dir, "partscope.toml", b"[machine]\nuser_m_codes = [101]\n");
    let (_, diags) = check_json(&[prog.to_str().unwrap()]);
    assert!(codes(&diags).is_empty(), "{diags:?}");
}

/// `run` names the machine profile it used and breaks the auxiliary time down by
/// category, in JSON and in the human summary; the shipped example profiles load.
#[test]
fn run_names_the_machine_profile_and_its_auxiliary_times() {
    let dir = tempdir("aux-times");
    let f = write(
        &dir,
        "part.nc",
        b"%\nO1000\nT1 M6\nS8000 M3\nM8\nG0 X100. Y120.\nM9\nM5\nM30\n%\n",
    );
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/machines");
    let vmc = examples.join("vmc.toml");
    let run = |extra: &[&str]| -> Value {
        let out = bin()
            .args(["run", "--format", "json", f.to_str().unwrap()])
            .args(extra)
            .output()
            .unwrap();
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let v = run(&["--machine", vmc.to_str().unwrap()]);
    assert_eq!(v["machine_profile"], vmc.to_str().unwrap());
    let a = &v["auxiliary"];
    assert_eq!(a["tool_change_s"], 4.0);
    assert_eq!(a["tool_changes"], 1);
    // 0.2 s + 0.25 s per 1000 rpm, up to S8000 and down again.
    assert_eq!(a["spindle_s"], 4.4);
    assert_eq!(a["coolant_s"], 0.2);
    assert_eq!(a["program_stop_s"], 0.0);
    let total = a["total_s"].as_f64().unwrap();
    let parts = v["tool_change_s"].as_f64().unwrap() + v["other_s"].as_f64().unwrap();
    assert!((total - parts).abs() < 1e-12, "{a}");
    // With no profile the output says the times are missing.
    let v = run(&[]);
    assert_eq!(
        v["machine_profile"],
        "built-in fanuc default (no tool-change or spindle times)"
    );
    assert_eq!(v["auxiliary"]["total_s"], 0.0);
    let human = bin()
        .args([
            "run",
            f.to_str().unwrap(),
            "--machine",
            vmc.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&human.stdout);
    assert!(
        text.contains(&format!("  machine      {}\n", vmc.display())),
        "{text}"
    );
    assert!(
        text.contains("  tool change     00:04.000  (1 change)\n"),
        "{text}"
    );
    assert!(text.contains("  spindle         00:04.400\n"), "{text}");
    for other in ["router.toml", "linuxcnc-mill/partscope.toml"] {
        let p = examples.join(other);
        let flag = if other.ends_with("partscope.toml") {
            "--config"
        } else {
            "--machine"
        };
        let out = bin()
            .args([
                "run",
                "--format",
                "json",
                f.to_str().unwrap(),
                flag,
                p.to_str().unwrap(),
            ])
            .args(["--dialect", "fanuc"])
            .output()
            .unwrap();
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(
            v["auxiliary"]["tool_change_s"].as_f64().unwrap() > 0.0,
            "{other}: {v}"
        );
    }
}

/// Mistyped rule selectors and levels are usage errors (exit 2) that name the
/// nearest valid value, not a silent change of what is checked.
#[test]
fn unknown_selectors_and_levels_are_usage_errors() {
    let dir = tempdir("selectors");
    let prog = write(&dir, "p.ngc", b"G21 G90\nG0 X1\nM2\n");
    let p = prog.to_str().unwrap();
    for (args, needle) in [
        (vec!["--select", "NOPE"], "--select NOPE: no rule"),
        (
            vec!["--ignore", "G001,modal-group-conflcit"],
            "--ignore modal-group-conflcit: no rule",
        ),
        (vec!["--fail-level", "erorr"], "did you mean `error`?"),
    ] {
        let out = bin().arg("check").args(&args).arg(p).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    // Codes, prefixes, names and ALL are accepted.
    let out = bin()
        .args([
            "check",
            "--select",
            "ALL,G0,modal-group-conflict",
            "--fail-level",
            "error",
            p,
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Machine values the planner cannot use are configuration errors (exit 2) that
/// name every bad key, in `run --machine`, in `run` and in `check` with a
/// `partscope.toml`; a cycle time from a negative feed cap would be nonsense.
#[test]
fn machine_values_out_of_range_are_located_warnings() {
    let dir = tempdir("machine_ranges");
    let prog = write(&dir, "p.ngc", b"G21 G90\nG1 X10 F100\nM2\n");
    let machine = write(
        &dir,
        "m.toml",
        b"[machine]\ntraj_max_velocity = -5.0\ntool_change_time = nan\nservo_period = 1e-9\nlookahed = 3\n\n[[machine.axes]]\nletter = \"X\"\nmin_travel = 10.0\nmax_travel = -10.0\n",
    );
    // Each value is reported where it is, and the run goes on with the default.
    let expected = [
        ":2:21: warning: `machine.traj_max_velocity`: -5 must be greater than 0 (the default is used)",
        ":3:20: warning: `machine.tool_change_time`: NaN is not a finite number (the default is used)",
        ":4:16: warning: `machine.servo_period`: 0.000000001 must be between 0.00001 and 1 (the default is used)",
        ":5:1: warning: unknown key `lookahed`: did you mean `lookahead`? (ignored)",
        "warning: `machine.axes`: axis 1: `min_travel` = 10 must not exceed `max_travel` = -10 (the default is used)",
    ];
    let out = bin()
        .args(["run", "--machine"])
        .arg(&machine)
        .arg(&prog)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8_lossy(&out.stderr);
    for e in expected {
        assert!(
            err.contains(&format!("m.toml{e}")) || err.contains(e),
            "{e}\n{err}"
        );
    }
    assert!(String::from_utf8_lossy(&out.stdout).contains("cycle time"));

    std::fs::copy(&machine, dir.join("partscope.toml")).unwrap();
    let out = bin().arg("run").arg(&prog).output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8_lossy(&out.stderr);
    for e in &expected[..4] {
        // One line per problem: `partscope: FILE:LINE:COL: warning: …`.
        let line = format!("partscope: {}{e}\n", dir.join("partscope.toml").display());
        assert!(err.contains(&line), "run: {e}\n{err}");
    }
    // `check` reports them as findings of L016 in the config file, once, in
    // every format: the warnings fail the check at the default fail level.
    let out = bin()
        .args(["check", "--format", "json"])
        .arg(&prog)
        .arg(&prog)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
    let found: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    let l016: Vec<(u64, u64, &str)> = found
        .iter()
        .filter(|d| d["code"] == "L016")
        .map(|d| {
            assert!(
                d["path"].as_str().unwrap().ends_with("partscope.toml"),
                "{d}"
            );
            assert_eq!(d["severity"], "warning");
            (
                d["line"].as_u64().unwrap(),
                d["column"].as_u64().unwrap(),
                d["message"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(found.len(), l016.len(), "{found:?}");
    let want: Vec<(u64, u64, &str)> = vec![
        (2, 21, "`machine.traj_max_velocity`: -5 must be greater than 0 (the default is used)"),
        (3, 20, "`machine.tool_change_time`: NaN is not a finite number (the default is used)"),
        (4, 16, "`machine.servo_period`: 0.000000001 must be between 0.00001 and 1 (the default is used)"),
        (5, 1, "unknown key `lookahed`: did you mean `lookahead`? (ignored)"),
        (7, 1, "`machine.axes`: axis 1: `min_travel` = 10 must not exceed `max_travel` = -10 (the default is used)"),
    ];
    assert_eq!(l016, want);
    let out = bin()
        .args(["check", "--format", "github"])
        .arg(&prog)
        .output()
        .unwrap();
    let gh = String::from_utf8_lossy(&out.stdout);
    assert!(
        gh.contains("partscope.toml,line=5,col=1,endLine=5,endColumn=9,title=L016 config-issue::unknown key `lookahed`"),
        "{gh}"
    );
    // The rule is turned off like any other.
    let out = bin()
        .args(["check", "--ignore", "L016"])
        .arg(&prog)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(!String::from_utf8_lossy(&out.stdout).contains("L016"));
    // A file that is not TOML stops both commands, located.
    std::fs::write(dir.join("partscope.toml"), "[machine\n").unwrap();
    for cmd in ["run", "check"] {
        let out = bin().arg(cmd).arg(&prog).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        let all = String::from_utf8_lossy(&out.stdout).to_string()
            + &String::from_utf8_lossy(&out.stderr);
        assert!(all.contains("partscope.toml:1:"), "{cmd}: {all}");
    }
    // The shipped example machines are in range.
    std::fs::remove_file(dir.join("partscope.toml")).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for m in [
        "examples/machines/vmc.toml",
        "examples/machines/router.toml",
    ] {
        let out = bin()
            .args(["run", "--machine"])
            .arg(root.join(m))
            .arg(&prog)
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(0),
            "{m}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// `run --svg`/`--png` never overwrite a file the run reads, and only regular
/// files are read as programs (a FIFO would block the open for ever).
#[cfg(unix)]
#[test]
fn outputs_never_overwrite_inputs_and_fifos_are_refused() {
    let dir = tempdir("outputs");
    let prog = write(&dir, "p.ngc", b"G21 G90\nG0 X1\nM2\n");
    let p = prog.to_str().unwrap();
    for flag in ["--svg", "--png", "--html"] {
        let out = bin().args(["run", p, flag, p]).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{flag}");
        assert_eq!(std::fs::read(&prog).unwrap(), b"G21 G90\nG0 X1\nM2\n");
    }
    // Nor a subprogram file the run loaded.
    let caller = write(&dir, "caller.ngc", b"G21 G90\no<lib> call\nM2\n");
    let lib = write(&dir, "lib.ngc", b"o<lib> sub\nG0 X2\no<lib> endsub\n");
    for flag in ["--svg", "--png", "--html"] {
        let out = bin()
            .args(["run", caller.to_str().unwrap(), flag, lib.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{flag}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("that is a file the run reads"),
            "{flag}"
        );
        assert_eq!(
            std::fs::read(&lib).unwrap(),
            b"o<lib> sub\nG0 X2\no<lib> endsub\n"
        );
    }
    let svg = dir.join("p.svg");
    let out = bin()
        .args(["run", p, "--svg", svg.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    // No temporary file is left beside the output.
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    let fifo = dir.join("pipe.ngc");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        for sub in ["check", "run"] {
            let out = bin().args([sub, fifo.to_str().unwrap()]).output().unwrap();
            assert_eq!(out.status.code(), Some(2), "{sub}");
            let all = format!(
                "{}{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(all.contains("not a regular file (a FIFO)"), "{sub}: {all}");
        }
    }
}

/// Terminal escape sequences in a program never reach the terminal through
/// the human output: control bytes are shown as control pictures.
#[test]
fn human_output_shows_control_bytes_visibly() {
    let dir = tempdir("escapes");
    let prog = write(&dir, "p.ngc", b"G21 G90\n(\x1b[2J\x07)\nG2 X20 Y0\nM2\n");
    let out = bin()
        .args(["check", prog.to_str().unwrap()])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        !out.stdout.contains(&0x1b) && !out.stdout.contains(&0x07),
        "{text}"
    );
    assert!(text.contains("(\u{241b}[2J\u{2407})"), "{text}");
    // The report still points at its own line.
    assert!(text.contains("p.ngc:3:1"), "{text}");
}

/// SARIF 2.1.0: columns are declared (code points), and a file under the
/// current folder is a percent-encoded URI relative to `%SRCROOT%`.
#[test]
fn sarif_locations_are_relative_encoded_uris() {
    let d = tempdir("sarif-uri");
    let f = write(&d, "my part#1.ngc", b"G1 X1.2.3 F100\nM2\n");
    let out = bin()
        .current_dir(&d)
        .args(["check", "--format", "sarif", "my part#1.ngc"])
        .output()
        .unwrap();
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let run = &v["runs"][0];
    assert_eq!(run["columnKind"], "unicodeCodePoints");
    let root = format!("file://{}/", d.canonicalize().unwrap().display());
    assert_eq!(
        run["originalUriBaseIds"]["%SRCROOT%"]["uri"],
        root.replace(' ', "%20")
    );
    assert_eq!(
        run["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"],
        serde_json::json!({"uri": "my%20part%231.ngc", "uriBaseId": "%SRCROOT%"})
    );
    drop(f);
}

/// `run` says where the time goes, by hand on the trapezoid planner (X, Y at
/// 100 mm/s and 1000 mm/s², TRAJ 100 mm/s, exact stops):
/// - G0 X10: a triangle up to 100 mm/s, 2·sqrt(10/1000) = 0.2 s of rapids;
/// - G1 X60 F3000: 50 mm at 50 mm/s, 1 s at feed and v/a = 0.05 s of ramps;
/// - G4 P2: 2 s of dwell;
/// - G1 Y100 F12000: 200 mm/s capped to 100 by TRAJ: 0.5 s at feed, 0.5 s for
///   the cap, 0.1 s of ramps.
///
/// The what-ifs: 120 % feed runs the F3000 move at 60 mm/s (50/60 + 0.06 s);
/// G64 P0.05 changes nothing here (every move stops for the rapid, the dwell
/// or the end); 2000 mm/s² lets the rapid reach 100 mm/s (10/100 + 0.05 s)
/// and halves every ramp.
#[test]
fn run_says_where_the_time_goes() {
    let d = tempdir("causes");
    let f = write(
        &d,
        "hand.ngc",
        b"G21 G90 G94 G61.1\nG0 X10\nG1 X60 F3000\nG4 P2\nG1 X60 Y100 F12000\nM2\n",
    );
    let m = write(&d, "m.toml", b"[machine]\nplanner = \"trapezoid\"\n");
    let run = |extra: &[&str]| {
        let out = bin()
            .args(["run", f.to_str().unwrap(), "--machine", m.to_str().unwrap()])
            .args(extra)
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let human = run(&[]);
    let section: Vec<&str> = human
        .lines()
        .skip_while(|l| *l != "  where the time goes")
        .take_while(|l| *l != "  slowest blocks")
        .collect();
    assert_eq!(
        section,
        [
            "  where the time goes",
            "  cutting at programmed feed            00:01.500   34.5 %",
            "  limited by acceleration               00:00.150    3.4 %",
            "  limited by the TRAJ velocity cap      00:00.500   11.5 %",
            "  rapids                                00:00.200    4.6 %",
            "  dwell                                 00:02.000   46.0 %",
            "  - 1 move programmed above the TRAJ velocity cap of F6000 cost 0.500 s: 23 % of cutting time",
            "  - ramps at the acceleration limit (2 moves, at starts, stops and short moves) cost 0.150 s: 7.0 % of cutting time",
            "",
            "  what if (planned again)",
            "  feed override 120 %                   00:04.193     -0.157 s  (-3.6 %)",
            "  G64 P0.05 (mm) on every move          00:04.350     +0.000 s  (+0.0 %)",
            "  2× acceleration on every axis         00:04.225     -0.125 s  (-2.9 %)",
            "",
        ],
        "{human}"
    );
    assert!(
        human.contains(
            "  line 4           2.000 s       0.00 mm  peak        0 mm/min  dwell 100 %"
        ),
        "{human}"
    );

    let v: serde_json::Value = serde_json::from_str(&run(&["--format", "json"])).unwrap();
    let close = |key: &str, got: &serde_json::Value, want: f64| {
        let g = got.as_f64().unwrap_or(f64::NAN);
        assert!((g - want).abs() < 1e-9, "{key}: got {g}, want {want}");
    };
    let c = &v["time_causes"];
    for (k, want) in [
        ("feed_s", 1.5),
        ("accel_s", 0.15),
        ("corner_s", 0.0),
        ("traj_cap_s", 0.5),
        ("axis_cap_s", 0.0),
        ("rapid_s", 0.2),
        ("dwell_s", 2.0),
        ("auxiliary_s", 0.0),
    ] {
        close(k, &c[k], want);
    }
    close("cycle_time_s", &v["cycle_time_s"], 4.35);
    assert_eq!(c["moves"]["traj_cap"], 1);
    let what: Vec<(String, f64)> = v["what_if"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| {
            (
                w["key"].as_str().unwrap().to_string(),
                w["cycle_time_s"].as_f64().unwrap(),
            )
        })
        .collect();
    let want = [
        ("feed_override", 0.2 + 50.0 / 60.0 + 0.06 + 2.0 + 1.1),
        ("blend", 4.35),
        ("acceleration", 0.15 + 1.025 + 2.0 + 1.05),
    ];
    assert_eq!(what.len(), 3);
    for ((k, got), (wk, w)) in what.iter().zip(want) {
        assert_eq!(k, wk);
        close(k, &serde_json::json!(got), w);
    }
    // Per block: time on the program clock and its causes.
    let blocks = v["blocks"].as_array().unwrap();
    let lines: Vec<u64> = blocks.iter().map(|b| b["line"].as_u64().unwrap()).collect();
    assert_eq!(lines, [2, 3, 4, 5]);
    close("line 3 feed", &blocks[1]["causes"]["feed_s"], 1.0);
    close("line 3 accel", &blocks[1]["causes"]["accel_s"], 0.05);
    close("line 4 start", &blocks[2]["start_s"], 1.25);
    close("line 4 dwell", &blocks[2]["causes"]["dwell_s"], 2.0);
    close("line 5 start", &blocks[3]["start_s"], 3.25);
    close("line 5 cap", &blocks[3]["causes"]["traj_cap_s"], 0.5);
    close("line 5 end", &blocks[3]["end_s"], 4.35);
    assert_eq!(blocks[3]["causes"].as_object().unwrap().len(), 3);

    // Without what-ifs the JSON streams, with the same figures.
    let s: serde_json::Value =
        serde_json::from_str(&run(&["--format", "json", "--what-if", "off"])).unwrap();
    assert_eq!(s["what_if"], serde_json::Value::Null);
    assert_eq!(s["time_causes"], v["time_causes"]);
    assert_eq!(s["blocks"], v["blocks"]);
}

/// The JSON of the data block in a page written by `run --html`.
fn page_data(page: &str) -> Value {
    let open = r#"<script type="application/json" id="partscope-data">"#;
    let start = page.find(open).expect("the page has a data block") + open.len();
    let len = page[start..].find("</script>").unwrap();
    serde_json::from_str(&page[start..start + len]).unwrap()
}

/// `run --html` writes one page holding the viewer and the dry run the editor's
/// preview gets, and nothing that would be fetched.
#[test]
fn run_html_page_holds_the_dry_run_and_fetches_nothing() {
    let d = tempdir("html");
    let f = write(
        &d,
        "rect & <b>.ngc",
        b"G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F600\nG1 X40 F1200\nG1 Y20\nG1 X0\nG1 Y0\nG0 Z5\nM2\n",
    );
    let html = d.join("rect.html");
    let out = bin()
        .args(["run", f.to_str().unwrap(), "--html", html.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"));
    assert!(page.contains("<title>rect &amp; &lt;b&gt;.ngc — Partscope toolpath</title>"));
    // Style and script are inline; nothing names another file or a server.
    assert!(page.contains("<style>") && page.contains("global.PartscopePreview = Preview;"));
    for external in ["http://", "https://", " src=", " href=", "@import", "url("] {
        assert!(!page.contains(external), "the page holds {external}");
    }
    assert!(page.contains("default-src 'none'"));
    let v = page_data(&page);
    assert_eq!(v["title"], "rect & <b>.ngc");
    let data = &v["data"];
    let summary = bin()
        .args(["run", f.to_str().unwrap(), "--format", "json"])
        .output()
        .unwrap();
    let summary: Value = serde_json::from_slice(&summary.stdout).unwrap();
    assert_eq!(data["cycle_time_s"], summary["cycle_time_s"]);
    assert_eq!(data["cutting_s"], summary["cutting_s"]);
    assert_eq!(data["complete"], true);
    assert_eq!(data["stopped_at"], Value::Null);
    assert_eq!(data["distance_mm"], 135.0);
    assert_eq!(
        data["toolpath"]["bounds"],
        serde_json::json!({"min": [0.0, 0.0, 0.0], "max": [40.0, 20.0, 5.0]})
    );
    let segs: Vec<(String, u64, f64)> = data["toolpath"]["segments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["kind"].as_str().unwrap().to_string(),
                s["line"].as_u64().unwrap(),
                s["feed"].as_f64().unwrap(),
            )
        })
        .collect();
    let want: Vec<(String, u64, f64)> = [
        ("rapid", 1, 0.0),
        ("feed", 2, 600.0),
        ("feed", 3, 1200.0),
        ("feed", 4, 1200.0),
        ("feed", 5, 1200.0),
        ("feed", 6, 1200.0),
        ("rapid", 7, 0.0),
    ]
    .iter()
    .map(|(k, l, f)| (k.to_string(), *l, *f))
    .collect();
    assert_eq!(segs, want);
    assert_eq!(
        data["toolpath"]["segments"][3]["points"],
        serde_json::json!([[40.0, 0.0, 0.0], [40.0, 20.0, 0.0]])
    );
}

/// A run that stops in a called file says so on the page, at the call, and a
/// reason holding `</script>` cannot end the data block.
#[test]
fn run_html_page_of_a_stopped_run_names_the_call() {
    let d = tempdir("html-stop");
    let main = write(
        &d,
        "main.ngc",
        b"G21 G90\nG0 X0 Y0 Z5\no<sub> call\nG1 X10 F500\nM2\n",
    );
    write(
        &d,
        "sub.ngc",
        b"o<sub> sub\nG1 X5 F500\n(abort, </script><script>alert 1)\no<sub> endsub\n",
    );
    let html = d.join("main.html");
    let out = bin()
        .args([
            "run",
            main.to_str().unwrap(),
            "--html",
            html.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    assert_eq!(
        page.matches("</script>").count(),
        2,
        "data block and viewer only"
    );
    let data = &page_data(&page)["data"];
    assert_eq!(data["complete"], false);
    assert_eq!(data["stopped_at"]["line"], 2, "{}", data["stopped_at"]);
    let reason = data["stopped_at"]["reason"].as_str().unwrap();
    assert!(
        reason.contains("</script><script>alert 1") && reason.contains("(in sub.ngc, line 3)"),
        "{reason}"
    );
}

/// `--png` is the `--svg` picture rasterised: the title and the legend's text,
/// which only text colours, are there, and the toolpath lies where the SVG
/// draws it.
#[test]
fn run_png_is_the_svg_picture_with_its_text() {
    use resvg::tiny_skia::Pixmap;
    let d = tempdir("png");
    let f = write(
        &d,
        "p.ngc",
        b"G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F600\nG1 X10 F1200\nG2 X20 Y0 I5 J0\nG0 Z5\nM2\n",
    );
    let (svg, png) = (d.join("p.svg"), d.join("p.png"));
    let out = bin()
        .args([
            "run",
            f.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let pm = Pixmap::load_png(&png).unwrap();
    assert_eq!((pm.width(), pm.height()), (1200, 800));
    let pixel = |x: u32, y: u32| {
        let p = pm.pixel(x, y).unwrap();
        (p.red(), p.green(), p.blue())
    };
    // Pixels of a box darker than the picture's #fafafa backdrop by more than a shade.
    let dark = |x0: u32, y0: u32, x1: u32, y1: u32| {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| pixel(x, y).0 < 160)
            .count()
    };
    // The title line (font size 18, baseline 30) and the legend's labels (12, baseline 782).
    assert!(
        dark(16, 14, 400, 36) > 300,
        "title: {}",
        dark(16, 14, 400, 36)
    );
    assert!(dark(62, 770, 100, 786) > 40, "rapid label");
    assert!(dark(310, 770, 460, 786) > 150, "feed label");
    // Where nothing is drawn the backdrop stays.
    assert_eq!(dark(1000, 4, 1196, 44), 0);
    assert_eq!(pixel(1100, 20), (250, 250, 250));
    // The first feed polyline of the SVG is drawn at its own coordinates in the PNG.
    let text = std::fs::read_to_string(&svg).unwrap();
    let poly = text
        .lines()
        .find(|l| l.contains("data-line"))
        .expect("a feed move");
    let points = poly.split("points=\"").nth(1).unwrap();
    let (x, y) = points.split(' ').next().unwrap().split_once(',').unwrap();
    let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
    let near = (-2..=2)
        .flat_map(|dy| (-2..=2).map(move |dx| (dx, dy)))
        .map(|(dx, dy)| {
            pixel(
                (x.round() as i64 + dx) as u32,
                (y.round() as i64 + dy) as u32,
            )
        })
        .filter(|&(r, g, b)| (r, g, b) != (250, 250, 250))
        .count();
    assert!(near > 3, "feed move at {x},{y} not drawn");
}

/// `--max-html-mb` bounds the page's toolpath: the drawing stops at a segment,
/// the title and a warning say where, the figures stay the whole run's.
#[test]
fn run_html_page_is_cut_to_its_size_limit() {
    let d = tempdir("html-cut");
    let mut program = String::from("G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F600\n");
    for i in 0..20_000 {
        program.push_str(&format!("G1 X{} Y{} F1200\n", i % 97, i % 89));
    }
    program.push_str("M2\n");
    let f = write(&d, "long.ngc", program.as_bytes());
    let html = d.join("long.html");
    let run = |mb: &str| {
        bin()
            .args(["run", f.to_str().unwrap(), "--html", html.to_str().unwrap()])
            .args(["--max-html-mb", mb, "--format", "json"])
            .output()
            .unwrap()
    };
    let whole = run("64");
    let page = std::fs::read_to_string(&html).unwrap();
    let full = page_data(&page);
    assert_eq!(full["title"], "long.ngc");
    assert_eq!(
        full["data"]["toolpath"]["segments"]
            .as_array()
            .unwrap()
            .len(),
        20_002
    );
    assert_eq!(whole.status.code(), Some(0));
    let out = run("0");
    let page = std::fs::read_to_string(&html).unwrap();
    let cut = page_data(&page);
    assert_eq!(cut["data"]["toolpath"]["segments"], serde_json::json!([]));
    assert_eq!(
        cut["title"],
        "long.ngc — toolpath cut off at line 2 to keep the page under 0 MB (--max-html-mb)"
    );
    assert_eq!(cut["data"]["cycle_time_s"], full["data"]["cycle_time_s"]);
    assert_eq!(cut["data"]["distance_mm"], full["data"]["distance_mm"]);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let warning = v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["message"].as_str().unwrap().contains("--max-html-mb"))
        .expect("a warning names the limit");
    assert_eq!(warning["code"], "F004");
    assert_eq!(warning["line"], 2);
}

/// A picture cut off by `--max-svg-mb` shows the same moves in every view, and
/// the PNG (the same picture) is cut at the same line.
#[test]
fn a_cut_off_picture_draws_the_same_moves_in_every_view() {
    let d = tempdir("svg-cut");
    let mut program = String::from("G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F600\n");
    for i in 0..20_000 {
        program.push_str(&format!("G1 X{} Y{} Z-{} F1200\n", i % 97, i % 89, i % 3));
    }
    program.push_str("M2\n");
    let f = write(&d, "long.ngc", program.as_bytes());
    let (svg, png) = (d.join("long.svg"), d.join("long.png"));
    let run = |flag: &str, out: &Path| {
        let o = bin()
            .args([
                "run",
                f.to_str().unwrap(),
                "--format",
                "json",
                "--max-svg-mb",
                "1",
            ])
            .args([flag, out.to_str().unwrap()])
            .output()
            .unwrap();
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        v["diagnostics"]
            .as_array()
            .unwrap()
            .iter()
            .find(|d| d["message"].as_str().unwrap().contains("--max-svg-mb"))
            .map(|d| d["line"].clone())
            .expect("a warning names the limit")
    };
    let svg_cut = run("--svg", &svg);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.len() <= 1 << 20, "{} bytes", text.len());
    let per_view: Vec<usize> = text
        .split(r##"font-size="12" fill="#666">"##)
        .skip(1)
        .map(|view| view.matches("<polyline").count())
        .collect();
    assert_eq!(per_view.len(), 4);
    assert!(per_view.iter().all(|&n| n == per_view[0]), "{per_view:?}");
    // The moves drawn are the first ones, up to the line the warning names.
    let drawn = per_view[0] as u64;
    assert!(drawn > 1000 && drawn < 20_002, "{drawn}");
    assert_eq!(
        svg_cut,
        drawn + 2,
        "segment {drawn} is on line {}",
        drawn + 2
    );
    assert!(text.contains(&format!("toolpath cut off at line {}", drawn + 2)));
    assert_eq!(run("--png", &png), svg_cut);
}

/// FANUC O9000–O9029 are called for T, M and G codes: a file holding one is a
/// called program even when it also holds M30 (corpus class N11).
#[test]
fn code_call_macros_are_called_programs() {
    let dir = tempdir("code_macro");
    let p = write(
        &dir,
        "O9025.nc",
        b"%\nO9025 (CHECK)\nIF[#1000 EQ 1] GOTO1\nM99\nN1 #3000 = 12 (WRONG STATE)\nM30\n%\n",
    );
    let (code, diags) = check_json(&["--dialect", "fanuc", p.to_str().unwrap()]);
    assert_eq!((code, codes(&diags)), (0, vec![]));
}

/// LinuxCNC finds a subroutine file by the subroutine's name: a file of definitions
/// named after one of them is a library (no M2 needed); one named otherwise cannot be
/// called, and run as a program it ends without M2, as `rs274` reports on its last line.
#[test]
fn ngc_library_is_named_after_its_subroutine() {
    let dir = tempdir("ngc-library-name");
    let sub = b"o<z_touch> sub\nG38.2 Z-10 F25\no<z_touch> endsub\n";
    let good = write(&dir, "z_touch.ngc", sub);
    let bad = write(&dir, "z_probe.ngc", sub);
    let (code, diags) = check_json(&[good.to_str().unwrap()]);
    assert_eq!((code, codes(&diags)), (0, vec![]));
    let (code, diags) = check_json(&[bad.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert_eq!(
        codes(&diags),
        vec![("P005".to_string(), 3, "error".to_string())]
    );
}

/// `run --format json` writes a `blocks` entry per line for programs up to 1 MiB
/// (`--blocks auto`); above that it says how to get them, and `--blocks on|off` decide.
#[test]
fn run_json_blocks_are_bounded_by_size_unless_asked() {
    let d = tempdir("run-json-blocks");
    let small = write(&d, "small.ngc", b"G21 G90 G94\nG1 X10 F600\nG1 Y10\nM2\n");
    let mut big_text = String::from("G21 G90 G94 F600\n");
    let mut i = 0u32;
    while big_text.len() <= 1 << 20 {
        i += 1;
        big_text.push_str(&format!("G1 X{}.{:03} Y1\n", i % 50, i % 1000));
    }
    big_text.push_str("M2\n");
    let big = write(&d, "big.ngc", big_text.as_bytes());
    let json = |args: &[&str]| -> Value {
        let out = bin().arg("run").args(args).output().unwrap();
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let s = small.to_str().unwrap();
    let v = json(&["--format", "json", s]);
    assert_eq!(v["blocks"].as_array().map(|b| b.len()), Some(2));
    assert!(v.get("blocks_skipped").is_none());
    let v = json(&["--format", "json", "--blocks", "off", s]);
    assert_eq!(v["blocks"].as_array().map(|b| b.len()), Some(0));
    let b = big.to_str().unwrap();
    let v = json(&["--format", "json", b]);
    assert_eq!(v["blocks"].as_array().map(|b| b.len()), Some(0));
    assert_eq!(
        v["blocks_skipped"],
        "the program is larger than 1024 KiB; --blocks on writes them"
    );
    let v = json(&["--format", "json", "--blocks", "on", b]);
    assert!(v["blocks"].as_array().is_some_and(|b| b.len() > 50_000));
}
