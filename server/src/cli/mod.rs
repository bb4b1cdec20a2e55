//! Command-line interface: `check`, `run`, `rule`, `lsp`.

pub mod check;
mod excerpt;
mod output;
mod run;
mod stream;
pub mod workspace;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

#[derive(Parser)]
#[command(
    name = "partscope",
    version,
    about = "Lint, dry-run and language server for CNC part programs"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Human,
    Json,
    Sarif,
    Github,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum DialectArg {
    Servoworks,
    Rs274ngc,
    Fanuc,
}

impl DialectArg {
    pub fn dialect(self) -> analyzer::Dialect {
        match self {
            DialectArg::Servoworks => analyzer::Dialect::Servoworks,
            DialectArg::Rs274ngc => analyzer::Dialect::Rs274ngc,
            DialectArg::Fanuc => analyzer::Dialect::Fanuc,
        }
    }
}

#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// Files or directories (walked recursively, honouring .gitignore).
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Dialect of the programs (overrides config and sniffing).
    #[arg(long, value_enum)]
    pub dialect: Option<DialectArg>,
    /// A partscope.toml to use instead of discovering one upward from each file.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Rules to enable, by code, prefix or name (comma separated); adds off-by-default rules.
    #[arg(long, value_delimiter = ',')]
    pub select: Vec<String>,
    /// Rules to disable, by code, prefix or name (comma separated).
    #[arg(long, value_delimiter = ',')]
    pub ignore: Vec<String>,
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
    /// Lowest severity that makes the exit status 1: error, warning, info or hint.
    #[arg(long)]
    pub fail_level: Option<String>,
    /// Only the static checks (no interpreter).
    #[arg(long)]
    pub no_run: bool,
    /// Blocks the interpreter may execute per file before it reports a runaway program
    /// (default: a million plus a hundred per block of the file).
    #[arg(long)]
    pub step_budget: Option<u64>,
    /// Motions the interpreter may produce per file before it stops (default: a
    /// million plus eight per block of the file).
    #[arg(long)]
    pub motion_budget: Option<u64>,
    /// Diagnostics of one rule code reported per file (default 1000); the rest are
    /// summed up in one "… and N more" diagnostic.
    #[arg(long)]
    pub max_per_code: Option<usize>,
    /// Diagnostics reported per file (default 20000).
    #[arg(long)]
    pub max_per_file: Option<usize>,
    /// Runtime errors the dry run reports and recovers from per file before it
    /// stops (default 100, `[rules] max_runtime_errors`).
    #[arg(long)]
    pub max_runtime_errors: Option<usize>,
    /// Largest program to read, in MB (default: no limit); a larger file gets
    /// one located error (L000) and exit status 2. Programs above 32 MB are
    /// read in windows of 4 MB, so memory does not grow with the file.
    #[arg(long)]
    pub max_file_size: Option<u64>,
    /// Read every program in windows of this many bytes (tests compare it
    /// with the whole-file check).
    #[arg(long, hide = true)]
    pub window_bytes: Option<usize>,
}

#[derive(Subcommand)]
enum Command {
    /// Lint part programs.
    Check(CheckArgs),
    /// Dry-run a program: cycle time, breakdown, toolpath.
    Run(run::RunArgs),
    /// Explain a rule (`partscope rule G001`), or list all rules (`--all`).
    Rule {
        code: Option<String>,
        #[arg(long)]
        all: bool,
        /// Print as JSON (code, name, summary, origin, default, implements, doc).
        #[arg(long)]
        json: bool,
    },
    /// Run the language server on stdio.
    Lsp,
}

pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    match cli.command {
        Command::Check(args) => check::run(args),
        Command::Run(args) => run::run(args),
        Command::Rule { code, all, json } => rule(code, all, json),
        Command::Lsp => crate::lsp::run(),
    }
}

fn rule(code: Option<String>, all: bool, json: bool) -> ExitCode {
    let rules = crate::rules::all();
    let text = if json {
        let pick: Vec<_> = rules
            .iter()
            .filter(|r| {
                all || code.as_deref().is_none_or(|c| {
                    r.code.eq_ignore_ascii_case(c) || r.name.eq_ignore_ascii_case(c)
                })
            })
            .map(|r| {
                serde_json::json!({
                    "code": r.code, "name": r.name, "summary": r.summary,
                    "origin": format!("{:?}", r.origin).to_ascii_lowercase(),
                    "default_enabled": r.default_enabled, "implements": r.implements,
                    "doc": crate::rules::clean_doc(r.doc),
                })
            })
            .collect();
        format!("{}\n", serde_json::Value::Array(pick))
    } else if all || code.is_none() {
        let mut text = String::new();
        for r in &rules {
            let off = if r.default_enabled {
                ""
            } else {
                " (off by default)"
            };
            text.push_str(&format!(
                "{:<6} {:<36} {}{}\n",
                r.code, r.name, r.summary, off
            ));
        }
        text
    } else {
        let code = code.unwrap_or_default();
        match crate::rules::lookup(&code) {
            Some(r) => format!(
                "# {} {}\n\n{}\n\n{}\n",
                r.code,
                r.name,
                r.summary,
                crate::rules::clean_doc(r.doc)
            ),
            None => {
                eprintln!("partscope: unknown rule `{code}` (see `partscope rule --all`)");
                return ExitCode::from(2);
            }
        }
    };
    print_out(&text)
}

/// Writes `text` to standard output (see [`write_failure`]).
fn print_out(text: &str) -> ExitCode {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => write_failure(&e).unwrap_or(ExitCode::SUCCESS),
    }
}

/// What a command does when its output cannot be written: a reader that stops
/// early (`partscope rule --all | head`, `check … | head`) closes the pipe,
/// which ends the output and is no failure, so `None` (the command exits with
/// the status its findings give); any other error is reported, exit status 2.
pub(crate) fn write_failure(e: &std::io::Error) -> Option<ExitCode> {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        return None;
    }
    eprintln!("partscope: cannot write the output: {e}");
    Some(ExitCode::from(2))
}
