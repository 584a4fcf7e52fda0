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
    let mut stdout = cli::Stdout::new(io::stdout().lock());
    let mut result = cli::execute(cli.command, &mut stdin.lock(), &mut stdout);
    // A command that met a write error and went on (its work done, only its report lost)
    // has said so; the flush's retry of that report is not a new failure.
    let reported = stdout.error().is_some();
    if result.is_ok()
        && let Err(e) = stdout.flush()
        && !reported
    {
        result = Err(e.into());
    }
    // A failed write to stdout, whatever the command made of it: a reader that went away
    // (`| head -1`) ends the program quietly with status 0, as ripgrep does; any other failure
    // (a full disk, /dev/full) is named as stdout's, status 1.
    // (A command that finished its work and only failed to report it has returned Ok.)
    if let (Err(_), Some(e)) = (&result, stdout.error()) {
        if e.kind() == io::ErrorKind::BrokenPipe {
            return ExitCode::SUCCESS;
        }
        eprintln!("error: cannot write to stdout: {e}");
        return ExitCode::from(1);
    }
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
