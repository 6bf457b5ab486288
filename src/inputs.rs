//! The files to show, given on the command line: a mesh and textures for its material slots
//! (shared by the viewer and `render`).

use std::path::PathBuf;

use bumpview::height::Kernel;
use bumpview::load::{TextureSlots, load_scene, replace_textures};
use bumpview::scene::Scene;
use bumpview::scene::builtin::teaching_scene_with_kernel;

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
    /// The loaded scene with the given textures in its slots (a texture without a mesh goes
    /// on the built-in scene made with `kernel`), or `None` when no file was given. The
    /// error is the loader's one-line message.
    pub fn scene(&self, kernel: Kernel) -> Result<Option<Scene>, String> {
        let slots = TextureSlots {
            color: self.color.clone(),
            normal: self.normal.clone(),
            height: self.height.clone(),
            gloss: self.gloss.clone(),
        };
        let mut scene = match &self.mesh {
            Some(path) => load_scene(path).map_err(|e| e.to_string())?,
            None if slots.is_empty() => return Ok(None),
            None => teaching_scene_with_kernel(kernel),
        };
        replace_textures(&mut scene, &slots).map_err(|e| e.to_string())?;
        Ok(Some(scene))
    }
}
