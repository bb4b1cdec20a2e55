//! The spec coverage ledger (`spec-coverage.toml`) accounts for every candidate
//! diagnostic id of the three spec digests: implemented by a rule (with a
//! fixture that shows it), left to the runtime, or declined with a reason.

use std::collections::BTreeSet;
use std::path::Path;

use analyzer::rules::registry::RULES;
use analyzer::rules::Origin;

/// RS274/NGC ids of the digest's catalogue (§9), by number.
const NGC: &[u32] = &[
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26,
    27, 28, 29, 30, 31, 32, 33, 34, 100, 101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111,
    112, 113, 114, 115, 200, 201, 202, 203, 204, 205, 206, 207, 208, 209, 210, 211, 212, 213, 214,
    215, 216, 217, 218, 219, 220, 221, 222, 223, 224, 225, 226, 227, 228, 229, 230, 231, 232, 241,
    300, 301, 302, 303, 304, 305, 306, 307, 308, 309, 310, 311, 312, 313, 314, 315, 316, 317, 318,
    319, 320, 330, 331, 332, 333, 334, 335, 336, 337, 338, 400, 401, 402, 403, 404, 405, 406, 407,
    408, 409, 410, 411, 412, 413, 414, 415, 416, 417, 418, 419, 420, 421, 422, 423, 424, 425, 426,
    427, 428, 429, 430, 431, 432, 433, 500, 501, 502, 503, 504, 505, 506, 507, 508, 509, 510, 511,
    600, 601, 602, 603, 604, 605, 606, 607, 608, 609, 610, 611, 612, 613, 614, 615, 616, 617, 618,
    700, 701, 702, 703, 704, 705, 707, 708, 709, 710, 711, 712, 800, 801, 802, 803, 804, 805, 806,
    807, 808, 809, 810, 811, 812, 813, 814, 815, 816, 817, 818, 819, 820, 821, 822, 823,
];

/// FANUC ids of the digest's catalogue (§7), by number.
const FAN: &[u32] = &[
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 20, 21, 22, 23, 24, 25, 26, 27, 28,
    30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47, 48, 49, 50, 51, 52, 55,
    56, 57, 60, 61, 62, 63, 70, 71, 72, 73, 74, 75, 76, 77, 78, 79, 80, 81, 82, 83, 84, 85, 86, 87,
    88, 89, 90, 91, 95, 96, 97, 100, 101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 120, 121,
    122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136, 137, 138, 139, 140,
    141, 142, 143, 144, 145, 146, 147, 150, 151, 152, 153, 154, 155, 156, 157, 158, 159, 160, 161,
    162, 163,
];

fn expected_ids() -> BTreeSet<String> {
    let mut ids: BTreeSet<String> = (1..=151).map(|n| format!("SW{n:03}")).collect();
    ids.extend(NGC.iter().map(|n| format!("NGC{n:03}")));
    ids.extend(FAN.iter().map(|n| format!("FAN{n:03}")));
    ids
}

/// The ids a digest mentions, when the shared spec folder is next to the checkout.
fn digest_ids(dir: &Path) -> Option<BTreeSet<String>> {
    let mut ids = BTreeSet::new();
    for (file, prefix) in [
        ("servoworks.md", "SW"),
        ("rs274ngc.md", "NGC"),
        ("fanuc.md", "FAN"),
    ] {
        let text = std::fs::read_to_string(dir.join(file)).ok()?;
        let bytes = text.as_bytes();
        let mut i = 0;
        while let Some(pos) = text[i..].find(prefix) {
            let start = i + pos;
            let digits = &bytes[start + prefix.len()..];
            let n = digits.iter().take_while(|b| b.is_ascii_digit()).count();
            let before_ok = start == 0 || !bytes[start - 1].is_ascii_alphanumeric();
            if n == 3 && before_ok && digits.get(3).is_none_or(|b| !b.is_ascii_alphanumeric()) {
                ids.insert(text[start..start + prefix.len() + 3].to_string());
            }
            i = start + prefix.len();
        }
    }
    Some(ids)
}

