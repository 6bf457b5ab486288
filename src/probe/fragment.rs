//! The probe's fragment ([`Fragment`]): the vertex stage's outputs interpolated at a pinned
//! point (the frames the renderer draws with, on the same possibly unwelded mesh), the
//! textures the instance binds read as the GPU's trilinear sampler reads them (level of detail
//! from the footprint, [`sample_trilinear`] on the uploaded mip chain), and fine derivatives
//! over the 2×2 pixel quad holding the point's pixel, each of its pixels interpolated where
//! its centre's ray meets the triangle's plane ([`Quad`]). No shading here: the chain decides
//! what is read where.

use glam::{Mat3, Mat4, UVec2, Vec2, Vec3, Vec4};

use super::ProbeScene;
use super::pick::{Quad, corner_positions};
use crate::chain::legacy::vertex_vectors;
use crate::chain::{Footprint, Fragment, Map, Varyings};
use crate::frame::FrameParams;
use crate::math::normal_matrix;
use crate::prepare::{DrawnFrames, PreparedInstance};
use crate::scene::sample::{sample_trilinear, sample_trilinear_texels};
use crate::scene::{Material, Mesh, SamplerWrap};

/// One pinned point of one instance seen in a view.
pub struct Pixel<'a> {
    probe: &'a ProbeScene,
    pub instance: &'a PreparedInstance,
    pub material: &'a Material,
    mesh: &'a Mesh,
    pub frames: Option<&'a DrawnFrames>,
    corners: &'a [u32],
    barycentric: Vec3,
    front_facing: bool,
    model: Mat4,
    normal_matrix: Mat4,
    params: &'a FrameParams,
    quad: Option<Quad<'a>>,
}

impl<'a> Pixel<'a> {
    /// The point on `triangle` of `instance` at `barycentric` in a `size` view under `params`.
    pub fn new(probe: &'a ProbeScene, point: &super::ProbePoint, params: &'a FrameParams, size: [u32; 2]) -> Self {
        let instance = &probe.prepared.instances[point.instance];
        let prepared_mesh = &probe.prepared.meshes[instance.mesh];
        let mesh = &prepared_mesh.mesh;
        let corners = &mesh.indices[3 * point.triangle..3 * point.triangle + 3];
        let mut pixel = Pixel {
            probe,
            instance,
            material: &probe.scene().materials[instance.material],
            mesh,
            frames: prepared_mesh.frames.as_ref(),
            corners,
            barycentric: point.barycentric,
            front_facing: point.front_facing,
            model: instance.transform,
            normal_matrix: normal_matrix(instance.transform),
            params,
            quad: None,
        };
        let position = pixel.varyings().position;
        pixel.quad = corner_positions(mesh, corners, &pixel.model).map(|triangle| Quad {
            camera: &params.camera,
            size,
            triangle,
            position,
        });
        pixel
    }

    /// The corners' `values` weighted by `barycentric`.
    fn mix<T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T> + Copy>(
        &self,
        barycentric: Vec3,
        value: impl Fn(usize) -> T,
    ) -> T {
        let [a, b, c] = [0, 1, 2].map(|k| value(self.corners[k] as usize));
        a * barycentric.x + b * barycentric.y + c * barycentric.z
    }

    /// The vertex stage's outputs at `barycentric`, at world `position`.
    fn varyings_at(&self, barycentric: Vec3, position: Vec3) -> Varyings {
        let mirror = if self.instance.mirrored() { -1.0 } else { 1.0 };
        let world_tangent = self.frames.map(|f| {
            let t = self.mix(barycentric, |i| f.tangents[i]);
            self.model.transform_vector3(t.truncate()).extend(t.w * mirror)
        });
        let (eye, first) = (self.params.camera.eye(), self.params.lights.first_on());
        let per_vertex = |i: usize| {
            let p = self.model.transform_point3(self.mesh.positions[i]);
            let n = self.normal_matrix.transform_vector3(self.mesh.normals[i]);
            let (l, h) = vertex_vectors(p, n, first, eye);
            Mat3::from_cols(l, h, Vec3::ZERO)
        };
        let vectors = self.mix(barycentric, per_vertex);
        Varyings {
            position,
            world_normal: self.normal_matrix.transform_vector3(self.mix(barycentric, |i| self.mesh.normals[i])),
            uv: self.mix(barycentric, |i| self.mesh.uvs.get(i).copied().unwrap_or(Vec2::ZERO)),
            world_tangent,
            vertex_light: vectors.x_axis,
            vertex_half: vectors.y_axis,
        }
    }

