//! Arbitrary bytes through the interpreter and the planner: the first byte
//! picks the dialect and variant, the second whether LinuxCNC canonical lines
//! are produced. A small step budget keeps each input cheap; endless loops
//! must end at the budget with a diagnostic, not hang.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some((dialect, variant, rest)) = partscope_fuzz::split_dialect(data) {
        partscope_fuzz::interpret(dialect, variant, rest);
    }
});
