//! The chain after the texture reads, in the stages the WGSL has: the surface (the `*_surface`
//! functions of `shaders/mesh.wgsl`: geometric normal, tangent frame, the bump → the shading
//! normal), the coat's normal (`clearcoat_normal`), every light's terms, the lit colour
//! (`lit_color` and the legacy looks of `lit_or_legacy`, shaders/surface_color.wgsl) and the
//! colour the view stores (`surface_color`).

use glam::{Mat3, Vec3};

use super::detail::{self, DetailValues};
use super::mip::{self, MipInputs, MipValues};
use super::read::{BumpSample, SurfaceSample};
use super::{ChainValues, LightTerms, legacy, mistakes};
use crate::frame::{BumpKind, FrameParams, LegacyLook, LightingSpace, ShadingMode, SurfaceLighting, ViewMode};
use crate::math::{linear_to_srgb, normalize_or, smoothstep};
use crate::scene::{MAX_LIGHTS, Material, NormalMap, ShadingModel};
use crate::shading::lights::incident;
use crate::shading::pbr::{ClearcoatInputs, PbrInputs, metallic_roughness};
use crate::shading::spaces::{inverse_tbn, tangent_lighting_vectors, view_lighting_vectors};
use crate::shading::{
    LightingInputs, LightingVectors, NormalTexel, OVER_TILT_COLOR, SELF_SHADOW_FADE, blinn_phong, debug_color,
    decode_normal, handedness_color, object_space_normal, over_tilt_grey, over_tilted, packed_gloss,
    surface_gradient_normal, tangent_space_normal, world_vectors,
};

/// What every stage reads: the instance's bump kind, its material, the texture reads and
/// interpolated values at the point, and the frame.
#[derive(Clone, Copy)]
struct ChainPoint<'a> {
    bump: BumpKind,
    material: &'a Material,
    sample: &'a SurfaceSample,
    frame: &'a FrameParams,
}

/// The surface stage's values: the frame and the bump at the point.
struct Surface<'a> {
    /// The geometric normal, facing the viewer's side on a double-sided back face.
    n: Vec3,
    /// T, B and the handedness `w` (as the frame's mistake makes them); `None` without a
    /// tangent stream.
    tangent_frame: Option<(Vec3, Vec3, f32)>,
    /// The normal map the bump reads (tangent- or object-space bumps only).
    map: Option<&'a NormalMap>,
    strength: f32,
    texel: Option<NormalTexel>,
    decoded: Option<Vec3>,
    after_strength: Option<Vec3>,
    detail: Option<DetailValues>,
    /// The tangent-space normal taken to world space (after the detail blend).
    drawn_tangent_normal: Option<Vec3>,
    shading_normal: Vec3,
}

