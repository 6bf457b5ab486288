//! `bumpview check`: what in a mesh file breaks bump mapping.

use std::path::PathBuf;
use std::process::ExitCode;

use bumpview::check::{Severity, check_scene};
use bumpview::load::load_scene;

#[derive(clap::Args)]
pub struct CheckArgs {
    /// glTF (.gltf, .glb) or OBJ files.
    #[arg(required = true)]
    files: Vec<PathBuf>,
}

/// Prints a check report per file; the exit status is the worst finding (a file that does
/// not load is an error): 0 clean, 1 warnings, 2 errors.
pub fn run(args: &CheckArgs) -> ExitCode {
    let mut worst = Severity::Clean;
    for path in &args.files {
        println!("{}", path.display());
        let severity = match load_scene(path) {
            Ok(scene) => {
                let report = check_scene(&scene);
                print!("{}", report.to_text());
                report.severity()
            }
            Err(e) => {
                println!("  error: {e}");
                Severity::Error
            }
        };
        worst = worst.max(severity);
    }
    ExitCode::from(worst.exit_code())
}
