//! Every planner key of `[machine]` reaches the planner's profile. A key the
//! reference documents (docs/configuration.md) but `MachineProfile::with`
//! forgets would be read without a word and change no cycle time.

use analyzer::config::MachineConfig;
use analyzer::Dialect;
use runtime::machine::MachineProfile;

/// Values to try for a key: the words its documentation quotes (as TOML
/// strings and as written), then numbers, booleans, an M-code table and axes.
fn candidates(values: &str) -> Vec<String> {
    let mut out = Vec::new();
    for w in values.split('`').skip(1).step_by(2) {
        out.push(format!("\"{w}\""));
        out.push(w.to_string());
    }
    for v in [
        "0",
        "1",
        "0.37",
        "3",
        "250",
        "0.0005",
        "true",
        "false",
        "{ M8 = 1.5 }",
        "[\"X\", \"Y\"]",
        "[{ letter = \"X\", max_velocity = 7.0 }]",
    ] {
        out.push(v.to_string());
    }
    out
}

#[test]
fn every_planner_key_changes_the_profile() {
    let keys = MachineConfig::planner_keys();
    assert!(keys.len() > 20, "{} planner keys", keys.len());
    let mut missing = Vec::new();
    for dialect in [Dialect::Rs274ngc, Dialect::Fanuc, Dialect::Servoworks] {
        let base = MachineProfile::default_for(dialect);
        for key in keys {
            let applied = candidates(key.values).iter().any(|v| {
                let (m, issues) = MachineConfig::load(&format!("{} = {v}\n", key.name));
                issues.is_empty() && !m.is_empty() && base.with(&m) != base
            });
            if !applied {
                missing.push(format!("{} ({})", key.name, dialect.as_str()));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "planner keys that no valid value makes reach MachineProfile::with: {missing:?}"
    );
}
