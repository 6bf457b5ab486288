//! A glTF file's document: the JSON (or GLB container) parsed and validated, its required
//! extensions checked against what the loader reads ([`super::gltf`] builds the scene).

use std::path::Path;

use crate::error::LoadError;

/// Extensions a file may list in `extensionsRequired`.
const SUPPORTED_REQUIRED: [&str; 8] = [
    "KHR_texture_transform",
    "KHR_mesh_quantization",
    "KHR_draco_mesh_compression",
    "KHR_materials_clearcoat",
    "KHR_materials_emissive_strength",
    "KHR_texture_basisu",
    "EXT_texture_webp",
    super::meshopt::EXTENSION,
];

/// Extensions that give a texture its image in place of its `source` (KTX2 and WebP images,
/// both decoded here), the first found preferred.
const IMAGE_SOURCE_EXTENSIONS: [&str; 2] = ["KHR_texture_basisu", "EXT_texture_webp"];

/// The image a texture reads: an extension's `source` ([`IMAGE_SOURCE_EXTENSIONS`]), else its
/// own; an error when that image does not exist.
pub(super) fn texture_image(document: &gltf::Document, texture: &gltf::Texture) -> Result<usize, String> {
    let from_extension =
        IMAGE_SOURCE_EXTENSIONS.iter().find_map(|name| texture.extension_value(name)?.get("source")?.as_u64());
    let index = match from_extension {
        Some(index) => usize::try_from(index).unwrap_or(usize::MAX),
        None => document.as_json().textures[texture.index()].source.value(),
    };
    let images = document.images().len();
    if index >= images {
        return Err(format!("texture {} names no image among the {images} there are", texture.index()));
    }
    Ok(index)
}

/// Whether texture `index` of `root` takes its image from an extension.
fn source_by_extension(root: &gltf::json::Root, index: usize) -> bool {
    let extensions = root.textures.get(index).and_then(|t| t.extensions.as_ref());
    extensions.is_some_and(|e| IMAGE_SOURCE_EXTENSIONS.iter().any(|name| e.others.contains_key(*name)))
}

/// Parses and validates the JSON (or GLB container) and checks `extensionsRequired`.
pub(super) fn parse(bytes: &[u8], path: &Path) -> Result<(gltf::Document, Option<Vec<u8>>), LoadError> {
    let describe = |e: gltf::Error| match e {
        gltf::Error::Deserialize(e) => format!("invalid glTF JSON: {e}"),
        gltf::Error::Binary(e) => format!("truncated or invalid GLB container: {e}"),
        gltf::Error::Validation(errors) => {
            let listed: Vec<_> = errors.iter().take(3).map(|(at, error)| format!("{at}: {error}")).collect();
            format!("invalid glTF ({} problems): {}", errors.len(), listed.join("; "))
        }
        e => format!("invalid glTF: {e}"),
    };
    // A GLB's header states the file's length; the gltf crate checks only that the file is not
    // shorter (and underflows on a stated length under 12): a length that differs is corrupt.
    if let Some(stated) = bytes.strip_prefix(b"glTF").and_then(|rest| rest.get(4..8)) {
        let stated = u32::from_le_bytes(stated.try_into().expect("4 bytes"));
        if stated as usize != bytes.len() {
            let problem = format!("the GLB header gives a length of {stated} bytes, but the file has {}", bytes.len());
            return Err(LoadError::new(path, format!("truncated or invalid GLB container: {problem}")));
        }
    }
    let gltf = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| LoadError::new(path, describe(e)))?;
    if let Some(missing) = gltf.extensions_required().find(|e| !SUPPORTED_REQUIRED.contains(e)) {
        return Err(LoadError::new(path, format!("requires the glTF extension {missing}, which is not supported")));
    }
    let root = gltf.document.into_json();
    // gltf-json's validation indexes `accessors` with a primitive's POSITION accessor
    // unchecked (it panics on an index out of range): check attribute indices first.
    let attributes = root.meshes.iter().flat_map(|m| &m.primitives).flat_map(|p| p.attributes.values());
    if let Some(bad) = attributes.map(|a| a.value()).find(|&a| a >= root.accessors.len()) {
        let count = root.accessors.len();
        return Err(LoadError::new(path, format!("a primitive attribute names accessor {bad}, but there are {count}")));
    }
    // `Document::from_json`'s validation, without the copy of the JSON it would need here.
    let mut errors = vec![];
    gltf::json::validation::Validate::validate(&root, &root, gltf::json::Path::new, &mut |path, error| {
        errors.push((path(), error))
    });
    let document = match errors.is_empty() {
        true => gltf::Document::from_json_without_validation(root),
        false => {
            // The gltf crate does not know two extensions this loader reads: it calls them
            // unsupported, and Draco's accessors (which have no bufferView) incomplete.
            let draco_accessors = draco_accessors(&root);
            let known = |(at, error): &(gltf::json::Path, gltf::json::validation::Error)| {
                // e.g. `extensionsRequired[0] = "KHR_mesh_quantization"`, `accessors[2].bufferView`.
                let at = at.to_string();
                let extension = at.starts_with("extensionsRequired[").then(|| at.rsplit('"').nth(1)).flatten();
                let accessor = at.strip_prefix("accessors[").and_then(|rest| rest.strip_suffix("].bufferView"));
                let accessor = accessor.and_then(|i| i.parse::<usize>().ok());
                let texture = at.strip_prefix("textures[").and_then(|rest| rest.strip_suffix("].source"));
                let texture = texture.and_then(|i| i.parse::<usize>().ok());
                match error {
                    gltf::json::validation::Error::Unsupported => {
                        extension.is_some_and(|e| SUPPORTED_REQUIRED.contains(&e))
                    }
                    gltf::json::validation::Error::Missing if texture.is_some() => {
                        texture.is_some_and(|t| source_by_extension(&root, t))
                    }
                    gltf::json::validation::Error::Missing => accessor.is_some_and(|a| draco_accessors.contains(&a)),
                    _ => false,
                }
            };
            let remaining: Vec<_> = errors.into_iter().filter(|e| !known(e)).collect();
            if !remaining.is_empty() {
                return Err(LoadError::new(path, describe(gltf::Error::Validation(remaining))));
            }
            gltf::Document::from_json_without_validation(root)
        }
    };
    Ok((document, gltf.blob))
}

/// The accessors of Draco-compressed primitives (their data comes from the Draco stream).
fn draco_accessors(root: &gltf::json::Root) -> Vec<usize> {
    let compressed = root
        .meshes
        .iter()
        .flat_map(|m| &m.primitives)
        .filter(|p| p.extensions.as_ref().is_some_and(|e| e.others.contains_key("KHR_draco_mesh_compression")));
    compressed.flat_map(|p| p.attributes.values().map(|a| a.value()).chain(p.indices.map(|i| i.value()))).collect()
}
