//! Files outside the open documents, always confined to the workspace folders.
//! Subprogram files are found by the host's one resolver
//! ([`crate::resolve::FsResolver`], shared with the command line).
//!
//! Every path is canonicalized before it is read, so a symlink inside the
//! workspace that points outside it is rejected like a plain outside path.

use std::path::{Path, PathBuf};

pub use crate::resolve::{confine, subroutine_path};

/// Canonicalizes workspace folders; folders that do not exist are dropped.
pub fn canonical_roots(paths: impl IntoIterator<Item = PathBuf>) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = paths
        .into_iter()
        .filter_map(|p| p.canonicalize().ok())
        .collect();
    out.sort();
    out.dedup();
    out
}

/// Reads a file inside the workspace; `None` outside it or on any error.
pub fn read_confined(path: &Path, roots: &[PathBuf]) -> Option<(PathBuf, String)> {
    let canon = confine(path, roots)?;
    let text = std::fs::read(&canon).ok()?;
    Some((canon, String::from_utf8_lossy(&text).into_owned()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_outside_the_workspace_are_not_read() {
        let base = std::env::temp_dir().join(format!("partscope-lsp-ws-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(base.join("ws/sub")).unwrap();
        std::fs::create_dir_all(base.join("outside")).unwrap();
        std::fs::write(base.join("outside/secret.ngc"), "o<secret> sub\n").unwrap();
        std::fs::write(base.join("ws/sub/inner.ngc"), "o<inner> sub\n").unwrap();
        let roots = canonical_roots([base.join("ws")]);
        assert_eq!(
            read_confined(&base.join("outside/secret.ngc"), &roots),
            None
        );
        assert_eq!(
            read_confined(&roots[0].join("../outside/secret.ngc"), &roots),
            None
        );
        assert!(read_confined(&roots[0].join("sub/inner.ngc"), &roots).is_some());
    }
}
