//! The files to show, given on the command line: a mesh and textures for its material slots
//! (shared by the viewer and `render`).

use std::path::PathBuf;

use bumpview::state::preset::PresetFiles;

#[derive(clap::Args, Clone, Debug, Default)]
pub struct InputArgs {
    /// A glTF 2.0 (.gltf, .glb) or OBJ (.obj) file; without one, the built-in scene.
    #[arg(value_name = "MESH")]
    pub mesh: Option<PathBuf>,
    /// Colour texture (sRGB) for every material; PNG, JPEG, TGA or BMP.
    #[arg(long, value_name = "FILE")]
    pub color: Option<PathBuf>,
    /// Tangent-space normal map (OpenGL convention, +Y up) for every material.
    #[arg(long, value_name = "FILE")]
    pub normal: Option<PathBuf>,
    /// Height map (white = high) for every material; it also becomes the normal map unless
    /// --normal is given.
    #[arg(long, value_name = "FILE")]
    pub height: Option<PathBuf>,
    /// Gloss/specular map for every material (kept with it; not yet shaded).
    #[arg(long, value_name = "FILE")]
    pub gloss: Option<PathBuf>,
}

impl InputArgs {
    /// Whether no file was given.
    pub fn is_empty(&self) -> bool {
        self.mesh.is_none()
            && self.color.is_none()
            && self.normal.is_none()
            && self.height.is_none()
            && self.gloss.is_none()
    }

    /// The files given here over `files` (a preset's), slot by slot.
    pub fn over(&self, files: PresetFiles) -> PresetFiles {
        let pick = |given: &Option<PathBuf>, preset: Option<PathBuf>| given.clone().or(preset);
        PresetFiles {
            mesh: pick(&self.mesh, files.mesh),
            color: pick(&self.color, files.color),
            normal: pick(&self.normal, files.normal),
            height: pick(&self.height, files.height),
            gloss: pick(&self.gloss, files.gloss),
        }
    }

    /// The same files as command-line arguments.
    #[cfg(feature = "ui")]
    pub fn from_files(files: &PresetFiles) -> InputArgs {
        InputArgs {
            mesh: files.mesh.clone(),
            color: files.color.clone(),
            normal: files.normal.clone(),
            height: files.height.clone(),
            gloss: files.gloss.clone(),
        }
    }
}
