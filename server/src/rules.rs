//! The combined rule registry: the analyzer's syntax and static rules plus the
//! runtime's flow-sensitive rules.

use analyzer::rules::RuleMeta;

pub fn all() -> Vec<&'static RuleMeta> {
    let mut v: Vec<&'static RuleMeta> = analyzer::rules::registry::RULES.to_vec();
    v.extend(runtime::rules::REGISTRY.iter().copied());
    v.sort_by_key(|r| r.code);
    v
}

pub fn lookup(code: &str) -> Option<&'static RuleMeta> {
    all()
        .into_iter()
        .find(|r| r.code.eq_ignore_ascii_case(code) || r.name.eq_ignore_ascii_case(code))
}

/// A rule doc as text: the doc comment lines with their single leading space removed.
pub fn clean_doc(doc: &str) -> String {
    doc.lines()
        .map(|l| l.strip_prefix(' ').unwrap_or(l))
        .collect::<Vec<_>>()
        .join("\n")
}
