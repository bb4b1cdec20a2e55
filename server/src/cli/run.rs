//! `partscope run`: dry-run a program — cycle time, breakdown, toolpath.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use analyzer::{Diagnostic, Severity, Span};
use runtime::dryrun::{self, DryRun};
use runtime::machine::MachineProfile;
use serde_json::json;

use super::output::{self, FileReport};
use super::workspace::{self, ConfigCache};
use super::DialectArg;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunFormat {
    Human,
    Json,
}

/// An output that costs more on long programs (`--what-if`, `--blocks`): `auto`
/// gives it for programs up to [`WHAT_IF_AUTO_BYTES`].
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum AutoSwitch {
    /// For programs up to 1 MiB (what-ifs: that make at most 200 000 motions).
    Auto,
    On,
    Off,
}

impl AutoSwitch {
    /// Whether it applies to a program of `bytes` (the motion count is checked later).
    fn on_for(self, bytes: usize) -> bool {
        match self {
            AutoSwitch::On => true,
            AutoSwitch::Off => false,
            AutoSwitch::Auto => bytes <= WHAT_IF_AUTO_BYTES,
        }
    }
}

/// Largest program (bytes) and run (motions) `--what-if auto` plans again: each
/// estimate costs one more planner run, and a larger `--format json` run streams
/// instead of keeping the motions a rerun needs.
const WHAT_IF_AUTO_BYTES: usize = 1 << 20;
const WHAT_IF_AUTO_MOTIONS: usize = 200_000;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Emit {
    /// Per-block times as CSV (line, start, end, length, peak feed).
    Blocks,
    /// Per-block times as JSON.
    BlocksJson,
    /// The toolpath as JSON polylines.
    Toolpath,
    /// LinuxCNC canonical calls (rs274ngc), like `rs274`.
    Canon,
}

#[derive(clap::Args, Debug)]
pub struct RunArgs {
    pub file: PathBuf,
    #[arg(long, value_enum)]
    pub dialect: Option<DialectArg>,
    /// A partscope.toml (otherwise discovered upward from the file).
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Machine profile: a TOML file (`[machine]` table or bare) or a LinuxCNC `.ini`.
    #[arg(long)]
    pub machine: Option<PathBuf>,
    /// Feed override as a factor (1.0 = 100 %) or percentage (`120%`).
    #[arg(long)]
    pub feed_override: Option<String>,
    #[arg(long, value_enum, default_value = "human")]
    pub format: RunFormat,
    /// What-if estimates, each planned again: feed override 120 %, G64 P0.05 on
    /// every move (rs274ngc), 2x acceleration. `auto`: for programs up to 1 MiB
    /// and 200 000 motions.
    #[arg(long, value_enum, default_value = "auto")]
    pub what_if: AutoSwitch,
    /// Per-block times and causes in `--format json` (`blocks`, one entry per line):
    /// `auto` writes them for programs up to 1 MiB; `--emit blocks` gives the same
    /// table as CSV.
    #[arg(long, value_enum, default_value = "auto")]
    pub blocks: AutoSwitch,
    #[arg(long, value_enum)]
    pub emit: Option<Emit>,
    /// LinuxCNC tool table (`.tbl`).
    #[arg(long)]
    pub tool_table: Option<PathBuf>,
    /// LinuxCNC parameter file (`.var`).
    #[arg(long)]
    pub var_file: Option<PathBuf>,
    /// Write an SVG picture of the toolpath.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Largest SVG picture to write, in MB (default 32); a longer toolpath is cut
    /// off with a warning.
    #[arg(long)]
    pub max_svg_mb: Option<u64>,
    /// Write a PNG picture of the toolpath (the SVG picture, rasterised).
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Write one self-contained HTML page with the toolpath viewer of the VS Code
    /// preview and this run's result (no network access, no other files).
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Largest toolpath data in the HTML page, in MB (default 64); a longer toolpath
    /// is cut off with a warning, and the page's title says where.
    #[arg(long)]
    pub max_html_mb: Option<u64>,
    /// Step budget: blocks executed before a runaway program is stopped (default: a
    /// million plus a hundred per block of the file).
    #[arg(long)]
    pub step_budget: Option<u64>,
    /// Motion budget: motions simulated before the run stops (default: a million
    /// plus eight per block of the file).
    #[arg(long)]
    pub motion_budget: Option<u64>,
    /// Diagnostics of one rule code reported per file (default 1000); the rest are
    /// summed up in one "… and N more" diagnostic.
    #[arg(long)]
    pub max_per_code: Option<usize>,
    /// Diagnostics reported per file (default 20000).
    #[arg(long)]
    pub max_per_file: Option<usize>,
    /// Largest program to read, in MB (default 128); larger files are refused
    /// with an error instead of exhausting memory. The summary alone (no
    /// `--emit`, pictures, what-ifs or blocks) reads a program above 32 MB in
    /// windows and has no default limit.
    #[arg(long)]
    pub max_file_size: Option<u64>,
    /// Read the program in windows of this many bytes (tests compare it with
    /// the whole-file run).
    #[arg(long, hide = true)]
    pub window_bytes: Option<usize>,
    /// Runtime errors the dry run reports and recovers from before it stops
    /// (default 100, `[rules] max_runtime_errors`).
    #[arg(long)]
    pub max_runtime_errors: Option<usize>,
}

/// Largest toolpath data written into an HTML page by default, in MB.
const DEFAULT_MAX_HTML_MB: u64 = 64;

impl RunArgs {
    /// The files the run writes besides its standard output, with their flags.
    /// Whether only the summary is asked for (human or JSON), which a file
    /// read in windows can give.
    fn summary_only(&self) -> bool {
        self.emit.is_none()
            && self.outputs().iter().all(|(_, o)| o.is_none())
            && self.what_if != AutoSwitch::On
            && self.blocks != AutoSwitch::On
    }

