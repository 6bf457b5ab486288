//! glTF 2.0 (`.gltf` with external or base64 buffers, `.glb`) → [`Scene`].
//!
//! The `gltf` crate parses and validates the document; buffers and images are read here, so
//! that an error names the file that failed. The node tree gives one [`Instance`] per
//! primitive with its world matrix (mirroring matrices are drawn with clockwise front faces,
//! see `render::pipelines::Pass`). glTF UVs already follow the crate convention (v down).
//!
//! A mesh has one UV stream: the set (and `KHR_texture_transform`) of the normal map when the
//! material has one, else of the base colour texture; the transform is applied to the UVs at
//! load, so tangents generated from them follow the texture as drawn.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3, Vec4};

use super::budget::{Budget, INDEX_BYTES, VERTEX_BYTES};
use super::gltf_document::{parse, texture_image};
use super::gltf_mesh::{PrimitiveKey, UvChoice, primitive_mesh};
use super::image::{decode_texture_stored, texel_room};
use super::uri::{NOT_PORTABLE_NOTE, UriTarget, read_uri, resolve_uri};
use crate::error::{LoadError, LoadWarning};
use crate::read::FileKind;
use crate::scene::{
    Clearcoat, Instance, Material, NormalMap, Occlusion, SamplerWrap, Scene, ShadingModel, TextureImage, TextureKind,
    Wrap,
};
use crate::shading::pbr::roughness_exponent;
use crate::texture::compressed::Stored;

/// Blinn-Phong exponents a glTF roughness maps to.
const SHININESS: std::ops::RangeInclusive<f32> = 1.0..=1024.0;

