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
    /// The size limit for every program read, in MB (`--max-file-size`).
    max_mb: u64,
    /// Files found but not read, by the name called: why.
    refused: Mutex<Vec<(String, String)>>,
    /// Every file handed to the interpreter: (name as called, path, text).
    loaded: Mutex<Vec<crate::lsp::Loaded>>,
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
            loaded: Mutex::new(Vec::new()),
            main_dir,
            search: Vec::new(),
            root,
            dialect,
            max_mb: crate::cli::workspace::DEFAULT_MAX_FILE_MB,
            refused: Mutex::new(Vec::new()),
        }
    }

    /// Called files obey the same size limit as the main program.
    pub fn with_max_file_size(mut self, max_mb: u64) -> FsResolver {
        self.max_mb = max_mb;
        self
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
                for base in [
                    format!("O{name}"),
                    format!("O{name:0>4}"),
                    format!("O{name:0>5}"),
                    name.to_string(),
                ] {
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
    fn searches_like_the_control(&self) -> bool {
        !self.search.is_empty()
    }

    fn refused(&self, name: &str) -> Option<String> {
        let refused = self.refused.lock().ok()?;
        refused
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, why)| why.clone())
    }

    fn resolve(&self, name: &str, from: FileId) -> Option<ResolvedFile> {
        let found = self.find(name, from)?;
        if let Ok(mut l) = self.loaded.lock() {
            l.push((name.to_string(), found.path.clone(), found.text.clone()));
        }
        Some(found)
    }
}

impl FsResolver {
    /// The files the run loaded, in order: (name as called, path, text).
    pub fn loaded(&self) -> Vec<crate::lsp::Loaded> {
        self.loaded.lock().map(|l| l.clone()).unwrap_or_default()
    }

    fn find(&self, name: &str, from: FileId) -> Option<ResolvedFile> {
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
                if let Some(found) = self.load(name, &p, &canonical) {
                    return Some(found);
                }
            }
        }
        // A control finds a program by the O number of its head, not by a file
        // name (`gauge_tool_o1002.nc` holds O1002): look at the heads of the
        // G-code files in the caller's folder.
        if self.dialect == Dialect::Fanuc {
            let number: u32 = name.parse().ok()?;
            let dir = self
                .dirs
                .lock()
                .ok()
                .and_then(|d| d.get(from.0 as usize).cloned())
                .unwrap_or_else(|| self.main_dir.clone());
            return self.by_program_head(name, &dir, number);
        }
        None
    }
}

impl FsResolver {
    /// Reads a found file and records its folder as the one its own calls
    /// search first.
    fn load(&self, name: &str, path: &Path, canonical: &Path) -> Option<ResolvedFile> {
        let text = match crate::cli::workspace::read_program(canonical, self.max_mb) {
            Ok(text) => text,
            Err(why) => {
                if let Ok(mut r) = self.refused.lock() {
                    r.push((name.to_string(), format!("{}: {why}", file_name(path))));
                }
                return None;
            }
        };
        if let Ok(mut d) = self.dirs.lock() {
            d.push(
                canonical
                    .parent()
                    .map(Path::to_path_buf)
                    .unwrap_or_default(),
            );
        }
        Some(ResolvedFile {
            path: path.display().to_string(),
            text,
        })
    }
}

/// How much of a file is read to find its program head.
const HEAD_BYTES: usize = 4096;
/// Files looked at per folder when searching by program head.
const HEAD_FILES: usize = 2000;

impl FsResolver {
    /// The first file of `dir` whose first program head is `O<number>`.
    fn by_program_head(&self, name: &str, dir: &Path, number: u32) -> Option<ResolvedFile> {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
            .ok()?
            .filter_map(|e| e.ok())
            .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
            .map(|e| e.path())
            .filter(|p| {
                p.extension().and_then(|x| x.to_str()).is_some_and(|x| {
                    crate::cli::workspace::EXTENSIONS.contains(&x.to_ascii_lowercase().as_str())
                })
            })
            .take(HEAD_FILES)
            .collect();
        entries.sort();
        for p in entries {
            let Some(canonical) = self.inside_root(&p) else {
                continue;
            };
            let Ok(file) = std::fs::File::open(&canonical) else {
                continue;
            };
            let mut head = Vec::with_capacity(HEAD_BYTES);
            use std::io::Read;
            if file.take(HEAD_BYTES as u64).read_to_end(&mut head).is_err() {
                continue;
            }
            if first_program_number(&head) != Some(number) {
                continue;
            }
            if let Some(found) = self.load(name, &p, &canonical) {
                return Some(found);
            }
        }
        None
    }
}

/// The number of the first `O1234` / `:1234` program head in a file's start.
fn first_program_number(head: &[u8]) -> Option<u32> {
    for line in head.split(|b| *b == b'\n') {
        let line = line.trim_ascii();
        match line.first() {
            None | Some(b'%' | b'(') => continue,
            Some(b'O' | b'o' | b':') => {
                let digits: Vec<u8> = line[1..]
                    .iter()
                    .copied()
                    .take_while(u8::is_ascii_digit)
                    .collect();
                return std::str::from_utf8(&digits).ok()?.parse().ok();
            }
            _ => return None,
        }
    }
    None
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

/// A path's last part, for messages (the full path is the user's own business).
fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}
