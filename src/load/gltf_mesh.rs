//! One glTF mesh primitive → [`Mesh`]: triangles (lists, strips and fans), the chosen UV set
//! with its `KHR_texture_transform` applied, flat normals when the file has none. Attributes
//! may be quantized (`KHR_mesh_quantization`, [`super::accessor`]) or Draco-compressed
//! (`KHR_draco_mesh_compression`, [`super::draco`]).

use std::path::Path;

use glam::{Vec2, Vec3, Vec4};
use gltf::json::Value;
use gltf::mesh::{Mode, Semantic};

use super::accessor::read_vectors;
use super::accessor_rules::{AccessorUse, check_accessor};
use super::budget::{Budget, INDEX_BYTES, VERTEX_BYTES, try_vec};
use super::draco;
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
    /// The transform as an affine matrix on `(u, v, 1)` ([`super::mesh_ops::transform_uvs`]).
    pub fn matrix(&self) -> glam::Mat3 {
        let (sin, cos) = self.rotation.sin_cos();
        let (sx, sy) = (self.scale.x, self.scale.y);
        glam::Mat3::from_cols(
            glam::Vec3::new(cos * sx, -sin * sx, 0.0),
            glam::Vec3::new(sin * sy, cos * sy, 0.0),
            self.offset.extend(1.0),
        )
    }

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

/// What makes two primitives the same mesh: their attribute and index accessors, mode and
/// Draco stream (as the JSON states them) and the UV set and transform their material
/// chooses. Primitives with equal keys are read once.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct PrimitiveKey(String);

impl PrimitiveKey {
    pub fn new(
        document: &gltf::Document,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        uv: UvChoice,
    ) -> PrimitiveKey {
        let json = &document.as_json().meshes[mesh.index()].primitives[primitive.index()];
        let draco = primitive.extension_value("KHR_draco_mesh_compression").map(Value::to_string);
        let uv = (
            uv.set,
            uv.offset.to_array().map(f32::to_bits),
            uv.rotation.to_bits(),
            uv.scale.to_array().map(f32::to_bits),
        );
        PrimitiveKey(format!("{:?}|{:?}|{:?}|{draco:?}|{uv:?}", json.attributes, json.indices, json.mode))
    }
}

