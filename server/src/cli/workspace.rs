//! Finding files, configs and dialects on disk (the host side of the pure analyzer).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use analyzer::config::{ConfigIssue, MachineConfig};
use analyzer::{Config, Dialect, Settings};

/// File extensions `check` picks up when walking a directory.
pub const EXTENSIONS: &[&str] = &[
    "nc", "ngc", "tap", "cnc", "gcode", "eia", "dat", "min", "mpf", "fnc", "sw",
];

/// Default `--max-file-size` in MB. The whole program is held in memory with
/// its syntax tree and interpreter output: `check` of a 100 MB program peaked
/// at 5.8 GB RSS (about 56 bytes per byte, fuzz/RESULTS.md), so 128 MB keeps
/// one file near 7 GB instead of letting a multi-GB file exhaust memory.
pub const DEFAULT_MAX_FILE_MB: u64 = 128;

/// A loaded config and where it came from.
#[derive(Clone, Debug, Default)]
pub struct LoadedConfig {
    pub config: Config,
    /// Where the config was found (for messages and relative paths).
    pub path: Option<PathBuf>,
    /// What is wrong in it, located (`partscope.toml:3:1: …`); the keys concerned
    /// keep their defaults.
    pub issues: Vec<String>,
    /// Whether the file could not be read as TOML at all (its whole content is ignored).
    pub unreadable: bool,
    /// The same problems as findings of rule L016 in the file, and its text (for
    /// `check`, which reports them with the programs' findings).
    pub findings: Vec<analyzer::Diagnostic>,
    pub text: Arc<[u8]>,
    /// The LinuxCNC files the config names, read on first use and shared by the
    /// clones the [`ConfigCache`] hands out: every program under one config reuses them.
    files: Arc<OnceLock<ConfigFiles>>,
}

/// Configuration files and LinuxCNC `ini` files, read once and kept while they
/// are unchanged on disk (same length and modification time). The language
/// server resolves a document's settings on every edit; the CLI reads each
/// file once per process through [`ConfigCache`].
#[derive(Default)]
pub struct FileCache {
    configs: Stamped<LoadedConfig>,
    inis: Stamped<IniMachine>,
}

/// Each file's reading with the stamp it was read at.
type Stamped<T> = Mutex<HashMap<PathBuf, (Stamp, Result<T, String>)>>;

/// What tells a file changed: its length and modification time.
type Stamp = Option<(u64, std::time::SystemTime)>;

fn stamp(path: &Path) -> Stamp {
    let m = std::fs::metadata(path).ok()?;
    Some((m.len(), m.modified().ok()?))
}

/// `map[path]` while the file's stamp is unchanged, else `read(path)` kept there.
fn cached<T: Clone>(
    map: &Stamped<T>,
    path: &Path,
    read: impl FnOnce(&Path) -> Result<T, String>,
) -> Result<T, String> {
    let now = stamp(path);
    if let Ok(map) = map.lock() {
        if let Some((s, v)) = map.get(path) {
            if now.is_some() && *s == now {
                return v.clone();
            }
        }
    }
    let v = read(path);
    if let Ok(mut map) = map.lock() {
        map.insert(path.to_path_buf(), (now, v.clone()));
    }
    v
}

impl FileCache {
    /// [`load_config`], read again only when the file changed.
    pub fn config(&self, path: &Path) -> Result<LoadedConfig, String> {
        cached(&self.configs, path, load_config)
    }

    /// [`read_ini`], read again only when the file changed.
    pub fn ini(&self, path: &Path) -> Result<IniMachine, String> {
        cached(&self.inis, path, read_ini)
    }
}

/// Caches `partscope.toml` lookups per directory.
#[derive(Default)]
pub struct ConfigCache {
    by_dir: Mutex<HashMap<PathBuf, Result<LoadedConfig, String>>>,
}

impl ConfigCache {
    /// Every configuration file found so far, once each.
    pub fn found(&self) -> Vec<LoadedConfig> {
        let mut out: Vec<LoadedConfig> = Vec::new();
        if let Ok(map) = self.by_dir.lock() {
            for c in map.values().flatten() {
                if c.path.is_some() && !out.iter().any(|o| o.path == c.path) {
                    out.push(c.clone());
                }
            }
        }
        out
    }

    /// The nearest `partscope.toml` at or above `dir`, or the empty config.
    pub fn for_dir(&self, dir: &Path) -> Result<LoadedConfig, String> {
        if let Ok(map) = self.by_dir.lock() {
            if let Some(c) = map.get(dir) {
                return c.clone();
            }
        }
        let candidate = dir.join("partscope.toml");
        let result = if candidate.is_file() {
            load_config(&candidate)
        } else {
            match dir.parent() {
                Some(parent) if parent != dir => self.for_dir(parent),
                _ => Ok(LoadedConfig::default()),
            }
        };
        if let Ok(mut map) = self.by_dir.lock() {
            map.insert(dir.to_path_buf(), result.clone());
        }
        result
    }
}

