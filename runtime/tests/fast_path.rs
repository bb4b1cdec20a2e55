//! The interpreter's fast path for plain motion blocks (`X… Y… Z… F…` under a modal
//! G0/G1) must change nothing: every program here runs with and without it and
//! the motions, events, snapshots and diagnostics must be identical.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use analyzer::syntax::{parse, ParseOptions};
use analyzer::{Dialect, Settings};

fn ngc_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            ngc_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "ngc") {
            out.push(p);
        }
    }
}

/// Runs `text` both ways and returns how many motions it made.
fn same(name: &str, text: &[u8]) -> usize {
    same_with(name, text, &[])
}

/// [`same`] with extra rules selected.
fn same_with(name: &str, text: &[u8], select: &[&str]) -> usize {
    let dialect = Dialect::Rs274ngc;
    let program = parse(ParseOptions::new(dialect), Arc::<[u8]>::from(text));
    let mut settings = Settings::new(dialect);
    settings.select = select.iter().map(|s| s.to_string()).collect();
    let machine = analyzer::config::MachineConfig::default();
    let input = runtime::RunInput {
        program: &program,
        settings: &settings,
        machine: &machine,
        resolver: &runtime::NoResolver,
        step_budget: 1_000_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    };
    let fast = runtime::run_with_snapshots(&input, true);
    let general = runtime::interp::run_without_fast_path(&input, true);
    assert_eq!(fast.motions, general.motions, "{name}: motions");
    assert_eq!(fast.events, general.events, "{name}: events");
    assert_eq!(fast.snapshots, general.snapshots, "{name}: snapshots");
    assert_eq!(
        format!("{:?}", fast.diagnostics),
        format!("{:?}", general.diagnostics),
        "{name}: diagnostics"
    );
    fast.motions.len()
}

#[test]
fn fast_path_matches_general_path_on_test_programs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    ngc_files(&root.join("../tests/conformance/programs"), &mut files);
    ngc_files(&root.join("tests/data"), &mut files);
    files.sort();
    assert!(files.len() > 150, "{} programs found", files.len());
    let mut motions = 0;
    for f in &files {
        let text = std::fs::read(f).unwrap_or_default();
        motions += same(&f.display().to_string(), &text);
    }
    assert!(motions > 1000, "{motions} motions");
}

/// States next to the fast path's preconditions, each followed by plain motion lines.
#[test]
fn fast_path_matches_general_path_at_its_edges() {
    let cases: &[(&str, &str)] = &[
        (
            "feed words",
            "G21 G90 G1 F100 X0\nX1 F200\nF300 Y1 Z-1\nG0 X0\nZ5 F50\nG1 X1\nM2\n",
        ),
        ("zero feed", "G21 G90\nG1 X1\nX2 Y2\nM2\n"),
        ("spindle off, feed on", "G21 G90 F100\nG1 X1\nX2\nZ-1\nM2\n"),
        (
            "M6 keeps the old length offset",
            "G21 G90 T1 M6 G43 H1 F100 G1 X0\nT2 M6\nZ-1\nX2\nM2\n",
        ),
        (
            "first move after G40",
            "G21 G90 F100 T1 M6\nG41 D1 G1 X5 Y5\nX10\nG40\nX20 Y20\nX30\nM2\n",
        ),
        (
            "arc after a line after G40",
            "G21 G90 F100 T1 M6\nG41 D1 G1 X5 Y5\nX10\nG40\nX20 Y20\nG2 X30 Y30 R10\nM2\n",
        ),
        (
            "compensation on",
            "G21 G90 F100 T1 M6\nG42 G1 X5 Y5\nX10\nY10\nX0\nG40 X-5\nM2\n",
        ),
        (
            "inverse time",
            "G21 G90 G93\nG1 X1 F10\nX2 F5\nG94 F100 X3\nX4\nM2\n",
        ),
        (
            "per revolution",
            "G21 G90 S1000 M3 G95 F0.1\nG1 X1\nX2\nM2\n",
        ),
        (
            "diameter mode",
            "G21 G90 G7 F100\nG1 X10\nX20 Z-1\nG8\nX5\nM2\n",
        ),
        ("inch", "G20 G90 F10\nG1 X1\nY1 Z-0.1\nG21 X2\nM2\n"),
        ("incremental", "G21 G91 F100\nG1 X1\nX1 Y1\nG0 Z1\nZ1\nM2\n"),
        (
            "offsets",
            "G21 G90 G10 L2 P2 X5 Y5\nG55 G0 X0 Y0\nX1\nG92 X0\nG1 F50 X1\nM2\n",
        ),
        ("rapid to the same point", "G21 G90\nG0 X1\nX1\nG0 X1\nM2\n"),
        ("repeated letter", "G21 G90 F100\nG1 X1 X2\nX3\nM2\n"),
        ("after end", "G21 G90 F100\nG1 X1\nM2\nX5\n"),
        ("G80 motion mode", "G21 G90 F100\nG80\nX1\nM2\n"),
        (
            "canned cycle",
            "G21 G90 F100 G0 Z5\nG81 X1 Y1 Z-1 R1\nX2\nY3\nG80\nX0\nM2\n",
        ),
        ("arc mode", "G21 G90 F100\nG2 X2 Y0 R1\nX0 R1\nM2\n"),
        (
            "comments and N",
            "G21 G90 F100\nN10 G1 X1\nX2 (c)\n; x\nX3\nM2\n",
        ),
        ("no end", "G21 G90 F100\nG1 X1\nX2\n"),
    ];
    for (name, text) in cases {
        same(name, text.as_bytes());
    }
    // The optional rule for feed moves with the spindle stopped, on and off.
    let spindle = "G21 G90 F100\nG1 X1\nX2\nS1000 M3\nX3\nM5\nX4\nG0 X0\nM2\n";
    let warned = |select: &[&str]| {
        let program = parse(
            ParseOptions::new(Dialect::Rs274ngc),
            Arc::<[u8]>::from(spindle.as_bytes()),
        );
        let mut settings = Settings::new(Dialect::Rs274ngc);
        settings.select = select.iter().map(|s| s.to_string()).collect();
        let machine = analyzer::config::MachineConfig::default();
        let input = runtime::RunInput {
            program: &program,
            settings: &settings,
            machine: &machine,
            resolver: &runtime::NoResolver,
            step_budget: 1_000_000,
            motion_budget: u64::MAX,
            emit_canon: false,
            tool_table: None,
            var_file: None,
        };
        runtime::run_with_snapshots(&input, false)
            .diagnostics
            .iter()
            .filter(|d| d.code == "F015")
            .count()
    };
    same_with(
        "feed with the spindle stopped",
        spindle.as_bytes(),
        &["F015"],
    );
    // G1 X1, X2 and X4 feed with the spindle stopped.
    assert_eq!(warned(&["F015"]), 3);
    assert_eq!(warned(&[]), 0);
    // M70 saved in a subroutine: the level is dropped on return, so M72 fails.
    same(
        "M70 levels",
        b"G21 G90 F100\no100 sub\nM70\nG1 X1\no100 endsub\no100 call\nX2\nM72\nM2\n",
    );
}
