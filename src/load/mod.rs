//! Loading scenes and textures from files: glTF 2.0 ([`gltf`]), OBJ + MTL ([`obj`]) and
//! images ([`image`]). Every loader stores data in the crate conventions (UVs with `v` down the
//! image, CCW front faces, unit normals) and returns a [`LoadError`] naming the file and the
//! problem; none panics on any input.

mod accessor;
mod accessor_rules;
mod budget;
mod draco;
mod files;
mod framing;
pub mod gltf;
mod gltf_document;
mod gltf_mesh;
pub mod image;
mod mesh_ops;
mod meshopt;
mod mtl;
pub mod obj;
mod uri;

use std::path::Path;

pub use crate::error::LoadError;
use glam::Vec3;

use crate::read::FileKind;
use crate::scene::Scene;
pub use files::{
    SceneFiles, TextureSlot, add_height_map, is_image_path, load_model, replace_textures, texture_scene,
    xray_pair_beside,
};
pub use framing::{bounds, frame_scene};

/// Loads a mesh file into a [`Scene`] with a camera framing it and a light above and in
/// front, choosing the loader by the extension (`.gltf`, `.glb`, `.obj`; any case).
pub fn load_scene(path: &Path) -> Result<Scene, LoadError> {
    let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let mut scene = match extension.as_deref() {
        Some("gltf" | "glb") => gltf::load(path)?,
        Some("obj") => obj::load(path)?,
        _ => return Err(LoadError::new(path, "unsupported mesh file type (expected .gltf, .glb or .obj)")),
    };
    if scene.instances.is_empty() {
        return Err(LoadError::new(path, "the file holds no triangles to draw"));
    }
    frame_scene(&mut scene);
    Ok(scene)
}

/// The bytes of `path` read as `kind` ([`crate::read::read_file`]: regular files only, up to
/// the kind's cap); `what` says what the file is for in the error ("image", "glTF"...).
fn read_file(path: &Path, kind: FileKind, what: &str) -> Result<Vec<u8>, LoadError> {
    crate::read::read_file(path, kind).map_err(|e| LoadError::new(path, format!("could not read the {what} file: {e}")))
}

/// A scene without content; [`frame_scene`] sets its view.
fn empty_scene() -> Scene {
    Scene {
        meshes: vec![],
        materials: vec![],
        textures: vec![],
        instances: vec![],
        ambient: Vec3::ZERO,
        default_light: crate::scene::builtin::default_light(),
        default_camera: crate::scene::builtin::default_camera(),
        files: vec![],
        warnings: vec![],
    }
}
