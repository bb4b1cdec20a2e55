//! Keeps every source file of the runtime small enough to read in one sitting
//! (issue 16): a file that grows past the limit must be split by topic.

use std::path::{Path, PathBuf};

const MAX_LINES: usize = 1_500;

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn no_runtime_source_file_exceeds_the_line_limit() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    // The runtime has about a hundred source files; a handful means the walk went wrong.
    assert!(
        files.len() >= 50,
        "only {} files under {}",
        files.len(),
        src.display()
    );
    let too_long: Vec<String> = files
        .iter()
        .filter_map(|path| {
            let text = std::fs::read_to_string(path).expect("readable source file");
            let lines = text.lines().count();
            (lines > MAX_LINES).then(|| format!("{}: {lines} lines", path.display()))
        })
        .collect();
    assert!(
        too_long.is_empty(),
        "split these files by topic (at most {MAX_LINES} lines each):\n{}",
        too_long.join("\n")
    );
}
