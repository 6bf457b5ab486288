//! `bumpview check`: what in a mesh file (or a normal-map image) breaks bump mapping.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use bumpview::atomic::check_outputs;
use bumpview::check::{CheckReport, Severity, check_scene};
use bumpview::error::escape_controls;
use bumpview::load::{is_image_path, load_model, texture_scene};
use bumpview::render::capture::write_png_atomically;
use bumpview::scene::Scene;
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
    /// Write each normal map's green votes as a PNG heat map over the map into DIR (made when
    /// missing): `<file stem>.<k>.<slot>.votes.png` for the k-th map (slot `normal` or
    /// `clearcoat`); blue tiles vote OpenGL, orange DirectX, the stronger the more opaque.
    #[arg(long, value_name = "DIR")]
    explain: Option<PathBuf>,
    /// With --explain: replace pictures that exist (an input is never written over).
    #[arg(long, requires = "explain")]
    force: bool,
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
                let scene = overrides.applied_to(&scene);
                let mut report = check_scene(&scene);
                if args.normal_layout.is_some() {
                    report.normal_maps.iter_mut().for_each(|m| m.layout_reason = "given by --normal-layout".into());
                }
                // Names and paths in it come from the files.
                report.to_text().lines().for_each(|line| println!("{}", escape_controls(line)));
                let explained = match &args.explain {
                    Some(dir) => write_votes(path, &scene, &report, dir, args.force),
                    None => Severity::Clean,
                };
                report.severity().max(explained)
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

/// Writes the votes picture of each map of `report` (checked from `input`) into `dir`, naming
/// each; a refused or failed write is an error line (exit 2), and nothing of this file is
/// written when any output is refused.
fn write_votes(input: &Path, scene: &Scene, report: &CheckReport, dir: &Path, force: bool) -> Severity {
    let stem = input.file_stem().map_or_else(|| "map".into(), |s| s.to_string_lossy().into_owned());
    let outputs: Vec<PathBuf> = report
        .normal_maps
        .iter()
        .enumerate()
        .map(|(k, map)| dir.join(format!("{stem}.{}.{}.votes.png", k + 1, map.slot.file_name())))
        .collect();
    let planned: Vec<&Path> = outputs.iter().map(PathBuf::as_path).collect();
    let failure = std::fs::create_dir_all(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))
        .and_then(|()| check_outputs(&[input], &planned, force).map_err(|e| e.to_string()));
    if let Err(message) = failure {
        println!("  error: {}", escape_controls(&message));
        return Severity::Error;
    }
    for (map, output) in report.normal_maps.iter().zip(&outputs) {
        let written = map.votes_picture(scene).map(|picture| write_png_atomically(&picture, output));
        match written {
            Some(Ok(())) => println!(
                "    votes of {}: {}",
                escape_controls(&map.name()),
                escape_controls(&output.display().to_string())
            ),
            Some(Err(e)) => {
                println!("  error: {}", escape_controls(&e.to_string()));
                return Severity::Error;
            }
            None => {}
        }
    }
    Severity::Clean
}