    /// The texture bound at `map` and the sampler it is read with.
    fn texture(&self, map: Map) -> Option<(usize, SamplerWrap)> {
        let (slots, material) = (&self.instance.textures, self.material);
        let (detail, base) = (material.detail_wrap, material.base_color_wrap);
        match map {
            Map::BaseColor => material.base_color_texture.map(|t| (t, base)),
            Map::Emissive => slots.emissive.map(|t| (t, base)),
            Map::Bump => slots.bump.map(|t| (t, detail)),
            Map::BumpCorrection => slots.bump_correction.map(|t| (t, detail)),
            Map::MetallicRoughness => slots.metallic_roughness.map(|t| (t, detail)),
            Map::Occlusion => slots.occlusion.map(|t| (t, detail)),
            Map::Gloss => slots.gloss.map(|t| (t, detail)),
            Map::Clearcoat => slots.clearcoat.map(|t| (t, detail)),
            Map::ClearcoatRoughness => slots.clearcoat_roughness.map(|t| (t, detail)),
            Map::ClearcoatNormal => slots.clearcoat_normal.map(|t| (t, detail)),
            Map::Height => slots.height.map(|t| (t, detail)),
            Map::Detail => slots.detail.map(|t| (t, detail)),
        }
    }

    /// The uploaded mip chain of the texture at `map` (level 0 first) and its sampler.
    fn mips(&self, map: Map) -> Option<(&'a [crate::scene::TextureImage], SamplerWrap)> {
        let probe: &'a ProbeScene = self.probe;
        let (texture, wrap) = self.texture(map)?;
        probe.mips.get(texture).filter(|chain| !chain.is_empty()).map(|chain| (chain.as_slice(), wrap))
    }
}

impl Fragment for Pixel<'_> {
    fn varyings(&self) -> Varyings {
        let position = self.model.transform_point3(self.mix(self.barycentric, |i| self.mesh.positions[i]));
        self.varyings_at(self.barycentric, position)
    }

    fn front_facing(&self) -> bool {
        self.front_facing
    }

    fn normal_matrix(&self) -> Mat3 {
        Mat3::from_mat4(self.normal_matrix)
    }

    fn derivatives<T: std::ops::Sub<Output = T> + Copy>(&self, value: impl Fn(&Varyings) -> T) -> Option<(T, T)> {
        self.quad.as_ref()?.derivatives(|b, p| value(&self.varyings_at(b, p)))
    }

    fn sample(&self, map: Map, uv: Vec2, footprint: Footprint) -> Option<Vec4> {
        self.mips(map).map(|(chain, wrap)| sample_trilinear(chain, uv, wrap, footprint))
    }

    fn size(&self, map: Map) -> Option<UVec2> {
        self.mips(map).map(|(chain, _)| UVec2::new(chain[0].width, chain[0].height))
    }

    fn mip_filter(&self) -> crate::texture::MipFilter {
        self.instance.mip_filter
    }

    fn lean_moments(&self, uv: Vec2, footprint: Footprint) -> Option<Vec4> {
        if self.instance.mip_filter != crate::texture::MipFilter::Lean {
            return None;
        }
        let (texture, wrap) = self.texture(Map::Bump)?;
        let chain = self.probe.lean.get(texture).filter(|chain| !chain.is_empty())?;
        Some(sample_trilinear_texels(chain, uv, wrap, footprint))
    }
}
