//! The spec coverage ledger against the combined registry (analyzer + runtime):
//! every `rule = CODE` names a rule that exists and claims the id, and every id a
//! runtime rule claims is recorded as implemented. (analyzer/tests/spec_coverage.rs
//! checks completeness and the static rules' fixtures.)

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use serde_json::Value;

#[test]
fn ledger_agrees_with_the_runtime_rules() {
    let out = Command::new(env!("CARGO_BIN_EXE_partscope"))
        .args(["rule", "--all", "--json"])
        .output()
        .unwrap();
    let rules: Vec<Value> = serde_json::from_slice(&out.stdout).unwrap();
    let by_code: BTreeMap<String, &Value> = rules
        .iter()
        .map(|r| (r["code"].as_str().unwrap().to_string(), r))
        .collect();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let ledger: toml::Table = std::fs::read_to_string(root.join("analyzer/spec-coverage.toml"))
        .unwrap()
        .parse()
        .unwrap();
    let claims = |code: &str, id: &str| {
        by_code
            .get(code)
            .is_some_and(|r| r["implements"].as_array().unwrap().iter().any(|i| i == id))
    };
    let mut errors = Vec::new();
    let (mut implemented, mut runtime_left, mut declined) = (0, 0, 0);
    for (id, entry) in &ledger {
        if let Some(code) = entry.get("rule").and_then(|v| v.as_str()) {
            implemented += 1;
            if !by_code.contains_key(code) {
                errors.push(format!("{id}: rule {code} does not exist"));
            } else if !claims(code, id) {
                errors.push(format!(
                    "{id}: rule {code} does not list it in `implements`"
                ));
            }
        } else if entry.get("runtime").is_some() {
            runtime_left += 1;
        } else {
            declined += 1;
        }
    }
    for r in rules.iter().filter(|r| r["origin"] == "runtime") {
        let code = r["code"].as_str().unwrap();
        for id in r["implements"].as_array().unwrap() {
            let id = id.as_str().unwrap();
            match ledger.get(id).and_then(|e| e.get("rule")).and_then(|v| v.as_str()) {
                Some(recorded) if claims(recorded, id) => {}
                other => errors.push(format!("{code} claims {id}, but the ledger records {other:?} (run scripts/update_ledger.py)")),
            }
        }
    }
    println!("ledger: {} ids, {implemented} implemented, {runtime_left} left to the runtime, {declined} declined", ledger.len());
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}
