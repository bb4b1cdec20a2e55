//! Which settings apply to a document.
//!
//! Sources, most specific first:
//! 1. the nearest `partscope.toml`, walking up from the document's folder and
//!    stopping at the workspace folder that holds it (a project's file beats
//!    an editor-wide setting);
//! 2. a `(partscope: dialect=…)` comment on the first line (it names the
//!    dialect of this one file);
//! 3. the client's options: `initializationOptions` or the `partscope`
//!    section of `workspace/configuration` (`{dialect, machine, select, ignore,
//!    maxFileSize}`);
//! 4. sniffing the extension and content; the default is `rs274ngc`.
//!
//! Rule `select`/`ignore` lists of the client are added to the file's.

use std::path::{Path, PathBuf};

use analyzer::config::MachineConfig;
use analyzer::settings::{dialect_directive, sniff_file_dialect_why};
use analyzer::{Config, Dialect, Settings};

use crate::cli::workspace::FileCache;
use serde_json::Value;

/// Default size above which a document is only parsed (no rules, no dry run).
pub const DEFAULT_MAX_FILE_SIZE: usize = 64 * 1024 * 1024;
/// Default size up to which the interpreter runs with every analysis (its
/// diagnostics are published); larger files run only on request. A
/// million-line program of CAM output (18–28 MB) is below it
/// (BENCHMARKS.md, "Editor dry run of 1M-line programs").
pub const DEFAULT_MAX_RUN_FILE_SIZE: usize = 32 * 1024 * 1024;

/// Options the client sends (initializationOptions or workspace/configuration).
#[derive(Debug, Clone, Default)]
pub struct ClientOptions {
    pub dialect: Option<Dialect>,
    /// An inline machine table, or the path of a machine-profile TOML (relative
    /// to the first workspace folder).
    pub machine: Option<MachineOption>,
    pub select: Vec<String>,
    pub ignore: Vec<String>,
    pub max_file_size: Option<usize>,
    pub max_run_file_size: Option<usize>,
    /// Cap on the toolpath points of a `partscope/dryRun` answer
    /// (`maxToolpathPoints`; `document::decimate`).
    pub max_toolpath_points: Option<usize>,
    /// The `format` object: defaults of document formatting (`numbers`,
    /// `start`, `step`, `spacing`, `uppercase`; see `lsp::formatting`).
    pub format: Option<Value>,
    /// What the inlay hints show of each block's time (`blockTimes`).
    pub block_times: Option<BlockTimes>,
}

/// The per-block time in inlay hints: `block` (the block's own time, the
/// default), `cumulative` (the program time when it ends) or `off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BlockTimes {
    #[default]
    Block,
    Cumulative,
    Off,
}

impl BlockTimes {
    pub fn parse(s: &str) -> Option<BlockTimes> {
        match s.to_ascii_lowercase().as_str() {
            "block" | "on" | "true" => Some(BlockTimes::Block),
            "cumulative" => Some(BlockTimes::Cumulative),
            "off" | "none" | "false" => Some(BlockTimes::Off),
            _ => None,
        }
    }
}

#[derive(Debug, Clone)]
pub enum MachineOption {
    Table(toml::Table),
    Path(String),
}

impl ClientOptions {
    /// Reads options from JSON, accepting either the options object itself or
    /// an object with a `partscope` key. Unknown keys and wrong types are ignored.
    pub fn from_json(v: &Value) -> ClientOptions {
        let v = v.get("partscope").unwrap_or(v);
        let strings = |key: &str| -> Vec<String> {
            match v.get(key) {
                Some(Value::Array(a)) => a
                    .iter()
                    .filter_map(|s| s.as_str().map(str::to_string))
                    .collect(),
                Some(Value::String(s)) => s
                    .split(',')
                    .map(|s| s.trim().to_string())
                    .filter(|s| !s.is_empty())
                    .collect(),
                _ => Vec::new(),
            }
        };
        let machine = match v.get("machine") {
            Some(Value::String(s)) if !s.is_empty() => Some(MachineOption::Path(s.clone())),
            Some(obj @ Value::Object(_)) => {
                // JSON → TOML through serde; values TOML cannot hold (null) make it fail, and then it is ignored.
                serde_json::from_value::<toml::Table>(obj.clone())
                    .ok()
                    .map(MachineOption::Table)
            }
            _ => None,
        };
        ClientOptions {
            dialect: v
                .get("dialect")
                .and_then(Value::as_str)
                .and_then(Dialect::parse),
            machine,
            select: strings("select"),
            ignore: strings("ignore"),
            max_file_size: v
                .get("maxFileSize")
                .or_else(|| v.get("max_file_size"))
                .and_then(Value::as_u64)
                .map(|n| n as usize),
            max_run_file_size: v
                .get("maxRunFileSize")
                .and_then(Value::as_u64)
                .map(|n| n as usize),
            max_toolpath_points: v
                .get("maxToolpathPoints")
                .and_then(Value::as_u64)
                .map(|n| n as usize),
            format: v.get("format").filter(|f| f.is_object()).cloned(),
            block_times: match v.get("blockTimes") {
                Some(Value::String(s)) => BlockTimes::parse(s),
                Some(Value::Bool(true)) => Some(BlockTimes::Block),
                Some(Value::Bool(false)) => Some(BlockTimes::Off),
                _ => None,
            },
        }
    }
}

