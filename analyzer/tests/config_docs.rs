//! `docs/configuration.md` is generated from the key declarations of
//! `analyzer/src/config.rs`; this test fails when the committed file differs.
//! `PARTSCOPE_UPDATE_DOCS=1 cargo test -p analyzer --test config_docs` rewrites it.

use std::path::Path;

#[test]
fn configuration_reference_is_generated_from_the_declarations() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/configuration.md");
    let want = analyzer::config::reference_markdown();
    if std::env::var_os("PARTSCOPE_UPDATE_DOCS").is_some() {
        std::fs::write(&path, &want).expect("write docs/configuration.md");
        return;
    }
    let have = std::fs::read_to_string(&path).expect("read docs/configuration.md");
    assert!(
        have == want,
        "docs/configuration.md is stale: run PARTSCOPE_UPDATE_DOCS=1 cargo test -p analyzer --test config_docs"
    );
}

#[test]
fn every_declared_key_has_a_row_with_values_and_meaning() {
    let doc = analyzer::config::reference_markdown();
    for k in analyzer::config::MachineConfig::KEYS {
        let row = format!("| `{}` |", k.name);
        assert!(doc.contains(&row), "{}", k.name);
        assert!(!k.meaning.is_empty() && !k.values.is_empty(), "{}", k.name);
    }
}
