//! `bumpview check`: what in a mesh file (or a normal-map image) breaks bump mapping.

use std::path::PathBuf;
use std::process::ExitCode;

use bumpview::check::{Severity, check_scene};
use bumpview::error::escape_controls;
use bumpview::load::{is_image_path, load_model, texture_scene};
use bumpview::scene::{MaterialOverrides, NormalLayout};

use super::args;

#[derive(clap::Args)]
pub struct CheckArgs {
    /// glTF (.gltf, .glb) or OBJ files, or images: a colour texture NAME.* with X-Ray's
    /// NAME_bump.* (and NAME_bump#.*) beside it is checked as that pair, any other image as a
    /// normal map.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Check the normal maps in this channel layout (rgb, rg, ag, xray) instead of the one
    /// they load with.
    #[arg(long, value_parser = args::named::<NormalLayout>())]
    normal_layout: Option<NormalLayout>,
    /// Let the meshes read files outside their folders (an absolute path, `..`, or a
    /// symbolic link leading out); without it such a file is refused, named.
    #[arg(long)]
    allow_outside_files: bool,
}

/// Prints a check report per file; the exit status is the worst finding (a file that does
/// not load is an error): 0 clean, 1 warnings, 2 errors.
pub fn run(args: &CheckArgs) -> ExitCode {
    let mut worst = Severity::Clean;
    for path in &args.files {
        println!("{}", escape_controls(&path.display().to_string()));
        let loaded = if is_image_path(path) { texture_scene(path) } else { load_model(path, args.allow_outside_files) };
        let severity = match loaded {
            Ok(scene) => {
                let overrides = MaterialOverrides { layout: args.normal_layout, ..Default::default() };
                let mut report = check_scene(&overrides.applied_to(&scene));
                if args.normal_layout.is_some() {
                    report.normal_maps.iter_mut().for_each(|m| m.layout_reason = "given by --normal-layout".into());
                }
                // Names and paths in it come from the files.
                report.to_text().lines().for_each(|line| println!("{}", escape_controls(line)));
                report.severity()
            }
            Err(e) => {
                println!("  error: {}", escape_controls(&e.to_string()));
                Severity::Error
            }
        };
        worst = worst.max(severity);
    }
    ExitCode::from(worst.exit_code())
}
