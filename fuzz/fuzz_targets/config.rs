//! Arbitrary text as a `partscope.toml` and as a machine profile: reading it
//! never panics, every issue's span lies in the text, and the settings, the
//! interpreter's table and the planner's profile are derived from what was read.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let (config, issues) = analyzer::Config::load(&text);
    for i in &issues {
        if let Some(s) = &i.span {
            assert!(s.start <= s.end && s.end <= text.len());
        }
    }
    for dialect in analyzer::Dialect::ALL {
        let _ = analyzer::Settings::from_config(&config, Some(dialect));
        let profile = runtime::dryrun::profile_from_table(&config.machine, dialect);
        let _ = profile.check_ranges();
    }
    let _ = analyzer::config::MachineConfig::load(&text);
});
