//! A scene's GPU resources. Only what the scene's materials use is uploaded: no tangent
//! stream for meshes drawn without one, no normal map for a material that has none.

use glam::{Vec2, Vec3, Vec4};
use wgpu::util::DeviceExt;

use super::glyphs::{MAX_GLYPHS_PER_MESH, glyph_lines};
use super::pipelines::{Layouts, Pass, Variant};
use super::uniforms::ObjectUniform;
use super::{BumpKind, BumpSource, SceneOptions, bump_kind};
use crate::counters::WorkCounters;
use crate::scene::{Mesh, SamplerWrap, Scene, TextureImage, TextureKind, Wrap};
use crate::tangent::{self, TangentMethod};

pub struct GpuMesh {
    pub positions: wgpu::Buffer,
    pub normals: wgpu::Buffer,
    pub uvs: wgpu::Buffer,
    pub tangents: Option<wgpu::Buffer>,
    /// Reference frames for the Difference view, made on its first use.
    pub reference_tangents: Option<wgpu::Buffer>,
    /// The T/B/N glyph line list and its vertex count, made on first use (meshes with frames).
    pub glyphs: Option<(wgpu::Buffer, u32)>,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
}

/// The frames a mesh with a tangent stream is drawn with, and the geometry they belong to
/// (unwelded for per-face frames), kept to make reference frames on demand.
pub struct DrawnFrames {
    pub mesh: Mesh,
    /// The frames drawn, one per vertex of `mesh`.
    pub tangents: Vec<Vec4>,
    pub method: TangentMethod,
}

pub struct GpuInstance {
    pub mesh: usize,
    pub pass: Pass,
    pub bind_group: wgpu::BindGroup,
}

/// The light marker: an octahedron whose model matrix follows the light.
pub struct GpuMarker {
    pub positions: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
    pub model: wgpu::Buffer,
    pub bind_group: wgpu::BindGroup,
}

pub struct GpuScene {
    /// What the scene asked for but could not get, one line each, for the user.
    pub notices: Vec<String>,
    pub meshes: Vec<GpuMesh>,
    /// Per mesh: how its tangent stream was made; `None` for meshes drawn without one.
    pub frames: Vec<Option<DrawnFrames>>,
    pub instances: Vec<GpuInstance>,
    pub marker: GpuMarker,
    pub ambient: Vec3,
}

/// Light marker size, metres from centre to tip.
pub const MARKER_RADIUS: f32 = 0.06;

fn buffer<T: bytemuck::Pod>(device: &wgpu::Device, label: &str, data: &[T], usage: wgpu::BufferUsages) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::cast_slice(data),
        usage,
    })
}

/// The per-attribute array, or zeros when the mesh lacks it or it has the wrong length.
fn stream<T: Copy + Default>(values: &[T], count: usize) -> Vec<T> {
    if values.len() == count { values.to_vec() } else { vec![T::default(); count] }
}

/// Uploads textures on first use, each once.
struct TextureCache<'a> {
    device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
    views: Vec<Option<wgpu::TextureView>>,
    white: Option<wgpu::TextureView>,
    /// What could not be uploaded as given (textures larger than the adapter allows).
    notices: Vec<String>,
}

