//! The `bumpview` command: the viewer ([`app`], the default) and the command line ([`cli`]:
//! `render`, `report`, `bake`, `check`). In the web build (wasm32) only the viewer, started by
//! eframe's web runner in the page's canvas (docs/web.md).

#[cfg(feature = "ui")]
mod app;
#[cfg(not(target_arch = "wasm32"))]
mod cli;

#[cfg(not(target_arch = "wasm32"))]
use std::process::ExitCode;

#[cfg(not(target_arch = "wasm32"))]
use clap::Parser;

/// The web build's start: wasm-bindgen's start-up calls `main`, which hands the page's canvas to
/// the viewer and returns; the viewer then runs on the browser's frames.
#[cfg(all(target_arch = "wasm32", feature = "ui"))]
fn main() {
    app::web::start();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> ExitCode {
    match cli::Cli::try_parse() {
        Ok(cli) => cli::run(cli),
        Err(e) if !e.use_stderr() => {
            // --help and --version.
            let _ = e.print();
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bumpview: {}", whole_message(&e.to_string()));
            ExitCode::from(2)
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
/// clap's message for a bad command line, whole: what is wrong and what is allowed (the
/// missing flags, the ones it conflicts with, the possible values, the usage line), without its
/// `error: ` prefix and closing pointer to `--help`, so it starts on the `bumpview:` line.
fn whole_message(message: &str) -> String {
    let message = message.trim_start_matches("error: ");
    let lines: Vec<&str> = message.lines().filter(|l| !l.starts_with("For more information, try")).collect();
    lines.join("\n").trim_end().to_owned()
}
