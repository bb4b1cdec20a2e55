//! Structure-aware inputs (`partscope_fuzz::structured_program`): deep nesting of
//! every kind and long loops, through the parser, the static rules, the interpreter
//! and the planner. Each must end within its bounds with located diagnostics.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Some((dialect, variant, text)) = partscope_fuzz::structured_program(data) {
        partscope_fuzz::parse_and_analyze(dialect, variant, text.as_bytes());
        partscope_fuzz::interpret(dialect, variant, text.as_bytes());
    }
});
