//! Files outside the open documents: finding subprogram files, always
//! confined to the workspace folders.
//!
//! Every path is canonicalized before it is read, so a symlink inside the
//! workspace that points outside it is rejected like a plain outside path.

use std::path::{Path, PathBuf};

use analyzer::Dialect;

/// The canonical form of `path` when it exists and lies inside one of `roots`
/// (which are canonical already).
pub fn confine(path: &Path, roots: &[PathBuf]) -> Option<PathBuf> {
    let canon = path.canonicalize().ok()?;
    roots.iter().any(|r| canon.starts_with(r)).then_some(canon)
}

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

/// Looks for `file_name` in `dir`, exactly or ignoring ASCII case (programs are
/// often written `O1234.NC` on one machine and called `o1234.nc` on another).
fn find_in_dir(dir: &Path, file_name: &str, roots: &[PathBuf]) -> Option<PathBuf> {
    let exact = dir.join(file_name);
    if exact.is_file() {
        return confine(&exact, roots);
    }
    let entries = std::fs::read_dir(dir).ok()?;
    for e in entries.flatten() {
        let name = e.file_name();
        if name
            .to_str()
            .is_some_and(|n| n.eq_ignore_ascii_case(file_name))
        {
            let p = e.path();
            if p.is_file() {
                return confine(&p, roots);
            }
        }
    }
    None
}

/// Where the file defining subprogram/program `key` may be, in search order.
///
/// - `rs274ngc`: `<name>.ngc` next to the document, then in each folder of
///   `subroutine_path` (relative to the config's folder), then at each
///   workspace folder's top.
/// - `servoworks`: `O<name>.dat` next to the document (the manual's rule).
/// - `fanuc`: `O<number>` with the extensions CAM systems use, next to the document.
pub fn find_program_file(
    dialect: Dialect,
    key: &str,
    doc: &Path,
    subroutine_path: &[PathBuf],
    roots: &[PathBuf],
) -> Option<PathBuf> {
    let dir = doc.parent()?;
    let candidates: Vec<String> = match dialect {
        Dialect::Rs274ngc => vec![format!("{key}.ngc")],
        Dialect::Servoworks => vec![format!("O{key}.dat")],
        Dialect::Fanuc => {
            let n = key
                .parse::<u32>()
                .map(|n| format!("{n:04}"))
                .unwrap_or_else(|_| key.to_string());
            ["", ".nc", ".txt", ".tap", ".prg"]
                .iter()
                .map(|ext| format!("O{n}{ext}"))
                .collect()
        }
    };
    let mut dirs: Vec<PathBuf> = vec![dir.to_path_buf()];
    if dialect == Dialect::Rs274ngc {
        dirs.extend(subroutine_path.iter().cloned());
        dirs.extend(roots.iter().cloned());
    }
    for d in &dirs {
        for c in &candidates {
            if let Some(p) = find_in_dir(d, c, roots) {
                return Some(p);
            }
        }
    }
    None
}

/// Reads a file inside the workspace; `None` outside it or on any error.
pub fn read_confined(path: &Path, roots: &[PathBuf]) -> Option<(PathBuf, String)> {
    let canon = confine(path, roots)?;
    let text = std::fs::read(&canon).ok()?;
    Some((canon, String::from_utf8_lossy(&text).into_owned()))
}

pub use crate::resolve::subroutine_path;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symlinks_escaping_the_workspace_are_rejected() {
        let base = std::env::temp_dir().join(format!("partscope-lsp-ws-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(base.join("ws/sub")).unwrap();
        std::fs::create_dir_all(base.join("outside")).unwrap();
        std::fs::write(base.join("outside/secret.ngc"), "o<secret> sub\n").unwrap();
        std::fs::write(base.join("ws/sub/inner.ngc"), "o<inner> sub\n").unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(base.join("outside/secret.ngc"), base.join("ws/secret.ngc"))
            .unwrap();
        let roots = canonical_roots([base.join("ws")]);
        let doc = roots[0].join("main.ngc");
        assert!(find_program_file(
            Dialect::Rs274ngc,
            "inner",
            &doc,
            &[roots[0].join("sub")],
            &roots
        )
        .is_some());
        assert_eq!(
            find_program_file(Dialect::Rs274ngc, "secret", &doc, &[], &roots),
            None
        );
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

    #[test]
    fn program_file_names_per_dialect() {
        let base = std::env::temp_dir().join(format!("partscope-lsp-names-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(&base).unwrap();
        std::fs::write(base.join("OMoveXY.dat"), "G1 X1\nM99\n").unwrap();
        std::fs::write(base.join("o1234.nc"), "O1234;\nM99;\n").unwrap();
        let roots = canonical_roots([base.clone()]);
        let doc = roots[0].join("main.nc");
        let sw = find_program_file(Dialect::Servoworks, "MoveXY", &doc, &[], &roots).unwrap();
        assert!(sw.ends_with("OMoveXY.dat"));
        let f = find_program_file(Dialect::Fanuc, "1234", &doc, &[], &roots).unwrap();
        assert!(f.ends_with("o1234.nc"));
        assert_eq!(
            find_program_file(Dialect::Fanuc, "99", &doc, &[], &roots),
            None
        );
    }
}
