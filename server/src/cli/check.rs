//! `partscope check`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use analyzer::{Severity, Span};
use rayon::prelude::*;

use super::output::{self, FileReport};
use super::workspace::{self, ConfigCache, LoadedConfig};
use super::CheckArgs;

pub fn run(args: CheckArgs) -> ExitCode {
    let flags = crate::rules::check_selectors("--select", &args.select)
        .and_then(|_| crate::rules::check_selectors("--ignore", &args.ignore))
        .and_then(|_| match args.fail_level.as_deref() {
            Some(l) => crate::rules::check_level("--fail-level", l).map(|_| ()),
            None => Ok(()),
        });
    if let Err(e) = flags {
        eprintln!("partscope: {e}");
        return ExitCode::from(2);
    }
    let explicit = match &args.config {
        Some(p) => match workspace::load_config(p) {
            Ok(c) if c.unreadable => {
                for i in &c.issues {
                    eprintln!("partscope: {i}");
                }
                return ExitCode::from(2);
            }
            Ok(c) => Some(c),
            Err(e) => {
                eprintln!("partscope: {e}");
                return ExitCode::from(2);
            }
        },
        None => None,
    };
    let (files, walk_errors) = workspace::collect_files(&args.paths);
    let cache = ConfigCache::default();
    let mut reports: Vec<FileReport> = files
        .par_iter()
        .map(|f| check_file(f, &args, explicit.as_ref(), &cache))
        .collect();
    for (p, e) in walk_errors {
        reports.push(FileReport::io_error(p, e));
    }
    // The configurations' own problems, once per file, beside the programs'.
    let configs = match &explicit {
        Some(c) => vec![c.clone()],
        None => cache.found(),
    };
    reports.extend(configs.iter().filter_map(|c| config_report(c, &args)));
    reports.sort_by(|a, b| a.path.cmp(&b.path));
    let fail_level = args
        .fail_level
        .as_deref()
        .and_then(Severity::parse)
        .or_else(|| {
            explicit
                .as_ref()
                .map(|c| analyzer::settings::fail_level(&c.config))
        })
        .unwrap_or(Severity::Warning);
    if let Some(code) = output::emit(args.format, &reports)
        .err()
        .and_then(|e| super::write_failure(&e))
    {
        return code;
    }
    if reports.iter().any(|r| r.io_error) {
        return ExitCode::from(2);
    }
    let failed = reports
        .iter()
        .any(|r| r.diagnostics.iter().any(|d| d.severity >= fail_level));
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// The findings of rule L016 in a configuration file, unless its own `[rules]`
/// or the command line turn the rule off.
fn config_report(c: &LoadedConfig, args: &CheckArgs) -> Option<FileReport> {
    let path = c.path.clone()?;
    if c.unreadable {
        // Every program under it is reported as unreadable already.
        return None;
    }
    // Found by walking up from a program, the path is absolute: shown from the
    // working directory, like the programs named on the command line.
    let path = std::env::current_dir()
        .ok()
        .and_then(|d| d.canonicalize().ok())
        .and_then(|d| path.strip_prefix(d).ok().map(Path::to_path_buf))
        .unwrap_or(path);
    let settings = workspace::settings_for(
        &c.config,
        analyzer::Dialect::Rs274ngc,
        &args.select,
        &args.ignore,
    );
    if c.findings.is_empty() || !settings.rule_enabled(&analyzer::rules::CONFIG_ISSUE) {
        return None;
    }
    Some(FileReport {
        path,
        text: c.text.clone(),
        diagnostics: c.findings.clone(),
        io_error: false,
        extra_files: Vec::new(),
        dialect: None,
        sparse: None,
    })
}

fn check_file(
    path: &Path,
    args: &CheckArgs,
    explicit: Option<&LoadedConfig>,
    cache: &ConfigCache,
) -> FileReport {
    let max_mb = args.max_file_size.unwrap_or(u64::MAX >> 20);
    let limit = crate::resolve::SizeLimit::megabytes(max_mb);
    // A program too large to hold is read in windows; its head names the dialect.
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    let window = args
        .window_bytes
        .or_else(|| (size > super::stream::STREAM_ABOVE).then_some(super::stream::WINDOW_BYTES));
    let text = match window {
        Some(_) => crate::resolve::read_head(path, &limit, 64 * 1024),
        None => crate::resolve::read_program(path, &limit),
    };
    let mut text = match text {
        Ok(b) => b,
        Err(e) => return FileReport::io_error(path.to_path_buf(), e),
    };
    let dir = path
        .parent()
        .map(|p| {
            if p.as_os_str().is_empty() {
                Path::new(".")
            } else {
                p
            }
        })
        .unwrap_or(Path::new("."));
    let dir = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    let loaded = match explicit {
        Some(c) => c.clone(),
        None => match cache.for_dir(&dir) {
            Ok(c) if c.unreadable => {
                return FileReport::io_error(path.to_path_buf(), c.issues.join("; "))
            }
            Ok(c) => c,
            Err(e) => return FileReport::io_error(path.to_path_buf(), e),
        },
    };
    let (dialect, dialect_reason) =
        workspace::resolve_dialect(args.dialect.map(|d| d.dialect()), &loaded, path, &text);
    let mut settings = workspace::settings_for(&loaded.config, dialect, &args.select, &args.ignore);
    settings.max_per_code = args.max_per_code.unwrap_or(settings.max_per_code);
    if let Some(n) = args.max_runtime_errors {
        settings.max_runtime_errors = n.max(1);
    }
    settings.max_per_file = args.max_per_file.unwrap_or(settings.max_per_file);
    settings.file_stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .map(str::to_string);
    let dat_subprogram = dialect == analyzer::Dialect::Servoworks
        && path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("dat"))
        && path
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| n.starts_with('O'));
    if let Some(window) = window {
        let called = crate::resolve::SizeLimit::megabytes(
            args.max_file_size.unwrap_or(workspace::DEFAULT_MAX_FILE_MB),
        );
        let job = super::stream::Job {
            path,
            args,
            loaded: &loaded,
            settings: &settings,
            window,
            called,
            subprogram_by_name: dat_subprogram,
        };
        let reason = (dialect, dialect_reason.clone());
        if let Some(r) = super::stream::check_file(&job, text, reason) {
            return r;
        }
        // Flow control in a file small enough to hold: read it whole.
        text = match crate::resolve::read_program(path, &limit) {
            Ok(b) => b,
            Err(e) => return FileReport::io_error(path.to_path_buf(), e),
        };
    }
    let parsed = analyzer::parse_text_lean(text.clone(), &settings);
    // Subprogram files are analysed when they are called, from the caller's point of
    // view: ServoWorks `O<name>.dat` files, RS274/NGC files that only define
    // `o<name> sub`s, and FANUC/ServoWorks files that return with M99 and never end
    // the program (as the language server judges them).
    let is_subprogram = dat_subprogram
        || runtime::interp::files::is_subprogram_file(
            &parsed.program,
            settings.file_stem.as_deref(),
        );
    // Neither a binary file nor a program for another control (P010) is interpreted.
    let interpret = !args.no_run
        && !is_subprogram
        && !analyzer::reports_l009(&parsed, &settings)
        && !analyzer::reports_mismatch(&parsed, &settings);
    // The static rules and the interpreter only read the syntax tree: they run side by
    // side, on two cores when the pool has them free.
    let (mut diagnostics, run) = rayon::join(
        || analyzer::lint(&parsed, &settings),
        || {
            if !interpret {
                return None;
            }
            with_run_parts(path, &settings, &loaded, args, limit, |parts| {
                let input = parts.input(&parsed.program, parsed.program.blocks.len());
                // Lint needs the diagnostics only: motions are dropped as they are produced.
                let out = runtime::run_streaming(&input, &mut |_, _| {});
                let diagnostics = analyzer::finish(&parsed.program, &settings, out.diagnostics);
                Some((diagnostics, out.files))
            })
        },
    );
    let mut extra_files = Vec::new();
    if let Some((run_diagnostics, files)) = run {
        diagnostics = analyzer::merge(diagnostics, run_diagnostics, &settings);
        extra_files = output::read_extra_files(&files);
    }
    FileReport {
        path: path.to_path_buf(),
        text,
        diagnostics,
        io_error: false,
        extra_files,
        dialect: Some((dialect, dialect_reason)),
        sparse: None,
    }
}

