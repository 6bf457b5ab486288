//! `KHR_draco_mesh_compression`: a primitive's triangles and attributes from its Draco stream.
//!
//! Decoded by `draco-core`, a pure-Rust port of Google's Draco decoder: nothing to build in
//! C++ (the `draco-rs` bindings need the C++ library and a C++ toolchain), and it decodes the
//! edgebreaker and sequential streams glTF exporters write. The extension names, per glTF
//! attribute, the Draco attribute's unique id; the primitive's accessors then only describe the
//! decoded data (count, type, normalisation).

use gltf::json::Value;
use gltf::mesh::Semantic;

/// A decoded Draco stream and the extension's attribute ids.
pub struct DecodedPrimitive {
    mesh: draco_core::Mesh,
    /// glTF attribute name (`POSITION`, `TEXCOORD_0`...) → Draco unique id.
    ids: Vec<(String, u32)>,
    /// Three per triangle, counter-clockwise as in the file.
    pub indices: Vec<u32>,
}

/// The glTF attribute name of `semantic`.
fn attribute_name(semantic: &Semantic) -> String {
    match semantic {
        Semantic::Positions => "POSITION".into(),
        Semantic::Normals => "NORMAL".into(),
        Semantic::Tangents => "TANGENT".into(),
        Semantic::Colors(n) => format!("COLOR_{n}"),
        Semantic::TexCoords(n) => format!("TEXCOORD_{n}"),
        Semantic::Joints(n) => format!("JOINTS_{n}"),
        Semantic::Weights(n) => format!("WEIGHTS_{n}"),
        #[allow(unreachable_patterns)] // feature-gated variants
        _ => "?".into(),
    }
}

/// Decodes the Draco stream the extension object `extension` of `primitive` names.
pub fn decode(document: &gltf::Document, extension: &Value, buffers: &[Vec<u8>]) -> Result<DecodedPrimitive, String> {
    let view_index = extension.get("bufferView").and_then(Value::as_u64).ok_or("no bufferView")?;
    let view =
        document.views().nth(view_index as usize).ok_or_else(|| format!("bufferView {view_index} does not exist"))?;
    let bytes = buffers
        .get(view.buffer().index())
        .and_then(|b| b.get(view.offset()..view.offset() + view.length()))
        .ok_or_else(|| format!("bufferView {view_index} lies outside its buffer"))?;
    let ids = match extension.get("attributes").and_then(Value::as_object) {
        Some(map) => map.iter().filter_map(|(k, v)| Some((k.clone(), u32::try_from(v.as_u64()?).ok()?))).collect(),
        None => return Err("no attributes".into()),
    };
    let mut mesh = draco_core::Mesh::new();
    draco_core::MeshDecoder::new()
        .decode(&mut draco_core::DecoderBuffer::new(bytes), &mut mesh)
        .map_err(|e| format!("the Draco stream does not decode: {e}"))?;
    let points = mesh.num_points() as u32;
    let mut indices = Vec::with_capacity(mesh.num_faces() * 3);
    for face in 0..mesh.num_faces() {
        indices.extend(mesh.face(draco_core::FaceIndex(face as u32)).map(|p| p.0));
    }
    if let Some(bad) = indices.iter().find(|&&i| i >= points) {
        return Err(format!("a face names point {bad}, but the stream has {points}"));
    }
    Ok(DecodedPrimitive { mesh, ids, indices })
}

impl DecodedPrimitive {
    /// The decoded values of the glTF attribute `semantic`, `N` floats per point.
    pub fn attribute<const N: usize>(&self, semantic: &Semantic) -> Result<Vec<[f32; N]>, String> {
        let name = attribute_name(semantic);
        let id = self.ids.iter().find(|(n, _)| *n == name).map(|(_, id)| *id);
        let id = id.ok_or_else(|| format!("the extension names no Draco attribute for {name}"))?;
        let attribute = self.mesh.attribute_by_unique_id(id).ok_or_else(|| format!("no Draco attribute {id}"))?;
        if attribute.num_components() as usize != N {
            return Err(format!("Draco attribute {id} has {} components, {N} expected", attribute.num_components()));
        }
        let points = self.mesh.num_points();
        let flat = attribute.read_f32s(points, N);
        Ok(flat.chunks_exact(N).map(|c| std::array::from_fn(|i| c[i])).collect())
    }
}
