//! The `bumpview` command: the viewer ([`app`], the default) and the command line ([`cli`]:
//! `render`, `report`, `check`).

#[cfg(feature = "ui")]
mod app;
mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    match cli::Cli::try_parse() {
        Ok(cli) => cli::run(cli),
        Err(e) if !e.use_stderr() => {
            // --help and --version.
            let _ = e.print();
            ExitCode::SUCCESS
        }
        Err(e) => {
            // One line: the first line of clap's message names the bad flag or value.
            let message = e.to_string();
            eprintln!("bumpview: {}", message.lines().next().unwrap_or("bad arguments").trim_start_matches("error: "));
            ExitCode::from(2)
        }
    }
}
