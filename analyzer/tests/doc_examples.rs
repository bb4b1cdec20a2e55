//! Every rule's documented examples are checked: the fenced blocks under
//! `## Example` must produce the rule's code, the ones under `Use instead:`
//! must not. The fence tag (`ngc`, `servoworks`, `fanuc`) names the dialect;
//! an optional `variant=NAME` after it selects the variant or profile, and
//! `integer_machine_unit` turns that ServoWorks machine option on.

use analyzer::dialect::{Dialect, Variant};
use analyzer::rules::registry::RULES;
use analyzer::{analyze, Settings};

#[derive(Debug, PartialEq)]
enum Part {
    Example,
    Instead,
    Other,
}

type Fence = (Dialect, Option<Variant>, bool);

/// (dialect and variant, code text, expect the rule's code) for each fenced block.
fn examples(doc: &str) -> Vec<(Fence, String, bool)> {
    let mut out = Vec::new();
    let mut part = Part::Other;
    let mut fence: Option<(Fence, String)> = None;
    for line in doc.lines() {
        let t = line.trim();
        if let Some((d, body)) = fence.as_mut() {
            if t == "```" {
                if part != Part::Other {
                    out.push((*d, std::mem::take(body), part == Part::Example));
                }
                fence = None;
            } else {
                body.push_str(line.strip_prefix(' ').unwrap_or(line));
                body.push('\n');
            }
            continue;
        }
        if let Some(tag) = t.strip_prefix("```") {
            let mut parts = tag.split_whitespace();
            let d = match parts.next().unwrap_or("") {
                "ngc" => Dialect::Rs274ngc,
                "servoworks" => Dialect::Servoworks,
                "fanuc" => Dialect::Fanuc,
                _ => panic!("fence tag `{tag}` is not a dialect"),
            };
            let opts: Vec<&str> = parts.collect();
            let v = opts
                .iter()
                .find_map(|p| p.strip_prefix("variant="))
                .map(|v| Variant::parse(v).expect("known variant"));
            let imu = opts.contains(&"integer_machine_unit");
            fence = Some(((d, v, imu), String::new()));
        } else if t.starts_with("## Example") {
            part = Part::Example;
        } else if t.starts_with("Use instead") {
            part = Part::Instead;
        } else if t.starts_with("## ") {
            part = Part::Other;
        }
    }
    assert!(fence.is_none(), "unterminated fence");
    out
}

#[test]
fn rule_doc_examples() {
    let mut failures = Vec::new();
    // Rules whose trigger is not program text (a file that cannot be read, bytes that are
    // not text, a configuration file) have no gcode examples; their behaviour is tested in
    // the CLI tests.
    const NOT_TEXT_TRIGGERED: &[&str] = &["L000", "L009", "L016"];
    for meta in RULES {
        if NOT_TEXT_TRIGGERED.contains(&meta.code) {
            continue;
        }
        let ex = examples(meta.doc);
        if !ex.iter().any(|e| e.2) || !ex.iter().any(|e| !e.2) {
            failures.push(format!(
                "{}: needs an `## Example` and a `Use instead:` block",
                meta.code
            ));
        }
        for ((dialect, variant, imu), text, expect) in ex {
            let mut settings = Settings::new(dialect);
            settings.integer_machine_unit = imu;
            if let Some(v) = variant {
                settings.variant = v;
            }
            settings.select = vec!["ALL".into(), meta.code.into()];
            let a = analyze(text.as_bytes().to_vec(), &settings);
            let found = a.diagnostics.iter().any(|d| d.code == meta.code);
            if found != expect {
                let got: Vec<String> = a
                    .diagnostics
                    .iter()
                    .map(|d| format!("{} {}", d.code, d.message))
                    .collect();
                failures.push(format!(
                    "{} ({}): {} block {}:\n{text}got: {got:#?}",
                    meta.code,
                    dialect.as_str(),
                    if expect { "Example" } else { "Use instead" },
                    if expect {
                        "does not produce the code"
                    } else {
                        "produces the code"
                    }
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