impl TextureCache<'_> {
    /// Uploads `image` with its mip chain. A texture larger than the adapter allows starts at
    /// the first mip level that fits (a notice says so) instead of failing.
    fn upload(&mut self, image: &TextureImage, counters: &mut WorkCounters) -> wgpu::TextureView {
        let format = match image.kind {
            TextureKind::Color => wgpu::TextureFormat::Rgba8UnormSrgb,
            TextureKind::NormalMap | TextureKind::Height | TextureKind::Data => wgpu::TextureFormat::Rgba8Unorm,
        };
        let limit = self.device.limits().max_texture_dimension_2d;
        let mut mips = image.mip_chain();
        let fits = mips.iter().position(|m| m.width <= limit && m.height <= limit).unwrap_or(mips.len() - 1);
        if fits > 0 {
            let (w, h) = (mips[fits].width, mips[fits].height);
            self.notices.push(format!(
                "texture {:?} is {}x{}, more than the adapter's {limit} per side: downscaled to {w}x{h}",
                image.name, image.width, image.height
            ));
            mips.drain(..fits);
        }
        let base = &mips[0];
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(&image.name),
            size: wgpu::Extent3d { width: base.width, height: base.height, depth_or_array_layers: 1 },
            mip_level_count: mips.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        for (level, mip) in mips.iter().enumerate() {
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level as u32,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                &mip.rgba,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * mip.width),
                    rows_per_image: Some(mip.height),
                },
                wgpu::Extent3d { width: mip.width, height: mip.height, depth_or_array_layers: 1 },
            );
        }
        counters.textures_uploaded += 1;
        texture.create_view(&Default::default())
    }

    fn get(&mut self, scene: &Scene, index: usize, counters: &mut WorkCounters) -> wgpu::TextureView {
        if self.views[index].is_none() {
            self.views[index] = Some(self.upload(&scene.textures[index], counters));
        }
        self.views[index].clone().expect("uploaded above")
    }

    /// A 1×1 white colour texture for materials without a base colour texture.
    fn white(&mut self, counters: &mut WorkCounters) -> wgpu::TextureView {
        if self.white.is_none() {
            let image = TextureImage {
                name: "white".into(),
                width: 1,
                height: 1,
                kind: TextureKind::Color,
                rgba: vec![255; 4],
            };
            self.white = Some(self.upload(&image, counters));
        }
        self.white.clone().expect("uploaded above")
    }
}

/// The variant an instance is drawn with: by its [`BumpKind`]; without a bump, with the
/// tangent stream when the mesh supplies tangents (for the T/B views), else plain.
fn variant_of(scene: &Scene, mesh: usize, material: usize, bump_source: BumpSource) -> Variant {
    match bump_kind(scene, mesh, material, bump_source) {
        BumpKind::HeightInShader => Variant::HeightBump,
        BumpKind::TangentSpace => Variant::NormalMapped,
        BumpKind::ObjectSpace => Variant::ObjectSpace,
        BumpKind::None => {
            let mesh = &scene.meshes[mesh];
            if mesh.tangents.as_ref().is_some_and(|t| t.len() == mesh.positions.len()) {
                Variant::Tangent
            } else {
                Variant::Plain
            }
        }
    }
}

/// A notice per mesh whose material has a normal or height map but which has no texture
/// coordinates: it is drawn without bump.
fn missing_uv_notices(scene: &Scene) -> Vec<String> {
    let mut notices = vec![];
    for instance in &scene.instances {
        let (mesh, material) = (&scene.meshes[instance.mesh], &scene.materials[instance.material]);
        let bumped = material.normal_map.is_some() || material.height_map.is_some();
        let notice = format!("mesh {:?} has no texture coordinates: drawn without its bump map", mesh.name);
        if bumped && mesh.uvs.len() != mesh.positions.len() && !notices.contains(&notice) {
            notices.push(notice);
        }
    }
    notices
}

/// Samplers by wrap mode, made on first use (linear filtering, trilinear mips).
#[derive(Default)]
struct SamplerCache {
    made: Vec<(SamplerWrap, wgpu::Sampler)>,
}

impl SamplerCache {
    fn get(&mut self, device: &wgpu::Device, wrap: SamplerWrap) -> wgpu::Sampler {
        if let Some((_, sampler)) = self.made.iter().find(|(w, _)| *w == wrap) {
            return sampler.clone();
        }
        let mode = |w| match w {
            Wrap::Repeat => wgpu::AddressMode::Repeat,
            Wrap::ClampToEdge => wgpu::AddressMode::ClampToEdge,
            Wrap::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
        };
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material"),
            address_mode_u: mode(wrap.u),
            address_mode_v: mode(wrap.v),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        self.made.push((wrap, sampler.clone()));
        sampler
    }
}

/// The light marker's geometry: an octahedron of radius [`MARKER_RADIUS`] around the origin.
fn octahedron() -> (Vec<Vec3>, Vec<u32>) {
    let positions = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].map(|v| v * MARKER_RADIUS).to_vec();
    let mut indices = vec![];
    for (a, b) in [(0u32, 4u32), (4, 1), (1, 5), (5, 0)] {
        indices.extend([b, a, 2, a, b, 3]);
    }
    (positions, indices)
}

