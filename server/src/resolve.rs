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

    /// Adds the `SUBROUTINE_PATH` folders, searched after the caller's and the
    /// main program's folders (RS274/NGC and FANUC; ServoWorks looks only beside
    /// the main program).
    pub fn with_search(mut self, dirs: Vec<PathBuf>) -> FsResolver {
        self.search = dirs;
        self
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

/// The `SUBROUTINE_PATH` folders: `machine.subroutine_path` (a string with `:`
/// separators, or an array) relative to the config file's folder.
pub fn subroutine_path(machine: &toml::Table, config: Option<&Path>) -> Vec<PathBuf> {
    let base = config
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let parts: Vec<String> = match machine.get("subroutine_path") {
        Some(toml::Value::String(s)) => s.split(':').map(str::to_string).collect(),
        Some(toml::Value::Array(a)) => a
            .iter()
            .filter_map(|v| v.as_str().map(str::to_string))
            .collect(),
        _ => Vec::new(),
    };
    parts
        .into_iter()
        .filter(|p| !p.trim().is_empty())
        .map(|p| base.join(p.trim()))
        .collect()
}

/// The project a file on the command line belongs to, which bounds what its
/// subprogram calls may read: the nearest folder above it holding `.git`, else
/// the current folder when the file is inside it, else the file's own folder.
/// A `--config` file's folder is not the project (`ci/partscope.toml` would
/// hide the programs beside `src/main.nc`).
pub fn project_root(file: &Path) -> PathBuf {
    let file = file.canonicalize().unwrap_or_else(|_| file.to_path_buf());
    let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
    if let Some(git) = dir.ancestors().find(|a| a.join(".git").exists()) {
        return git.to_path_buf();
    }
    match std::env::current_dir().and_then(|c| c.canonicalize()) {
        Ok(cwd) if dir.starts_with(&cwd) => cwd,
        _ => dir,
    }
}
