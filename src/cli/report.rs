//! `bumpview report`: error against run time of every tangent method and height kernel.

use std::path::PathBuf;

use super::Failure;

#[derive(clap::Args)]
pub struct ReportArgs {
    /// Directory for report.md, report.csv and the charts (created if missing).
    #[arg(long, default_value = "report")]
    out: PathBuf,
    /// Fewer resolutions and runs, for tests and CI.
    #[arg(long)]
    quick: bool,
}

/// Runs the measurements and writes the report; says what it wrote and how long it took.
pub fn run(args: &ReportArgs) -> Result<(), Failure> {
    let started = std::time::Instant::now();
    let plan = if args.quick { bumpview::report::Plan::quick() } else { bumpview::report::Plan::full() };
    let files = bumpview::report::run(&args.out, &plan).map_err(|e| Failure::Failed(e.to_string()))?;
    let names: Vec<_> = files.iter().map(|f| f.display().to_string()).collect();
    println!("wrote {} in {:.1} s", names.join(", "), started.elapsed().as_secs_f64());
    Ok(())
}