/// Everything a document's analysis needs besides its text.
#[derive(Debug, Clone)]
pub struct DocSettings {
    pub settings: Settings,
    /// The machine profile for the runtime.
    pub machine: MachineConfig,
    /// The planner's machine: the table's keys over the dialect's defaults, or
    /// over the config's LinuxCNC `ini` (as `partscope run` has it).
    pub profile: runtime::machine::MachineProfile,
    /// The `partscope.toml` the settings came from.
    pub config_path: Option<PathBuf>,
    /// A problem reading the configuration, reported to the user.
    pub config_error: Option<String>,
    pub max_file_size: usize,
    pub max_run_file_size: usize,
    /// LinuxCNC tool table and parameter file named by the config (resolved
    /// against its folder; read only inside the workspace).
    pub tool_table: Option<PathBuf>,
    pub var_file: Option<PathBuf>,
    /// Why the document is read in its dialect.
    pub dialect_reason: String,
}

/// Finds the nearest `partscope.toml` for `doc`, never looking above `root`
/// (and not at all when the document is outside every workspace folder).
pub fn find_config(doc: &Path, roots: &[PathBuf]) -> Option<PathBuf> {
    let root = roots
        .iter()
        .filter(|r| doc.starts_with(r))
        .max_by_key(|r| r.components().count())?;
    let mut dir = doc.parent()?;
    loop {
        let candidate = dir.join("partscope.toml");
        if candidate.is_file() {
            return Some(candidate);
        }
        if dir == root.as_path() {
            return None;
        }
        dir = dir.parent()?;
    }
}

