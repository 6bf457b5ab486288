//! A prepared scene's GPU resources ([`crate::prepare`] decides what is drawn and with what;
//! this uploads it): no tangent stream for meshes drawn without one, no texture no instance
//! binds.

use std::sync::Arc;

use glam::Vec3;
use wgpu::util::DeviceExt;

use super::bindings;
use super::glyphs::{MAX_GLYPHS_PER_MESH, glyph_lines};
use super::pipelines::Layouts;
use super::uniforms::ObjectUniform;
use crate::counters::WorkCounters;
use crate::prepare::{PreparedMesh, PreparedScene, Variant};
use crate::scene::{MAX_LIGHTS, SamplerWrap, ShadingModel, TextureImage, TextureKind, Wrap};
use crate::tangent;

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

pub struct GpuInstance {
    pub mesh: usize,
    pub variant: Variant,
    /// Single-sided material: back faces are culled.
    pub cull_back_faces: bool,
    /// The model matrix mirrors: front faces are clockwise on screen.
    pub mirrored: bool,
    /// The material's own shading model (a frame may override it).
    pub shading_model: ShadingModel,
    /// A height map is bound for the parallax family (a normal-mapped instance of a material
    /// with a height map, uploaded with [`crate::frame::SceneOptions::parallax`]).
    pub parallax_height: bool,
    /// The optional textures and lobes its material has ([`super::uniforms::MATERIAL_FEATURES`]
    /// bits of the object uniform's flags), which its mesh pipelines are specialised to.
    pub features: u32,
    pub bind_group: wgpu::BindGroup,
}

/// The light markers: an octahedron drawn once per light that is on, at its centre in its
/// colour ([`MarkerUniform`]).
pub struct GpuMarker {
    pub positions: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
    /// `[MarkerUniform; MAX_LIGHTS]`, by the frame's light index.
    pub lights: wgpu::Buffer,
    pub bind_group: wgpu::BindGroup,
}

/// WGSL `Marker` (shaders/marker.wgsl): one light's marker.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MarkerUniform {
    /// World space, metres ([`crate::frame::FrameParams::marker_position`]); w unused.
    pub centre: [f32; 4],
    /// The light's colour with each channel at most 1; a unused.
    pub color: [f32; 4],
}

pub struct GpuScene {
    /// What the scene asked for but could not get, one line each, for the user.
    pub notices: Vec<String>,
    pub meshes: Vec<GpuMesh>,
    pub instances: Vec<GpuInstance>,
    pub marker: GpuMarker,
    /// What was uploaded: kept for what is made on first use (reference frames, glyphs), and
    /// for the probe of the picture drawn from it.
    pub prepared: Arc<PreparedScene>,
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
    fn upload(
        &mut self,
        image: &TextureImage,
        mips: &[TextureImage],
        counters: &mut WorkCounters,
    ) -> wgpu::TextureView {
        let format = match image.kind {
            TextureKind::Color => wgpu::TextureFormat::Rgba8UnormSrgb,
            TextureKind::NormalMap | TextureKind::Height | TextureKind::Data => wgpu::TextureFormat::Rgba8Unorm,
        };
        let limit = self.device.limits().max_texture_dimension_2d;
        let fits = mips.iter().position(|m| m.width <= limit && m.height <= limit).unwrap_or(mips.len() - 1);
        if fits > 0 {
            let (w, h) = (mips[fits].width, mips[fits].height);
            self.notices.push(format!(
                "texture {:?} is {}x{}, more than the adapter's {limit} per side: downscaled to {w}x{h}",
                image.name, image.width, image.height
            ));
        }
        let mips = &mips[fits..];
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

    fn get(&mut self, prepared: &PreparedScene, index: usize, counters: &mut WorkCounters) -> wgpu::TextureView {
        if self.views[index].is_none() {
            let image = &prepared.scene.textures[index];
            self.views[index] = Some(self.upload(image, &prepared.mip_chain(index), counters));
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
            self.white = Some(self.upload(&image, &image.mip_chain(), counters));
        }
        self.white.clone().expect("uploaded above")
    }
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

/// Uploads what `prepared` holds: its drawn geometry, tangent streams where it made frames,
/// and each texture an instance binds, once, with its mip chain.
pub fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layouts: &Layouts,
    prepared: Arc<PreparedScene>,
    counters: &mut WorkCounters,
) -> GpuScene {
    counters.scenes_uploaded += 1;
    counters.tangent_frames_generated += prepared.tangent_frames_generated;
    let scene = &prepared.scene;
    let meshes = prepared.meshes.iter().map(|m| upload_mesh(device, m)).collect();
    let mut samplers = SamplerCache::default();
    let mut textures =
        TextureCache { device, queue, views: vec![None; scene.textures.len()], white: None, notices: vec![] };
    let instances = prepared
        .instances
        .iter()
        .map(|instance| {
            let material = &scene.materials[instance.material];
            let object = ObjectUniform::new(instance, material);
            let uniform = buffer(device, "object", &[object], wgpu::BufferUsages::UNIFORM);
            let slots = &instance.textures;
            let base_color = match slots.base_color {
                Some(t) => textures.get(&prepared, t, counters),
                None => textures.white(counters),
            };
            // Without a metallic-roughness, occlusion, gloss, emissive or clear-coat texture the
            // base colour view stands in (no upload); the shader then ignores it (flags,
            // occlusion strength 0).
            let mut optional = |slot: Option<usize>| match slot {
                Some(t) => textures.get(&prepared, t, counters),
                None => base_color.clone(),
            };
            let metallic_roughness = optional(slots.metallic_roughness);
            let occlusion = optional(slots.occlusion);
            let gloss = optional(slots.gloss);
            let emissive = optional(slots.emissive);
            let clearcoat = optional(slots.clearcoat);
            let clearcoat_roughness = optional(slots.clearcoat_roughness);
            let clearcoat_normal = optional(slots.clearcoat_normal);
            let height = optional(slots.height);
            let correction = optional(slots.bump_correction);
            let base_sampler = samplers.get(device, material.base_color_wrap);
            let detail_sampler = samplers.get(device, material.detail_wrap);
            let view = wgpu::BindingResource::TextureView;
            let sampler = wgpu::BindingResource::Sampler;
            let mut entries = vec![
                bindings::OBJECT.entry(uniform.as_entire_binding()),
                bindings::BASE_COLOR_TEXTURE.entry(view(&base_color)),
                bindings::BASE_COLOR_SAMPLER.entry(sampler(&base_sampler)),
                bindings::DETAIL_SAMPLER.entry(sampler(&detail_sampler)),
                bindings::METALLIC_ROUGHNESS_TEXTURE.entry(view(&metallic_roughness)),
                bindings::OCCLUSION_TEXTURE.entry(view(&occlusion)),
                bindings::GLOSS_TEXTURE.entry(view(&gloss)),
                bindings::EMISSIVE_TEXTURE.entry(view(&emissive)),
                bindings::CLEARCOAT_TEXTURE.entry(view(&clearcoat)),
                bindings::CLEARCOAT_ROUGHNESS_TEXTURE.entry(view(&clearcoat_roughness)),
                bindings::CLEARCOAT_NORMAL_TEXTURE.entry(view(&clearcoat_normal)),
                bindings::HEIGHT_TEXTURE.entry(view(&height)),
            ];
            // The normal map or the height map, as the variant needs.
            let bump = slots.bump.map(|t| textures.get(&prepared, t, counters));
            if let Some(bump) = &bump {
                entries.push(bindings::BUMP_TEXTURE.entry(view(bump)));
                entries.push(bindings::BUMP_CORRECTION_TEXTURE.entry(view(&correction)));
            }
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&scene.meshes[instance.mesh].name),
                layout: layouts.material(instance.variant),
                entries: &entries,
            });
            // A mirroring transform turns front faces clockwise on screen; the pipeline's front
            // face follows, so culling and `front_facing` (the double-sided flip) stay right.
            GpuInstance {
                mesh: instance.mesh,
                variant: instance.variant,
                cull_back_faces: !material.double_sided,
                mirrored: instance.mirrored(),
                shading_model: material.shading_model,
                parallax_height: instance.textures.height.is_some(),
                features: object.features(),
                bind_group,
            }
        })
        .collect();

    let (positions, indices) = octahedron();
    let lights = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("light markers"),
        size: std::mem::size_of::<[MarkerUniform; MAX_LIGHTS]>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("light marker"),
        layout: &layouts.marker,
        entries: &[bindings::MARKERS.entry(lights.as_entire_binding())],
    });
    let marker = GpuMarker {
        positions: buffer(device, "marker positions", &positions, wgpu::BufferUsages::VERTEX),
        indices: buffer(device, "marker indices", &indices, wgpu::BufferUsages::INDEX),
        index_count: indices.len() as u32,
        lights,
        bind_group,
    };
    let notices = prepared.notices.iter().cloned().chain(textures.notices).collect();
    GpuScene { meshes, instances, marker, notices, prepared }
}

