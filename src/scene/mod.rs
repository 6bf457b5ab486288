//! Scene data as plain arrays: meshes, materials, textures, instances, light and camera.
//! Conventions (UV origin, tangent handedness, colour spaces) are in the crate docs.

pub mod bricks;
pub mod builtin;
pub mod camera;
pub mod detail;
pub mod light;
pub mod material;
pub mod overrides;
pub mod sample;
pub mod teaching;

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::error::LoadWarning;

pub use camera::OrbitCamera;
pub use detail::{DEFAULT_DETAIL_TILING, DetailBlend, DetailMap, sine_pair_normal_map};
pub use light::{Attenuation, Light, LightKind, Lights, LightsError, MAX_LIGHTS, SpecularMode};
pub use material::{
    Clearcoat, GreenAxis, HeightMap, Material, NormalConvention, NormalLayout, NormalMap, NormalSpace, Occlusion,
    SamplerWrap, ShadingModel, Wrap, stored_layout,
};
pub use overrides::{MaterialOverrides, PerMaterialOverrides};
// Images are plain data below scene and height (see [`crate::texture`]); scenes hold them.
pub use crate::texture::{TextureImage, TextureKind, decode_height, encode_height};

/// Indexed triangle mesh in its own (model) space.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub name: String,
    /// Positions in metres, model space.
    pub positions: Vec<Vec3>,
    /// Unit normals, model space.
    pub normals: Vec<Vec3>,
    /// Texture coordinates, origin top-left, v down (crate conventions).
    pub uvs: Vec<Vec2>,
    /// MikkTSpace-style tangents `(T.xyz, w)` supplied with the mesh (e.g. by the file),
    /// model space; `None` when it supplies none.
    pub tangents: Option<Vec<Vec4>>,
    /// The exact frame of a parametric surface (built-in meshes), same form as `tangents`.
    pub analytic_tangents: Option<Vec<Vec4>>,
    /// Three indices per triangle, counter-clockwise front faces.
    pub indices: Vec<u32>,
}

/// One placed mesh: indices into [`Scene::meshes`] and [`Scene::materials`], and its
/// model→world transform.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    pub mesh: usize,
    pub material: usize,
    pub transform: Mat4,
}

/// Everything the renderer draws.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    /// The images, shared: a copy of the scene (the material overrides make one) shares them
    /// instead of copying every texel.
    pub textures: Vec<std::sync::Arc<TextureImage>>,
    pub instances: Vec<Instance>,
    /// Linear RGB ambient light, multiplied by the albedo (Blinn-Phong; metallic-roughness
    /// materials take their ambient light from the procedural sky instead).
    pub ambient: Vec3,
    /// The light a new view starts with (alone: see [`Scene::default_lights`]).
    pub default_light: Light,
    /// The camera a new view starts with and that "reset camera" returns to.
    pub default_camera: OrbitCamera,
    /// The files the mesh file referred to and that were read (buffers, material libraries,
    /// textures; wherever they are), for hot reload. Empty for the built-in scene.
    pub files: Vec<std::path::PathBuf>,
    /// What the loader could not read or honour (the scene opened without it).
    pub warnings: Vec<LoadWarning>,
}

impl Scene {
    /// The lights a new view starts with: the default light alone, with the scene's ambient.
    pub fn default_lights(&self) -> Lights {
        Lights::one(self.default_light, self.ambient)
    }
}

impl Mesh {
    /// A mesh without positions or attributes, to be filled.
    pub fn empty(name: &str) -> Mesh {
        Mesh {
            name: name.to_owned(),
            positions: vec![],
            normals: vec![],
            uvs: vec![],
            tangents: None,
            analytic_tangents: None,
            indices: vec![],
        }
    }

    /// The same triangles with one vertex per corner (no vertex shared between triangles),
    /// so that per-face attributes can be drawn.
    /// Attributes shorter than `positions` read as zero there; tangent arrays of the wrong
    /// length are dropped.
    pub fn unwelded(&self) -> Mesh {
        fn gather<T: Copy + Default>(values: &[T], indices: &[u32]) -> Vec<T> {
            indices.iter().map(|&i| values.get(i as usize).copied().unwrap_or_default()).collect()
        }
        let frames = |values: &Option<Vec<Vec4>>| {
            values.as_ref().filter(|v| v.len() == self.positions.len()).map(|v| gather(v, &self.indices))
        };
        Mesh {
            name: self.name.clone(),
            positions: gather(&self.positions, &self.indices),
            normals: gather(&self.normals, &self.indices),
            uvs: gather(&self.uvs, &self.indices),
            tangents: frames(&self.tangents),
            analytic_tangents: frames(&self.analytic_tangents),
            indices: (0..self.indices.len() as u32).collect(),
        }
    }
}
