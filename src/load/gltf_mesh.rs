//! One glTF mesh primitive → [`Mesh`]: triangles (lists, strips and fans), the chosen UV set
//! with its `KHR_texture_transform` applied, flat normals when the file has none.

use std::path::Path;

use glam::{Vec2, Vec3, Vec4};
use gltf::json::Value;
use gltf::mesh::{Mode, Semantic};

use super::mesh_ops::{check, transform_uvs, with_flat_normals};
use crate::error::LoadError;
use crate::math::normalize_or;
use crate::scene::Mesh;

/// Which `TEXCOORD_n` a mesh takes and the `KHR_texture_transform` applied to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvChoice {
    pub set: u32,
    pub offset: Vec2,
    /// Radians, counter-clockwise in the image.
    pub rotation: f32,
    pub scale: Vec2,
}

impl Default for UvChoice {
    fn default() -> Self {
        UvChoice { set: 0, offset: Vec2::ZERO, rotation: 0.0, scale: Vec2::ONE }
    }
}

impl UvChoice {
    /// From a texture reference's `texCoord` and its `KHR_texture_transform` object, if any
    /// (whose own `texCoord` overrides the reference's).
    pub fn from_json(tex_coord: u32, transform: Option<&Value>) -> UvChoice {
        let Some(t) = transform else { return UvChoice { set: tex_coord, ..Default::default() } };
        let pair = |key: &str, default: Vec2| match t.get(key).and_then(Value::as_array).map(Vec::as_slice) {
            Some([x, y]) => Vec2::new(x.as_f64().unwrap_or(0.0) as f32, y.as_f64().unwrap_or(0.0) as f32),
            _ => default,
        };
        UvChoice {
            set: t.get("texCoord").and_then(Value::as_u64).map_or(tex_coord, |s| s.min(u32::MAX as u64) as u32),
            offset: pair("offset", Vec2::ZERO),
            rotation: t.get("rotation").and_then(Value::as_f64).unwrap_or(0.0) as f32,
            scale: pair("scale", Vec2::ONE),
        }
    }
}

/// The primitive as a triangle mesh, or `None` for points and lines.
pub fn primitive_mesh(
    primitive: &gltf::Primitive,
    name: &str,
    uv: UvChoice,
    buffers: &[Vec<u8>],
    path: &Path,
) -> Result<Option<Mesh>, LoadError> {
    if !matches!(primitive.mode(), Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
        return Ok(None);
    }
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    // An attribute the primitive names but whose data cannot be read is an error.
    let unreadable = |semantic: Semantic| {
        let accessor = primitive.get(&semantic).map_or(0, |a| a.index());
        LoadError::new(path, format!("{name}: accessor {accessor} ({semantic:?}) lies outside its buffer"))
    };
    let mut mesh = Mesh::empty(name);
    mesh.positions = match reader.read_positions() {
        Some(p) => p.map(Vec3::from).collect(),
        None if primitive.get(&Semantic::Positions).is_some() => return Err(unreadable(Semantic::Positions)),
        None => return Err(LoadError::new(path, format!("{name}: a primitive has no POSITION attribute"))),
    };
    let has = |semantic: Semantic| primitive.get(&semantic).is_some();
    mesh.normals = match reader.read_normals() {
        Some(n) => n.map(Vec3::from).collect(),
        None if has(Semantic::Normals) => return Err(unreadable(Semantic::Normals)),
        None => vec![],
    };
    mesh.uvs = match reader.read_tex_coords(uv.set) {
        Some(t) => t.into_f32().map(Vec2::from).collect(),
        None if has(Semantic::TexCoords(uv.set)) => return Err(unreadable(Semantic::TexCoords(uv.set))),
        None => vec![],
    };
    transform_uvs(&mut mesh.uvs, uv.offset, uv.rotation, uv.scale);
    mesh.tangents = match reader.read_tangents() {
        Some(t) => Some(t.map(Vec4::from).collect()),
        None if has(Semantic::Tangents) => return Err(unreadable(Semantic::Tangents)),
        None => None,
    };
    let list: Vec<u32> = match reader.read_indices() {
        Some(i) => i.into_u32().collect(),
        None if primitive.indices().is_some() => {
            return Err(LoadError::new(path, format!("{name}: the index accessor lies outside its buffer")));
        }
        None => (0..mesh.positions.len() as u32).collect(),
    };
    mesh.indices = triangle_list(primitive.mode(), &list);
    let count = mesh.positions.len();
    let lengths = [mesh.normals.len(), mesh.uvs.len(), mesh.tangents.as_ref().map_or(0, Vec::len)];
    if lengths.iter().any(|&l| l != 0 && l != count) {
        return Err(LoadError::new(path, format!("{name}: attributes have different vertex counts")));
    }
    check(&mesh, path)?;
    if mesh.normals.is_empty() {
        mesh = with_flat_normals(&mesh);
    }
    mesh.normals.iter_mut().for_each(|n| *n = normalize_or(*n, Vec3::Z));
    Ok(Some(mesh))
}

/// Triangle-list indices from glTF's list, strip or fan, each triangle counter-clockwise.
fn triangle_list(mode: Mode, indices: &[u32]) -> Vec<u32> {
    match mode {
        Mode::TriangleStrip => (0..indices.len().saturating_sub(2))
            .flat_map(|i| {
                let [a, b, c] = [indices[i], indices[i + 1], indices[i + 2]];
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => {
            (1..indices.len().saturating_sub(1)).flat_map(|i| [indices[0], indices[i], indices[i + 1]]).collect()
        }
        _ => indices[..indices.len() / 3 * 3].to_vec(),
    }
}