#[test]
fn ledger_covers_every_spec_id() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text =
        std::fs::read_to_string(root.join("spec-coverage.toml")).expect("read spec-coverage.toml");
    let ledger: toml::Table = match toml::from_str(&text) {
        Ok(t) => t,
        Err(e) => panic!("spec-coverage.toml does not parse: {}", e.message()),
    };
    let expected = expected_ids();
    let mut errors = Vec::new();

    let spec_dir = root.join("../../shared/spec");
    if spec_dir.is_dir() {
        let found = digest_ids(&spec_dir).expect("read the digests");
        for id in found.difference(&expected) {
            errors.push(format!(
                "{id} appears in the digests but not in this test's id lists"
            ));
        }
        for id in expected.difference(&found) {
            errors.push(format!(
                "{id} is in this test's id lists but no longer in the digests"
            ));
        }
    }

    for id in &expected {
        if !ledger.contains_key(id) {
            errors.push(format!("{id}: missing from spec-coverage.toml"));
        }
    }
    for (id, entry) in &ledger {
        if !expected.contains(id) {
            errors.push(format!("{id}: not a candidate id of the digests"));
            continue;
        }
        let Some(entry) = entry.as_table() else {
            errors.push(format!("{id}: not a table"));
            continue;
        };
        let kinds: Vec<&str> = ["rule", "runtime", "no"]
            .into_iter()
            .filter(|k| entry.contains_key(*k))
            .collect();
        if kinds.len() != 1 {
            errors.push(format!(
                "{id}: needs exactly one of rule/runtime/no, has {kinds:?}"
            ));
            continue;
        }
        for key in entry.keys() {
            if !["rule", "runtime", "no", "fixture"].contains(&key.as_str()) {
                errors.push(format!("{id}: unknown key {key}"));
            }
        }
        let value = entry[kinds[0]].as_str().unwrap_or("");
        if value.trim().is_empty() {
            errors.push(format!("{id}: empty {}", kinds[0]));
        }
        if kinds[0] != "rule" {
            if entry.contains_key("fixture") {
                errors.push(format!("{id}: a fixture only goes with a rule"));
            }
            continue;
        }
        // Runtime rules (A, C, D, F, K, T, X codes) live in the runtime crate; the
        // server's spec_coverage test checks them against the combined registry.
        if value.starts_with(['A', 'C', 'D', 'F', 'K', 'T', 'X']) {
            continue;
        }
        let Some(meta) = analyzer::rules::registry::lookup(value).filter(|m| m.code == value)
        else {
            errors.push(format!("{id}: rule {value} is not in the registry"));
            continue;
        };
        if !meta.implements.contains(&id.as_str()) {
            errors.push(format!(
                "{id}: rule {value} does not list it in `implements`"
            ));
        }
        if matches!(meta.origin, Origin::Static | Origin::Syntax) {
            match entry.get("fixture").and_then(|f| f.as_str()) {
                None => errors.push(format!("{id}: static rule {value} needs a fixture")),
                Some(f) => {
                    let path = root.join(f);
                    let in_dir = f.starts_with(&format!("tests/rules/{value}/invalid_"));
                    if !path.is_file() || !in_dir {
                        errors.push(format!("{id}: fixture {f} is not an existing tests/rules/{value}/invalid_* file"));
                    }
                }
            }
        }
    }
    // Every id a rule claims is recorded against that rule.
    for meta in RULES {
        for id in meta.implements {
            let recorded = ledger
                .get(*id)
                .and_then(|e| e.get("rule"))
                .and_then(|r| r.as_str());
            if recorded != Some(meta.code) {
                errors.push(format!(
                    "{}: claims {id}, but the ledger says {recorded:?}",
                    meta.code
                ));
            }
        }
    }
    assert!(
        errors.is_empty(),
        "{} problem(s):\n{}",
        errors.len(),
        errors.join("\n")
    );
}