/// Uploads a prepared mesh's streams (already repaired and one entry per vertex).
fn upload_mesh(device: &wgpu::Device, prepared: &PreparedMesh) -> GpuMesh {
    let (mesh, usage) = (&prepared.mesh, wgpu::BufferUsages::VERTEX);
    GpuMesh {
        positions: buffer(device, "positions", &mesh.positions, usage),
        normals: buffer(device, "normals", &mesh.normals, usage),
        uvs: buffer(device, "uvs", &mesh.uvs, usage),
        tangents: prepared.frames.as_ref().map(|f| buffer(device, "tangents", &f.tangents, usage)),
        reference_tangents: None,
        glyphs: None,
        index_count: mesh.indices.len() as u32,
        indices: buffer(device, "indices", &mesh.indices, wgpu::BufferUsages::INDEX),
    }
}

impl GpuScene {
    /// Makes the T/B/N glyph lines of every mesh with a tangent stream, once.
    pub fn ensure_glyphs(&mut self, device: &wgpu::Device) {
        for (gpu, prepared) in self.meshes.iter_mut().zip(&self.prepared.meshes) {
            let Some(frames) = &prepared.frames else { continue };
            if gpu.glyphs.is_none() {
                let lines = glyph_lines(&prepared.mesh, &frames.tangents, MAX_GLYPHS_PER_MESH);
                let count = lines.len() as u32;
                gpu.glyphs = Some((buffer(device, "T/B/N glyphs", &lines, wgpu::BufferUsages::VERTEX), count));
            }
        }
    }

    /// Makes the Difference view's reference frames (analytic where the mesh has them,
    /// else MikkTSpace) for every mesh with a tangent stream, once.
    pub fn ensure_reference_frames(&mut self, device: &wgpu::Device, counters: &mut WorkCounters) {
        for (gpu, prepared) in self.meshes.iter_mut().zip(&self.prepared.meshes) {
            if prepared.frames.is_some() && gpu.reference_tangents.is_none() {
                let (reference, method) = tangent::reference(&prepared.mesh);
                if method.is_generated() {
                    counters.tangent_frames_generated += reference.len() as u64;
                }
                gpu.reference_tangents =
                    Some(buffer(device, "reference tangents", &reference, wgpu::BufferUsages::VERTEX));
            }
        }
    }
}
