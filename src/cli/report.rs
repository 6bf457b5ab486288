//! `bumpview report`: error against run time of every tangent method and height kernel, and
//! of the parallax family against displacement.

use std::path::PathBuf;

use super::{Failure, progress};

#[derive(clap::Args)]
pub struct ReportArgs {
    /// Directory for report.md, report.csv and the charts (created if missing).
    #[arg(long, default_value = "report")]
    out: PathBuf,
    /// Fewer resolutions and runs, for tests and CI (the parallax study: the wall alone at 0°
    /// and 70°, 8 and 32 layers, 320x180).
    #[arg(long)]
    quick: bool,
    /// The shared assets folder holding textures/ambientCG_Rock058 for the parallax and compression studies
    /// [default: $BUMPVIEW_TEST_ASSETS; without either the rock is left out].
    #[arg(long, value_name = "DIR")]
    assets: Option<PathBuf>,
}

/// Runs the measurements (a progress bar on a terminal) and writes the report; says what it
/// wrote and how long it took.
pub fn run(args: &ReportArgs) -> Result<(), Failure> {
    if std::fs::symlink_metadata(&args.out).is_ok() && !args.out.is_dir() {
        let out = args.out.display();
        return Err(Failure::BadArguments(format!(
            "--out {out}: is not a directory: the report writes its files into one"
        )));
    }
    let started = std::time::Instant::now();
    let mut plan = if args.quick { bumpview::report::Plan::quick() } else { bumpview::report::Plan::full() };
    if !args.quick {
        plan.parallax.assets =
            args.assets.clone().or_else(|| std::env::var_os("BUMPVIEW_TEST_ASSETS").map(PathBuf::from));
        plan.compression.assets = plan.parallax.assets.clone();
    }
    let bar = progress::bar(0, "report");
    let files = bumpview::report::run(&args.out, &plan, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let files = files.map_err(|e| Failure::Failed(e.to_string()))?;
    let names: Vec<_> = files.iter().map(|f| f.display().to_string()).collect();
    println!("wrote {} in {:.1} s", names.join(", "), started.elapsed().as_secs_f64());
    Ok(())
}