/// The LinuxCNC files a config names, read: `tool_table` and `var_file` (paths
/// relative to the config file), falling back to the `TOOL_TABLE` and
/// `PARAMETER_FILE` of its `ini`, whose limits also become the machine profile.
/// Files a config merely names are optional: a missing one is a warning, so a
/// copied config still checks.
#[derive(Debug, Default)]
pub struct ConfigFiles {
    pub tool_table: Option<String>,
    pub var_file: Option<String>,
    pub ini_profile: Option<runtime::machine::MachineProfile>,
    pub warnings: Vec<String>,
}

impl LoadedConfig {
    /// Prints the config's issues on stderr, once per process.
    pub fn warn(&self) {
        for i in &self.issues {
            say_once(i);
        }
    }

    fn dir(&self) -> PathBuf {
        self.path
            .as_ref()
            .and_then(|p| p.parent().map(Path::to_path_buf))
            .unwrap_or_default()
    }

    pub fn linuxcnc_files(&self) -> &ConfigFiles {
        self.files.get_or_init(|| self.read_linuxcnc_files())
    }

    fn read_linuxcnc_files(&self) -> ConfigFiles {
        let dir = self.dir();
        let mut out = ConfigFiles::default();
        let mut tbl = self.config.tool_table.as_ref().map(|t| dir.join(t));
        let mut var = self.config.var_file.as_ref().map(|t| dir.join(t));
        if let Some(ini) = &self.config.ini {
            let ini = dir.join(ini);
            match read_ini(&ini) {
                Ok(ini) => {
                    tbl = tbl.or(ini.tool_table);
                    var = var.or(ini.var_file);
                    out.ini_profile = Some(ini.profile);
                }
                Err(e) => out.warnings.push(format!("{}: {e}", ini.display())),
            }
        }
        let mut read = |p: Option<PathBuf>, what: &str| {
            let p = p?;
            match std::fs::read_to_string(&p) {
                Ok(t) => Some(t),
                Err(e) => {
                    out.warnings
                        .push(format!("{}: {e}; running without a {what}", p.display()));
                    None
                }
            }
        };
        let tool_table = read(tbl, "tool table");
        let var_file = read(var, "parameter file");
        out.tool_table = tool_table;
        out.var_file = var_file;
        out
    }
}

/// Prints a warning on stderr once per process: a directory of programs under one
/// config would otherwise repeat it for every file.
pub fn warn_once(msg: &str) {
    say_once(&format!("warning: {msg}"));
}

/// Prints `partscope: {msg}` on stderr once per process (a located message
/// names its own severity).
pub fn say_once(msg: &str) {
    static SEEN: Mutex<Vec<String>> = Mutex::new(Vec::new());
    if let Ok(mut seen) = SEEN.lock() {
        if seen.iter().any(|s| s == msg) {
            return;
        }
        seen.push(msg.to_string());
    }
    eprintln!("partscope: {msg}");
}

/// A LinuxCNC `.ini` as a machine profile, with the tool table and parameter
/// file it names (relative paths resolved against the `.ini`'s folder).
#[derive(Clone)]
pub struct IniMachine {
    pub profile: runtime::machine::MachineProfile,
    pub tool_table: Option<PathBuf>,
    pub var_file: Option<PathBuf>,
}

/// Reads a LinuxCNC `.ini` (the `ini` key of `partscope.toml`); the CLI and the
/// language server both read it here.
pub fn read_ini(path: &Path) -> Result<IniMachine, String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let (profile, extras) = runtime::machine::MachineProfile::from_linuxcnc_ini(&text)?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    Ok(IniMachine {
        profile,
        tool_table: extras.tool_table.map(|t| base.join(t)),
        var_file: extras.parameter_file.map(|t| base.join(t)),
    })
}

/// The interpreter's `[machine]` table for a config with a LinuxCNC `ini`: the
/// ini's axes (travel limits) unless the table lists its own.
pub fn machine_table_with(
    table: &MachineConfig,
    ini: Option<&runtime::machine::MachineProfile>,
) -> MachineConfig {
    let mut t = table.clone();
    if let (Some(p), None) = (ini, &t.axes) {
        t.axes = Some(
            p.axes
                .iter()
                .map(runtime::machine::Axis::as_config)
                .collect(),
        );
    }
    t
}

/// The machine a configuration describes, the same for `run` and the language
/// server: the interpreter's table and the planner's profile. With a LinuxCNC
/// `ini` its limits are the planner's machine and its axes the table's unless the
/// table lists its own; the table's other keys (times, overrides, `planner`)
/// apply over it.
pub fn machine_of(
    table: &MachineConfig,
    ini: Option<&runtime::machine::MachineProfile>,
    dialect: Dialect,
) -> (MachineConfig, runtime::machine::MachineProfile) {
    match ini {
        Some(p) => {
            let mut keys = table.clone();
            keys.axes = None;
            (machine_table_with(table, Some(p)), p.with(&keys))
        }
        None => (
            table.clone(),
            runtime::dryrun::profile_from_table(table, dialect),
        ),
    }
}

