//! Rule codes are typed. A diagnostic of the analyzer takes its code from its rule's
//! `declare_rule!` static (`UNKNOWN_CODE.error(span, msg)`), never from a string
//! literal, so a typo cannot emit a code no rule documents; and every rule declared in
//! the analyzer is in `registry::RULES`, the list `partscope rule`, hover and SARIF
//! read. Both tests read the analyzer's own source, so neither needs a second list of
//! codes kept by hand.

#[path = "../../tests/common/rule_scan.rs"]
mod rule_scan;

use analyzer::rules::registry::RULES;
use analyzer::rules::Origin;
use rule_scan::{code_shaped, scan, sources};

/// The letters of the analyzer's codes (`L`, `G`, `W`, `P`, `S`), read from the registry.
fn analyzer_letter(code: &str) -> bool {
    RULES.iter().any(|r| r.code.get(..1) == code.get(..1))
}

#[test]
fn no_rule_code_is_written_as_a_literal_outside_its_declaration() {
    let mut found = Vec::new();
    for (file, scan) in sources(env!("CARGO_MANIFEST_DIR")) {
        for (line, code) in scan.code_literals {
            // The one exception: twins.rs pairs analyzer codes with the runtime's
            // (W003 with A005), and the analyzer cannot name the runtime's statics
            // (the runtime depends on it, not the other way round). Only codes of
            // the runtime's letters may stay there;
            // server/tests/one_fault_one_diagnostic.rs checks each is a
            // documented rule.
            if file == "twins.rs" && !analyzer_letter(&code) {
                continue;
            }
            found.push(format!("src/{file}:{line}: \"{code}\""));
        }
    }
    assert!(
        found.is_empty(),
        "rule codes written as literals; emit with the rule's static \
         (`RULE.error(span, msg)`) and compare with `RULE.code`:\n{}",
        found.join("\n")
    );
}

#[test]
fn every_rule_the_analyzer_declares_is_registered() {
    // With no code literal outside `declare_rule!` (the test above), every code the
    // analyzer emits is the code of a declared static; so every declared static must
    // be in RULES, and RULES must hold nothing else.
    let mut declared = Vec::new();
    for (file, scan) in sources(env!("CARGO_MANIFEST_DIR")) {
        for (name, code, origin) in scan.declared {
            assert!(
                code_shaped(&code) && !name.is_empty(),
                "src/{file}: unreadable declare_rule! ({name:?}, {code:?})"
            );
            assert!(
                origin == "Syntax" || origin == "Static",
                "src/{file}: {name} ({code}) has origin {origin}; runtime rules live in runtime"
            );
            let registered = RULES.iter().find(|r| r.code == code);
            assert!(
                registered.is_some(),
                "src/{file}: {name} ({code}) is not in registry::RULES"
            );
            if let Some(r) = registered {
                let want = if origin == "Syntax" {
                    Origin::Syntax
                } else {
                    Origin::Static
                };
                assert_eq!(r.origin, want, "{code}");
            }
            declared.push(code);
        }
    }
    declared.sort();
    let mut registered: Vec<String> = RULES.iter().map(|r| r.code.to_string()).collect();
    registered.sort();
    assert_eq!(declared, registered, "declared rules vs registry::RULES");
}

#[test]
fn the_scan_sees_literals_where_the_compiler_would() {
    let src = r##"
        declare_rule! {
            /// Not "G001" here.
            pub static A = { code: "G001", name: "a", summary: "s",
                implements: &[], origin: Static, default_enabled: true }
        }
        fn f<'a>(x: &'a str) -> bool {
            // "W001" in a comment
            /* "W002" /* nested */ "W003" */
            let _ = (b"M098", '"', '\'', b'"', r#"raw "W004" "#, "a \" W005");
            x == "P006" || x == "p007"
        }
        #[cfg(test)]
        mod tests {
            fn g() { let _ = "G004"; }
        }
        const LATE: &str = "L009";
    "##;
    let s = scan(src);
    let codes: Vec<&str> = s.code_literals.iter().map(|(_, c)| c.as_str()).collect();
    assert_eq!(codes, ["P006", "L009"]);
    assert_eq!(s.code_literals[0].0, 11);
    assert_eq!(s.declared, [("A".into(), "G001".into(), "Static".into())]);
}
