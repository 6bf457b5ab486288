//! The pixel probe: the whole shading chain at one pixel of the 3D view, on the CPU.
//!
//! [`ProbeScene::pick`] casts the ray through a pixel's centre ([`OrbitCamera::ray_through_pixel`])
//! against every drawn triangle in world space (brute force, nearest hit; back faces of
//! single-sided materials are culled as on the GPU) and pins the surface point as a triangle
//! and its barycentric coordinates ([`ProbePoint`]). [`ProbeScene::readout`] then hands the
//! chain ([`crate::chain::shade`]) the point as the GPU's fragment stage gets it
//! ([`fragment::Pixel`]): what the vertex shader passes on, interpolated (position, normal, UV,
//! tangent frame — the frames the renderer draws with: the same [`tangent::resolve`] on the
//! same, possibly unwelded, mesh with the same scene options and material overrides), the
//! textures read as the GPU's trilinear sampler reads them, and the derivatives of the pixel's
//! 2×2 quad. The chain marches parallax, reads, bumps and lights; the probe holds no shading
//! step. The pinned point stays where it is when the camera or light moves; only the readout
//! is recomputed.
//!
//! Spaces and units follow the crate conventions: positions in metres, world space; vectors
//! unit length, world space unless named tangent space; colours linear RGB 0..1 unless named
//! sRGB. The barycentric coordinates of a ray-triangle hit are the perspective-correct ones
//! the rasteriser interpolates with, so the interpolated values equal the GPU's up to float
//! rounding. Screen-space derivatives (texture footprints, the parallax footprint, the height
//! bump, the triangle frame of tangent-space lighting) come from the values at the four pixel
//! centres of the 2×2 quad holding the point's pixel, found on the triangle's plane as the
//! rasteriser does for the quad. Where the GPU downscaled a texture larger than the adapter
//! allows, the probe differs from the picture.

mod fragment;
mod pick;

use std::borrow::Cow;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use crate::chain::{ChainValues, Fragment, MarchValues, shade};
use crate::frame::{BumpKind, FrameParams, SceneOptions};
use crate::prepare::PreparedScene;
pub use crate::scene::sample::{nearest_texel, sample_bilinear};
use crate::scene::{OrbitCamera, Scene, TextureImage};
use crate::shading::NormalTexel;
use crate::tangent::TangentMethod;
use fragment::Pixel;
pub use pick::project_to_pixel;
use pick::{corner_positions, intersect};

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
    /// The parallax march at the point, as the chain made it (`chain.march`; `None`: parallax
    /// off, depth 0, or no height map on a normal-mapped surface). The textures below are read
    /// at its shifted UV.
    pub march: Option<MarchValues>,
    /// Whether bump mapping is on (the `B` toggle); off, the shading normal is `normal`.
    pub bump_enabled: bool,
    /// The normal map's texel containing `uv` at mip 0: its integer coordinates and raw bytes
    /// (RGBA, 0–255, before filtering).
    pub texel_xy: Option<[u32; 2]>,
    pub texel_raw: Option<[u8; 4]>,
    /// The normal map's filtered sample at the read UV (RGBA, 0..1, linear; at the mip levels
    /// the GPU reads, with X-Ray's `bump#` correction): what the shader decodes (`chain.texel`).
    pub texel: Option<NormalTexel>,
    /// The tangent method the frames come from.
    pub tangent_method: Option<TangentMethod>,
    /// Every value of the shading chain at the point ([`crate::chain::shade`]): the decoded
    /// texel, after strength, T, B, N, w, shading normal, N·L, N·H, colour and what the view stores.
    pub chain: ChainValues,
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
    /// Per texture: LEAN's texture as uploaded ([`PreparedScene::lean_texture`]); empty where
    /// no instance draws it with LEAN.
    lean: Vec<Vec<crate::texture::LeanTexels>>,
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
            .map(|index| {
                if used(&index) {
                    prepared.mip_chain(index).map_or_else(|_| prepared.neutral_chain(index), Cow::into_owned)
                } else {
                    vec![]
                }
            })
            .collect();
        let lean =
            (0..prepared.scene.textures.len()).map(|index| prepared.lean_texture(index).unwrap_or_default()).collect();
        ProbeScene { prepared, mips, lean }
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
    /// `size` pixels large (texture footprints, the parallax march and the height bump depend
    /// on the pixel grid): [`crate::chain::shade`] on the point as the fragment stage gets it.
    pub fn readout(&self, point: &ProbePoint, params: &FrameParams, size: [u32; 2]) -> ProbeReadout {
        let pixel = Pixel::new(self, point, params, size);
        let (instance, material) = (pixel.instance, pixel.material);
        let chain = shade(instance.bump, material, &pixel, params);
        let at = pixel.varyings();
        // The normal map's texel holding the read UV at mip 0, as stored.
        let read_uv = chain.march.map_or(at.uv, |m| m.uv);
        let normal_map =
            instance.textures.bump.filter(|_| matches!(instance.bump, BumpKind::TangentSpace | BumpKind::ObjectSpace));
        let nearest = normal_map.map(|t| {
            let texture = &self.scene().textures[t];
            let xy = nearest_texel(texture, read_uv, material.detail_wrap);
            (xy, texture.texel(xy[0] as i64, xy[1] as i64))
        });
        ProbeReadout {
            point: *point,
            mesh: instance.mesh,
            material: instance.material,
            position: at.position,
            distance: (params.camera.eye() - at.position).length(),
            uv: at.uv,
            bump: instance.bump,
            march: chain.march,
            bump_enabled: params.shading.bump_enabled,
            texel_xy: nearest.map(|n| n.0),
            texel_raw: nearest.map(|n| n.1),
            texel: chain.texel,
            tangent_method: pixel.frames.map(|f| f.method),
            chain,
        }
    }

    /// [`Self::pick`] then [`Self::readout`] with `params`' camera.
    pub fn probe(&self, params: &FrameParams, size: [u32; 2], pixel: [u32; 2]) -> Option<ProbeReadout> {
        self.pick(&params.camera, size, pixel).map(|point| self.readout(&point, params, size))
    }
}
