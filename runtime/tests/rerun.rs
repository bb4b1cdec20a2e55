//! `rerun` (restart from a checkpoint, stop where the state meets the
//! previous run again) gives exactly what a full run of the edited program
//! gives: diagnostics with their spans, motions, events and per-block
//! snapshots, over random edit sequences in every dialect.

#[path = "../../tests/common/rng.rs"]
mod rng;

use analyzer::{Dialect, Settings};
use rng::Rng;
use runtime::{rerun, run_checkpointed_recording, NoResolver, RunInput, RunOutput, ValueLimits};

/// Lines a straight CAM-like program is made of, per dialect. Some change
/// the modal state downstream (units, distance mode, work offset, tool,
/// compensation), so an edit's effect must be followed past a checkpoint.
fn lines(d: Dialect) -> Vec<&'static str> {
    let mut v = vec![
        "G0 X10 Y5",
        "G1 X12.5 Y7 F300",
        "G1 Z-1 F100",
        "G1 X0 Y0",
        "G17 G90|G0 X0 Y0|G2 X10 Y0 I5 J0",
        "G17 G90|G0 X10 Y0|G3 X0 Y0 R5",
        "G91",
        "G90",
        "G0 Z5",
        "G55",
        "G54",
        "M3 S1200",
        "M5",
        "G4 P0.5",
        "G0 X10 Y10 Z10",
        "G0 X10 Y10 Z10",
        "(comment)",
        "",
        "M8",
        "M9",
        "G18|G17",
        "T2 M6",
        "G43 H2",
        "G49",
        "G90 G41 D1|G1 X20 Y20 F300|G1 X40 Y20|G40|G1 X45 Y25",
        "G90 G81 X1 Y1 Z-2 R1 F50|X5|G80",
    ];
    match d {
        Dialect::Rs274ngc => v.extend([
            "G20",
            "G21",
            "#1 = [#1 + 1]",
            "G1 X[#1] F200",
            "G64 P0.01",
            "G61",
        ]),
        Dialect::Fanuc => v.extend(["G20", "G21", "#100=#100+1.", "G1 X#100 F200.", "G61", "G64"]),
        Dialect::Servoworks => v.extend([
            "G21",
            "G05 P10000|G1 X5 Y5|G08 P0",
            "G61",
            "G64",
            "#101 = 2",
        ]),
    }
    v
}

/// A pool entry as text: `|` separates blocks.
fn entry(d: Dialect, e: &str) -> String {
    format!("{}{}", e.replace('|', eob(d)), eob(d))
}

fn eob(d: Dialect) -> &'static str {
    match d {
        Dialect::Rs274ngc => "\n",
        _ => ";\n",
    }
}

fn program(d: Dialect, rng: &mut Rng, n: usize) -> String {
    let pool = lines(d);
    let mut s = String::new();
    if d != Dialect::Rs274ngc {
        s.push_str("%\n");
    }
    s.push_str(&format!("G21 G90 G17 M3 S1000 T1 M6 F500{}", eob(d)));
    for _ in 0..n {
        s.push_str(&entry(d, rng.pick(&pool)));
    }
    s.push_str(&format!("M30{}", eob(d)));
    if d != Dialect::Rs274ngc {
        s.push_str("%\n");
    }
    s
}

/// One random edit: replace, insert or delete a line, or splice a few bytes.
fn edit(d: Dialect, rng: &mut Rng, text: &str) -> String {
    let pool = lines(d);
    let mut rows: Vec<String> = text.split_inclusive('\n').map(str::to_string).collect();
    let at = rng.below(rows.len());
    let line = entry(d, rng.pick(&pool));
    match rng.below(6) {
        0 => rows[at] = line,
        // Errors (which stop an RS274/NGC run) and notes.
        5 if rng.below(4) == 0 => {
            let bad = [
                "G1 X3 Y4 F0",
                "G2 X1 Y1 I0.3 J0.2",
                "G1 Y2 Q1",
                "G0 X10 Y5 X1",
                "Q",
            ];
            rows.insert(at, format!("{}{}", rng.pick(&bad), eob(d)));
        }
        1 => rows.insert(at, line),
        2 if rows.len() > 2 => {
            rows.remove(at);
        }
        3 => {
            // A burst of lines, so an edit can span a checkpoint.
            for _ in 0..rng.below(3000) {
                let l = entry(d, rng.pick(&pool));
                rows.insert(at, l);
            }
        }
        4 => {
            let end = (at + rng.below(3000)).min(rows.len());
            rows.drain(at..end);
        }
        _ => {
            let s: String = rows.concat();
            let pos = rng.below(s.len() + 1);
            let pos = (0..=pos)
                .rev()
                .find(|p| s.is_char_boundary(*p))
                .unwrap_or(0);
            let junk = [
                "1",
                "X",
                ".5",
                " ",
                "\n",
                "G",
                "(",
                "-",
                "G1 G0 X1\n",
                "#1=[1/0]\n",
                "X[#2*2]\n",
                "G3 X1 Y1 R0.5\n",
                "G2 X0 Y0 R0\n",
                " F0",
                " Z1e308",
                "%",
                ";",
                "]",
                "[",
            ];
            let ins = rng.pick(&junk);
            return format!("{}{}{}", &s[..pos], ins, &s[pos..]);
        }
    }
    rows.concat()
}

