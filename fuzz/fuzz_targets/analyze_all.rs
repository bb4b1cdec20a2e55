//! Arbitrary bytes through the whole static analysis; the first byte picks
//! the dialect and variant.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some((dialect, variant, rest)) = partscope_fuzz::split_dialect(data) {
        partscope_fuzz::parse_and_analyze(dialect, variant, rest);
    }
});
