//! `sky-train`: render, sample and benchmark the sky models from the command line.

use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser;
use sky_train::args::ParamError;
use sky_train::cli::{self, Cli};

fn main() -> ExitCode {
    // A write cut short by Ctrl-C or a kill leaves no hidden temporary file behind (when the
    // handlers cannot be installed, the next run's sweep removes what a signal left).
    let _ = sky_train::output_path::remove_temporaries_on_signals();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // One line: clap's first paragraph (what is wrong, and with which argument), without
            // the usage block that follows.
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            eprintln!("{}", first.join(" "));
            return ExitCode::from(2);
        }
    };
    let stdin = io::stdin();
    let stdout = io::stdout();
    let result = cli::execute(cli.command, &mut stdin.lock(), &mut stdout.lock());
    let _ = io::stdout().flush();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One line, whatever the causes' own layout (a TOML error spans several).
            let text = format!("{e:#}");
            let lines: Vec<&str> = text
                .lines()
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .collect();
            eprintln!("error: {}", lines.join(" "));
            // Bad input anywhere in the chain is bad input, whatever context was added.
            let bad_input = e.chain().any(|c| c.is::<ParamError>());
            ExitCode::from(if bad_input { 2 } else { 1 })
        }
    }
}
