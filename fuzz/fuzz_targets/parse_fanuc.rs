//! Parse, print and analyse arbitrary bytes as a Fanuc program.
#![no_main]

use analyzer::dialect::Dialect;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    partscope_fuzz::parse_and_analyze(Dialect::Fanuc, 0, data);
});