/// Uploads what `scene` uses with `options`. Meshes drawn with a tangent stream get frames by
/// `options.tangent_method` (`None`: the mesh's own, else MikkTSpace; see [`tangent::resolve`]).
pub fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layouts: &Layouts,
    scene: &Scene,
    options: SceneOptions,
    counters: &mut WorkCounters,
) -> GpuScene {
    let tangent_method = options.tangent_method;
    let variants: Vec<Variant> =
        scene.instances.iter().map(|i| variant_of(scene, i.mesh, i.material, options.bump_source)).collect();
    let mut frames = vec![];
    let mut notices = missing_uv_notices(scene);
    let meshes = scene
        .meshes
        .iter()
        .enumerate()
        .map(|(index, mesh)| {
            let drawn_with_tangents = scene
                .instances
                .iter()
                .zip(&variants)
                .any(|(i, &v)| i.mesh == index && matches!(v, Variant::Tangent | Variant::NormalMapped));
            if !drawn_with_tangents {
                frames.push(None);
                return upload_mesh(device, mesh, None, &mut notices);
            }
            // Per-face frames need a vertex per corner.
            let drawn = if tangent_method == Some(TangentMethod::PerFace) { mesh.unwelded() } else { mesh.clone() };
            let (tangents, method) = tangent::resolve(&drawn, tangent_method);
            if method.is_generated() {
                counters.tangent_frames_generated += tangents.len() as u64;
            }
            let gpu = upload_mesh(device, &drawn, Some(&tangents), &mut notices);
            frames.push(Some(DrawnFrames { mesh: drawn, tangents, method }));
            gpu
        })
        .collect();

    let mut samplers = SamplerCache::default();
    let mut textures =
        TextureCache { device, queue, views: vec![None; scene.textures.len()], white: None, notices: vec![] };
    let instances = scene
        .instances
        .iter()
        .zip(variants)
        .map(|(instance, variant)| {
            let material = &scene.materials[instance.material];
            let uniform =
                buffer(device, "object", &[ObjectUniform::new(instance, material)], wgpu::BufferUsages::UNIFORM);
            let base_color = match material.base_color_texture {
                Some(t) => textures.get(scene, t, counters),
                None => textures.white(counters),
            };
            // Without a metallic-roughness, occlusion or gloss texture the base colour view stands
            // in (no upload); the shader then ignores it (flags, occlusion strength 0).
            let mut optional = |slot: Option<usize>| match slot {
                Some(t) => textures.get(scene, t, counters),
                None => base_color.clone(),
            };
            let metallic_roughness = optional(material.metallic_roughness_texture);
            let occlusion = optional(material.occlusion.as_ref().map(|o| o.texture));
            let gloss = optional(material.gloss_texture);
            let base_sampler = samplers.get(device, material.base_color_wrap);
            let detail_sampler = samplers.get(device, material.detail_wrap);
            let mut entries = vec![
                wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&base_color) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::Sampler(&base_sampler) },
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::Sampler(&detail_sampler) },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&metallic_roughness) },
                wgpu::BindGroupEntry { binding: 6, resource: wgpu::BindingResource::TextureView(&occlusion) },
                wgpu::BindGroupEntry { binding: 7, resource: wgpu::BindingResource::TextureView(&gloss) },
            ];
            // Binding 3: the normal map or the height map, as the variant needs.
            let bump_texture = match (variant, &material.normal_map, &material.height_map) {
                (Variant::NormalMapped | Variant::ObjectSpace, Some(map), _) => {
                    Some(textures.get(scene, map.texture, counters))
                }
                (Variant::HeightBump, _, Some(map)) => Some(textures.get(scene, map.texture, counters)),
                _ => None,
            };
            if let Some(view) = &bump_texture {
                entries.push(wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::TextureView(view) });
            }
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&scene.meshes[instance.mesh].name),
                layout: layouts.material(variant),
                entries: &entries,
            });
            // A mirroring transform turns front faces clockwise on screen; the pipeline's front
            // face follows, so culling and `front_facing` (the double-sided flip) stay right.
            let mirrored = instance.transform.determinant() < 0.0;
            GpuInstance {
                mesh: instance.mesh,
                pass: Pass::Mesh { variant, cull_back_faces: !material.double_sided, mirrored },
                bind_group,
            }
        })
        .collect();

    let (positions, indices) = octahedron();
    let model = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("light marker model"),
        size: 64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("light marker"),
        layout: &layouts.marker,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: model.as_entire_binding() }],
    });
    let marker = GpuMarker {
        positions: buffer(device, "marker positions", &positions, wgpu::BufferUsages::VERTEX),
        indices: buffer(device, "marker indices", &indices, wgpu::BufferUsages::INDEX),
        index_count: indices.len() as u32,
        model,
        bind_group,
    };
    notices.append(&mut textures.notices);
    GpuScene { meshes, frames, instances, marker, ambient: scene.ambient, notices }
}

