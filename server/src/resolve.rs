//! The host side of subprogram resolution: finds the file a call names, never
//! outside the workspace root (symlinks and `..` included).

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use analyzer::{Dialect, FileId};
use runtime::{ResolvedFile, Resolver};

pub struct FsResolver {
    /// Directory of the main program (ServoWorks looks only here).
    main_dir: PathBuf,
    /// Additional search directories (LinuxCNC SUBROUTINE_PATH).
    search: Vec<PathBuf>,
    /// Canonical workspace root: nothing outside it is read.
    root: PathBuf,
    dialect: Dialect,
    /// Directories of resolved files, by FileId (index 0 = main file).
    dirs: Mutex<Vec<PathBuf>>,
}

impl FsResolver {
    pub fn new(main_file: &Path, root: Option<&Path>, dialect: Dialect) -> FsResolver {
        let main_dir = main_file
            .parent()
            .map(|p| {
                if p.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    p
                }
            })
            .unwrap_or(Path::new("."))
            .to_path_buf();
        let main_dir = main_dir.canonicalize().unwrap_or(main_dir);
        let root = root
            .and_then(|r| r.canonicalize().ok())
            .unwrap_or_else(|| main_dir.clone());
        FsResolver {
            dirs: Mutex::new(vec![main_dir.clone()]),
            main_dir,
            search: Vec::new(),
            root,
            dialect,
        }
    }

    fn candidates(&self, name: &str) -> Vec<String> {
        match self.dialect {
            Dialect::Servoworks => vec![
                format!("O{name}.dat"),
                format!("O{name}.DAT"),
                format!("o{name}.dat"),
            ],
            Dialect::Rs274ngc => vec![
                format!("{name}.ngc"),
                format!("{}.ngc", name.to_ascii_lowercase()),
                format!("{name}.NGC"),
            ],
            Dialect::Fanuc => {
                let mut v = Vec::new();
                for base in [format!("O{name}"), format!("O{name:0>4}"), name.to_string()] {
                    for ext in ["", ".nc", ".NC", ".fnc", ".txt", ".TXT"] {
                        v.push(format!("{base}{ext}"));
                    }
                }
                v
            }
        }
    }

    fn inside_root(&self, p: &Path) -> Option<PathBuf> {
        let c = p.canonicalize().ok()?;
        c.starts_with(&self.root).then_some(c)
    }
}

impl Resolver for FsResolver {
    fn resolve(&self, name: &str, from: FileId) -> Option<ResolvedFile> {
        if name.is_empty() || name.contains(['/', '\\']) || name.contains("..") {
            return None;
        }
        let mut dirs = Vec::new();
        let from_dir = self
            .dirs
            .lock()
            .ok()
            .and_then(|d| d.get(from.0 as usize).cloned());
        if let Some(d) = from_dir {
            dirs.push(d);
        }
        dirs.push(self.main_dir.clone());
        if self.dialect != Dialect::Servoworks {
            dirs.extend(self.search.iter().cloned());
        }
        for dir in dirs {
            for file in self.candidates(name) {
                let p = dir.join(&file);
                if !p.is_file() {
                    continue;
                }
                let Some(canonical) = self.inside_root(&p) else {
                    continue;
                };
                let Ok(text) = std::fs::read(&canonical) else {
                    continue;
                };
                if let Ok(mut d) = self.dirs.lock() {
                    d.push(
                        canonical
                            .parent()
                            .map(|p| p.to_path_buf())
                            .unwrap_or_default(),
                    );
                }
                return Some(ResolvedFile {
                    path: p.display().to_string(),
                    text: text.into(),
                });
            }
        }
        None
    }
}
