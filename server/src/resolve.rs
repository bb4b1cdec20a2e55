//! The host side of subprogram resolution, shared by the command line and the
//! language server: which files a call names (one list of candidate names per
//! dialect), where they are looked for (the caller's folder, the main
//! program's, then `machine.subroutine_path`), what may be read (only inside
//! the workspace roots, symlinks and `..` included, after canonicalisation) and
//! how (regular files only, under one size limit). The two hosts differ only in
//! their roots — the project (git root, else the current folder) for `check`
//! and `run`, the workspace folders for the editor — and in the size limit's
//! setting.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use analyzer::config::MachineConfig;
use analyzer::{Dialect, FileId};
use runtime::{ResolvedFile, Resolver};

/// A file the resolver loaded: (name as called, path, text).
pub type Loaded = (String, String, Arc<[u8]>);

/// The largest program a host reads, and the setting that raises it (named in
/// the refusal).
#[derive(Clone, Copy, Debug)]
pub struct SizeLimit {
    bytes: u64,
    /// Whether the limit was given in megabytes (`--max-file-size`) rather
    /// than bytes (`maxRunFileSize`): messages use the setting's unit.
    megabytes: bool,
    setting: &'static str,
}

impl SizeLimit {
    /// `--max-file-size` of the command line, in MB.
    pub fn megabytes(mb: u64) -> SizeLimit {
        SizeLimit {
            bytes: mb.saturating_mul(1024 * 1024),
            megabytes: true,
            setting: "--max-file-size",
        }
    }

    /// A limit in bytes, raised by the named setting.
    pub fn bytes(bytes: u64, setting: &'static str) -> SizeLimit {
        SizeLimit {
            bytes,
            megabytes: false,
            setting,
        }
    }

    fn too_large(&self, len: u64) -> String {
        let (len, limit, unit) = if self.megabytes {
            (len.div_ceil(1024 * 1024), self.bytes / (1024 * 1024), "MB")
        } else {
            (len, self.bytes, "bytes")
        };
        format!(
            "too large to analyse: {len} {unit}, above the limit of {limit} {unit} \
             (raise it with {}, or split the program)",
            self.setting
        )
    }
}

/// What a non-regular file is, for messages.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a directory"
    } else {
        "not a plain file"
    }
}

/// Reads a program, refusing files above the limit: by their size before
/// reading, and by reading at most one byte more than the limit, so a device or
/// pipe without a size (`/dev/zero`) cannot exhaust memory either. Every
/// program either host reads, main or called, comes through here.
/// The first `n` bytes of a program [`read_program`] would read (a host that
/// reads the rest in windows looks at them first), with the same refusals.
pub fn read_head(path: &Path, limit: &SizeLimit, n: u64) -> Result<Arc<[u8]>, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err(format!(
            "not a regular file ({}): partscope reads programs only from regular files",
            file_kind(&meta)
        ));
    }
    if meta.len() > limit.bytes {
        return Err(limit.too_large(meta.len()));
    }
    let mut head = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(n).read_to_end(&mut head))
        .map_err(|e| e.to_string())?;
    Ok(Arc::from(head))
}

pub fn read_program(path: &Path, limit: &SizeLimit) -> Result<Arc<[u8]>, String> {
    use std::io::Read;
    // Opening a FIFO blocks until a writer comes, and a device may never end:
    // only regular files are programs.
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err(format!(
            "not a regular file ({}): partscope reads programs only from regular files",
            file_kind(&meta)
        ));
    }
    let mut file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let len = file.metadata().map_err(|e| e.to_string())?.len();
    if len > limit.bytes {
        return Err(limit.too_large(len));
    }
    // The syntax tree shares the text as an `Arc<[u8]>`: reading straight into one
    // spares a copy of the whole file (and, for a large file, as many fresh pages).
    let size = usize::try_from(len).unwrap_or(0);
    let mut text: Arc<[u8]> = (0..size).map(|_| 0u8).collect();
    let mut filled = 0;
    if let Some(buf) = Arc::get_mut(&mut text) {
        while filled < buf.len() {
            match file.read(&mut buf[filled..]) {
                Ok(0) => break,
                Ok(n) => filled += n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e.to_string()),
            }
        }
    }
    // The file may have changed size since its length was read: whatever is shorter
    // or longer than expected is read the ordinary way.
    let mut rest = Vec::new();
    file.take(limit.bytes.saturating_add(1).saturating_sub(filled as u64))
        .read_to_end(&mut rest)
        .map_err(|e| e.to_string())?;
    if filled < size || !rest.is_empty() {
        let mut all = text.get(..filled).unwrap_or(&[]).to_vec();
        all.extend_from_slice(&rest);
        if all.len() as u64 > limit.bytes {
            return Err(limit.too_large(all.len() as u64));
        }
        text = all.into();
    }
    Ok(text)
}

