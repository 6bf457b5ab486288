//! The pixel probe: the whole shading chain at one pixel of the 3D view, on the CPU.
//!
//! [`ProbeScene::pick`] casts the ray through a pixel's centre ([`OrbitCamera::ray_through_pixel`])
//! against every drawn triangle in world space (brute force, nearest hit; back faces of
//! single-sided materials are culled as on the GPU) and pins the surface point as a triangle
//! and its barycentric coordinates ([`ProbePoint`]). [`ProbeScene::readout`] then interpolates
//! what the vertex shader passes on (position, normal, UV, tangent frame — the frames the
//! renderer draws with: the same [`tangent::resolve`] on the same, possibly unwelded, mesh
//! with the same scene options and material overrides), samples the textures as the GPU's
//! trilinear sampler does (level of detail from the UV footprint of the pixel's 2×2 quad,
//! [`sample_bilinear`] on the mip levels around it) and runs the CPU twin of `shaders/mesh.wgsl`
//! ([`crate::shading`]). With a parallax technique on, it first marches the height map as
//! `shaders/parallax.wgsl` does ([`crate::chain::parallax`], [`MarchReadout`]) and reads the
//! other textures at the shifted UV. The pinned point stays where it is when the camera or light moves;
//! only the readout is recomputed.
//!
//! Spaces and units follow the crate conventions: positions in metres, world space; vectors
//! unit length, world space unless named tangent space; colours linear RGB 0..1 unless named
//! sRGB. The barycentric coordinates of a ray-triangle hit are the perspective-correct ones
//! the rasteriser interpolates with, so the interpolated values equal the GPU's up to float
//! rounding. Screen-space derivatives (texture footprints, the height bump in the shader) come
//! from the values at the four pixel centres of the 2×2 quad holding the point's pixel, found
//! on the triangle's plane as the rasteriser does for the quad. Where the GPU
//! downscaled a texture larger than the adapter allows, the probe differs from the picture.

mod pick;

use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3, Vec4};

use crate::chain::legacy::{EmbossSample, vertex_vectors};
use crate::chain::parallax::{MarchInputs, light_in_tangent_space, march, soft_shadow};
use crate::chain::{BumpSample, ChainValues, SurfaceSample, shade};
use crate::frame::{BumpKind, FrameParams, Parallax, SceneOptions};
use crate::math::{normal_matrix, normalize_or};
use crate::prepare::PreparedScene;
use crate::scene::sample::sample_trilinear;
pub use crate::scene::sample::{nearest_texel, sample_bilinear};
use crate::scene::{MAX_LIGHTS, OrbitCamera, SamplerWrap, Scene, TextureImage, Wrap};
use crate::shading::lights::incident;
use crate::shading::spaces::triangle_inverse_tbn;
use crate::shading::{NormalTexel, height_sample};
use crate::tangent::TangentMethod;
pub use pick::project_to_pixel;
use pick::{Quad, corner_positions, intersect};

/// A pinned surface point: a triangle of one instance and barycentric coordinates on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbePoint {
    /// Index into [`Scene::instances`].
    pub instance: usize,
    /// Triangle index into the drawn mesh's indices (`3 · triangle ..`); the drawn mesh is the
    /// unwelded one for per-face frames, with the same triangle order.
    pub triangle: usize,
    /// Weights of the triangle's three corners (sum 1).
    pub barycentric: Vec3,
    /// Whether the hit face is a front face (else a back face of a double-sided material).
    pub front_facing: bool,
}