/// The chain after the texture reads: the surface, the bump, the mip filter's widening (by
/// `mip`), every light of `frame` (already dimmed by the relief's shadow) and the view's
/// colour at `sample`.
pub(super) fn lit(
    bump: BumpKind,
    material: &Material,
    sample: &SurfaceSample,
    frame: &FrameParams,
    mip: MipInputs,
) -> ChainValues {
    let at = ChainPoint { bump, material, sample, frame };
    let shading = &frame.shading;
    let surface = at.surface(&mip);
    let n = surface.n;
    let clearcoat_normal = at.clearcoat_normal(&surface);
    let tangent_space_normal = bump == BumpKind::TangentSpace && surface.tangent_frame.is_some();
    let lighting = shading.surface_lighting(material.shading_model, tangent_space_normal);
    let shininess = shading.shininess.unwrap_or(material.shininess).max(1.0);
    let metal_rough = sample.metallic_roughness.unwrap_or(Vec3::ONE);
    let roughness =
        (lighting.shading_model == ShadingModel::MetallicRoughness).then_some(material.roughness * metal_rough.y);
    let mip = MipValues::new(mip, surface.texel, (surface.strength, shading.bump_enabled), shininess, roughness);
    let eye = frame.camera.eye();
    let albedo = sample.base_color.unwrap_or(Vec3::ONE) * material.base_color_factor.truncate();
    let lit_albedo = if shading.mode == ShadingMode::BumpOnly { Vec3::ONE } else { albedo };
    let inputs = LightingInputs {
        albedo: lit_albedo,
        geometric_normal: n,
        shading_normal: surface.shading_normal,
        position: sample.position,
        eye,
        lights: frame.lights,
        specular: material.specular * sample.gloss.unwrap_or(Vec3::ONE) * (at.packed_gloss(&surface) * mip.energy),
        shininess: mip.shininess,
        specular_mode: shading.specular,
    };
    // The world-space directions the lighting sees: the per-vertex mistakes replace the first
    // light's (mistakes::seen_vectors).
    let seen = mistakes::seen_vectors(
        shading.mistake,
        world_vectors(&inputs),
        &frame.lights,
        sample.vertex_light,
        sample.vertex_half,
    );
    let dot3_light = at.dot3_light();
    let lit_color = match shading.mode {
        ShadingMode::ColourOnly => albedo,
        _ => at.lit_or_legacy(&surface, lighting, &inputs, &seen, dot3_light, (&mip, clearcoat_normal)),
    };
    let color_linear = lit_color + at.emission();
    ChainValues {
        march: None,
        texel: match sample.bump {
            Some(BumpSample::NormalMap(texel)) => Some(texel),
            _ => None,
        },
        decoded: surface.decoded,
        strength: surface.strength,
        after_strength: surface.after_strength,
        detail: surface.detail,
        tangent: surface.tangent_frame.map(|f| f.0),
        bitangent: surface.tangent_frame.map(|f| f.1),
        w: surface.tangent_frame.map(|f| f.2),
        normal: n,
        shading_normal: surface.shading_normal,
        clearcoat_normal,
        view_dir: normalize_or(eye - sample.position, n),
        vertex_light: sample.vertex_light,
        dot3_light,
        lights: at.light_terms(n, surface.shading_normal, &seen),
        albedo,
        shading_model: lighting.shading_model,
        lighting_space: lighting.lighting_space,
        mip,
        color_linear,
        shown: at.surface_color(&surface, clearcoat_normal, color_linear),
    }
}

