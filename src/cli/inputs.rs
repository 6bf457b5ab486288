//! The files to show, given on the command line: a mesh and textures for its material slots
//! (shared by the viewer and `render`), read once into the library's [`SceneFiles`].

use std::path::PathBuf;

use bumpview::load::SceneFiles;

/// The command line's face of [`SceneFiles`]: the same six files and permission, with their help.
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
    /// Gloss (Blinn-Phong specular) map for every material: linear RGB multiplying the
    /// highlight, black matte, white full.
    #[arg(long, value_name = "FILE")]
    pub gloss: Option<PathBuf>,
    /// Detail normal map (tangent space, OpenGL convention) tiled over every material's normal
    /// map; its tiling, strength and blend: --detail-tiling, --detail-strength, --detail-blend.
    #[arg(long, value_name = "FILE")]
    pub detail: Option<PathBuf>,
    /// Let the mesh read files outside its folder (buffers, textures and material libraries
    /// named by an absolute path, through `..`, or by a symbolic link leading out); without
    /// it (or a preset's `allow_outside_files = true` in [files]) such a file is refused.
    #[arg(long)]
    pub allow_outside_files: bool,
}

impl InputArgs {
    /// The files given.
    pub fn files(&self) -> SceneFiles {
        let InputArgs { mesh, color, normal, height, gloss, detail, allow_outside_files } = self.clone();
        SceneFiles { mesh, color, normal, height, gloss, detail, builtin: None, allow_outside_files }
    }
}
