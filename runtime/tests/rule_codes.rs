//! Rule codes are typed in the runtime too. A diagnostic of the interpreter takes its
//! code from its rule's `declare_rule!` static (`ZERO_FEED.error(span, msg)`,
//! `cx.out.diag(&ZERO_FEED, …)`), never from a string literal, so a typo cannot emit a
//! code no rule documents; and every rule declared in the runtime is in
//! `runtime::rules::REGISTRY`, the list `partscope rule`, hover and SARIF read. The
//! scan is the analyzer's (`tests/common/rule_scan.rs`), over the runtime's source.

#[path = "../../tests/common/rule_scan.rs"]
mod rule_scan;

use analyzer::rules::Origin;
use rule_scan::{code_shaped, sources};
use runtime::rules::REGISTRY;

#[test]
fn no_rule_code_is_written_as_a_literal_outside_its_declaration() {
    let mut found = Vec::new();
    for (file, scan) in sources(env!("CARGO_MANIFEST_DIR")) {
        for (line, code) in scan.code_literals {
            found.push(format!("src/{file}:{line}: \"{code}\""));
        }
    }
    assert!(
        found.is_empty(),
        "rule codes written as literals; emit with the rule's static \
         (`RULE.error(span, msg)`, `cx.out.diag(&RULE, …)`) and compare with `RULE.code`:\n{}",
        found.join("\n")
    );
}

#[test]
fn every_rule_the_runtime_declares_is_registered() {
    let mut declared = Vec::new();
    for (file, scan) in sources(env!("CARGO_MANIFEST_DIR")) {
        for (name, code, origin) in scan.declared {
            assert!(
                code_shaped(&code) && !name.is_empty(),
                "src/{file}: unreadable declare_rule! ({name:?}, {code:?})"
            );
            assert_eq!(
                origin, "Runtime",
                "src/{file}: {name} ({code}) is declared in the runtime with origin {origin}"
            );
            let registered = REGISTRY.iter().find(|r| r.code == code);
            assert!(
                registered.is_some(),
                "src/{file}: {name} ({code}) is not in runtime::rules::REGISTRY"
            );
            if let Some(r) = registered {
                assert_eq!(r.origin, Origin::Runtime, "{code}");
            }
            declared.push(code);
        }
    }
    declared.sort();
    let mut registered: Vec<String> = REGISTRY.iter().map(|r| r.code.to_string()).collect();
    registered.sort();
    assert_eq!(
        declared, registered,
        "declared rules vs runtime::rules::REGISTRY"
    );
}