impl ChainPoint<'_> {
    /// The `*_surface` functions of mesh.wgsl: the geometric normal, the tangent frame and the
    /// bump by the instance's kind (the classic mistakes beside the right path).
    fn surface(&self, mip: &MipInputs) -> Surface<'_> {
        let (bump, material, sample, shading) = (self.bump, self.material, self.sample, &self.frame.shading);
        let facing = if sample.front_facing { 1.0 } else { -1.0 };
        let n = normalize_or(sample.world_normal, Vec3::Z) * facing;
        let mistake = shading.mistake;
        let tangent_frame = sample.world_tangent.map(|world| mistakes::tangent_frame(mistake, world, n));
        let base = mistakes::base_normal(mistake, sample.world_normal, facing, n);

        let map =
            material.normal_map.as_ref().filter(|_| matches!(bump, BumpKind::TangentSpace | BumpKind::ObjectSpace));
        let strength = shading.strength * map.map_or(1.0, |m| m.scale);
        let texel = match sample.bump {
            Some(BumpSample::NormalMap(texel)) => {
                map.map(|_| mistakes::texel_read(mistake, mip::lean_texel(texel, mip)))
            }
            _ => None,
        };
        let convention = map.map(|m| mistakes::convention_read(mistake, m.convention));
        let decoded = texel.zip(convention).map(|(texel, c)| decode_normal(texel, c));
        let after_strength =
            decoded.filter(|_| bump == BumpKind::TangentSpace).map(|d| tangent_space_normal(d, strength));
        let detail = detail::values(material, sample.detail, after_strength, shading);
        let drawn_tangent_normal = detail.map_or(after_strength, |d| Some(d.blended));
        let slopes = sample.bump;
        let shading_normal =
            match (shading.bump_enabled, bump, tangent_frame, drawn_tangent_normal, texel, convention, slopes) {
                (true, BumpKind::TangentSpace, Some((t, b, _)), Some(nt), ..) => {
                    mistakes::to_world(mistake, t, b, base, nt)
                }
                (true, BumpKind::ObjectSpace, _, _, Some(texel), Some(c), _) => {
                    object_space_normal(n, sample.normal_matrix, sample.front_facing, texel, strength, c)
                }
                (true, BumpKind::HeightInShader, .., Some(BumpSample::HeightSlopes { dp_dx, dp_dy, dh_dx, dh_dy })) => {
                    let height = material.height_map.as_ref();
                    let depth_sign = if height.is_some_and(|h| h.depth) { -1.0 } else { 1.0 };
                    let metres = depth_sign * height.map_or(0.0, |h| h.range_m) * shading.strength;
                    surface_gradient_normal(n, dp_dx, dp_dy, dh_dx * metres, dh_dy * metres)
                }
                _ => base,
            };
        Surface {
            n,
            tangent_frame,
            map,
            strength,
            texel,
            decoded,
            after_strength,
            detail,
            drawn_tangent_normal,
            shading_normal,
        }
    }

    /// WGSL `clearcoat_normal`: the coat's normal map through T, B, N; else the geometric
    /// normal.
    fn clearcoat_normal(&self, surface: &Surface) -> Vec3 {
        let shading = &self.frame.shading;
        let coat_map = self.material.visible_clearcoat().and_then(|c| c.normal_map.as_ref());
        match (shading.bump_enabled, surface.tangent_frame, coat_map, self.sample.clearcoat_normal) {
            (true, Some((t, b, _)), Some(map), Some(texel)) => {
                let decoded = decode_normal(NormalTexel::rgb(texel), map.convention);
                let nt = tangent_space_normal(decoded, shading.strength * map.scale);
                mistakes::to_world(shading.mistake, t, b, surface.n, nt)
            }
            _ => surface.n,
        }
    }

    /// X-Ray's bump carries a gloss that scales k_s (1 for the other layouts).
    fn packed_gloss(&self, surface: &Surface) -> f32 {
        match self.sample.bump {
            Some(BumpSample::NormalMap(raw)) => surface.map.map_or(1.0, |m| packed_gloss(raw, m.convention.layout)),
            _ => 1.0,
        }
    }

    /// Each light that is on at the point, as the lighting sees it (`seen`).
    fn light_terms(&self, n: Vec3, shading_normal: Vec3, seen: &LightingVectors) -> [Option<LightTerms>; MAX_LIGHTS] {
        let (lights_in, position) = (&self.frame.lights, self.sample.position);
        let mut lights = [None; MAX_LIGHTS];
        let on = lights.iter_mut().zip(lights_in.as_slice()).enumerate().filter(|(_, (_, light))| light.enabled);
        for (k, (terms, light)) in on {
            let arriving = incident(light, position, n);
            let (l, v) = (seen.lights[k], seen.views[k]);
            let n_dot_l = shading_normal.dot(l);
            let half = normalize_or(l + v, n);
            *terms = Some(LightTerms {
                direction: l,
                half,
                n_dot_l,
                n_dot_h: shading_normal.dot(half),
                r_dot_v: (2.0 * n_dot_l * shading_normal - l).dot(v),
                self_shadow: smoothstep(0.0, SELF_SHADOW_FADE, n.dot(l)),
                attenuation: arriving.attenuation,
                radiance: arriving.radiance,
            });
        }
        lights
    }

    /// DOT3's light vector: the per-vertex direction, through the normalization cube map when
    /// the look uses one; `None` outside DOT3.
    fn dot3_light(&self) -> Option<Vec3> {
        let legacy = self.frame.shading.legacy;
        (legacy.look == LegacyLook::Dot3).then(|| match legacy.cube_map_in_use() {
            Some(size) => legacy::cube_map_lookup(&legacy::cube_map(size), size, self.sample.vertex_light),
            None => self.sample.vertex_light,
        })
    }

    /// Emitted light: in the bump × colour picture only (not in the legacy looks).
    fn emission(&self) -> Vec3 {
        match self.frame.shading.mode {
            _ if self.frame.shading.legacy.look != LegacyLook::Off => Vec3::ZERO,
            ShadingMode::BumpTimesColour => self.material.emissive_factor * self.sample.emissive.unwrap_or(Vec3::ONE),
            ShadingMode::BumpOnly | ShadingMode::ColourOnly => Vec3::ZERO,
        }
    }

    /// WGSL `lit_or_legacy` and `lit_color` (without the emission): a legacy look, else the
    /// point lit in `lighting`'s model and space. `mip` and the coat's normal feed
    /// metallic-roughness.
    fn lit_or_legacy(
        &self,
        surface: &Surface,
        lighting: SurfaceLighting,
        inputs: &LightingInputs,
        seen: &LightingVectors,
        dot3_light: Option<Vec3>,
        (mip, clearcoat_normal): (&MipValues, Vec3),
    ) -> Vec3 {
        let (material, sample, frame, shading) = (self.material, self.sample, self.frame, &self.frame.shading);
        let (n, shading_normal, lit_albedo) = (surface.n, surface.shading_normal, inputs.albedo);
        let legacy = shading.legacy;
        let first = frame.lights.first_on().map(|light| (light, incident(light, sample.position, n)));
        match lighting.shading_model {
            // The legacy looks light with the first light that is on (the ambient light alone
            // without one), seen from where it is, whatever the mistake.
            _ if legacy.look == LegacyLook::Dot3 => match first {
                Some((_, arriving)) => {
                    legacy::dot3_color(lit_albedo, arriving.radiance, shading_normal, dot3_light.unwrap_or(Vec3::ZERO))
                }
                None => lit_albedo * frame.lights.ambient(),
            },
            _ if legacy.look == LegacyLook::Emboss => match (sample.emboss, surface.tangent_frame, first) {
                (Some(emboss), Some((t, b, _)), Some((light, arriving))) => {
                    let offset = legacy::emboss_light_offset(t, b, legacy::emboss_to_light(light, sample.position, n));
                    let strength = if shading.bump_enabled { shading.strength } else { 0.0 };
                    legacy::emboss_color(lit_albedo, arriving.radiance, &emboss, offset, strength)
                }
                _ => lit_albedo * frame.lights.ambient(),
            },
            ShadingModel::BlinnPhong => {
                let vectors = match lighting.lighting_space {
                    LightingSpace::World => *seen,
                    LightingSpace::Tangent => {
                        let own = surface.tangent_frame.map_or(Mat3::IDENTITY, |(t, b, _)| inverse_tbn(t, b, n));
                        let tangent_normal = if shading.bump_enabled { surface.drawn_tangent_normal } else { None };
                        let to_tangent = sample.triangle_frame.unwrap_or(own);
                        tangent_lighting_vectors(seen, to_tangent, tangent_normal.unwrap_or(Vec3::Z))
                    }
                    LightingSpace::View => view_lighting_vectors(seen, frame.camera.view_rotation()),
                };
                blinn_phong(inputs, &vectors)
            }
            ShadingModel::MetallicRoughness => {
                let metal_rough = sample.metallic_roughness.unwrap_or(Vec3::ONE);
                let occlusion_strength = material.occlusion.as_ref().map_or(0.0, |o| o.strength);
                metallic_roughness(&PbrInputs {
                    base_color: lit_albedo,
                    metallic: material.metallic * metal_rough.z,
                    roughness: mip.roughness.unwrap_or(material.roughness * metal_rough.y),
                    occlusion: 1.0 + occlusion_strength * (sample.occlusion.unwrap_or(1.0) - 1.0),
                    geometric_normal: n,
                    shading_normal,
                    position: sample.position,
                    eye: inputs.eye,
                    lights: frame.lights,
                    seen: Some(*seen),
                    clearcoat: material.visible_clearcoat().map(|c| ClearcoatInputs {
                        factor: c.factor * sample.clearcoat.unwrap_or(1.0),
                        roughness: c.roughness * sample.clearcoat_roughness.unwrap_or(1.0),
                        normal: clearcoat_normal,
                    }),
                })
            }
        }
    }

    /// WGSL `surface_color`: what the frame's view stores, 0..1, from the lit colour
    /// `color_linear`; `None` for the Difference and UV check views.
    fn surface_color(&self, surface: &Surface, clearcoat_normal: Vec3, color_linear: Vec3) -> Option<Vec3> {
        let (n, shading_normal, frame_tb) = (surface.n, surface.shading_normal, surface.tangent_frame);
        let zero = Vec3::ZERO;
        match self.frame.shading.view {
            ViewMode::Lit => Some(color_linear.map(linear_to_srgb)),
            ViewMode::OverTilt if over_tilted(n, shading_normal) => Some(OVER_TILT_COLOR),
            ViewMode::OverTilt => Some(over_tilt_grey(color_linear).map(linear_to_srgb)),
            ViewMode::Tangent => Some(debug_color(frame_tb.map_or(zero, |f| f.0))),
            ViewMode::Bitangent => Some(debug_color(frame_tb.map_or(zero, |f| f.1))),
            ViewMode::Normal => Some(debug_color(n)),
            ViewMode::ShadingNormal => Some(debug_color(shading_normal)),
            ViewMode::Handedness => {
                Some(handedness_color(frame_tb.map(|f| f.2), n, self.frame.camera.eye() - self.sample.position))
            }
            ViewMode::ClearcoatNormal => Some(debug_color(clearcoat_normal)),
            ViewMode::Difference | ViewMode::UvCheck => None,
        }
    }
}