/// Calls `run` with what `check`'s interpreter reads besides the program: the
/// resolver of `path` (called files within `limit`) and the configuration's
/// machine, tool table and parameter file; the budgets are the command line's.
pub(super) fn with_run_parts<R>(
    path: &Path,
    settings: &analyzer::Settings,
    loaded: &LoadedConfig,
    args: &CheckArgs,
    limit: crate::resolve::SizeLimit,
    run: impl FnOnce(&super::stream::RunParts<'_>) -> R,
) -> R {
    let resolver = crate::resolve::FsResolver::for_command_line(
        path,
        settings.dialect,
        &loaded.config.machine,
        loaded.path.as_deref(),
        limit,
    );
    let files = loaded.linuxcnc_files();
    for w in &files.warnings {
        workspace::warn_once(w);
    }
    let machine = workspace::machine_table_with(&loaded.config.machine, files.ini_profile.as_ref());
    run(&super::stream::RunParts {
        settings,
        machine: &machine,
        resolver: &resolver,
        tool_table: files.tool_table.as_deref(),
        var_file: files.var_file.as_deref(),
        step_budget: args.step_budget,
        motion_budget: args.motion_budget,
    })
}

impl FileReport {
    pub fn io_error(path: PathBuf, message: String) -> FileReport {
        FileReport {
            path,
            text: Arc::from(&b""[..]),
            diagnostics: vec![analyzer::rules::IO_ERROR
                .error(Span::new(0, 0), format!("cannot read file: {message}"))],
            io_error: true,
            extra_files: Vec::new(),
            dialect: None,
            sparse: None,
        }
    }
}