/// Loads a `.gltf` or `.glb` file. The camera and light are left to the caller.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let bytes = super::read_file(path, FileKind::Mesh, "glTF")?;
    let (document, blob) = parse(&bytes, path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let mut warnings = vec![];
    let buffers = document
        .buffers()
        .map(|buffer| {
            if super::meshopt::is_fallback(&buffer) {
                return Ok((Vec::new(), path.to_owned())); // made by `decompress_views`
            }
            let (data, source) = match buffer.source() {
                gltf::buffer::Source::Bin => {
                    let blob = blob.clone().ok_or_else(|| {
                        LoadError::new(
                            path,
                            format!("buffer {} is the GLB binary chunk, which is missing", buffer.index()),
                        )
                    })?;
                    (blob, path.to_owned())
                }
                gltf::buffer::Source::Uri(uri) => read_uri(uri, base, path, FileKind::Buffer, &mut warnings)?,
            };
            if data.len() < buffer.length() {
                let problem =
                    format!("buffer {} should hold {} bytes but has {}", buffer.index(), buffer.length(), data.len());
                let outside =
                    warnings.iter().any(|w| matches!(w, LoadWarning::NotPortable { file, .. } if *file == source));
                let note = if outside { format!("; {NOT_PORTABLE_NOTE}") } else { String::new() };
                return Err(LoadError::new(&source, format!("{problem} (truncated?){note}")));
            }
            Ok((data, source))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let (buffers, sources): (Vec<_>, Vec<_>) = buffers.into_iter().unzip();
    let read = bytes.len() as u64 + buffers.iter().map(|b| b.len() as u64).sum::<u64>();
    let mut loader = Loader {
        budget: Budget::for_input(read),
        path,
        base,
        document: &document,
        buffers,
        scene: Scene { files: sources.into_iter().filter(|s| s != path).collect(), warnings, ..super::empty_scene() },
        textures: HashMap::new(),
        materials: HashMap::new(),
        meshes: HashMap::new(),
        stored: HashMap::new(),
    };
    let (buffers, budget) = (&mut loader.buffers, &mut loader.budget);
    super::meshopt::decompress_views(&document, buffers, budget).map_err(|problem| LoadError::new(path, problem))?;
    loader.walk_nodes()?;
    Ok(loader.scene)
}

struct Loader<'a> {
    path: &'a Path,
    base: &'a Path,
    document: &'a gltf::Document,
    buffers: Vec<Vec<u8>>,
    scene: Scene,
    /// (glTF image, kind) → index in `scene.textures`; `None` for an image that could not be read.
    textures: HashMap<(usize, TextureKind), Option<usize>>,
    /// glTF material (`None`: the default material) → index in `scene.materials`.
    materials: HashMap<Option<usize>, usize>,
    /// A primitive's data ([`PrimitiveKey`]) → index in `scene.meshes`, so primitives that
    /// read the same accessors share one mesh; `None` for primitives without triangles
    /// (points, lines, fewer than 3 indices).
    meshes: HashMap<PrimitiveKey, Option<usize>>,
    /// What the meshes may still allocate.
    budget: Budget,
    /// Scene texture index → what its DDS or KTX2 file's format says about the channels.
    stored: HashMap<usize, Stored>,
}

impl Loader<'_> {
    /// Visits the default scene's node tree (or the first scene's, or every root node when
    /// the file has no scene) depth first, composing transforms.
    fn walk_nodes(&mut self) -> Result<(), LoadError> {
        let document = self.document;
        let roots: Vec<gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
            Some(scene) => scene.nodes().collect(),
            None => {
                let mut is_child = vec![false; document.nodes().len()];
                document.nodes().flat_map(|n| n.children()).for_each(|c| is_child[c.index()] = true);
                document.nodes().filter(|n| !is_child[n.index()]).collect()
            }
        };
        let mut visited = vec![false; document.nodes().len()];
        let mut stack: Vec<(gltf::Node, Mat4)> = roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY)).collect();
        while let Some((node, parent)) = stack.pop() {
            if std::mem::replace(&mut visited[node.index()], true) {
                return Err(LoadError::new(self.path, format!("node {} has more than one parent", node.index())));
            }
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            if let Some(mesh) = node.mesh() {
                for primitive in mesh.primitives() {
                    self.add_instance(&mesh, &primitive, world)?;
                }
            }
            stack.extend(node.children().map(|c| (c, world)).collect::<Vec<_>>().into_iter().rev());
        }
        Ok(())
    }

    fn add_instance(&mut self, mesh: &gltf::Mesh, primitive: &gltf::Primitive, world: Mat4) -> Result<(), LoadError> {
        let material = self.material(primitive.material())?;
        let uv = uv_choice(&primitive.material());
        let key = PrimitiveKey::new(self.document, mesh, primitive, uv);
        let index = match self.meshes.get(&key) {
            Some(&index) => index,
            None => {
                let name = format!("{} #{}", mesh.name().unwrap_or("mesh"), primitive.index());
                let (buffers, budget) = (&self.buffers, &mut self.budget);
                let loaded = primitive_mesh(self.document, primitive, &name, uv, buffers, budget, self.path)?;
                let loaded = loaded.and_then(|m| {
                    if m.indices.is_empty() {
                        self.scene.warnings.push(LoadWarning::EmptyPrimitive { mesh: name.clone() });
                        return None;
                    }
                    Some(m)
                });
                let index = loaded.map(|m| {
                    self.scene.meshes.push(m);
                    self.scene.meshes.len() - 1
                });
                self.meshes.insert(key, index);
                index
            }
        };
        if let Some(mesh) = index {
            // Each instance is drawn (and framed) vertex by vertex: its mesh counts again.
            let drawn = &self.scene.meshes[mesh];
            let bytes = drawn.positions.len() as u64 * VERTEX_BYTES + drawn.indices.len() as u64 * INDEX_BYTES;
            let bytes = bytes + std::mem::size_of::<Instance>() as u64;
            self.budget
                .charge(bytes)
                .map_err(|over| LoadError::new(self.path, format!("drawing mesh {:?} once more {over}", drawn.name)))?;
            self.scene.instances.push(Instance { mesh, material, transform: world });
        }
        Ok(())
    }

    /// The scene material for a glTF material, made once, shaded by metallic-roughness. For
    /// the Blinn-Phong lecture model, metallic and roughness (their factors times the mean of
    /// the metallic-roughness texture's blue and green) map to `k_s = mix(0.04, base colour,
    /// metallic)` and exponent `2/α² − 2` with `α = roughness²` (the usual Beckmann↔Phong
    /// match, [`roughness_exponent`]). Samplers: the base colour texture's, and the normal map's (else the
    /// metallic-roughness texture's) for the other slots.
    fn material(&mut self, material: gltf::Material) -> Result<usize, LoadError> {
        if let Some(&index) = self.materials.get(&material.index()) {
            return Ok(index);
        }
        let pbr = material.pbr_metallic_roughness();
        let base = Vec4::from(pbr.base_color_factor());
        let metallic_roughness_texture = match pbr.metallic_roughness_texture() {
            Some(info) => self.texture(info.texture(), TextureKind::Data)?,
            None => None,
        };
        let texture_mean = metallic_roughness_texture.map_or(Vec3::ONE, |t| mean_rgb(&self.scene.textures[t]));
        let metallic = (pbr.metallic_factor() * texture_mean.z).clamp(0.0, 1.0);
        let roughness = pbr.roughness_factor() * texture_mean.y;
        let base_color_texture = match pbr.base_color_texture() {
            Some(info) => self.texture(info.texture(), TextureKind::Color)?,
            None => None,
        };
        let normal_map = match material.normal_texture() {
            Some(normal) => {
                let texture = self.texture(normal.texture(), TextureKind::NormalMap)?;
                texture.map(|t| NormalMap::new(t, normal.scale()).with_stored(self.stored.get(&t)))
            }
            None => None,
        };
        let occlusion = match material.occlusion_texture() {
            Some(info) => self
                .texture(info.texture(), TextureKind::Data)?
                .map(|texture| Occlusion { texture, strength: info.strength() }),
            None => None,
        };
        let detail_sampler = material
            .normal_texture()
            .map(|n| n.texture().sampler())
            .or_else(|| pbr.metallic_roughness_texture().map(|i| i.texture().sampler()));
        let emissive_texture = match material.emissive_texture() {
            Some(info) => self.texture(info.texture(), TextureKind::Color)?,
            None => None,
        };
        let emissive_strength = material.emissive_strength().unwrap_or(1.0);
        let clearcoat = match material.extension_value("KHR_materials_clearcoat") {
            Some(json) => Some(self.clearcoat(&material, json)?),
            None => None,
        };
        self.scene.materials.push(Material {
            name: material.name().unwrap_or("material").to_owned(),
            base_color_factor: base,
            base_color_texture,
            normal_map,
            specular: Vec3::splat(0.04).lerp(base.truncate(), metallic),
            shininess: roughness_exponent(roughness).clamp(*SHININESS.start(), *SHININESS.end()),
            double_sided: material.double_sided(),
            shading_model: ShadingModel::MetallicRoughness,
            metallic: pbr.metallic_factor().clamp(0.0, 1.0),
            roughness: pbr.roughness_factor().clamp(0.0, 1.0),
            metallic_roughness_texture,
            occlusion,
            base_color_wrap: pbr.base_color_texture().map_or_else(Default::default, |i| wrap(&i.texture().sampler())),
            detail_wrap: detail_sampler.map_or_else(Default::default, |s| wrap(&s)),
            emissive_factor: Vec3::from(material.emissive_factor()) * emissive_strength,
            emissive_texture,
            clearcoat,
            ..Material::default()
        });
        let index = self.scene.materials.len() - 1;
        self.materials.insert(material.index(), index);
        Ok(index)
    }

    /// `KHR_materials_clearcoat` of `material` from its JSON: factors, the strength (red),
    /// roughness (green) and normal textures, and the transform from the mesh's texture
    /// coordinates to the layer's (its textures' `KHR_texture_transform`; the first texture's
    /// stands for all three).
    fn clearcoat(&mut self, material: &gltf::Material, json: &gltf::json::Value) -> Result<Clearcoat, LoadError> {
        use gltf::json::Value;
        let number = |key: &str, default: f64| json.get(key).and_then(Value::as_f64).unwrap_or(default) as f32;
        let name = material.name().unwrap_or("material").to_owned();
        let stream = uv_choice(material);
        let mut layer_uv = None;
        let mut slot = |loader: &mut Self, key: &str, kind: TextureKind| -> Result<Option<(usize, f32)>, LoadError> {
            let Some(info) = json.get(key) else { return Ok(None) };
            let index = info.get("index").and_then(Value::as_u64).and_then(|i| usize::try_from(i).ok());
            let Some(texture) = index.and_then(|i| loader.document.textures().nth(i)) else {
                let problem = format!("material {name:?}: {key} names no texture");
                return Err(LoadError::new(loader.path, problem));
            };
            let tex_coord = info.get("texCoord").and_then(Value::as_u64).unwrap_or(0).min(u32::MAX as u64) as u32;
            let choice = UvChoice::from_json(tex_coord, info.pointer("/extensions/KHR_texture_transform"));
            if choice.set != stream.set {
                let warning = LoadWarning::TextureCoordinates {
                    material: name.clone(),
                    texture: key.to_owned(),
                    wanted: choice.set,
                    drawn: stream.set,
                };
                loader.scene.warnings.push(warning);
            }
            layer_uv.get_or_insert(choice.matrix() * stream.matrix().inverse());
            let scale = info.get("scale").and_then(Value::as_f64).unwrap_or(1.0) as f32;
            Ok(loader.texture(texture, kind)?.map(|t| (t, scale)))
        };
        let texture = slot(self, "clearcoatTexture", TextureKind::Data)?.map(|(t, _)| t);
        let roughness_texture = slot(self, "clearcoatRoughnessTexture", TextureKind::Data)?.map(|(t, _)| t);
        let normal_map =
            slot(self, "clearcoatNormalTexture", TextureKind::NormalMap)?.map(|(t, scale)| NormalMap::new(t, scale));
        let normal_map = normal_map.map(|map| {
            let stored = self.stored.get(&map.texture);
            map.with_stored(stored)
        });
        let layer_uv = layer_uv.unwrap_or(glam::Mat3::IDENTITY);
        Ok(Clearcoat {
            factor: number("clearcoatFactor", 0.0).clamp(0.0, 1.0),
            texture,
            roughness: number("clearcoatRoughnessFactor", 0.0).clamp(0.0, 1.0),
            roughness_texture,
            normal_map,
            uv_transform: [layer_uv.row(0), layer_uv.row(1)],
        })
    }

    /// The scene texture for a glTF texture's image read as `kind`, decoded once; `None`
    /// (with a [`LoadWarning`]) when the image file cannot be read or decoded. An image the
    /// document describes wrongly (no uri or mimeType, outside its buffer) is an error.
    fn texture(&mut self, texture: gltf::Texture, kind: TextureKind) -> Result<Option<usize>, LoadError> {
        let image = texture_image(self.document, &texture).map_err(|problem| LoadError::new(self.path, problem))?;
        if let Some(&index) = self.textures.get(&(image, kind)) {
            return Ok(index);
        }
        let index = match self.decode(image, kind)? {
            Ok((decoded, stored)) => {
                self.scene.textures.push(decoded.into());
                let index = self.scene.textures.len() - 1;
                if let Some(stored) = stored {
                    self.stored.insert(index, stored);
                }
                Some(index)
            }
            Err(unreadable) => {
                let warning = LoadWarning::UnreadableTexture { file: unreadable.path, problem: unreadable.problem };
                if !self.scene.warnings.contains(&warning) {
                    self.scene.warnings.push(warning);
                }
                None
            }
        };
        self.textures.insert((image, kind), index);
        Ok(index)
    }

    /// Image `image` of the document, read and decoded as `kind` (inner `Err`: the image cannot be
    /// read or decoded); an image file is remembered in [`Scene::files`], readable or not, so
    /// that hot reload picks it up once it is fixed.
    fn decode(
        &mut self,
        image: usize,
        kind: TextureKind,
    ) -> Result<Result<(TextureImage, Option<Stored>), LoadError>, LoadError> {
        let image = self.document.images().nth(image).expect("texture_image checks the index");
        // gltf's `Image::source` unwraps the uri, or the mimeType of a bufferView image, and
        // validation does not always catch their absence (found by tests/fuzz.rs).
        let json = &self.document.as_json().images[image.index()];
        let valid = match &json.buffer_view {
            Some(view) => json.mime_type.is_some() && view.value() < self.document.views().len(),
            None => json.uri.is_some(),
        };
        if !valid {
            let problem = format!("image {} needs a uri, or a bufferView with a mimeType", image.index());
            return Err(LoadError::new(self.path, problem));
        }
        let (bytes, file) = match image.source() {
            gltf::image::Source::Uri { uri, .. } => {
                let target = match resolve_uri(uri, self.base, self.path, "image") {
                    Ok(UriTarget::File { path, .. }) => Some(path),
                    Ok(UriTarget::Data(_)) => None,
                    Err(unfetched) => return Ok(Err(unfetched)),
                };
                if let Some(file) = target.filter(|f| f != self.path && !self.scene.files.contains(f)) {
                    self.scene.files.push(file);
                }
                match read_uri(uri, self.base, self.path, FileKind::Image, &mut self.scene.warnings) {
                    Ok(read) => read,
                    Err(unreadable) => return Ok(Err(unreadable)),
                }
            }
            gltf::image::Source::View { view, .. } => {
                let range = view.offset()..view.offset() + view.length();
                let bytes = self.buffers.get(view.buffer().index()).and_then(|b| b.get(range));
                let bytes = bytes.ok_or_else(|| {
                    LoadError::new(self.path, format!("image {} lies outside its buffer", image.index()))
                })?;
                (bytes.to_vec(), PathBuf::from(format!("{} (image {})", self.path.display(), image.index())))
            }
        };
        let room = match texel_room(&self.scene) {
            Ok(room) => room,
            Err(problem) => return Ok(Err(LoadError::new(&file, problem))),
        };
        Ok(decode_texture_stored(&bytes, &file, kind, room))
    }
}