/// Everything along the chain at a probed point. Tangent-space quantities are `None` where the
/// mesh is drawn without tangents; normal-map quantities are `None` without a normal map.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeReadout {
    pub point: ProbePoint,
    /// Index into [`Scene::meshes`] and [`Scene::materials`].
    pub mesh: usize,
    pub material: usize,
    /// World-space position, metres.
    pub position: Vec3,
    /// Distance from the eye, metres.
    pub distance: f32,
    /// Texture coordinates (crate conventions: origin top-left, v down).
    pub uv: Vec2,
    pub bump: BumpKind,
    /// The parallax march at the point (`None`: parallax off, depth 0, or no height map on a
    /// normal-mapped surface). The textures below are read at its shifted UV.
    pub march: Option<MarchReadout>,
    /// Whether bump mapping is on (the `B` toggle); off, the shading normal is `normal`.
    pub bump_enabled: bool,
    /// The normal map's texel containing `uv` at mip 0: its integer coordinates and raw bytes
    /// (RGBA, 0–255, before filtering).
    pub texel_xy: Option<[u32; 2]>,
    pub texel_raw: Option<[u8; 4]>,
    /// The normal map's filtered sample at `uv` (RGBA, 0..1, linear; at the mip levels the GPU
    /// reads, with X-Ray's `bump#` correction): what the shader decodes.
    pub texel: Option<NormalTexel>,
    /// The tangent method the frames come from.
    pub tangent_method: Option<TangentMethod>,
    /// Every value of the shading chain at the point ([`crate::chain::shade`]): the decoded
    /// texel, after strength, T, B, N, w, shading normal, N·L, N·H, colour and what the view stores.
    pub chain: ChainValues,
}

/// The parallax march at a probed point ([`crate::chain::parallax::march`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchReadout {
    /// The unit direction to the eye in tangent space `(V·T, V·B, V·N)`; `None` without a
    /// tangent frame.
    pub view_tangent: Option<Vec3>,
    /// Layers of the linear search (0 for the offset techniques) and the first layer at or
    /// below the relief.
    pub layers: u32,
    pub layer_hit: u32,
    /// The UV the textures are read at, and its shift from the interpolated UV.
    pub uv: Vec2,
    pub shift: Vec2,
    /// The depth reached along the ray, 0..1 of the relief's depth.
    pub depth: f32,
    /// The height map at the shifted UV, 0..1 (white = high, a depth map flipped).
    pub height: f32,
    /// The share of each of the scene's lights (by index) reaching the point past the relief's
    /// own shadow ([`crate::chain::parallax::soft_shadow`]; 1 without shadows or light).
    pub light_visibility: [f32; MAX_LIGHTS],
}

impl ProbeReadout {
    /// `shown` as 8-bit values (unrounded), as they compare with a rendered PNG.
    pub fn shown_bytes(&self) -> Option<Vec3> {
        self.chain.shown.map(|c| c * 255.0)
    }
}

/// A prepared scene ([`PreparedScene`]: the renderer's drawn geometry, frames and overrides)
/// with the mip chains of the textures it uses, for probing. Re-make it when the scene or the
/// scene options change.
#[derive(Debug, Clone)]
pub struct ProbeScene {
    prepared: Arc<PreparedScene>,
    /// Per texture: its mip chain as uploaded, level 0 first; empty for textures no instance uses.
    mips: Vec<Vec<TextureImage>>,
}

impl ProbeScene {
    /// Prepares `scene` with `options` as the renderer does and wraps it.
    pub fn new(scene: &Scene, options: &SceneOptions) -> ProbeScene {
        ProbeScene::wrap(Arc::new(PreparedScene::new(scene, options)))
    }

    /// Probes the scene a renderer draws (the render module's `Renderer::prepared` hands it out).
    pub fn wrap(prepared: Arc<PreparedScene>) -> ProbeScene {
        let used = |index: &usize| prepared.uses_texture(*index);
        let mips = (0..prepared.scene.textures.len())
            .map(|index| if used(&index) { prepared.mip_chain(index).into_owned() } else { vec![] })
            .collect();
        ProbeScene { prepared, mips }
    }

    /// The prepared scene probed.
    pub fn prepared(&self) -> &Arc<PreparedScene> {
        &self.prepared
    }

    /// The scene with the material overrides applied.
    pub fn scene(&self) -> &Scene {
        &self.prepared.scene
    }

    /// Number of triangles a pick tests.
    pub fn triangle_count(&self) -> usize {
        self.prepared.triangle_count()
    }

