//! The command line: `bumpview [MESH] [flags]` opens the viewer; `render`, `report`, `bake`,
//! `check`, `lessons` and `slides` work without a window. Flags are read once into the
//! library's values: files into a [`bumpview::load::SceneFiles`], picture and method flags into viewer
//! [`bumpview::state::Command`]s, enum values by their derived names ([`args::named`]).

pub mod args;
mod bake;
mod bake_compressed;
mod bake_cone;
mod bake_detail;
mod check;
mod inputs;
mod lessons;
mod lights;
mod methods;
mod picture;
mod progress;
mod render;
mod report;
mod start;
#[cfg(feature = "ui")]
mod viewer;

use std::path::PathBuf;
use std::process::ExitCode;

use bumpview::error::{PresetError, PresetSceneError, RenderError, escape_controls};
use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "bumpview", version, about = "A viewer and teaching tool for bump and normal mapping")]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Viewer: close after this many frames have been presented with the scene shown (frames
    /// drawn while a scene is still being prepared do not count; for tests and CI).
    #[arg(long, value_name = "FRAMES")]
    exit_after: Option<u64>,
    /// Viewer: with --exit-after, save a screenshot of the whole window (UI included) here first.
    #[arg(long, value_name = "PATH", requires = "exit_after")]
    capture_window: Option<PathBuf>,
    /// Viewer: pin the pixel probe at this pixel of the 3D view (from its top-left corner) as
    /// soon as the view is laid out, as P + click there would.
    #[arg(long, value_name = "X,Y", value_parser = args::parse_pixel)]
    probe: Option<[u32; 2]>,
    /// Viewer: start from this preset (files and flags given as well override it). Without
    /// it, files or flags, the viewer restores the state it had when it last closed.
    #[arg(long, value_name = "FILE")]
    preset: Option<PathBuf>,
    /// Viewer: open this lesson file (yours or one of assets/lessons/) with its caption card,
    /// as the Lessons section opens a built-in one; its paths are relative to it.
    #[arg(long, value_name = "FILE", conflicts_with = "preset")]
    lesson: Option<PathBuf>,
    #[command(flatten)]
    methods: methods::MethodArgs,
    #[command(flatten)]
    picture: picture::PictureArgs,
    #[command(flatten)]
    inputs: inputs::InputArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Draw the built-in scene or a mesh file offscreen (no window, no display) and write a PNG.
    Render(Box<render::RenderArgs>),
    /// Measure error against run time of every tangent method and height kernel and write
    /// report.md, report.csv and PNG charts.
    Report(report::ReportArgs),
    /// Height maps to tangent-space normal map PNGs, or normal maps back to height maps
    /// (--to-height), files in parallel. Exit 1 when a file failed, 2 for a bad flag or value.
    Bake(Box<bake::BakeArgs>),
    /// Check mesh files for what breaks bump mapping (degenerate or mirrored UVs, seams, bad
    /// tangents, normal-map sanity and green convention). Exit 0 clean, 1 warnings, 2 errors.
    Check(check::CheckArgs),
    /// List the built-in lessons: name, title and the caption's first sentence.
    Lessons,
    /// Draw lessons as 16:9 slide PNGs with their measured numbers, one PDF of them all and an
    /// index.md.
    Slides(lessons::SlidesArgs),
}

/// Why a command failed: its arguments (exit status 2, as for flags clap rejects) or the
/// work itself (exit status 1). Either is one line on stderr, control characters escaped
/// ([`escape_controls`]: the message may quote text from files).
pub enum Failure {
    BadArguments(String),
    Failed(String),
}

impl From<PresetError> for Failure {
    fn from(error: PresetError) -> Self {
        Failure::Failed(error.to_string())
    }
}

impl From<PresetSceneError> for Failure {
    fn from(error: PresetSceneError) -> Self {
        Failure::Failed(error.to_string())
    }
}

impl From<RenderError> for Failure {
    fn from(error: RenderError) -> Self {
        Failure::Failed(error.to_string())
    }
}

/// Runs what the command line asks and returns the exit status: 0 done, 1 the work failed,
/// 2 bad arguments (`check` has its own statuses).
pub fn run(mut cli: Cli) -> ExitCode {
    let result = match cli.command.take() {
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Report(args)) => report::run(&args),
        Some(Command::Bake(args)) => bake::run(&args),
        Some(Command::Check(args)) => return check::run(&args),
        Some(Command::Lessons) => lessons::list(),
        Some(Command::Slides(args)) => lessons::slides(&args),
        None => viewer(&cli),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::BadArguments(message)) => {
            eprintln!("bumpview: {}", escape_controls(&message));
            ExitCode::from(2)
        }
        Err(Failure::Failed(message)) => {
            eprintln!("bumpview: {}", escape_controls(&message));
            ExitCode::FAILURE
        }
    }
}

#[cfg(feature = "ui")]
fn viewer(cli: &Cli) -> Result<(), Failure> {
    viewer::run(cli)
}

#[cfg(not(feature = "ui"))]
fn viewer(_cli: &Cli) -> Result<(), Failure> {
    Err(Failure::Failed("this build has no viewer (built without the `ui` feature); use `bumpview render`".into()))
}