    fn outputs(&self) -> [(&'static str, Option<&PathBuf>); 3] {
        [
            ("--svg", self.svg.as_ref()),
            ("--png", self.png.as_ref()),
            ("--html", self.html.as_ref()),
        ]
    }
}

fn fail(msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("partscope: {msg}");
    ExitCode::from(2)
}

/// The same file on disk (both exist and resolve to one path).
fn same_file(a: &Path, b: &Path) -> bool {
    matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}

/// Refuses an output path that is one of the files the run reads.
fn guard_output(flag: &str, out: Option<&PathBuf>, inputs: &[&Path]) -> Result<(), String> {
    match out {
        Some(o) if inputs.iter().any(|i| same_file(o, i)) => Err(format!(
            "{flag} {}: that is a file the run reads (a program or subprogram); choose another output file",
            o.display()
        )),
        _ => Ok(()),
    }
}

/// Writes `path` through a temporary file beside it, renamed into place when
/// `write` succeeds, so a failed or cut-short write never leaves half a file.
fn write_replacing<T>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<T, String>,
) -> Result<T, String> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let tmp = path.with_file_name(format!(".{name}.partscope-{}.tmp", std::process::id()));
    let result = write(&tmp).and_then(|v| {
        std::fs::rename(&tmp, path)
            .map(|_| v)
            .map_err(|e| e.to_string())
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

pub fn run(args: RunArgs) -> ExitCode {
    for (flag, out) in args.outputs() {
        if let Err(e) = guard_output(flag, out, &[&args.file]) {
            return fail(e);
        }
    }
    let size = std::fs::metadata(&args.file).map_or(0, |m| m.len());
    // The summary of a large program reads it in windows; its head names the dialect.
    let window = args
        .window_bytes
        .or_else(|| (size > super::stream::STREAM_ABOVE).then_some(super::stream::WINDOW_BYTES))
        .filter(|_| args.summary_only());
    let default_mb = match window {
        Some(_) => u64::MAX >> 20,
        None => workspace::DEFAULT_MAX_FILE_MB,
    };
    let max_mb = args.max_file_size.unwrap_or(default_mb);
    let limit = crate::resolve::SizeLimit::megabytes(max_mb);
    let text = match window {
        Some(_) => crate::resolve::read_head(&args.file, &limit, 64 * 1024),
        None => crate::resolve::read_program(&args.file, &limit),
    };
    let mut text = match text {
        Ok(b) => b,
        Err(e) => return fail(format_args!("{}: {e}", args.file.display())),
    };
    // A binary file gets its one L009 as the whole-file run gives it.
    let binary = window.is_some()
        && analyzer::parse_text_lean(
            text.clone(),
            &analyzer::Settings::new(analyzer::Dialect::Rs274ngc),
        )
        .binary;
    let window = window.filter(|_| !binary);
    if binary {
        let limit = crate::resolve::SizeLimit::megabytes(
            args.max_file_size.unwrap_or(workspace::DEFAULT_MAX_FILE_MB),
        );
        text = match crate::resolve::read_program(&args.file, &limit) {
            Ok(b) => b,
            Err(e) => return fail(format_args!("{}: {e}", args.file.display())),
        };
    }
    let loaded = match &args.config {
        Some(p) => workspace::load_config(p),
        None => {
            let dir = args
                .file
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            ConfigCache::default()
                .for_dir(&dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf()))
        }
    };
    let loaded = match loaded {
        Ok(l) if l.unreadable => return fail(l.issues.join("\n")),
        Ok(l) => l,
        Err(e) => return fail(e),
    };
    loaded.warn();
    let (dialect, dialect_reason) = workspace::resolve_dialect(
        args.dialect.map(|d| d.dialect()),
        &loaded,
        &args.file,
        &text,
    );
    let mut settings = workspace::settings_for(&loaded.config, dialect, &[], &[]);
    settings.max_per_code = args.max_per_code.unwrap_or(settings.max_per_code);
    if let Some(n) = args.max_runtime_errors {
        settings.max_runtime_errors = n.max(1);
    }
    settings.max_per_file = args.max_per_file.unwrap_or(settings.max_per_file);
    settings.file_stem = args
        .file
        .file_stem()
        .and_then(|s| s.to_str())
        .map(str::to_string);

    // Machine: --machine (TOML or LinuxCNC .ini), else the config's [machine] table.
    let mut machine_table = loaded.config.machine.clone();
    // Named in the output, so a figure is never read without its machine.
    let mut profile_name = match &loaded.path {
        Some(p) if !machine_table.is_empty() => format!("[machine] in {}", p.display()),
        _ => format!(
            "built-in {} default (no tool-change or spindle times)",
            dialect.as_str()
        ),
    };
    let mut profile_override: Option<MachineProfile> = None;
    let mut tool_table_path = args.tool_table.clone();
    let mut var_path = args.var_file.clone();
    if let Some(m) = &args.machine {
        profile_name = m.display().to_string();
        let machine_text = match std::fs::read_to_string(m) {
            Ok(t) => t,
            Err(e) => return fail(format_args!("{}: {e}", m.display())),
        };
        let is_ini = m
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("ini"));
        if is_ini {
            match MachineProfile::from_linuxcnc_ini(&machine_text) {
                Ok((p, extras)) => {
                    let base = m.parent().unwrap_or(Path::new("."));
                    if tool_table_path.is_none() {
                        tool_table_path = extras.tool_table.map(|t| base.join(t));
                    }
                    if var_path.is_none() {
                        var_path = extras.parameter_file.map(|t| base.join(t));
                    }
                    profile_override = Some(p);
                }
                Err(e) => return fail(format_args!("{}: {e}", m.display())),
            }
        } else {
            let (table, issues) = analyzer::config::MachineConfig::load(&machine_text);
            let located = workspace::locate_all(m, &machine_text, &issues);
            if issues
                .iter()
                .any(|i| i.severity == analyzer::Severity::Error)
            {
                return fail(located.join("\n"));
            }
            for w in &located {
                workspace::say_once(w);
            }
            machine_table = table;
        }
    }
    // The config's own LinuxCNC files (tool_table, var_file, ini) fill what the
    // command line left open.
    // Read only when the command line left one of them open, so that a config's
    // missing file is not reported for a run that names its own.
    let no_files = workspace::ConfigFiles::default();
    let cfg_files = if args.machine.is_none() || tool_table_path.is_none() || var_path.is_none() {
        loaded.linuxcnc_files()
    } else {
        &no_files
    };
    for w in &cfg_files.warnings {
        workspace::warn_once(w);
    }
    let config_ini = cfg_files
        .ini_profile
        .as_ref()
        .filter(|_| args.machine.is_none());
    if let (Some(_), Some(ini), Some(cfg)) = (config_ini, &loaded.config.ini, &loaded.path) {
        profile_name = format!("ini {ini} of {}", cfg.display());
    }
    let mut profile = match profile_override {
        // `--machine` names the whole machine.
        Some(p) => p,
        None => {
            let (table, profile) = workspace::machine_of(&machine_table, config_ini, dialect);
            machine_table = table;
            profile
        }
    };
    if let Some(fo) = &args.feed_override {
        let v = fo.trim_end_matches('%').parse::<f64>().ok().map(|v| {
            if fo.ends_with('%') {
                v / 100.0
            } else {
                v
            }
        });
        match v {
            Some(v) if v > 0.0 && v.is_finite() => profile.feed_override = v,
            _ => return fail(format_args!("bad --feed-override `{fo}`")),
        }
    }
    let read_opt = |p: &Option<PathBuf>| -> Result<Option<String>, String> {
        match p {
            Some(p) => std::fs::read_to_string(p)
                .map(Some)
                .map_err(|e| format!("{}: {e}", p.display())),
            None => Ok(None),
        }
    };
    // Files named on the command line must exist; files an INI or config refers to
    // are optional (a copied INI often names a tool table that is not beside it).
    let explicit_tbl = args.tool_table.is_some();
    let explicit_var = args.var_file.is_some();
    let tool_table = match read_opt(&tool_table_path) {
        Ok(None) => cfg_files.tool_table.clone(),
        Ok(t) => t,
        Err(e) if explicit_tbl => return fail(e),
        Err(e) => {
            eprintln!("partscope: warning: {e}; running without a tool table");
            None
        }
    };
    // `--emit canon` imitates the standalone rs274, which loads LinuxCNC's sample
    // tool table when given none; the same tools make compensation radii, tool
    // length offsets and "tool not found" errors agree.
    let tool_table = match tool_table {
        None if args.emit == Some(Emit::Canon) && dialect == analyzer::Dialect::Rs274ngc => {
            Some(RS274_DEFAULT_TOOL_TABLE.to_string())
        }
        t => t,
    };
    let var_file = match read_opt(&var_path) {
        Ok(None) => cfg_files.var_file.clone(),
        Ok(t) => t,
        Err(e) if explicit_var => return fail(e),
        Err(e) => {
            eprintln!("partscope: warning: {e}; running without a parameter file");
            None
        }
    };

    if let Some(window) = window {
        // Called files are read whole, within the usual limit.
        let called = crate::resolve::SizeLimit::megabytes(
            args.max_file_size.unwrap_or(workspace::DEFAULT_MAX_FILE_MB),
        );
        let resolver = crate::resolve::FsResolver::for_command_line(
            &args.file,
            dialect,
            &loaded.config.machine,
            loaded.path.as_deref(),
            called,
        );
        let parts = super::stream::RunParts {
            settings: &settings,
            machine: &machine_table,
            resolver: &resolver,
            tool_table: tool_table.as_deref(),
            var_file: var_file.as_deref(),
            step_budget: args.step_budget,
            motion_budget: args.motion_budget,
        };
        let reason = (dialect, dialect_reason.clone());
        return match super::stream::run_file(&args.file, window, &parts, &profile, reason) {
            Ok(w) => windowed_output(&args, w, &profile_name, &profile),
            Err(e) => fail(format_args!("{}: {e}", args.file.display())),
        };
    }
    let parsed = analyzer::parse_text_lean(text.clone(), &settings);
    if analyzer::reports_mismatch(&parsed, &settings) {
        // A lathe or Haas program: a cycle time read as a FANUC mill would mean nothing.
        let report = FileReport {
            path: args.file.clone(),
            text,
            diagnostics: analyzer::lint(&parsed, &settings),
            io_error: false,
            extra_files: Vec::new(),
            dialect: Some((dialect, dialect_reason)),
            sparse: None,
        };
        return mismatch_output(&args, &report, &profile_name);
    }
    let resolver = crate::resolve::FsResolver::for_command_line(
        &args.file,
        dialect,
        &loaded.config.machine,
        loaded.path.as_deref(),
        crate::resolve::SizeLimit::megabytes(max_mb),
    );
    let emit_canon = args.emit == Some(Emit::Canon);
    let input = runtime::RunInput {
        program: &parsed.program,
        settings: &settings,
        machine: &machine_table,
        resolver: &resolver,
        step_budget: args
            .step_budget
            .unwrap_or_else(|| runtime::default_step_budget(parsed.program.blocks.len())),
        motion_budget: args
            .motion_budget
            .unwrap_or_else(|| runtime::default_motion_budget(parsed.program.blocks.len())),
        emit_canon,
        tool_table: tool_table.as_deref(),
        var_file: var_file.as_deref(),
    };
    let progress = Progress::start(text.len());
    progress.stage("interpreting");
    // The JSON summary needs only the totals: the planner then consumes the motions as
    // the interpreter produces them, and memory stays flat however long the program.
    let what_if_asked = args.what_if.on_for(text.len());
    // Per-block output is several times the summary's cost on a long program.
    let with_blocks = args.blocks.on_for(text.len());
    if args.format == RunFormat::Json
        && args.emit.is_none()
        && args.outputs().iter().all(|(_, o)| o.is_none())
        && !what_if_asked
    {
        // The static rules run beside the interpreter and planner (both only read the tree).
        let (diagnostics, out, totals, blocks) = std::thread::scope(|scope| {
            let lint = scope.spawn(|| analyzer::lint(&parsed, &settings));
            let (out, totals, blocks) = plan_beside(&input, &profile, with_blocks);
            // A panic in the rules is passed on as if the rules had run on this thread.
            let diagnostics = lint.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
            (diagnostics, out, totals, blocks)
        });
        progress.finish();
        let diagnostics = analyzer::merge(
            diagnostics,
            analyzer::finish(&parsed.program, &settings, out.diagnostics),
            &settings,
        );
        let report = FileReport {
            path: args.file.clone(),
            text,
            diagnostics,
            io_error: false,
            extra_files: output::read_extra_files(&out.files),
            dialect: Some((dialect, dialect_reason.clone())),
            sparse: None,
        };
        let dry = DryRun {
            totals,
            blocks,
            ..DryRun::default()
        };
        let stop = stop_of(out.stopped.as_ref(), &out.files, out.skipped_calls, &report);
        let what_ifs = match args.what_if {
            AutoSwitch::Off => WhatIfs::Off,
            _ => WhatIfs::Skipped(format!(
                "the program is larger than {} KiB; --what-if on plans them",
                WHAT_IF_AUTO_BYTES >> 10
            )),
        };
        let stdout = std::io::stdout();
        let mut w = std::io::BufWriter::new(stdout.lock());
        let mut summary = summary_json(&dry, &report, &stop, &profile_name, &what_ifs, &profile);
        if !with_blocks && args.blocks == AutoSwitch::Auto {
            summary["blocks_skipped"] = blocks_skipped();
        }
        let res = write_summary(&mut w, summary, &dry.blocks, &out.files).and_then(|_| w.flush());
        if let Some(code) = res.err().and_then(|e| super::write_failure(&e)) {
            return code;
        }
        return exit_status(&report, &stop);
    }
    let out = runtime::run_with_snapshots(&input, false);
    progress.stage("planning");
    let diagnostics = analyzer::merge(
        analyzer::lint(&parsed, &settings),
        analyzer::finish(&parsed.program, &settings, out.diagnostics.clone()),
        &settings,
    );

    if emit_canon {
        return emit_canon_output(&out, &parsed.program, &diagnostics, &args.file);
    }

    let dry = dryrun::plan_run(&out, &profile);
    let what_ifs = if !what_if_asked {
        WhatIfs::Off
    } else if args.what_if == AutoSwitch::Auto && out.motions.len() > WHAT_IF_AUTO_MOTIONS {
        WhatIfs::Skipped(format!(
            "the run makes more than {} motions; --what-if on plans them",
            runtime::plan::explain::thousands(WHAT_IF_AUTO_MOTIONS as u64)
        ))
    } else {
        progress.stage("what if");
        WhatIfs::Ran(what_ifs(&out, &profile, dialect))
    };
    progress.finish();
    let extra_files = output::read_extra_files(&out.files);
    let mut report = FileReport {
        path: args.file.clone(),
        text: text.clone(),
        diagnostics,
        io_error: false,
        extra_files,
        dialect: Some((dialect, dialect_reason)),
        sparse: None,
    };

    let read: Vec<&Path> = out.files.iter().map(Path::new).collect();
    for (flag, o) in args.outputs() {
        if let Err(e) = guard_output(flag, o, &read) {
            return fail(e);
        }
    }
    if args.svg.is_some() || args.png.is_some() {
        let tp = dryrun::toolpath_on(&out, 0.01, &profile);
        let max_mb = args
            .max_svg_mb
            .unwrap_or(crate::picture::DEFAULT_MAX_SVG_MB);
        let max_bytes = max_mb.saturating_mul(1 << 20);
        let title = args.file.display().to_string();
        let mut cut = None;
        if let Some(svg) = &args.svg {
            let written = write_replacing(svg, |tmp| {
                let f = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
                let mut w = std::io::BufWriter::new(f);
                let cut = crate::picture::svg(&mut w, &tp, &title, &dry, max_bytes)
                    .map_err(|e| e.to_string())?;
                w.flush().map_err(|e| e.to_string())?;
                Ok(cut)
            });
            match written {
                Ok(c) => cut = c,
                Err(e) => return fail(format_args!("{}: {e}", svg.display())),
            }
        }
        if let Some(png) = &args.png {
            // The PNG is the SVG picture rasterised: one drawing, text and legend included.
            let mut svg = Vec::new();
            let drawn = crate::picture::svg(&mut svg, &tp, &title, &dry, max_bytes)
                .map_err(|e| e.to_string())
                .and_then(|c| {
                    cut = cut.or(c);
                    write_replacing(png, |tmp| crate::picture::png(&svg, tmp))
                });
            match drawn {
                Ok(true) => {}
                Ok(false) => workspace::warn_once(
                    "no font is installed, so the PNG picture has no text (install one, e.g. fonts-dejavu-core)",
                ),
                Err(e) => return fail(format_args!("{}: {e}", png.display())),
            }
        }
        if let Some((line, file)) = cut {
            // Located at the first line left out of the picture (the start of the
            // main file when that line is in a subprogram file).
            let at = if file == 0 {
                analyzer::LineIndex::new(&text)
                    .line_start(line)
                    .unwrap_or(0)
            } else {
                0
            };
            report.diagnostics.push(runtime::rules::STEP_BUDGET.warning(
                Span::new(at, at),
                format!("the SVG picture is cut off here to keep it under {max_mb} MB; raise the limit with --max-svg-mb"),
            ));
        }
    }
    if let Some(html) = &args.html {
        // The result `partscope/dryRun` gives the editor's preview, made by the same code.
        let mut result = crate::lsp::dry_run_result(
            &parsed.program,
            &args.file,
            &out,
            &profile,
            &dry,
            &resolver.loaded(),
        );
        let mut title = args
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| args.file.display().to_string());
        // The figures stay those of the whole run; only the drawing is cut short.
        let max_mb = args.max_html_mb.unwrap_or(DEFAULT_MAX_HTML_MB);
        let segments = &mut result.toolpath.segments;
        let keep = crate::page::segments_within(segments, max_mb.saturating_mul(1 << 20));
        if keep < segments.len() {
            let line = segments[keep].line;
            segments.truncate(keep);
            title = format!(
                "{title} — toolpath cut off at line {} to keep the page under {max_mb} MB (--max-html-mb)",
                line + 1
            );
            let at = analyzer::LineIndex::new(&text)
                .line_start(line)
                .unwrap_or(0);
            report.diagnostics.push(runtime::rules::STEP_BUDGET.warning(
                Span::new(at, at),
                format!("the HTML page's toolpath is cut off here to keep it under {max_mb} MB; raise the limit with --max-html-mb"),
            ));
        }
        let written = write_replacing(html, |tmp| {
            let f = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
            let mut w = std::io::BufWriter::new(f);
            crate::page::write(&mut w, &result, &title)
                .and_then(|_| w.flush())
                .map_err(|e| e.to_string())
        });
        if let Err(e) = written {
            return fail(format_args!("{}: {e}", html.display()));
        }
    }
    let stop = stop_of(out.stopped.as_ref(), &out.files, out.skipped_calls, &report);
    let stdout = std::io::stdout();
    let mut w = std::io::BufWriter::new(stdout.lock());
    let res = match args.emit {
        Some(Emit::Blocks) => {
            let mut r = writeln!(
                w,
                "line,start_s,end_s,duration_s,length_mm,peak_feed_mm_min,time_s,{}",
                CSV_CAUSES.join(",")
            );
            for b in dryrun::block_times(&out, &dry) {
                if r.is_ok() {
                    let causes: Vec<String> = block_parts(&b)
                        .iter()
                        .map(|(_, s)| format!("{s:.6}"))
                        .collect();
                    r = writeln!(
                        w,
                        "{},{:.6},{:.6},{:.6},{:.6},{:.3},{:.6},{}",
                        b.line + 1,
                        b.start_s,
                        b.end_s,
                        b.duration_s,
                        b.length_mm,
                        b.peak_feed,
                        b.time_s,
                        causes.join(",")
                    );
                }
            }
            r
        }
        Some(Emit::BlocksJson) => {
            let v: Vec<_> = dryrun::block_times(&out, &dry)
                .iter()
                .map(block_json)
                .collect();
            serde_json::to_writer_pretty(&mut w, &v)
                .map_err(std::io::Error::from)
                .and_then(|_| writeln!(w))
        }
        Some(Emit::Toolpath) => {
            let tp = dryrun::toolpath_on(&out, 0.01, &profile);
            serde_json::to_writer(&mut w, &tp)
                .map_err(std::io::Error::from)
                .and_then(|_| writeln!(w))
        }
        Some(Emit::Canon) | None => match args.format {
            RunFormat::Json => {
                let mut v = summary_json(&dry, &report, &stop, &profile_name, &what_ifs, &profile);
                let blocks: &[dryrun::BlockTime] = if with_blocks { &dry.blocks } else { &[] };
                if !with_blocks && args.blocks == AutoSwitch::Auto {
                    v["blocks_skipped"] = blocks_skipped();
                }
                write_summary(&mut w, v, blocks, &out.files)
            }
            RunFormat::Human => human(
                &mut w,
                &args.file,
                &dry,
                &out,
                &report,
                &stop,
                &profile_name,
                &what_ifs,
                &profile,
            ),
        },
    };
    if let Some(code) = res
        .and_then(|_| w.flush())
        .err()
        .and_then(|e| super::write_failure(&e))
    {
        return code;
    }
    exit_status(&report, &stop)
}