/// Resolves the settings of one document. Reads at most two small files (the
/// config and a machine profile); the caller runs it off the async threads.
pub fn resolve(
    doc: Option<&Path>,
    text: &[u8],
    roots: &[PathBuf],
    client: &ClientOptions,
    files: &FileCache,
) -> DocSettings {
    // Every problem of the configuration, located; shown once.
    let mut problems: Vec<String> = Vec::new();
    let mut config_path = None;
    let mut config = Config::default();
    if let Some(path) = doc.and_then(|d| find_config(d, roots)) {
        match files.config(&path) {
            Ok(c) => {
                problems.extend(c.issues);
                config = c.config;
            }
            Err(e) => problems.push(e),
        }
        config_path = Some(path);
    }
    // The dialect and why it was chosen (shown in hover, as the CLI prints it):
    // the config, the first-line directive, the editor's setting, the sniffer;
    // `sniff_file_dialect_why` reads the directive itself.
    let (dialect, dialect_reason) = match config.dialect {
        Some(d) => (d, "`dialect` in partscope.toml".to_string()),
        None => match client.dialect.filter(|_| dialect_directive(text).is_none()) {
            Some(d) => (d, "the editor's `partscope.dialect` setting".into()),
            None => sniff_file_dialect_why(
                doc.and_then(|d| d.file_name()).and_then(|e| e.to_str()),
                text,
            )
            .unwrap_or((
                Dialect::Rs274ngc,
                "the default: nothing in the file names a dialect".into(),
            )),
        },
    };
    if config.machine.is_empty() {
        match &client.machine {
            Some(MachineOption::Table(t)) => {
                let (m, issues) = MachineConfig::from_toml_table(t);
                config.machine = m;
                problems.extend(
                    issues.into_iter().map(|i| {
                        format!("the editor's `partscope.machine` setting: {}", i.message)
                    }),
                );
            }
            Some(MachineOption::Path(p)) => {
                let base = roots.first().cloned().unwrap_or_default();
                let path = base.join(p);
                // The profile must stay inside the workspace, like every file the server reads.
                match crate::resolve::confine(&path, roots)
                    .ok_or_else(|| {
                        format!(
                            "machine profile {} is outside the workspace",
                            path.display()
                        )
                    })
                    .and_then(|p| std::fs::read_to_string(p).map_err(|e| e.to_string()))
                {
                    Ok(text) => {
                        let (m, issues) = MachineConfig::load(&text);
                        config.machine = m;
                        problems.extend(crate::cli::workspace::locate_all(&path, &text, &issues));
                    }
                    Err(e) => problems.push(e),
                }
            }
            None => {}
        }
    }
    let mut settings = Settings::from_config(&config, Some(dialect));
    settings.select.extend(client.select.iter().cloned());
    settings.ignore.extend(client.ignore.iter().cloned());
    settings.file_stem = doc
        .and_then(|d| d.file_stem())
        .and_then(|s| s.to_str())
        .map(str::to_string);
    let config_dir = config_path
        .as_deref()
        .and_then(Path::parent)
        .map(Path::to_path_buf);
    let beside_config = |p: &Option<String>| {
        p.as_ref()
            .map(|p| config_dir.clone().unwrap_or_default().join(p))
    };
    let mut tool_table = beside_config(&config.tool_table);
    let mut var_file = beside_config(&config.var_file);
    let mut ini_profile = None;
    // A LinuxCNC `.ini` named by the config gives the machine's axes, and its
    // tool table and parameter file unless the config names its own, as in
    // `partscope check`. Like every file the server reads, it must be inside
    // the workspace.
    if let Some(ini) = beside_config(&config.ini) {
        match crate::resolve::confine(&ini, roots)
            .ok_or_else(|| format!("{} is outside the workspace", ini.display()))
            .and_then(|p| files.ini(&p))
        {
            Ok(ini) => {
                ini_profile = Some(ini.profile);
                tool_table = tool_table.or(ini.tool_table);
                var_file = var_file.or(ini.var_file);
            }
            Err(e) => problems.push(format!("{}: {e}", ini.display())),
        }
    }
    let (machine, profile) =
        crate::cli::workspace::machine_of(&config.machine, ini_profile.as_ref(), dialect);
    DocSettings {
        profile,
        tool_table,
        var_file,
        dialect_reason,
        settings,
        machine,
        config_path,
        config_error: (!problems.is_empty()).then(|| problems.join("; ")),
        max_file_size: client.max_file_size.unwrap_or(DEFAULT_MAX_FILE_SIZE),
        max_run_file_size: client
            .max_run_file_size
            .unwrap_or(DEFAULT_MAX_RUN_FILE_SIZE),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "partscope-lsp-config-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d.canonicalize().unwrap()
    }

    #[test]
    fn nearest_config_wins_and_search_stops_at_root() {
        let root = tmp("nearest");
        std::fs::create_dir_all(root.join("a/b")).unwrap();
        std::fs::write(root.join("partscope.toml"), "dialect = \"fanuc\"\n").unwrap();
        std::fs::write(root.join("a/partscope.toml"), "dialect = \"servoworks\"\n").unwrap();
        let doc = root.join("a/b/p.nc");
        let roots = vec![root.clone()];
        assert_eq!(
            find_config(&doc, &roots),
            Some(root.join("a/partscope.toml"))
        );
        let s = resolve(
            Some(&doc),
            b"G0 X1\n",
            &roots,
            &ClientOptions::default(),
            &FileCache::default(),
        );
        assert_eq!(s.settings.dialect, Dialect::Servoworks);
        // With the workspace folder at `a/b`, neither file is seen.
        let inner = vec![root.join("a/b")];
        assert_eq!(find_config(&doc, &inner), None);
        // Outside every workspace folder: nothing is read.
        assert_eq!(find_config(&doc, &[tmp("other")]), None);
    }

    #[test]
    fn precedence_directive_then_client_then_sniff() {
        let client = ClientOptions::from_json(
            &serde_json::json!({"partscope": {"dialect": "fanuc", "ignore": ["L008"]}}),
        );
        assert_eq!(client.dialect, Some(Dialect::Fanuc));
        let s = resolve(
            None,
            b"(partscope: dialect=servoworks)\nG0\n",
            &[],
            &client,
            &FileCache::default(),
        );
        assert_eq!(s.settings.dialect, Dialect::Servoworks);
        assert!(!s.settings.code_enabled("L008"));
        let s = resolve(None, b"G0\n", &[], &client, &FileCache::default());
        assert_eq!(s.settings.dialect, Dialect::Fanuc);
        let s = resolve(
            Some(Path::new("/nowhere/x.dat")),
            b"G0\n",
            &[],
            &ClientOptions::default(),
            &FileCache::default(),
        );
        assert_eq!(s.settings.dialect, Dialect::Servoworks);
        assert_eq!(s.max_file_size, DEFAULT_MAX_FILE_SIZE);
    }

    #[test]
    fn bad_config_is_reported_not_fatal() {
        let root = tmp("bad");
        std::fs::write(root.join("partscope.toml"), "dialekt = 3\n").unwrap();
        let s = resolve(
            Some(&root.join("p.ngc")),
            b"G0\n",
            std::slice::from_ref(&root),
            &ClientOptions::default(),
            &FileCache::default(),
        );
        assert!(s.config_error.is_some());
        assert_eq!(s.settings.dialect, Dialect::Rs274ngc);
    }

    #[test]
    fn an_edited_config_applies_to_the_next_analysis() {
        let root = tmp("edited");
        let doc = root.join("p.nc");
        let roots = std::slice::from_ref(&root);
        let files = FileCache::default();
        let dialect = |files: &FileCache| {
            resolve(Some(&doc), b"G0\n", roots, &ClientOptions::default(), files)
                .settings
                .dialect
        };
        std::fs::write(root.join("partscope.toml"), "dialect = \"fanuc\"\n").unwrap();
        assert_eq!(dialect(&files), Dialect::Fanuc);
        assert_eq!(dialect(&files), Dialect::Fanuc);
        std::fs::write(root.join("partscope.toml"), "dialect = \"servoworks\"\n").unwrap();
        assert_eq!(dialect(&files), Dialect::Servoworks);
        std::fs::remove_file(root.join("partscope.toml")).unwrap();
        assert_eq!(dialect(&files), Dialect::Rs274ngc);
    }
}
