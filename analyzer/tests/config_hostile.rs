//! Hostile configurations: `Config::load` never panics, and every wrong value is
//! one issue located at its own key.

use analyzer::config::{Config, MachineConfig};
use proptest::prelude::*;

/// Values of every TOML type, and numbers at the edges.
const VALUES: &[&str] = &[
    "\"x\"",
    "-1",
    "0",
    "9223372036854775807",
    "1e308",
    "-0.0",
    "nan",
    "inf",
    "true",
    "[]",
    "[1, \"a\"]",
    "{}",
    "{ a = 1 }",
    "1979-05-27T07:32:00Z",
];

#[test]
fn every_machine_key_with_every_kind_of_value() {
    for key in MachineConfig::KEYS {
        for value in VALUES {
            let line = format!("{} = {value}", key.name);
            let neighbour = if key.name == "coolant_time" {
                "spindle_orient_time"
            } else {
                "coolant_time"
            };
            let text = format!("[machine]\n{line}\n{neighbour} = 1.5\n");
            let (config, issues) = Config::load(&text);
            // The neighbour key is always read.
            let m = &config.machine;
            let read = if neighbour == "coolant_time" {
                m.coolant_time
            } else {
                m.spindle_orient_time
            };
            assert_eq!(read, Some(1.5), "{line}");
            assert!(issues.len() <= 1, "{line}: {issues:?}");
            for i in &issues {
                assert_eq!(i.key, format!("machine.{}", key.name), "{line}");
                let at = i.span.clone().expect("located");
                // On the key's own line.
                assert!(
                    at.start >= 10 && at.end <= 10 + line.len(),
                    "{line}: {at:?}"
                );
                assert!(i.message.contains(key.name), "{line}: {}", i.message);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn any_text_loads_without_panic(text in "(\\PC|\n|\\[|\\]|=|\"|\\{|\\}|,){0,200}") {
        let (_, issues) = Config::load(&text);
        for i in issues {
            if let Some(s) = i.span {
                prop_assert!(s.start <= s.end && s.end <= text.len());
            }
        }
    }

    #[test]
    fn any_machine_table_loads_without_panic(
        keys in proptest::collection::vec((0usize..80, 0usize..14), 0..20)
    ) {
        let mut text = String::from("[machine]\n");
        let names = MachineConfig::KEYS;
        let mut seen = std::collections::HashSet::new();
        for (k, v) in keys {
            let name = names[k % names.len()].name;
            if seen.insert(name) {
                text.push_str(&format!("{name} = {}\n", VALUES[v]));
            }
        }
        let (_, issues) = Config::load(&text);
        prop_assert!(issues.len() <= seen.len());
    }
}

#[test]
fn deep_nesting_is_an_issue_not_a_stack_overflow() {
    let text = format!(
        "[machine]\naxes = {}{}\n",
        "[".repeat(5000),
        "]".repeat(5000)
    );
    let (_, issues) = Config::load(&text);
    assert!(!issues.is_empty());
}