/// Why `--format json` has no per-block entries under `--blocks auto`.
fn blocks_skipped() -> serde_json::Value {
    serde_json::Value::String(format!(
        "the program is larger than {} KiB; --blocks on writes them",
        WHAT_IF_AUTO_BYTES >> 10
    ))
}

/// Chunks of motions in flight between the interpreter and the planner thread: enough
/// that neither waits on the other's jitter, few enough that memory stays flat.
const PLAN_QUEUE: usize = 4;

/// Runs `input` with the planner on a thread of its own, fed through a
/// bounded queue of motion chunks ([`plan_beside_with`]).
fn plan_beside(
    input: &runtime::RunInput<'_>,
    profile: &MachineProfile,
    with_blocks: bool,
) -> (
    runtime::RunOutput,
    runtime::plan::Totals,
    Vec<dryrun::BlockTime>,
) {
    plan_beside_with(profile, with_blocks, |sink| {
        runtime::run_streaming_owned(input, sink)
    })
}

/// Plans the motions `run` hands its sink on a thread of its own, through a
/// bounded queue (memory stays flat however long the program), and returns
/// what `run` returned with the totals (and per-block figures when asked).
/// `run` is called a second time, into a closed-form planner, when the run
/// passes the servo-simulation limit.
pub(super) fn plan_beside_with<R>(
    profile: &MachineProfile,
    with_blocks: bool,
    run: impl Fn(&mut runtime::interp::OwnedMotionSink<'_>) -> R,
) -> (R, runtime::plan::Totals, Vec<dryrun::BlockTime>) {
    let pass = |plan: dryrun::StreamPlan| {
        std::thread::scope(|scope| {
            type Chunk = (Vec<runtime::Motion>, Vec<runtime::Event>);
            let (tx, rx) = std::sync::mpsc::sync_channel::<Chunk>(PLAN_QUEUE);
            // Emptied buffers go back to the interpreter, so the chunks reuse memory.
            let (back_tx, back_rx) = std::sync::mpsc::channel::<Chunk>();
            let planner = scope.spawn(move || {
                let mut plan = plan;
                for (mut m, mut e) in rx {
                    plan.push(&m, &e);
                    m.clear();
                    e.clear();
                    let _ = back_tx.send((m, e));
                }
                plan.finish_with_blocks()
            });
            let out = run(&mut |m, e| {
                // The full buffers go to the planner; emptied ones come back.
                let (mut mb, mut eb) = back_rx.try_recv().unwrap_or_default();
                std::mem::swap(m, &mut mb);
                std::mem::swap(e, &mut eb);
                // The planner only stops early by panicking, which the join passes on.
                let _ = tx.send((mb, eb));
            });
            drop(tx);
            let totals = planner
                .join()
                .unwrap_or_else(|e| std::panic::resume_unwind(e));
            (out, totals)
        })
    };
    let plan = |p: dryrun::StreamPlan| if with_blocks { p.with_blocks() } else { p };
    match pass(plan(dryrun::StreamPlan::new(profile))) {
        (out, Some((totals, blocks))) => (out, totals, blocks),
        (_, None) => {
            let (out, r) = pass(plan(dryrun::StreamPlan::closed_form(profile)));
            let (totals, blocks) = r.unwrap_or_default();
            (out, totals, blocks)
        }
    }
}

/// The output of `run` for a program written for another control (P010): the
/// diagnostic, no figures (`cycle_time_s` and the other totals are null, `partial`
/// is true in JSON).
/// The summary of a run made in windows (`cli::stream::run_file`), as the
/// whole-file JSON summary path writes it (no per-block figures).
fn windowed_output(
    args: &RunArgs,
    w: super::stream::RunWindows,
    profile_name: &str,
    profile: &MachineProfile,
) -> ExitCode {
    let report = w.report;
    let Some(out) = w.out else {
        let why = if report.diagnostics.iter().any(analyzer::stream::is_mismatch) {
            NotComputed::OtherControl
        } else {
            NotComputed::NotRun
        };
        return no_figures_output(args, &report, profile_name, why);
    };
    let dry = DryRun {
        totals: w.totals,
        ..DryRun::default()
    };
    let stop = stop_of(out.stopped.as_ref(), &out.files, out.skipped_calls, &report);
    let stdout = std::io::stdout();
    let mut wr = std::io::BufWriter::new(stdout.lock());
    let res = match args.format {
        RunFormat::Json => {
            let what_ifs = match args.what_if {
                AutoSwitch::Off => WhatIfs::Off,
                _ => WhatIfs::Skipped(format!(
                    "the program is larger than {} KiB; --what-if on plans them",
                    WHAT_IF_AUTO_BYTES >> 10
                )),
            };
            let mut summary = summary_json(&dry, &report, &stop, profile_name, &what_ifs, profile);
            if args.blocks == AutoSwitch::Auto {
                summary["blocks_skipped"] = blocks_skipped();
            }
            write_summary(&mut wr, summary, &[], &out.files)
        }
        RunFormat::Human => human(
            &mut wr,
            &args.file,
            &dry,
            &out,
            &report,
            &stop,
            profile_name,
            &WhatIfs::Off,
            profile,
        ),
    };
    if let Some(code) = res
        .and_then(|_| wr.flush())
        .err()
        .and_then(|e| super::write_failure(&e))
    {
        return code;
    }
    exit_status(&report, &stop)
}

/// Why `run` gives no figures.
#[derive(Clone, Copy, PartialEq)]
enum NotComputed {
    /// P010: the program is for another control.
    OtherControl,
    /// F004: a program with flow control too large to hold.
    NotRun,
}

fn mismatch_output(args: &RunArgs, report: &FileReport, profile_name: &str) -> ExitCode {
    no_figures_output(args, report, profile_name, NotComputed::OtherControl)
}

/// The output of `run` without figures: the diagnostics, and (in JSON) null
/// totals with `partial` true.
fn no_figures_output(
    args: &RunArgs,
    report: &FileReport,
    profile_name: &str,
    why: NotComputed,
) -> ExitCode {
    let stdout = std::io::stdout();
    let mut w = std::io::BufWriter::new(stdout.lock());
    let located = output::locate(std::slice::from_ref(report));
    let res = if args.format == RunFormat::Json && args.emit.is_none() {
        let diags: Vec<serde_json::Value> = located
            .iter()
            .map(|l| {
                json!({"path": l.path, "line": l.line, "column": l.column, "end_line": l.end_line, "end_column": l.end_column,
                       "code": l.d.code, "severity": l.d.severity.as_str(), "message": l.d.message})
            })
            .collect();
        let (dialect, dialect_reason) = output::dialect_fields(report);
        let v = json!({
            "dialect": dialect,
            "dialect_reason": dialect_reason,
            "machine_profile": profile_name,
            "cycle_time_s": null,
            "motion_s": null,
            "rapid_s": null,
            "cutting_s": null,
            "dwell_s": null,
            "tool_change_s": null,
            "other_s": null,
            "auxiliary": null,
            "distance_mm": null,
            "per_tool": {},
            "partial": true,
            "complete": false,
            "stopped_at": null,
            "diagnostics": diags,
        });
        serde_json::to_writer_pretty(&mut w, &v)
            .map_err(std::io::Error::from)
            .and_then(|_| writeln!(w))
    } else {
        // Emits and pictures are not made either; the reason goes where a human reads it.
        let reason = match why {
            NotComputed::OtherControl => "the program is not for a FANUC 30i mill",
            NotComputed::NotRun => "the dry run was not made (F004)",
        };
        let mut r = writeln!(w, "{}", args.file.display())
            .and_then(|_| writeln!(w, "  cycle time   not computed: {reason}"));
        for l in &located {
            if r.is_ok() {
                r = writeln!(w, "  {}:{} {} {}", l.line, l.column, l.d.code, l.d.message);
            }
        }
        r
    };
    if let Some(code) = res
        .and_then(|_| w.flush())
        .err()
        .and_then(|e| super::write_failure(&e))
    {
        return code;
    }
    let stop = Stop {
        partial: why == NotComputed::NotRun,
        ..Stop::default()
    };
    exit_status(report, &stop)
}

/// Why the figures cover only part of the program: where the run stopped (an
/// error that leaves the state undefined, a budget, the runtime-error cap, a block
/// the control cannot read), or a budget diagnostic (F004, also the SVG cut-off).
#[derive(Default)]
struct Stop {
    partial: bool,
    /// Path, 1-based line and reason of the run's stop.
    at: Option<(String, u32, String)>,
    /// A budget (F004) stopped it.
    budget: bool,
    /// A budget diagnostic (F004) cut the figures short.
    cut: bool,
    /// A call the run could not follow was skipped (F002).
    skipped_calls: bool,
}

fn stop_of(
    stopped: Option<&runtime::Stopped>,
    files: &[String],
    skipped_calls: bool,
    report: &FileReport,
) -> Stop {
    let at = stopped.map(|s| {
        let path = if s.file == analyzer::FileId(0) {
            report.path.display().to_string()
        } else {
            files
                .get((s.file.0 as usize).saturating_sub(1))
                .cloned()
                .unwrap_or_default()
        };
        (path, s.line + 1, s.reason.clone())
    });
    let cut = partial(report);
    Stop {
        partial: at.is_some() || cut || skipped_calls,
        at,
        budget: stopped.is_some_and(|s| s.code == runtime::rules::STEP_BUDGET.code),
        cut,
        skipped_calls,
    }
}

/// 1 when the run reported an error or its cycle time is partial, else success.
fn exit_status(report: &FileReport, stop: &Stop) -> ExitCode {
    if stop.partial
        || report
            .diagnostics
            .iter()
            .any(|d| d.severity == Severity::Error)
    {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// The auxiliary times by category, with their sum, for `run --format json`.
fn auxiliary_json(a: &runtime::plan::Auxiliary) -> serde_json::Value {
    json!({
        "tool_change_s": a.tool_change_s,
        "tool_changes": a.tool_changes,
        "tool_select_s": a.tool_select_s,
        "spindle_s": a.spindle_s,
        "orient_s": a.orient_s,
        "coolant_s": a.coolant_s,
        "pallet_change_s": a.pallet_change_s,
        "m_code_s": a.m_code_s,
        "in_position_s": a.in_position_s,
        "program_stop_s": a.program_stop_s,
        "program_stops": a.program_stops,
        "total_s": a.total_s(),
    })
}

/// The what-if estimates of a run: planned, skipped (and why), or not asked for.
enum WhatIfs {
    Ran(Vec<dryrun::WhatIf>),
    Skipped(String),
    Off,
}

/// Plans the what-if estimates that apply to the dialect, side by side.
fn what_ifs(
    out: &runtime::RunOutput,
    profile: &MachineProfile,
    dialect: analyzer::Dialect,
) -> Vec<dryrun::WhatIf> {
    let events = dryrun::planner_events(out);
    let kinds: Vec<dryrun::WhatIfKind> = dryrun::WhatIfKind::ALL
        .into_iter()
        .filter(|k| k.applies(dialect))
        .collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = kinds
            .iter()
            .map(|k| {
                let events = &events;
                scope.spawn(move || dryrun::what_if(events, profile, *k))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
}

/// Cause columns of `--emit blocks`, in [`block_parts`] order.
const CSV_CAUSES: [&str; 10] = [
    "feed_s",
    "accel_s",
    "corner_s",
    "axis_cap_s",
    "traj_cap_s",
    "curve_cap_s",
    "servo_cap_s",
    "rapid_s",
    "dwell_s",
    "aux_s",
];

/// A block's time by cause, keyed as in [`CSV_CAUSES`].
fn block_parts(b: &dryrun::BlockTime) -> [(&'static str, f64); 10] {
    let c = &b.causes;
    [
        ("feed_s", c.feed_s),
        ("accel_s", c.accel_s),
        ("corner_s", c.corner_s),
        ("axis_cap_s", c.axis_cap_s),
        ("traj_cap_s", c.traj_cap_s),
        ("curve_cap_s", c.curve_cap_s),
        ("servo_cap_s", c.servo_cap_s),
        ("rapid_s", c.rapid_s),
        ("dwell_s", b.dwell_s),
        ("aux_s", b.aux_s),
    ]
}

/// One block for JSON: 1-based line, file (0 = the program, n = `files[n-1]`),
/// times on the program clock, and the causes that took time (others are 0).
fn block_json(b: &dryrun::BlockTime) -> serde_json::Value {
    let causes: serde_json::Map<String, serde_json::Value> = block_parts(b)
        .into_iter()
        .filter(|(_, s)| *s != 0.0)
        .map(|(k, s)| (k.to_string(), json!(s)))
        .collect();
    json!({"line": b.line + 1, "file": b.file, "start_s": b.start_s, "end_s": b.end_s,
           "time_s": b.time_s, "duration_s": b.duration_s, "length_mm": b.length_mm,
           "peak_feed": b.peak_feed, "causes": causes})
}

/// Writes the summary object with `blocks` and `files` added, one block per
/// line: a long program has a block for every line, and one object per line
/// keeps the output a fraction of its pretty-printed size.
fn write_summary(
    w: &mut impl Write,
    summary: serde_json::Value,
    blocks: &[dryrun::BlockTime],
    files: &[String],
) -> std::io::Result<()> {
    let mut head = serde_json::to_string_pretty(&summary).map_err(std::io::Error::other)?;
    // A pretty-printed object ends with "\n}".
    if head.ends_with("\n}") {
        head.truncate(head.len() - 2);
    } else {
        return writeln!(w, "{head}");
    }
    write!(w, "{head},\n  \"files\": ")?;
    serde_json::to_writer(&mut *w, files).map_err(std::io::Error::from)?;
    write!(w, ",\n  \"blocks\": [")?;
    for (i, b) in blocks.iter().enumerate() {
        w.write_all(if i == 0 { b"\n    " } else { b",\n    " })?;
        write_block(w, b)?;
    }
    writeln!(w, "\n  ]\n}}")
}

/// A JSON number, or `null` for what JSON cannot hold (as serde_json writes it).
struct Num(f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_finite() {
            // The shortest text that reads back as the same f64, with a point
            // (`1.0`) as serde_json writes a float.
            write!(f, "{:?}", self.0)
        } else {
            f.write_str("null")
        }
    }
}

/// [`block_json`] written straight out: a long program has a block per line,
/// and building a JSON value for each costs more than the planning.
fn write_block(w: &mut impl Write, b: &dryrun::BlockTime) -> std::io::Result<()> {
    write!(
        w,
        "{{\"line\":{},\"file\":{},\"start_s\":{},\"end_s\":{},\"time_s\":{},\"duration_s\":{},\"length_mm\":{},\"peak_feed\":{},\"causes\":{{",
        u64::from(b.line) + 1,
        b.file,
        Num(b.start_s),
        Num(b.end_s),
        Num(b.time_s),
        Num(b.duration_s),
        Num(b.length_mm),
        Num(b.peak_feed)
    )?;
    let mut first = true;
    for (k, s) in block_parts(b) {
        if s != 0.0 {
            write!(w, "{}\"{k}\":{}", if first { "" } else { "," }, Num(s))?;
            first = false;
        }
    }
    w.write_all(b"}}")
}

/// `time_causes` of the JSON summary: the cycle time by cause (summing to
/// `cycle_time_s`) and how many moves each cause touched.
fn causes_json(t: &runtime::plan::Totals) -> serde_json::Value {
    let mut m: serde_json::Map<String, serde_json::Value> = runtime::plan::explain::parts(t)
        .iter()
        .map(|p| (p.key.to_string(), json!(p.seconds)))
        .collect();
    let n = &t.cause_counts;
    m.insert(
        "moves".into(),
        json!({"accel": n.accel, "corner": n.corner, "axis_cap": n.axis_cap, "traj_cap": n.traj_cap,
               "curve_cap": n.curve_cap, "servo_cap": n.servo_cap}),
    );
    m.insert(
        "short_moves".into(),
        json!({"count": n.short, "time_s": n.short_s, "max_length_mm": n.short_max_mm,
               "min_feed": n.short_feed_min * 60.0, "max_feed": n.short_feed_max * 60.0}),
    );
    serde_json::Value::Object(m)
}

fn summary_json(
    dry: &DryRun,
    report: &FileReport,
    stop: &Stop,
    profile_name: &str,
    what_ifs: &WhatIfs,
    profile: &MachineProfile,
) -> serde_json::Value {
    let t = &dry.totals;
    let per_tool: serde_json::Map<String, serde_json::Value> = t
        .per_tool
        .iter()
        .map(|(tool, tt)| {
            (
                tool.to_string(),
                json!({"motion_s": tt.motion_s, "rapid_s": tt.rapid_s, "cutting_s": tt.cutting_s, "distance_mm": tt.distance_mm}),
            )
        })
        .collect();
    let located = output::locate(std::slice::from_ref(report));
    let diags: Vec<serde_json::Value> = located
        .iter()
        .map(|l| {
            json!({"path": l.path, "line": l.line, "column": l.column, "end_line": l.end_line, "end_column": l.end_column,
                   "code": l.d.code, "severity": l.d.severity.as_str(), "message": l.d.message})
        })
        .collect();
    let (dialect, dialect_reason) = output::dialect_fields(report);
    json!({
        "dialect": dialect,
        "dialect_reason": dialect_reason,
        "machine_profile": profile_name,
        "cycle_time_s": t.cycle_time_s,
        "motion_s": t.motion_s,
        "rapid_s": t.rapid_s,
        "cutting_s": t.cutting_s,
        "dwell_s": t.dwell_s,
        "tool_change_s": t.tool_change_s,
        "other_s": t.other_s,
        "auxiliary": auxiliary_json(&t.aux),
        "distance_mm": t.distance_mm,
        "per_tool": per_tool,
        "time_causes": causes_json(t),
        "top_causes": runtime::plan::explain::top_causes(t, profile.traj_max_velocity),
        "what_if": match what_ifs {
            WhatIfs::Ran(v) => json!(v),
            _ => serde_json::Value::Null,
        },
        "what_if_skipped": match what_ifs {
            WhatIfs::Skipped(why) => json!(why),
            _ => serde_json::Value::Null,
        },
        "partial": stop.partial,
        "complete": !stop.partial,
        "stopped_at": stop.at.as_ref().map(|(file, line, reason)| json!({"file": file, "line": line, "reason": reason})),
        "diagnostics": diags,
    })
}

/// Whether a budget (steps, motions, picture points: F004) cut the run short, so
/// that the totals cover only part of the program.
fn partial(report: &FileReport) -> bool {
    report
        .diagnostics
        .iter()
        .any(|d| d.code == runtime::rules::STEP_BUDGET.code)
}

/// `"  (3 changes)"`, or nothing for none.
fn count(n: u32, what: &str) -> String {
    match n {
        0 => String::new(),
        1 => format!("  (1 {what})"),
        n => format!("  ({n} {what}s)"),
    }
}

/// Seconds with three decimals, in scientific notation from 1e9 s on (a
/// 1e300 s dwell would otherwise print three hundred digits).
fn seconds(s: f64) -> String {
    if s.is_finite() && s.abs() >= 1e9 {
        format!("{s:.3e}")
    } else {
        format!("{s:.3}")
    }
}

fn hms(s: f64) -> String {
    // A program that moves to 1e308 or dwells 1e300 s has a cycle time that
    // overflows to infinity or does not fit an hour count: say so plainly
    // instead of printing a saturated integer.
    if s.is_infinite() && s > 0.0 {
        return "inf".into();
    }
    let s = s.max(0.0);
    if s >= 3600.0 * 1e9 {
        return format!("{:.3e} h", s / 3600.0);
    }
    let h = (s / 3600.0).floor();
    let m = ((s - h * 3600.0) / 60.0).floor();
    let sec = s - h * 3600.0 - m * 60.0;
    if h > 0.0 {
        format!("{}:{:02}:{:06.3}", h as u64, m as u64, sec)
    } else {
        format!("{:02}:{:06.3}", m as u64, sec)
    }
}

#[allow(clippy::too_many_arguments)]
fn human(
    w: &mut impl Write,
    file: &Path,
    dry: &DryRun,
    out: &runtime::RunOutput,
    report: &FileReport,
    stop: &Stop,
    profile_name: &str,
    what_ifs: &WhatIfs,
    profile: &MachineProfile,
) -> std::io::Result<()> {
    let t = &dry.totals;
    writeln!(w, "{}", file.display())?;
    if let Some((d, why)) = &report.dialect {
        writeln!(w, "  dialect      {:>12}  ({why})", d.as_str())?;
    }
    writeln!(
        w,
        "  cycle time   {:>12}  ({} s{})",
        hms(t.cycle_time_s),
        seconds(t.cycle_time_s),
        if stop.partial { ", partial" } else { "" }
    )?;
    writeln!(w, "  cutting      {:>12}", hms(t.cutting_s))?;
    writeln!(w, "  rapid        {:>12}", hms(t.rapid_s))?;
    writeln!(w, "  dwell        {:>12}", hms(t.dwell_s))?;
    let a = &t.aux;
    writeln!(
        w,
        "  tool change  {:>12}{}",
        hms(t.tool_change_s),
        count(a.tool_changes, "change")
    )?;
    // The other auxiliary categories, each when it takes time, then their sum.
    for (name, s) in [
        ("tool select ", a.tool_select_s),
        ("spindle     ", a.spindle_s),
        ("orient      ", a.orient_s),
        ("coolant     ", a.coolant_s),
        ("pallet      ", a.pallet_change_s),
        ("M codes     ", a.m_code_s),
        ("in position ", a.in_position_s),
    ] {
        if s > 0.0 {
            writeln!(w, "  {name} {:>12}", hms(s))?;
        }
    }
    if a.program_stop_s > 0.0 {
        writeln!(
            w,
            "  stops        {:>12}{}  (operator time at M0/M1)",
            hms(a.program_stop_s),
            count(a.program_stops, "stop")
        )?;
    }
    if a.total_s() > 0.0 {
        writeln!(
            w,
            "  auxiliary    {:>12}  (sum of the above but motion and dwell)",
            hms(a.total_s())
        )?;
    }
    writeln!(w, "  distance     {:>12.1} mm", t.distance_mm)?;
    writeln!(w, "  machine      {profile_name}")?;
    if let Some((path, line, reason)) = &stop.at {
        let place = if *path == file.display().to_string() {
            format!("line {line}")
        } else {
            format!("{path} line {line}")
        };
        writeln!(w, "  stopped at {place}: {reason}")?;
    }
    if stop.at.is_some() && !stop.budget {
        writeln!(
            w,
            "  partial: the run stopped early; the figures cover only what ran"
        )?;
    } else if stop.at.is_some() || stop.cut {
        writeln!(
            w,
            "  partial: a budget stopped the run (F004); the figures cover only what ran"
        )?;
    }
    if stop.skipped_calls {
        writeln!(
            w,
            "  partial: a called program was not run (F002); the figures leave out what it does"
        )?;
    }
    if !t.per_tool.is_empty() {
        writeln!(
            w,
            "\n  tool    motion      cutting     rapid       distance"
        )?;
        for (tool, tt) in &t.per_tool {
            writeln!(
                w,
                "  T{:<5} {:>11} {:>11} {:>11} {:>10.1} mm",
                tool,
                hms(tt.motion_s),
                hms(tt.cutting_s),
                hms(tt.rapid_s),
                tt.distance_mm
            )?;
        }
    }
    where_the_time_goes(w, t, what_ifs, profile)?;
    let mut blocks = dryrun::block_times(out, dry);
    blocks.sort_by(|a, b| b.time_s.total_cmp(&a.time_s));
    if !blocks.is_empty() {
        writeln!(w, "\n  slowest blocks")?;
        for b in blocks.iter().take(5) {
            let name = if b.file == 0 {
                String::new()
            } else {
                format!(
                    " ({})",
                    out.files
                        .get(b.file as usize - 1)
                        .map(String::as_str)
                        .unwrap_or("?")
                )
            };
            // The cause that took most of the block's time, when it is not the feed.
            let (key, most) =
                block_parts(b)
                    .into_iter()
                    .fold(("", 0.0), |m, p| if p.1 > m.1 { p } else { m });
            let why = if key.is_empty() || key == "feed_s" || b.time_s <= 0.0 {
                String::new()
            } else {
                format!(
                    "  {} {:.0} %",
                    key.trim_end_matches("_s").replace('_', " "),
                    100.0 * most / b.time_s
                )
            };
            writeln!(
                w,
                "  line {:<7} {:>9.3} s  {:>9.2} mm  peak {:>8.0} mm/min{}{}",
                b.line + 1,
                b.time_s,
                b.length_mm,
                b.peak_feed,
                why,
                name
            )?;
        }
    }
    let errors = report
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    let warnings = report
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Warning)
        .count();
    if errors + warnings > 0 {
        writeln!(
            w,
            "\n  {errors} error(s), {warnings} warning(s): run `partscope check {}` for details",
            file.display()
        )?;
    }
    Ok(())
}

/// The cycle time by cause, the top causes in words and the what-if estimates.
fn where_the_time_goes(
    w: &mut impl Write,
    t: &runtime::plan::Totals,
    what_ifs: &WhatIfs,
    profile: &MachineProfile,
) -> std::io::Result<()> {
    use runtime::plan::explain;
    if t.cycle_time_s <= 0.0 || !t.cycle_time_s.is_finite() {
        return Ok(());
    }
    writeln!(w, "\n  where the time goes")?;
    for p in explain::parts(t).iter().filter(|p| p.seconds > 0.0) {
        writeln!(
            w,
            "  {:<34} {:>12}  {:>5.1} %",
            p.label,
            hms(p.seconds),
            100.0 * p.seconds / t.cycle_time_s
        )?;
    }
    for line in explain::top_causes(t, profile.traj_max_velocity) {
        writeln!(w, "  - {line}")?;
    }
    match what_ifs {
        WhatIfs::Ran(v) if !v.is_empty() => {
            writeln!(w, "\n  what if (planned again)")?;
            for e in v {
                let d = e.cycle_time_s - t.cycle_time_s;
                writeln!(
                    w,
                    "  {:<34} {:>12}  {:>+9.3} s  ({:+.1} %)",
                    e.label,
                    hms(e.cycle_time_s),
                    d,
                    100.0 * d / t.cycle_time_s
                )?;
            }
        }
        WhatIfs::Skipped(why) => writeln!(w, "\n  what if: not planned ({why})")?,
        _ => {}
    }
    Ok(())
}

/// Canonical output like `rs274`: the calls on stdout; on an error the message and the
/// offending source line on stderr and exit status 1.
fn emit_canon_output(
    out: &runtime::RunOutput,
    program: &analyzer::syntax::Program,
    diagnostics: &[Diagnostic],
    file: &std::path::Path,
) -> ExitCode {
    let stdout = std::io::stdout();
    let mut w = std::io::BufWriter::new(stdout.lock());
    for l in &out.canon {
        if writeln!(w, "{l}").is_err() {
            return ExitCode::from(2);
        }
    }
    let _ = w.flush();
    // The interpreter knows the error that stopped it, worded as rs274 words it.
    if let Some(e) = &out.canon_error {
        let e = e.replace(runtime::CANON_FILE_NAME, &file.display().to_string());
        eprintln!("{e}");
        return ExitCode::from(1);
    }
    // rs274 stops reading at M2/M30: what follows is never parsed, so static errors
    // there do not fail the run.
    let end_offset = out
        .events
        .iter()
        .find(|e| matches!(e.kind, runtime::EventKind::ProgramEnd) && e.file == analyzer::FileId(0))
        .and_then(|e| program.blocks.get(e.block as usize))
        .map_or(usize::MAX, |b| b.span.end as usize);
    let first_error = diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error && d.file == analyzer::FileId(0))
        .filter(|d| (d.span.start as usize) < end_offset)
        .min_by_key(|d| d.span.start);
    match first_error {
        Some(d) => {
            let line = program
                .block_at(d.span.start)
                .and_then(|b| program.blocks.get(b))
                .map(|b| program.str_of(b.span).trim().to_string())
                .unwrap_or_default();
            eprintln!("{}\n{}", d.message, line);
            ExitCode::from(1)
        }
        None => ExitCode::SUCCESS,
    }
}

/// The tool table the standalone `rs274` of LinuxCNC 2.9 reads when run without
/// `-t` (its sample configuration's table; values in inches).
const RS274_DEFAULT_TOOL_TABLE: &str = "T1 P1 D0.125000 Z+0.511000\n\
T2 P2 D0.062500 Z+0.100000\n\
T3 P3 D0.201000 Z+1.273000\n\
T99999 P123 Z+0.100000\n";

/// A status line on stderr for long runs, shown only when stderr is a terminal and the
/// program is large (the interpreter and planner report no finer progress).
/// The stage shown, the stop flag and the drawing thread.
type ProgressState = (
    std::sync::Arc<std::sync::Mutex<&'static str>>,
    std::sync::Arc<std::sync::atomic::AtomicBool>,
    std::thread::JoinHandle<()>,
);

struct Progress {
    state: Option<ProgressState>,
}

impl Progress {
    fn start(bytes: usize) -> Progress {
        use std::io::IsTerminal;
        if bytes < 2_000_000 || !std::io::stderr().is_terminal() {
            return Progress { state: None };
        }
        let stage = std::sync::Arc::new(std::sync::Mutex::new("reading"));
        let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let (s2, d2) = (stage.clone(), done.clone());
        let handle = std::thread::spawn(move || {
            let t0 = std::time::Instant::now();
            let spin = ['|', '/', '-', '\\'];
            let mut i = 0;
            while !d2.load(std::sync::atomic::Ordering::Relaxed) {
                let st = s2.lock().map(|s| *s).unwrap_or("");
                eprint!(
                    "\r{} {st}… {:.1} s   ",
                    spin[i % 4],
                    t0.elapsed().as_secs_f64()
                );
                i += 1;
                std::thread::sleep(std::time::Duration::from_millis(120));
            }
            eprint!("\r{:40}\r", "");
        });
        Progress {
            state: Some((stage, done, handle)),
        }
    }

    fn stage(&self, name: &'static str) {
        if let Some((s, _, _)) = &self.state {
            if let Ok(mut g) = s.lock() {
                *g = name;
            }
        }
    }

    fn finish(self) {}
}

impl Drop for Progress {
    /// Clears the status line on every way out of `run`.
    fn drop(&mut self) {
        if let Some((_, done, handle)) = self.state.take() {
            done.store(true, std::sync::atomic::Ordering::Relaxed);
            let _ = handle.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The per-line writer of `--format json` and the JSON value of
    /// `--emit blocks-json` say the same, non-finite values as `null`.
    #[test]
    fn written_blocks_read_back_as_their_json_values() {
        let b = dryrun::BlockTime {
            file: 2,
            line: 41,
            start_s: 1.25,
            end_s: 3.5000000000000004,
            duration_s: 2.25,
            length_mm: 0.1,
            peak_feed: f64::INFINITY,
            time_s: 2.25,
            causes: runtime::plan::Causes {
                feed_s: 1.0,
                corner_s: 1e-20,
                ..Default::default()
            },
            dwell_s: 1.25,
            aux_s: 0.0,
        };
        let mut out = Vec::new();
        write_block(&mut out, &b).unwrap();
        let read: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(read, block_json(&b));
        assert_eq!(read["line"], 42);
        assert_eq!(read["peak_feed"], serde_json::Value::Null);
        assert_eq!(
            read["causes"],
            json!({"feed_s": 1.0, "corner_s": 1e-20, "dwell_s": 1.25})
        );
    }
}
