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

/// The configurations the project ships (examples, test workspaces, the README's
/// sample) read without a single issue: a key they use that the declarations
/// drop or rename would show here.
#[test]
fn shipped_configurations_read_cleanly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut texts: Vec<(String, String)> = Vec::new();
    let mut stack = vec![root.join("examples"), root.join("tests")];
    while let Some(dir) = stack.pop() {
        let Ok(rd) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "toml")
                && (p.ends_with("partscope.toml") || p.starts_with(root.join("examples")))
            {
                let text = std::fs::read_to_string(&p).expect("read");
                texts.push((p.display().to_string(), text));
            }
        }
    }
    assert!(texts.len() >= 8, "{texts:?}");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let sample = readme
        .split("```toml\n")
        .nth(1)
        .and_then(|s| s.split("```").next())
        .expect("a toml block in the README");
    texts.push(("README.md".into(), sample.to_string()));
    for (name, text) in &texts {
        let (_, issues) = analyzer::Config::load(text);
        assert_eq!(issues, vec![], "{name}");
    }
}