    /// The nearest drawn surface under the centre of pixel `pixel` (from the top-left) of a
    /// `size` view, or `None` where the ray meets nothing.
    pub fn pick(&self, camera: &OrbitCamera, size: [u32; 2], pixel: [u32; 2]) -> Option<ProbePoint> {
        let centre = Vec2::new(pixel[0] as f32 + 0.5, pixel[1] as f32 + 0.5);
        let (origin, dir) = camera.ray_through_pixel(centre, Vec2::new(size[0] as f32, size[1] as f32));
        let mut best: Option<(f32, ProbePoint)> = None;
        for (instance_index, instance) in self.prepared.instances.iter().enumerate() {
            let mesh = &self.prepared.meshes[instance.mesh].mesh;
            let double_sided = self.scene().materials[instance.material].double_sided;
            let mirror = if instance.mirrored() { -1.0 } else { 1.0 };
            for (triangle, corners) in mesh.indices.chunks_exact(3).enumerate() {
                let Some(p) = corner_positions(mesh, corners, &instance.transform) else { continue };
                let Some((t, barycentric)) = intersect(origin, dir, p) else { continue };
                let face = (p[1] - p[0]).cross(p[2] - p[0]) * mirror;
                let front_facing = face.dot(dir) < 0.0;
                if (!front_facing && !double_sided) || best.is_some_and(|(d, _)| d <= t) {
                    continue;
                }
                best = Some((t, ProbePoint { instance: instance_index, triangle, barycentric, front_facing }));
            }
        }
        best.map(|(_, point)| point)
    }