fn run_on(d: Dialect, text: &str, prev: Option<RunOutput>) -> RunOutput {
    let settings = Settings::new(d);
    let program = analyzer::analyze(text.as_bytes().to_vec(), &settings).program;
    let machine = analyzer::config::MachineConfig::default();
    let input = RunInput {
        program: &program,
        settings: &settings,
        machine: &machine,
        resolver: &NoResolver,
        step_budget: 5_000_000,
        motion_budget: u64::MAX,
        emit_canon: false,
        tool_table: None,
        var_file: None,
    };
    match prev {
        Some(p) => rerun(&input, true, p),
        // Small limits, so that reruns meet them too.
        None => run_checkpointed_recording(&input, true, Some(LIMITS)),
    }
}

/// Value-record limits the edited programs reach now and then.
const LIMITS: ValueLimits = ValueLimits {
    per_series: 3,
    per_block: 4,
    blocks: 1500,
    series: 2000,
};

fn assert_same(a: &RunOutput, b: &RunOutput, what: &str) {
    assert_eq!(a.diagnostics, b.diagnostics, "{what}: diagnostics");
    assert_eq!(a.motions.len(), b.motions.len(), "{what}: motion count");
    for (i, (x, y)) in a.motions.iter().zip(&b.motions).enumerate() {
        assert_eq!(x, y, "{what}: motion {i}");
    }
    assert_eq!(a.events, b.events, "{what}: events");
    assert_eq!(
        a.snapshots.len(),
        b.snapshots.len(),
        "{what}: snapshot count"
    );
    for (i, (x, y)) in a.snapshots.iter().zip(&b.snapshots).enumerate() {
        assert_eq!(x, y, "{what}: snapshot of block {i}");
    }
    assert_eq!(a.values, b.values, "{what}: values");
}

fn edit_sequence(d: Dialect, seed: u64, edits: usize) -> (u64, u64) {
    let mut rng = Rng(seed);
    let mut text = program(d, &mut rng, 9000);
    let mut prev = run_on(d, &text, None);
    let errors: Vec<_> = prev
        .diagnostics
        .iter()
        .filter(|x| x.severity == analyzer::Severity::Error)
        .collect();
    assert!(
        prev.checkpoints.len() >= 4,
        "{d:?}: too few checkpoints: {errors:?}"
    );
    let (mut rerun_blocks, mut full_blocks) = (0, 0);
    for k in 0..edits {
        // Sometimes several edits between runs, as when the language server
        // skips the runs of versions that were already stale.
        for _ in 0..1 + rng.below(3) {
            text = edit(d, &mut rng, &text);
        }
        let full = run_on(d, &text, None);
        let inc = run_on(d, &text, Some(prev));
        assert_same(&inc, &full, &format!("{d:?} seed {seed} edit {k}"));
        rerun_blocks += inc.checkpoints.executed();
        full_blocks += full.checkpoints.executed();
        prev = inc;
    }
    (rerun_blocks, full_blocks)
}

#[test]
fn rerun_equals_a_full_run_over_random_edits() {
    for d in [Dialect::Rs274ngc, Dialect::Fanuc, Dialect::Servoworks] {
        let seeds: u64 = std::env::var("RERUN_SEEDS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1);
        let (mut inc, mut full) = (0, 0);
        for k in 0..seeds {
            let (i, f) = edit_sequence(d, 0x5eed_0000 + d as u64 + 977 * k, 25);
            inc += i;
            full += f;
        }
        eprintln!("{d:?}: reruns executed {inc} blocks, full runs {full}");
    }
}

/// Programs with calls or loops are not single-pass: no checkpoints, and a
/// rerun is a full run (same result).
#[test]
fn programs_with_flow_control_rerun_in_full() {
    let d = Dialect::Rs274ngc;
    let text = "o100 sub\nG1 X[#1] F100\no100 endsub\no100 call [2]\nG0 X0\nM2\n".to_string();
    let first = run_on(d, &text, None);
    assert!(first.checkpoints.is_empty());
    let edited = text.replace("[2]", "[3]");
    let inc = run_on(d, &edited, Some(first));
    let full = run_on(d, &edited, None);
    assert_same(&inc, &full, "flow control");
    assert_eq!(inc.motions[0].end[0], 3.0);
}

/// An edit that changes the state for good (units) runs to the end; one that
/// does not meets the previous run at the next checkpoint, in every dialect.
#[test]
fn a_local_edit_reruns_a_few_thousand_blocks() {
    for d in [Dialect::Rs274ngc, Dialect::Fanuc, Dialect::Servoworks] {
        let e = eob(d);
        let mut text = format!("G21 G90 F100{e}");
        for i in 0..20_000 {
            text.push_str(&format!("G1 X{}. Y{}.{e}", i % 50, i % 7));
        }
        text.push_str(&format!("M30{e}"));
        let first = run_on(d, &text, None);
        let at = text.len() / 2;
        let at = text[at..].find('\n').map_or(at, |p| at + p + 1);
        // Up and down again: the state after it is the state before.
        let local = format!("{}G0 Z5.{e}G0 Z0{e}{}", &text[..at], &text[at..]);
        let inc = run_on(d, &local, Some(first.clone()));
        assert_same(&inc, &run_on(d, &local, None), "local edit");
        assert!(
            inc.checkpoints.executed() <= 3 * 2048 + 2,
            "{d:?}: executed {}",
            inc.checkpoints.executed()
        );
        let lasting = format!("{}G91{e}{}", &text[..at], &text[at..]);
        let inc = run_on(d, &lasting, Some(first));
        assert_same(&inc, &run_on(d, &lasting, None), "lasting edit");
        assert!(inc.checkpoints.executed() > 10_000, "{d:?}");
    }
}
