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

/// Checks the rule selectors of `--select`/`--ignore`: each must name at least
/// one rule (by code, code prefix or name, or be `ALL`), or the error names the
/// closest rule, so a typo does not silently turn rules off.
pub fn check_selectors(flag: &str, patterns: &[String]) -> Result<(), String> {
    let rules = all();
    for p in patterns.iter().map(|p| p.trim()).filter(|p| !p.is_empty()) {
        if rules
            .iter()
            .any(|r| analyzer::Settings::matches(p, r.code, r.name))
        {
            continue;
        }
        let near = rules
            .iter()
            .flat_map(|r| [r.code, r.name])
            .min_by_key(|c| edit_distance(&p.to_ascii_lowercase(), &c.to_ascii_lowercase()))
            .unwrap_or("ALL");
        return Err(format!(
            "{flag} {p}: no rule has this code, code prefix or name (did you mean `{near}`? `partscope rule --all` lists them)"
        ));
    }
    Ok(())
}

/// Checks a `--fail-level` value.
pub fn check_level(flag: &str, level: &str) -> Result<analyzer::Severity, String> {
    analyzer::Severity::parse(level).ok_or_else(|| {
        let near = ["error", "warning", "info", "hint"]
            .into_iter()
            .min_by_key(|c| edit_distance(&level.to_ascii_lowercase(), c))
            .unwrap_or("warning");
        format!("{flag} {level}: not a level; use error, warning, info or hint (did you mean `{near}`?)")
    })
}

/// Levenshtein distance, for "did you mean" suggestions.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}