    /// The chain at a pinned point under `params` (camera, light, strength, toggles) in a view
    /// `size` pixels large (texture footprints and the height bump depend on the pixel grid):
    /// the vertex stage's outputs interpolated with the point's barycentric weights, the
    /// textures sampled as the GPU does, then [`crate::chain::shade`].
    pub fn readout(&self, point: &ProbePoint, params: &FrameParams, size: [u32; 2]) -> ProbeReadout {
        let instance = &self.prepared.instances[point.instance];
        let material = &self.scene().materials[instance.material];
        let prepared_mesh = &self.prepared.meshes[instance.mesh];
        let mesh = &prepared_mesh.mesh;
        let corners = &mesh.indices[3 * point.triangle..3 * point.triangle + 3];
        let at = |barycentric: Vec3| {
            move |values: &[Vec3]| -> Vec3 {
                corners.iter().zip(barycentric.to_array()).fold(Vec3::ZERO, |acc, (&i, w)| acc + values[i as usize] * w)
            }
        };
        let uv_at = |barycentric: Vec3| {
            corners.iter().zip(barycentric.to_array()).fold(Vec2::ZERO, |acc, (&i, w)| acc + mesh.uvs[i as usize] * w)
        };
        let b = point.barycentric;
        let model = instance.transform;
        let position = model.transform_point3(at(b)(&mesh.positions));
        let uv = uv_at(b);
        // The pixel's 2×2 quad: texture footprints (mip levels) and the height bump need it.
        let quad = corner_positions(mesh, corners, &model).map(|triangle| Quad {
            camera: &params.camera,
            size,
            triangle,
            position,
        });
        let interpolated_footprint = quad.as_ref().and_then(|q| q.derivatives(|b, _| uv_at(b)));
        let normal_matrix = normal_matrix(model);
        let slots = &instance.textures;
        let detail = material.detail_wrap;
        // The parallax family (chain::parallax) marches the height map with the interpolated
        // UV's footprint; the other textures are read at the shifted UV, their footprint from
        // the shifted UVs of the quad's pixels (each marched with the point's derivatives).
        let facing = if point.front_facing { 1.0 } else { -1.0 };
        let eye = params.camera.eye();
        let parallax = &params.shading.parallax;
        let height_map = material.height_map.as_ref();
        let depth_m = parallax.depth_m.map_or(height_map.map_or(0.0, |h| h.range_m), |d| d.max(0.0));
        let marching =
            slots.height.zip(quad.as_ref()).filter(|_| parallax.technique != Parallax::Off && depth_m != 0.0);
        let march_at = marching.and_then(|(texture, quad)| {
            let (dp_dx, dp_dy) = quad.derivatives(|_, p| p)?;
            let (duv_dx, duv_dy) = interpolated_footprint?;
            let flip = height_map.is_some_and(|h| h.depth);
            let height = move |at: Vec2| {
                let sample =
                    height_sample(sample_trilinear(&self.mips[texture], at, detail, interpolated_footprint).truncate());
                if flip { 1.0 - sample } else { sample }
            };
            let clamp = [detail.u == Wrap::ClampToEdge, detail.v == Wrap::ClampToEdge];
            Some(move |b: Vec3, p: Vec3| {
                let normal = normalize_or(normal_matrix.transform_vector3(at(b)(&mesh.normals)), Vec3::Z) * facing;
                let view_dir = normalize_or(eye - p, normal);
                let inputs =
                    MarchInputs { uv: uv_at(b), normal, view_dir, dp_dx, dp_dy, duv_dx, duv_dy, depth_m, clamp };
                (march(parallax, &inputs, height), height, inputs)
            })
        });
        let marched = march_at.as_ref().map(|m| m(b, position));
        let read_uv = marched.map_or(uv, |(m, ..)| m.uv);
        // The relief's soft shadow dims each light (the shaders' parallax_light_visibility).
        let mut shaded = *params;
        let mut light_visibility = [1.0; MAX_LIGHTS];
        if let Some((m, height, inputs)) = marched {
            for (light, visibility) in shaded.lights.as_mut_slice().iter_mut().zip(&mut light_visibility) {
                let l = incident(light, position, inputs.normal).direction;
                *visibility = soft_shadow(parallax, &inputs, &m, light_in_tangent_space(&inputs, l), height);
                light.intensity *= *visibility;
            }
        }
        let footprint = match (&march_at, &quad) {
            (Some(m), Some(quad)) => quad.derivatives(|b, p| m(b, p).0.uv),
            _ => interpolated_footprint,
        };
        let sample_rgba =
            |texture: usize, wrap: SamplerWrap| sample_trilinear(&self.mips[texture], read_uv, wrap, footprint);
        let sample = |texture: usize, wrap: SamplerWrap| sample_rgba(texture, wrap).truncate();
        let frames = prepared_mesh.frames.as_ref();
        let world_tangent = frames.map(|f| {
            let t = corners.iter().zip(b.to_array()).fold(Vec4::ZERO, |acc, (&i, w)| acc + f.tangents[i as usize] * w);
            let mirror = if instance.mirrored() { -1.0 } else { 1.0 };
            model.transform_vector3(t.truncate()).extend(t.w * mirror)
        });

        // The clear coat's textures at the layer's coordinates; the footprint through the
        // linear part of its transform.
        let coat_sample = |texture: Option<usize>| {
            let coat = material.clearcoat.as_ref()?;
            let linear =
                |d: Vec2| Vec2::new(coat.uv_transform[0].truncate().dot(d), coat.uv_transform[1].truncate().dot(d));
            let coat_footprint = footprint.map(|(dx, dy)| (linear(dx), linear(dy)));
            Some(sample_trilinear(&self.mips[texture?], coat.layer_uv(read_uv), detail, coat_footprint).truncate())
        };
        let normal_map = slots.bump.filter(|_| matches!(instance.bump, BumpKind::TangentSpace | BumpKind::ObjectSpace));
        let nearest = normal_map.map(|t| {
            let texture = &self.scene().textures[t];
            let xy = nearest_texel(texture, read_uv, detail);
            (xy, texture.texel(xy[0] as i64, xy[1] as i64))
        });
        let bump = match (instance.bump, slots.bump) {
            (BumpKind::TangentSpace | BumpKind::ObjectSpace, Some(t)) => Some(BumpSample::NormalMap(NormalTexel {
                rgba: sample_rgba(t, detail),
                correction: slots.bump_correction.map(|c| sample(c, detail)),
            })),
            (BumpKind::HeightInShader, Some(t)) => quad.as_ref().and_then(|quad| {
                // Every pixel of the quad samples at the quad's footprint, as the GPU does.
                let height_at =
                    |b| height_sample(sample_trilinear(&self.mips[t], uv_at(b), detail, footprint).truncate());
                let (dx, dy) = quad.derivatives(|b, p| p.extend(height_at(b)))?;
                Some(BumpSample::HeightSlopes { dp_dx: dx.truncate(), dp_dy: dy.truncate(), dh_dx: dx.w, dh_dy: dy.w })
            }),
            _ => None,
        };
        // The vertex stage's per-vertex light and half vectors, interpolated.
        let (vertex_light, vertex_half) =
            corners.iter().zip(b.to_array()).fold((Vec3::ZERO, Vec3::ZERO), |(l, h), (&i, weight)| {
                let p = model.transform_point3(mesh.positions[i as usize]);
                let n = normal_matrix.transform_vector3(mesh.normals[i as usize]);
                let (vl, vh) = vertex_vectors(p, n, params.lights.first_on(), eye);
                (l + vl * weight, h + vh * weight)
            });
        // The emboss look's height neighbours at mip 0, where a height map is bound.
        let emboss = slots.height.map(|texture| {
            let level = &self.mips[texture][0];
            let flip = height_map.is_some_and(|h| h.depth);
            let texel = Vec2::new(level.width as f32, level.height as f32).recip();
            let height = |offset: Vec2| {
                let sample = height_sample(sample_bilinear(level, read_uv + offset, detail).truncate());
                if flip { 1.0 - sample } else { sample }
            };
            EmbossSample {
                left: height(Vec2::new(-texel.x, 0.0)),
                right: height(Vec2::new(texel.x, 0.0)),
                up: height(Vec2::new(0.0, -texel.y)),
                down: height(Vec2::new(0.0, texel.y)),
            }
        });
        let surface = SurfaceSample {
            position,
            world_normal: normal_matrix.transform_vector3(at(b)(&mesh.normals)),
            front_facing: point.front_facing,
            world_tangent,
            normal_matrix: Mat3::from_mat4(normal_matrix),
            base_color: material.base_color_texture.map(|t| sample(t, material.base_color_wrap)),
            bump,
            metallic_roughness: slots.metallic_roughness.map(|t| sample(t, detail)),
            occlusion: slots.occlusion.map(|t| sample(t, detail).x),
            gloss: slots.gloss.map(|t| sample(t, detail)),
            emissive: slots.emissive.map(|t| sample(t, material.base_color_wrap)),
            clearcoat: coat_sample(slots.clearcoat).map(|t| t.x),
            clearcoat_roughness: coat_sample(slots.clearcoat_roughness).map(|t| t.y),
            clearcoat_normal: coat_sample(slots.clearcoat_normal),
            vertex_light,
            vertex_half,
            emboss,
            triangle_frame: corner_positions(mesh, corners, &model).map(|[p0, p1, p2]| {
                // The triangle's frame from its edges: what the GPU gets from the pixel's
                // screen-space derivatives (the same differences up to a 2×2 change of basis).
                let uv = |k: usize| mesh.uvs[corners[k] as usize];
                let normal = normalize_or(normal_matrix.transform_vector3(at(b)(&mesh.normals)), Vec3::Z) * facing;
                triangle_inverse_tbn(p1 - p0, p2 - p0, uv(1) - uv(0), uv(2) - uv(0), normal)
            }),
        };
        let chain = shade(instance.bump, material, &surface, &shaded);
        let march = marched.map(|(m, height, _)| MarchReadout {
            view_tangent: chain.tangent.zip(chain.bitangent).map(|(t, b)| {
                Vec3::new(chain.view_dir.dot(t), chain.view_dir.dot(b), chain.view_dir.dot(chain.normal))
            }),
            layers: m.layers,
            layer_hit: m.layer_hit,
            uv: m.uv,
            shift: m.shift,
            depth: m.depth,
            height: height(m.uv),
            light_visibility,
        });
        ProbeReadout {
            point: *point,
            mesh: instance.mesh,
            material: instance.material,
            position,
            distance: (params.camera.eye() - position).length(),
            uv,
            bump: instance.bump,
            march,
            bump_enabled: params.shading.bump_enabled,
            texel_xy: nearest.map(|n| n.0),
            texel_raw: nearest.map(|n| n.1),
            texel: match bump {
                Some(BumpSample::NormalMap(texel)) => Some(texel),
                _ => None,
            },
            tangent_method: frames.map(|f| f.method),
            chain,
        }
    }

    /// [`Self::pick`] then [`Self::readout`] with `params`' camera.
    pub fn probe(&self, params: &FrameParams, size: [u32; 2], pixel: [u32; 2]) -> Option<ProbeReadout> {
        self.pick(&params.camera, size, pixel).map(|point| self.readout(&point, params, size))
    }
}