/// Reads a `partscope.toml`. Only an unreadable file is an error: what is wrong
/// inside it becomes the located [`LoadedConfig::issues`].
pub fn load_config(path: &Path) -> Result<LoadedConfig, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let (config, issues) = Config::load(&text);
    Ok(LoadedConfig {
        config,
        path: Some(path.to_path_buf()),
        unreadable: issues
            .iter()
            .any(|i| i.severity == analyzer::Severity::Error),
        issues: locate_all(path, &text, &issues),
        findings: issues.iter().map(ConfigIssue::diagnostic).collect(),
        text: Arc::from(text.as_bytes()),
        files: Arc::default(),
    })
}

/// Every issue of a configuration text, located ([`locate`]).
pub fn locate_all(path: &Path, text: &str, issues: &[ConfigIssue]) -> Vec<String> {
    issues.iter().map(|i| locate(path, text, i)).collect()
}

/// `path:line:col: severity: message` for one issue (line and column 1-based,
/// the column in characters).
pub fn locate(path: &Path, text: &str, issue: &ConfigIssue) -> String {
    let level = match issue.severity {
        analyzer::Severity::Error => "error",
        _ => "warning",
    };
    match issue.span.as_ref().and_then(|s| text.get(..s.start)) {
        Some(before) => {
            let line = before.matches('\n').count() + 1;
            let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            format!(
                "{}:{line}:{col}: {level}: {}",
                path.display(),
                issue.message
            )
        }
        None => format!("{}: {level}: {}", path.display(), issue.message),
    }
}

/// Chooses a file's dialect: command line, then config, then a first-line
/// directive, then the extension and content, then RS274/NGC. The reason is
/// shown with the results, so a wrong guess is visible.
pub fn resolve_dialect(
    cli: Option<Dialect>,
    loaded: &LoadedConfig,
    path: &Path,
    text: &[u8],
) -> (Dialect, String) {
    if let Some(d) = cli {
        return (d, "--dialect on the command line".into());
    }
    if let Some(d) = loaded.config.dialect {
        let from = match &loaded.path {
            Some(p) => format!("`dialect` in {}", p.display()),
            None => "`dialect` in the configuration".into(),
        };
        return (d, from);
    }
    // The directive, then the extension, then the content: the same order as
    // the language server (`sniff_dialect_why` is shared).
    let name = path.file_name().and_then(|e| e.to_str());
    analyzer::settings::sniff_file_dialect_why(name, text).unwrap_or_else(|| {
        (
            Dialect::Rs274ngc,
            "the default: nothing in the file names a dialect".into(),
        )
    })
}

/// Settings for one file.
pub fn settings_for(
    config: &Config,
    dialect: Dialect,
    select: &[String],
    ignore: &[String],
) -> Settings {
    let mut s = Settings::from_config(config, Some(dialect));
    s.select.extend(select.iter().cloned());
    s.ignore.extend(ignore.iter().cloned());
    s
}

/// Expands the command-line paths: files as given, directories walked with
/// .gitignore respected, keeping G-code extensions.
pub fn collect_files(paths: &[PathBuf]) -> (Vec<PathBuf>, Vec<(PathBuf, String)>) {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    for p in paths {
        if p.is_dir() {
            for entry in ignore::WalkBuilder::new(p).build() {
                match entry {
                    Ok(e) => {
                        let path = e.path();
                        let ok = e.file_type().is_some_and(|t| t.is_file())
                            && path.extension().and_then(|x| x.to_str()).is_some_and(|x| {
                                EXTENSIONS.contains(&x.to_ascii_lowercase().as_str())
                            });
                        if ok {
                            files.push(path.to_path_buf());
                        }
                    }
                    Err(e) => errors.push((p.clone(), e.to_string())),
                }
            }
        } else {
            files.push(p.clone());
        }
    }
    files.sort();
    files.dedup();
    (files, errors)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cached_config_is_read_again_only_when_it_changes() {
        let dir = std::env::temp_dir().join(format!("partscope-filecache-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("partscope.toml");
        std::fs::write(&path, "[machine]\nlookahead = 4\n").unwrap();
        let files = FileCache::default();
        let a = files.config(&path).unwrap();
        let b = files.config(&path).unwrap();
        // The same reading, not a second one.
        assert!(Arc::ptr_eq(&a.text, &b.text));
        assert_eq!(b.config.machine.lookahead, Some(4));
        std::fs::write(&path, "[machine]\nlookahead = 12\nlookahed = 1\n").unwrap();
        let c = files.config(&path).unwrap();
        assert_eq!(c.config.machine.lookahead, Some(12));
        assert_eq!(c.issues.len(), 1, "{:?}", c.issues);
        std::fs::remove_file(&path).unwrap();
        assert!(files.config(&path).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
