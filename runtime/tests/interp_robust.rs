//! `run` never panics: random programs built from G-code fragments, in every
//! dialect, must produce an output (a panic fails the test).

mod common;

use analyzer::Dialect;
use common::*;

const FRAGMENTS: &[&str] = &[
    "G0",
    "G1",
    "G2",
    "G3",
    "G4",
    "G10 L2 P1",
    "G10 L1 P1",
    "G10 L20 P2",
    "G17",
    "G18",
    "G19",
    "G20",
    "G21",
    "G28",
    "G30",
    "G33 K1",
    "G38.2",
    "G40",
    "G41 D1",
    "G42 D2",
    "G41.1 D0.5",
    "G43 H1",
    "G44 H1",
    "G49",
    "G50",
    "G51 P2.",
    "G50.1",
    "G51.1 X0",
    "G52",
    "G53",
    "G54",
    "G55",
    "G54.1 P3",
    "G61",
    "G64 P0.1",
    "G65 P9000 A1.",
    "G66 P9000",
    "G67",
    "G68 R30",
    "G69",
    "G73",
    "G76",
    "G80",
    "G81",
    "G82",
    "G83",
    "G84",
    "G85",
    "G86",
    "G87",
    "G88",
    "G89",
    "G90",
    "G91",
    "G92",
    "G92.1",
    "G93",
    "G94",
    "G95",
    "G98",
    "G99",
    "G15",
    "G16",
    "G05 P10000",
    "G08 P0",
    "M3",
    "M4",
    "M5",
    "M6",
    "M8",
    "M9",
    "M98 P1",
    "M99",
    "M30",
    "M2",
    "X1",
    "X-10.5",
    "Y2",
    "Z-1",
    "A90",
    "R5",
    "R-3",
    "I1",
    "J-1",
    "K2",
    "P3",
    "Q0.5",
    "L2",
    "F100",
    "F0",
    "S1000",
    "T1",
    "H1",
    "#1=[#1+1]",
    "#100=5",
    "#<a>=2",
    "X#1",
    "Y[#1*2]",
    "[1/0]",
    "o1 sub",
    "o1 endsub",
    "o1 call",
    "o2 while [#1 LT 3]",
    "o2 endwhile",
    "o3 if [#1 GT 1]",
    "o3 else",
    "o3 endif",
    "o4 repeat [2]",
    "o4 endrepeat",
    "o5 do",
    "o5 while [0]",
    "WHILE [#1 LT 3] DO 1",
    "END 1",
    "IF [#1 EQ 1] GOTO 10",
    "GOTO 10",
    "N10",
    "O1",
    "O9000",
    "(msg, hi)",
    "(debug, #1)",
    "%",
    "/",
    ";",
    "@1",
    "^30",
    "G2.3",
    "E1",
    "U1",
];

fn lcg(seed: &mut u64) -> u64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    *seed >> 33
}

#[test]
fn random_programs_never_panic() {
    let mut seed = 0x5eed_u64;
    for round in 0..250 {
        let mut text = String::new();
        let lines = 1 + lcg(&mut seed) % 30;
        for _ in 0..lines {
            let words = 1 + lcg(&mut seed) % 5;
            for _ in 0..words {
                let f = FRAGMENTS[(lcg(&mut seed) as usize) % FRAGMENTS.len()];
                text.push_str(f);
                text.push(' ');
            }
            text.push('\n');
        }
        for dialect in [Dialect::Rs274ngc, Dialect::Fanuc, Dialect::Servoworks] {
            let machine =
                "circle_error_allowance = 0.5\n[tools]\n1 = { length = 10.0, diameter = 4.0 }\n";
            let out = run_with(
                dialect,
                &text,
                machine,
                &[("1", "G0 X1\nM99\n"), ("9000", "G91 G0 Z#26\nM99\n")],
                None,
            );
            // Every motion is finite and every diagnostic is located in a known file.
            for m in &out.motions {
                assert!(
                    m.end.iter().all(|v| v.is_finite()),
                    "round {round} {dialect:?} line {} {:?}: {text}",
                    m.line,
                    m
                );
            }
            for d in &out.diagnostics {
                assert!(
                    (d.file.0 as usize) <= out.files.len(),
                    "round {round}: {d:?}"
                );
            }
        }
    }
}

#[test]
fn state_is_cheap_to_clone() {
    // The interpreter state is a value a host can checkpoint.
    fn assert_clone<T: Clone>() {}
    assert_clone::<runtime::interp::State>();
    let out = run_ngc("G21\nG0 X1\nM2\n");
    assert_eq!(out.snapshots.len(), 3);
}