/// The file names a call of `name` may be found under, in the order tried.
/// Matching ignores ASCII case (a program written `O1234.NC` on one machine is
/// called `o1234.nc` on another), an exact match first.
pub fn candidates(dialect: Dialect, name: &str) -> Vec<String> {
    match dialect {
        // The manual's rule: `M98 P<name>` runs `O<name>.dat`.
        Dialect::Servoworks => vec![format!("O{name}.dat")],
        Dialect::Rs274ngc => vec![format!("{name}.ngc")],
        // The program number with and without the padding controls and CAM
        // systems write, with the extensions they use.
        Dialect::Fanuc => {
            let mut v = Vec::new();
            for base in [
                format!("O{name}"),
                format!("O{name:0>4}"),
                format!("O{name:0>5}"),
                name.to_string(),
            ] {
                for ext in ["", ".nc", ".fnc", ".txt", ".tap", ".prg"] {
                    let file = format!("{base}{ext}");
                    if !v.contains(&file) {
                        v.push(file);
                    }
                }
            }
            v
        }
    }
}

/// The `SUBROUTINE_PATH` folders: `machine.subroutine_path` (a string with `:`
/// separators, or an array) relative to the config file's folder.
pub fn subroutine_path(machine: &MachineConfig, config: Option<&Path>) -> Vec<PathBuf> {
    let base = config
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    machine
        .subroutine_path
        .iter()
        .flatten()
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

/// The canonical form of `path` when it exists and lies inside one of `roots`
/// (which are canonical already).
pub fn confine(path: &Path, roots: &[PathBuf]) -> Option<PathBuf> {
    let canon = path.canonicalize().ok()?;
    roots.iter().any(|r| canon.starts_with(r)).then_some(canon)
}

/// Finds and reads the files a program calls, for the interpreter.
pub struct FsResolver {
    dialect: Dialect,
    /// Canonical folder of the main program; `None` for an unsaved document,
    /// whose calls find nothing.
    main_dir: Option<PathBuf>,
    /// `machine.subroutine_path` folders, searched after the caller's and the
    /// main program's (RS274/NGC and FANUC; ServoWorks looks only beside the
    /// main program).
    search: Vec<PathBuf>,
    /// Canonical workspace roots: nothing outside them is read.
    roots: Vec<PathBuf>,
    limit: SizeLimit,
    /// Polled by the interpreter: the editor's request was cancelled.
    cancel: Option<crate::document::run::CancelFlag>,
    /// Folders of resolved files, by FileId (index 0 = main file).
    dirs: Mutex<Vec<PathBuf>>,
    /// Files found but not read, by the name called: why.
    refused: Mutex<Vec<(String, String)>>,
    /// Every file handed to the interpreter.
    loaded: Mutex<Vec<Loaded>>,
    /// Calls (name, calling file) that found nothing: a loop that calls a missing
    /// program asks again on every pass, and a search reads folders.
    missed: Mutex<HashSet<(String, u32)>>,
}

impl FsResolver {
    /// The resolver of `check` and `run`: confined to the project of `file`
    /// ([`project_root`]), searching the `subroutine_path` of the file's config.
    pub fn for_command_line(
        file: &Path,
        dialect: Dialect,
        machine: &MachineConfig,
        config: Option<&Path>,
        limit: SizeLimit,
    ) -> FsResolver {
        let dir = file
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        FsResolver::new(
            Some(dir),
            vec![project_root(file)],
            dialect,
            subroutine_path(machine, config),
            limit,
        )
    }

    /// The language server's resolver for a document at `doc` (`None` when
    /// unsaved): confined to the workspace folders `roots` (canonical).
    pub fn for_workspace(
        doc: Option<&Path>,
        roots: &[PathBuf],
        dialect: Dialect,
        machine: &MachineConfig,
        config: Option<&Path>,
        limit: SizeLimit,
    ) -> FsResolver {
        FsResolver::new(
            doc.and_then(Path::parent),
            roots.to_vec(),
            dialect,
            subroutine_path(machine, config),
            limit,
        )
    }

    fn new(
        main_dir: Option<&Path>,
        roots: Vec<PathBuf>,
        dialect: Dialect,
        search: Vec<PathBuf>,
        limit: SizeLimit,
    ) -> FsResolver {
        let main_dir = main_dir.map(|d| d.canonicalize().unwrap_or_else(|_| d.to_path_buf()));
        let roots = roots
            .into_iter()
            .filter_map(|r| r.canonicalize().ok())
            .collect();
        FsResolver {
            dialect,
            dirs: Mutex::new(main_dir.iter().cloned().collect()),
            main_dir,
            search,
            roots,
            limit,
            cancel: None,
            refused: Mutex::new(Vec::new()),
            loaded: Mutex::new(Vec::new()),
            missed: Mutex::new(HashSet::new()),
        }
    }

    /// Lets the interpreter stop when `cancel` is set.
    pub fn with_cancel(mut self, cancel: crate::document::run::CancelFlag) -> FsResolver {
        self.cancel = Some(cancel);
        self
    }

    /// The files the run loaded, in order: (name as called, path, text).
    pub fn loaded(&self) -> Vec<Loaded> {
        self.loaded.lock().map(|l| l.clone()).unwrap_or_default()
    }

    /// The folders a call of `name` from file `from` searches, in order.
    fn folders(&self, from: FileId) -> Vec<PathBuf> {
        let mut dirs = Vec::new();
        let caller = self
            .dirs
            .lock()
            .ok()
            .and_then(|d| d.get(from.0 as usize).cloned());
        dirs.extend(caller);
        dirs.extend(self.main_dir.iter().cloned());
        if self.dialect != Dialect::Servoworks {
            dirs.extend(self.search.iter().cloned());
        }
        dirs.dedup();
        dirs
    }

    /// Every path tried for a call of `name` from file `from`, in order (before
    /// the case-insensitive match and the FANUC search by program head).
    pub fn candidate_paths(&self, name: &str, from: FileId) -> Vec<PathBuf> {
        if !callable_name(name) {
            return Vec::new();
        }
        let names = candidates(self.dialect, name);
        self.folders(from)
            .iter()
            .flat_map(|d| names.iter().map(move |n| d.join(n)))
            .collect()
    }

    /// The first file a call of `name` from `from` finds inside the roots for
    /// which `take` (given the path as found and its canonical form) answers.
    fn search<T>(
        &self,
        name: &str,
        from: FileId,
        mut take: impl FnMut(&Path, &Path) -> Option<T>,
    ) -> Option<T> {
        if !callable_name(name) || self.main_dir.is_none() {
            return None;
        }
        let names = candidates(self.dialect, name);
        let folders = self.folders(from);
        for dir in &folders {
            for p in matches_in(dir, &names) {
                let Some(canonical) = confine(&p, &self.roots) else {
                    continue;
                };
                if let Some(found) = take(&p, &canonical) {
                    return Some(found);
                }
            }
        }
        // A control finds a program by the O number of its head, not by a file
        // name (`gauge_tool_o1002.nc` holds O1002): look at the heads of the
        // G-code files in the caller's folder.
        if self.dialect == Dialect::Fanuc {
            let number: u32 = name.parse().ok()?;
            let dir = folders.first()?;
            for p in gcode_files(dir) {
                let Some(canonical) = confine(&p, &self.roots) else {
                    continue;
                };
                if !has_program_head(&canonical, number) {
                    continue;
                }
                if let Some(found) = take(&p, &canonical) {
                    return Some(found);
                }
            }
        }
        None
    }

    /// Where a call of `name` from the main program finds its file, without
    /// reading it (go-to-definition).
    pub fn locate(&self, name: &str) -> Option<PathBuf> {
        self.search(name, FileId(0), |_, canonical| {
            canonical.is_file().then(|| canonical.to_path_buf())
        })
    }

    /// Reads a found file and records its folder as the one its own calls
    /// search first; a file it refuses is recorded with the reason.
    fn load(&self, name: &str, path: &Path, canonical: &Path) -> Option<ResolvedFile> {
        if canonical.is_dir() {
            return None;
        }
        let text = match read_program(canonical, &self.limit) {
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

impl Resolver for FsResolver {
    fn resolve(&self, name: &str, from: FileId) -> Option<ResolvedFile> {
        let key = (name.to_string(), from.0);
        if self.missed.lock().is_ok_and(|m| m.contains(&key)) {
            return None;
        }
        let Some(found) = self.search(name, from, |p, c| self.load(name, p, c)) else {
            if let Ok(mut m) = self.missed.lock() {
                m.insert(key);
            }
            return None;
        };
        if let Ok(mut l) = self.loaded.lock() {
            l.push((name.to_string(), found.path.clone(), found.text.clone()));
        }
        Some(found)
    }

    fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(|c| c.is_cancelled())
    }

    /// A configured search path, even one naming no folder, is what the
    /// control would search: a name not found there is missing.
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
}

/// A name that cannot leave the folder it is looked for in.
fn callable_name(name: &str) -> bool {
    !name.is_empty() && !name.contains(['/', '\\']) && !name.contains("..")
}

/// The entries of `dir` named like one of `names`, in the order of `names`:
/// exact matches first, then matches ignoring ASCII case (the folder is read
/// only when no exact name exists).
fn matches_in(dir: &Path, names: &[String]) -> Vec<PathBuf> {
    let exact: Vec<PathBuf> = names
        .iter()
        .map(|n| dir.join(n))
        .filter(|p| p.exists())
        .collect();
    if !exact.is_empty() {
        return exact;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let entries: Vec<std::ffi::OsString> = entries.flatten().map(|e| e.file_name()).collect();
    let mut out = Vec::new();
    for n in names {
        for e in &entries {
            if e.to_str().is_some_and(|e| e.eq_ignore_ascii_case(n)) {
                out.push(dir.join(e));
            }
        }
    }
    out
}

/// How much of a file is read to find its program head.
const HEAD_BYTES: usize = 4096;
/// Files looked at per folder when searching by program head.
const HEAD_FILES: usize = 2000;

/// The G-code files of `dir` by name, the first [`HEAD_FILES`] the folder lists.
fn gcode_files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
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
    files.sort();
    files
}

/// Whether the first program head of the file at `path` is `O<number>`.
fn has_program_head(path: &Path, number: u32) -> bool {
    use std::io::Read;
    let Ok(file) = std::fs::File::open(path) else {
        return false;
    };
    let mut head = Vec::with_capacity(HEAD_BYTES);
    file.take(HEAD_BYTES as u64).read_to_end(&mut head).is_ok()
        && first_program_number(&head) == Some(number)
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

/// A path's last part, for messages (the full path is the user's own business).
fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("partscope-resolve-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d.canonicalize().unwrap()
    }

    fn workspace(root: &Path, dialect: Dialect, machine: &str) -> FsResolver {
        let machine = MachineConfig::from_toml(machine).unwrap();
        FsResolver::for_workspace(
            Some(&root.join("main.nc")),
            &[root.to_path_buf()],
            dialect,
            &machine,
            Some(&root.join("partscope.toml")),
            SizeLimit::bytes(1 << 20, "the test"),
        )
    }

    #[test]
    fn symlinks_escaping_the_workspace_are_rejected() {
        let base = tmp("escape");
        std::fs::create_dir_all(base.join("ws/sub")).unwrap();
        std::fs::create_dir_all(base.join("outside")).unwrap();
        std::fs::write(base.join("outside/secret.ngc"), "o<secret> sub\n").unwrap();
        std::fs::write(base.join("ws/sub/inner.ngc"), "o<inner> sub\n").unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink(base.join("outside/secret.ngc"), base.join("ws/secret.ngc"))
            .unwrap();
        let ws = base.join("ws");
        let r = workspace(&ws, Dialect::Rs274ngc, "subroutine_path = \"sub\"");
        assert_eq!(r.locate("inner"), Some(ws.join("sub/inner.ngc")));
        assert_eq!(r.locate("secret"), None);
        assert!(r.resolve("secret", FileId(0)).is_none());
        // A search folder outside the workspace is searched, but nothing in it is read.
        let r = workspace(&ws, Dialect::Rs274ngc, "subroutine_path = \"../outside\"");
        assert_eq!(r.locate("secret"), None);
        // `..` in a name never leaves the folder.
        assert_eq!(r.locate("../outside/secret"), None);
    }

    #[test]
    fn program_file_names_per_dialect() {
        let root = tmp("names");
        std::fs::write(root.join("OMoveXY.DAT"), "G1 X1\nM99\n").unwrap();
        std::fs::write(root.join("o1234.nc"), "O1234;\nM99;\n").unwrap();
        std::fs::write(root.join("O0012.TAP"), "O0012;\nM99;\n").unwrap();
        std::fs::write(root.join("gauge.nc"), "%\nO1002 (GAUGE)\nM99\n%\n").unwrap();
        std::fs::write(root.join("Drill.NGC"), "o<drill> sub\no<drill> endsub\n").unwrap();
        let sw = workspace(&root, Dialect::Servoworks, "");
        assert_eq!(sw.locate("MoveXY"), Some(root.join("OMoveXY.DAT")));
        let f = workspace(&root, Dialect::Fanuc, "");
        assert_eq!(f.locate("1234"), Some(root.join("o1234.nc")));
        assert_eq!(f.locate("12"), Some(root.join("O0012.TAP")));
        // By the number of its program head.
        assert_eq!(f.locate("1002"), Some(root.join("gauge.nc")));
        assert_eq!(f.locate("99"), None);
        let ngc = workspace(&root, Dialect::Rs274ngc, "");
        assert_eq!(ngc.locate("drill"), Some(root.join("Drill.NGC")));
    }

    #[test]
    fn refusals_say_why() {
        let root = tmp("refused");
        std::fs::write(root.join("big.ngc"), "G1 X1\n".repeat(100)).unwrap();
        let machine = MachineConfig::default();
        let r = FsResolver::for_workspace(
            Some(&root.join("main.ngc")),
            std::slice::from_ref(&root),
            Dialect::Rs274ngc,
            &machine,
            None,
            SizeLimit::bytes(100, "the `maxRunFileSize` setting"),
        );
        assert!(r.resolve("big", FileId(0)).is_none());
        assert_eq!(
            r.refused("big").as_deref(),
            Some(
                "big.ngc: too large to analyse: 600 bytes, above the limit of 100 bytes \
                 (raise it with the `maxRunFileSize` setting, or split the program)"
            )
        );
        // Within one run a missing program stays missing: a loop calling it
        // searches once.
        assert!(r.resolve("later", FileId(0)).is_none());
        std::fs::write(root.join("later.ngc"), "o<later> sub\no<later> endsub\n").unwrap();
        assert!(r.resolve("later", FileId(0)).is_none());
        assert!(r.locate("later").is_some());
        #[cfg(unix)]
        if std::process::Command::new("mkfifo")
            .arg(root.join("pipe.ngc"))
            .status()
            .is_ok_and(|s| s.success())
        {
            assert!(r.resolve("pipe", FileId(0)).is_none());
            assert_eq!(
                r.refused("pipe").as_deref(),
                Some(
                    "pipe.ngc: not a regular file (a FIFO): partscope reads programs only \
                     from regular files"
                )
            );
        }
    }
}