/// Uploads a mesh, repairing what would put NaN on screen (loaders reject such data; a scene
/// built in code may still hold it): triangles touching a non-finite or out-of-range position
/// are dropped, non-finite normals become +Z and non-finite UVs 0. A notice says so.
fn upload_mesh(device: &wgpu::Device, mesh: &Mesh, tangents: Option<&[Vec4]>, notices: &mut Vec<String>) -> GpuMesh {
    let count = mesh.positions.len();
    let usage = wgpu::BufferUsages::VERTEX;
    let usable = |i: &u32| mesh.positions.get(*i as usize).is_some_and(|p| p.is_finite());
    let indices: Vec<u32> = mesh.indices.chunks_exact(3).filter(|t| t.iter().all(usable)).flatten().copied().collect();
    let normals: Vec<Vec3> =
        stream(&mesh.normals, count).into_iter().map(|n| if n.is_finite() { n } else { Vec3::Z }).collect();
    let uvs: Vec<Vec2> =
        stream::<Vec2>(&mesh.uvs, count).into_iter().map(|uv| if uv.is_finite() { uv } else { Vec2::ZERO }).collect();
    let dropped = (mesh.indices.len() - indices.len()) / 3;
    let repaired =
        mesh.normals.iter().filter(|n| !n.is_finite()).count() + mesh.uvs.iter().filter(|uv| !uv.is_finite()).count();
    if dropped + repaired > 0 {
        notices.push(format!(
            "mesh {:?}: NaN or infinite data: {dropped} triangles dropped, {repaired} normals or UVs replaced",
            mesh.name
        ));
    }
    GpuMesh {
        positions: buffer(device, "positions", &mesh.positions, usage),
        normals: buffer(device, "normals", &normals, usage),
        uvs: buffer(device, "uvs", &uvs, usage),
        tangents: tangents.map(|t| buffer(device, "tangents", &stream::<Vec4>(t, count), usage)),
        reference_tangents: None,
        glyphs: None,
        index_count: indices.len() as u32,
        indices: buffer(device, "indices", &indices, wgpu::BufferUsages::INDEX),
    }
}

impl GpuScene {
    /// Makes the T/B/N glyph lines of every mesh with a tangent stream, once.
    pub fn ensure_glyphs(&mut self, device: &wgpu::Device) {
        for (gpu, drawn) in self.meshes.iter_mut().zip(&self.frames) {
            let Some(drawn) = drawn else { continue };
            if gpu.glyphs.is_none() {
                let lines = glyph_lines(&drawn.mesh, &drawn.tangents, MAX_GLYPHS_PER_MESH);
                let count = lines.len() as u32;
                gpu.glyphs = Some((buffer(device, "T/B/N glyphs", &lines, wgpu::BufferUsages::VERTEX), count));
            }
        }
    }

    /// Makes the Difference view's reference frames (analytic where the mesh has them,
    /// else MikkTSpace) for every mesh with a tangent stream, once.
    pub fn ensure_reference_frames(&mut self, device: &wgpu::Device, counters: &mut WorkCounters) {
        for (gpu, drawn) in self.meshes.iter_mut().zip(&self.frames) {
            let Some(drawn) = drawn else { continue };
            if gpu.reference_tangents.is_none() {
                let (reference, method) = tangent::reference(&drawn.mesh);
                if method.is_generated() {
                    counters.tangent_frames_generated += reference.len() as u64;
                }
                gpu.reference_tangents =
                    Some(buffer(device, "reference tangents", &reference, wgpu::BufferUsages::VERTEX));
            }
        }
    }
}