/// The primitive as a triangle mesh, or `None` for points and lines. The mesh it will make
/// (from the accessors' counts) is charged to `budget` before any accessor is read.
pub fn primitive_mesh(
    document: &gltf::Document,
    primitive: &gltf::Primitive,
    name: &str,
    uv: UvChoice,
    buffers: &[Vec<u8>],
    budget: &mut Budget,
    path: &Path,
) -> Result<Option<Mesh>, LoadError> {
    if !matches!(primitive.mode(), Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
        return Ok(None);
    }
    // The counts charged are first checked by the rules (a count no bytes back is named as such).
    let compressed = primitive.extension_value("KHR_draco_mesh_compression").is_some();
    if let Some(accessor) = primitive.get(&Semantic::Positions).filter(|_| !compressed) {
        let index = accessor.index();
        check_accessor(document.as_json(), index, AccessorUse::Positions, buffers)
            .map_err(|p| LoadError::new(path, format!("{name}: accessor {index} (Positions) {p}")))?;
    }
    if let Some(accessor) = primitive.indices().filter(|_| !compressed) {
        let index = accessor.index();
        check_accessor(document.as_json(), index, AccessorUse::Indices, buffers)
            .map_err(|p| LoadError::new(path, format!("{name}: index accessor {index} {p}")))?;
    }
    budget.charge(mesh_bytes(primitive)).map_err(|over| {
        LoadError::new(path, format!("{name}: the primitive's accessors declare a mesh that {over}"))
    })?;
    let mut mesh = Mesh::empty(name);
    let draco = match primitive.extension_value("KHR_draco_mesh_compression") {
        Some(extension) => Some(
            draco::decode(document, extension, buffers)
                .map_err(|p| LoadError::new(path, format!("{name}: KHR_draco_mesh_compression: {p}")))?,
        ),
        None => None,
    };
    // Each attribute: from the Draco stream when the primitive is compressed, else its accessor.
    macro_rules! attribute {
        ($semantic:expr, $use:expr, $n:literal) => {{
            let semantic = $semantic;
            match (&draco, primitive.get(&semantic)) {
                (Some(decoded), Some(_)) => decoded.attribute::<$n>(&semantic).map(Some).map_err(|p| {
                    LoadError::new(path, format!("{name}: KHR_draco_mesh_compression: {semantic:?}: {p}"))
                })?,
                (None, Some(accessor)) => {
                    let index = accessor.index();
                    Some(
                        read_vectors::<$n>(document, accessor, $use, buffers).map_err(|p| {
                            LoadError::new(path, format!("{name}: accessor {index} ({semantic:?}) {p}"))
                        })?,
                    )
                }
                (_, None) => None,
            }
        }};
    }
    mesh.positions = match attribute!(Semantic::Positions, AccessorUse::Positions, 3) {
        Some(p) => p.into_iter().map(Vec3::from).collect(),
        None => return Err(LoadError::new(path, format!("{name}: a primitive has no POSITION attribute"))),
    };
    mesh.normals = attribute!(Semantic::Normals, AccessorUse::Normals, 3)
        .unwrap_or_default()
        .into_iter()
        .map(Vec3::from)
        .collect();
    mesh.uvs = attribute!(Semantic::TexCoords(uv.set), AccessorUse::TexCoords, 2)
        .unwrap_or_default()
        .into_iter()
        .map(Vec2::from)
        .collect();
    transform_uvs(&mut mesh.uvs, uv.offset, uv.rotation, uv.scale);
    mesh.tangents =
        attribute!(Semantic::Tangents, AccessorUse::Tangents, 4).map(|t| t.into_iter().map(Vec4::from).collect());
    let list = match &draco {
        Some(decoded) => decoded.indices.clone(),
        None => accessor_indices(document, primitive, buffers, mesh.positions.len(), (name, path))?,
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

/// The index list of a primitive without Draco: its index accessor's (checked by the rules
/// first), else `0..vertex_count`. Errors name the primitive (`name`) and the file.
fn accessor_indices(
    document: &gltf::Document,
    primitive: &gltf::Primitive,
    buffers: &[Vec<u8>],
    vertex_count: usize,
    (name, path): (&str, &Path),
) -> Result<Vec<u32>, LoadError> {
    let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
    Ok(match primitive.indices() {
        // The rules first: the gltf crate's index reader panics on what glTF forbids.
        Some(accessor) => {
            let index = accessor.index();
            check_accessor(document.as_json(), index, AccessorUse::Indices, buffers)
                .map_err(|p| LoadError::new(path, format!("{name}: index accessor {index} {p}")))?;
            let indices = reader.read_indices();
            let indices = indices
                .ok_or_else(|| LoadError::new(path, format!("{name}: index accessor {index} has no data")))?
                .into_u32();
            let mut list = try_vec(accessor.count())
                .ok_or_else(|| LoadError::new(path, format!("{name}: no memory for index accessor {index}")))?;
            list.extend(indices);
            list
        }
        None => (0..vertex_count as u32).collect(),
    })
}

/// Bytes of the [`Mesh`] a primitive makes at most, from its accessors' declared counts:
/// its vertices, its index list and the triangle list made from it (three per index for a
/// strip or fan), and a vertex per corner when the file has no normals
/// ([`with_flat_normals`]). Draco primitives count their accessors' counts too.
fn mesh_bytes(primitive: &gltf::Primitive) -> u64 {
    let vertices = primitive.get(&Semantic::Positions).map_or(0, |a| a.count() as u64);
    let listed = primitive.indices().map_or(vertices, |a| a.count() as u64);
    let corners = if primitive.mode() == Mode::Triangles { listed } else { listed.saturating_mul(3) };
    let flat = if primitive.get(&Semantic::Normals).is_none() { corners } else { 0 };
    let vertex_bytes = vertices.saturating_add(flat).saturating_mul(VERTEX_BYTES);
    vertex_bytes.saturating_add(listed.saturating_add(corners).saturating_mul(INDEX_BYTES))
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