/// A glTF sampler's wrap modes.
fn wrap(sampler: &gltf::texture::Sampler) -> SamplerWrap {
    let mode = |m| match m {
        gltf::texture::WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        gltf::texture::WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
    };
    SamplerWrap { u: mode(sampler.wrap_s()), v: mode(sampler.wrap_t()) }
}

/// The mean of a texture's red, green and blue, each in 0..1.
fn mean_rgb(texture: &TextureImage) -> Vec3 {
    let sum =
        texture.rgba.chunks_exact(4).fold(Vec3::ZERO, |s, t| s + Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32));
    sum / (255.0 * (texture.rgba.len() / 4).max(1) as f32)
}

/// The UV set and transform of the normal map, else of the base colour texture. (The `gltf`
/// crate parses the extension on texture infos; on normal textures it stays JSON.)
fn uv_choice(material: &gltf::Material) -> UvChoice {
    match (material.normal_texture(), material.pbr_metallic_roughness().base_color_texture()) {
        (Some(normal), _) => UvChoice::from_json(normal.tex_coord(), normal.extension_value("KHR_texture_transform")),
        (None, Some(info)) => match info.texture_transform() {
            Some(t) => UvChoice {
                set: t.tex_coord().unwrap_or(info.tex_coord()),
                offset: t.offset().into(),
                rotation: t.rotation(),
                scale: t.scale().into(),
            },
            None => UvChoice { set: info.tex_coord(), ..Default::default() },
        },
        (None, None) => UvChoice::default(),
    }
}
