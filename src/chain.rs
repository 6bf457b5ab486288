//! The one CPU shading chain: the twin of the fragment stage of `shaders/mesh.wgsl` (with
//! `parallax.wgsl`, `mistakes.wgsl`, `legacy.wgsl`, `lights.wgsl`, `pbr.wgsl`), step by step,
//! returning every intermediate value. [`shade`] takes what the fragment shader gets — the
//! interpolated vertex outputs and a texture sampler with quad derivatives, a [`Fragment`] —
//! and runs the same formulas ([`crate::shading`]) in the same order: the parallax march and
//! the UV it shifts ([`parallax`]), the texture reads there, the geometric normal, the tangent
//! frame, the bump by the instance's [`BumpKind`] (the classic [`mistakes`] beside the right
//! path), every light dimmed by the relief's soft shadow and lit in the frame's
//! [`ShadingMode`] with the material's (or the overriding) shading model (or a [`legacy`]
//! look), and the colour the frame's [`ViewMode`] stores. The pixel probe, the report and the
//! CPU reference tests call it; none of them holds a shading step of its own.
//!
//! Spaces and units follow the crate conventions: positions in metres, world space; vectors
//! unit length, world space unless named tangent space; colours linear RGB 0..1 unless named
//! stored (what the target holds: sRGB-encoded for the lit picture, `0.5·v + 0.5` for
//! vector views).

pub mod detail;
pub mod fragment;
pub mod legacy;
mod mip;
pub mod mistakes;
pub mod parallax;
mod read;
mod relief;

pub use detail::DetailValues;
pub use fragment::{Footprint, Fragment, Map, Varyings};
pub use mip::{MipInputs, MipValues};
use read::{BumpSample, SurfaceSample};
pub use relief::MarchValues;

use glam::{Mat3, Vec3};

use crate::frame::{BumpKind, FrameParams, LegacyLook, LightingSpace, MipFilter, ShadingMode, ViewMode};
use crate::math::{linear_to_srgb, normalize_or, smoothstep};
use crate::scene::{MAX_LIGHTS, Material, ShadingModel};
use crate::shading::lights::incident;
use crate::shading::pbr::{ClearcoatInputs, PbrInputs, metallic_roughness};
use crate::shading::spaces::{inverse_tbn, tangent_lighting_vectors, view_lighting_vectors};
use crate::shading::{
    LightingInputs, NormalTexel, OVER_TILT_COLOR, SELF_SHADOW_FADE, blinn_phong, debug_color, decode_normal,
    handedness_color, object_space_normal, over_tilt_grey, over_tilted, packed_gloss, surface_gradient_normal,
    tangent_space_normal, world_vectors,
};

/// Every value along the chain at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainValues {
    /// The parallax step ([`MarchValues`]); `None`: parallax off, depth 0, no height map bound,
    /// or no quad derivatives. The textures are read at its shifted UV.
    pub march: Option<MarchValues>,
    /// The normal map's filtered texel as read (RGBA 0..1 linear, with X-Ray's `bump#`),
    /// before any mistake; `None` without a normal map.
    pub texel: Option<NormalTexel>,
    /// The decoded normal-map vector ([`decode_normal`]): tangent space, or model space for an
    /// object-space map. `None` without a normal map.
    pub decoded: Option<Vec3>,
    /// The effective strength: the frame's strength times the material's `normalTexture.scale`
    /// (the height bump uses the frame's strength alone).
    pub strength: f32,
    /// Tangent-space normal after strength, `normalize(x·s, y·s, max(z, 0))` (tangent-space
    /// maps only).
    pub after_strength: Option<Vec3>,
    /// The detail step ([`DetailValues`]: base, detail and blended tangent-space normals);
    /// `None` without a detail map. Its blended normal is what goes to world space.
    pub detail: Option<DetailValues>,
    /// World-space tangent after Gram-Schmidt against `normal`, bitangent `w · cross(N, T)`,
    /// handedness `w = ±1`; `None` without a tangent stream.
    pub tangent: Option<Vec3>,
    pub bitangent: Option<Vec3>,
    pub w: Option<f32>,
    /// The geometric normal, facing the viewer's side on a double-sided back face.
    pub normal: Vec3,
    /// The normal used for lighting.
    pub shading_normal: Vec3,
    /// The clear-coat layer's normal (its normal map through T, B, N; else `normal`).
    pub clearcoat_normal: Vec3,
    /// Unit direction from the point to the eye.
    pub view_dir: Vec3,
    /// The per-vertex light direction as interpolated ([`SurfaceSample::vertex_light`]), and
    /// the light vector DOT3 lit with: that one, or it through the normalization cube map;
    /// `None` outside DOT3.
    pub vertex_light: Vec3,
    pub dot3_light: Option<Vec3>,
    /// Each of the frame's lights at the point, in the frame's order; `None` for a light
    /// that is off and past the last light. Under the per-vertex mistakes the first light
    /// that is on has the direction and half vector the mistake sees
    /// ([`mistakes::seen_light_direction`], [`mistakes::seen_view_direction`]).
    pub lights: [Option<LightTerms>; MAX_LIGHTS],
    /// Linear albedo: base colour texture times the factor.
    pub albedo: Vec3,
    /// The model the point is lit with (the frame's override, else the material's).
    pub shading_model: ShadingModel,
    /// The space the point is lit in: the frame's for the classic model on tangent-space
    /// normal-mapped surfaces with a tangent frame, else world space.
    pub lighting_space: LightingSpace,
    /// The normal map's mip filtering at the point ([`MipValues`]): the method, the level of
    /// detail, `|Na|`, and the exponent or roughness it widens to.
    pub mip: MipValues,
    /// The lit colour in the frame's shading mode, linear RGB.
    pub color_linear: Vec3,
    /// What the frame's view stores, 0..1; `None` for the Difference and UV check views,
    /// which need screen-space data of a whole triangle.
    pub shown: Option<Vec3>,
}

/// One light at one point of the chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightTerms {
    /// Unit direction from the point to the light, and its half vector with the view direction.
    pub direction: Vec3,
    pub half: Vec3,
    /// `N·L`, `N·H` and `R·V` (`R = 2(N·L)N − L`) with the shading normal, signed (the
    /// shading uses `max(·, 0)`).
    pub n_dot_l: f32,
    pub n_dot_h: f32,
    pub r_dot_v: f32,
    /// The geometric self-shadow fade `smoothstep(0, SELF_SHADOW_FADE, N_geo·L)`, 0..1.
    pub self_shadow: f32,
    /// The distance attenuation (1 for a directional light) and the radiance arriving,
    /// `color · intensity · attenuation`, linear RGB.
    pub attenuation: f32,
    pub radiance: Vec3,
}

/// The fragment stage at `fragment` on an instance bumped by `bump`, drawn with `material`
/// under `frame` (whose lights carry the ambient light), in the shader's order: the parallax
/// step (the UV and footprint the textures are read with), the texture reads, the frame, the
/// bump, every light dimmed by the relief's soft shadow, and the colour the view stores.
pub fn shade(bump: BumpKind, material: &Material, fragment: &impl Fragment, frame: &FrameParams) -> ChainValues {
    let at = fragment.varyings();
    let facing = if fragment.front_facing() { 1.0 } else { -1.0 };
    let step = relief::step(material, fragment, &at, facing, frame);
    let n = normalize_or(at.world_normal, Vec3::Z) * facing;
    let surface = read::read(bump, material, fragment, &at, (step.uv, step.footprint), n, frame);
    let (dimmed, visibility) = relief::shadowed(material, fragment, &step, at.position, frame);
    let filter = fragment.mip_filter();
    // Geometric specular AA differentiates the shading normal over the quad: each pixel's own
    // chain up to its normal (its own UV, without the parallax shift).
    let normal_derivatives = (filter == MipFilter::GeometricSpecularAa)
        .then(|| {
            fragment.derivatives(|v| {
                let n = normalize_or(v.world_normal, Vec3::Z) * facing;
                let surface = read::read(bump, material, fragment, v, (v.uv, step.footprint), n, frame);
                lit(bump, material, &surface, frame, MipInputs::NONE).shading_normal
            })
        })
        .flatten();
    let lod = mip::normal_map_lod(fragment, step.footprint).filter(|_| surface.bump.is_some());
    let moments = (filter == MipFilter::Lean).then(|| fragment.lean_moments(step.uv, step.footprint)).flatten();
    let inputs = MipInputs { filter, normal_derivatives, lod, moments };
    let values = lit(bump, material, &surface, &dimmed, inputs);
    ChainValues { march: relief::values(material, fragment, &step, visibility, &values), ..values }
}

/// The chain after the texture reads: the frame, the bump, the mip filter's widening (by
/// `mip`), every light of `frame` (already dimmed by the relief's shadow) and the view's
/// colour at `point`.
fn lit(bump: BumpKind, material: &Material, point: &SurfaceSample, frame: &FrameParams, mip: MipInputs) -> ChainValues {
    let shading = &frame.shading;
    let facing = if point.front_facing { 1.0 } else { -1.0 };
    let n = normalize_or(point.world_normal, Vec3::Z) * facing;
    let mistake = shading.mistake;
    let tangent_frame = point.world_tangent.map(|world| mistakes::tangent_frame(mistake, world, n));
    let base = mistakes::base_normal(mistake, point.world_normal, facing, n);

    let map = material.normal_map.as_ref().filter(|_| matches!(bump, BumpKind::TangentSpace | BumpKind::ObjectSpace));
    let strength = shading.strength * map.map_or(1.0, |m| m.scale);
    let texel = match point.bump {
        Some(BumpSample::NormalMap(texel)) => map.map(|_| mistakes::texel_read(mistake, mip::lean_texel(texel, &mip))),
        _ => None,
    };
    let convention = map.map(|m| mistakes::convention_read(mistake, m.convention));
    let decoded = texel.zip(convention).map(|(texel, c)| decode_normal(texel, c));
    let after_strength = decoded.filter(|_| bump == BumpKind::TangentSpace).map(|d| tangent_space_normal(d, strength));
    let detail = detail::values(material, point.detail, after_strength, shading);
    let drawn_tangent_normal = detail.map_or(after_strength, |d| Some(d.blended));
    let slopes = point.bump;
    let shading_normal =
        match (shading.bump_enabled, bump, tangent_frame, drawn_tangent_normal, texel, convention, slopes) {
            (true, BumpKind::TangentSpace, Some((t, b, _)), Some(nt), ..) => {
                mistakes::to_world(mistake, t, b, base, nt)
            }
            (true, BumpKind::ObjectSpace, _, _, Some(texel), Some(c), _) => {
                object_space_normal(n, point.normal_matrix, point.front_facing, texel, strength, c)
            }
            (true, BumpKind::HeightInShader, .., Some(BumpSample::HeightSlopes { dp_dx, dp_dy, dh_dx, dh_dy })) => {
                let height = material.height_map.as_ref();
                let depth_sign = if height.is_some_and(|h| h.depth) { -1.0 } else { 1.0 };
                let metres = depth_sign * height.map_or(0.0, |h| h.range_m) * shading.strength;
                surface_gradient_normal(n, dp_dx, dp_dy, dh_dx * metres, dh_dy * metres)
            }
            _ => base,
        };

    let coat = material.visible_clearcoat();
    let coat_map = coat.and_then(|c| c.normal_map.as_ref());
    let clearcoat_normal = match (shading.bump_enabled, tangent_frame, coat_map, point.clearcoat_normal) {
        (true, Some((t, b, _)), Some(map), Some(texel)) => {
            let decoded = decode_normal(NormalTexel::rgb(texel), map.convention);
            let nt = tangent_space_normal(decoded, shading.strength * map.scale);
            mistakes::to_world(mistake, t, b, n, nt)
        }
        _ => n,
    };

    // X-Ray's bump carries a gloss that scales k_s (1 for the other layouts).
    let gloss = match point.bump {
        Some(BumpSample::NormalMap(raw)) => map.map_or(1.0, |m| packed_gloss(raw, m.convention.layout)),
        _ => 1.0,
    };
    let shading_model = shading.shading_override.unwrap_or(material.shading_model);
    let shininess = shading.shininess.unwrap_or(material.shininess).max(1.0);
    let metal_rough = point.metallic_roughness.unwrap_or(Vec3::ONE);
    let roughness = (shading_model == ShadingModel::MetallicRoughness).then(|| material.roughness * metal_rough.y);
    let mip = MipValues::new(mip, texel, (strength, shading.bump_enabled), shininess, roughness);
    let eye = frame.camera.eye();
    let view_dir = normalize_or(eye - point.position, n);
    let albedo = point.base_color.unwrap_or(Vec3::ONE) * material.base_color_factor.truncate();
    let lit_albedo = if shading.mode == ShadingMode::BumpOnly { Vec3::ONE } else { albedo };
    let inputs = LightingInputs {
        albedo: lit_albedo,
        geometric_normal: n,
        shading_normal,
        position: point.position,
        eye,
        lights: frame.lights,
        specular: material.specular * point.gloss.unwrap_or(Vec3::ONE) * (gloss * mip.energy),
        shininess: mip.shininess,
        specular_mode: shading.specular,
    };
    // The world-space directions the lighting sees: the per-vertex mistakes replace the first
    // light's (mistakes::seen_vectors).
    let seen =
        mistakes::seen_vectors(mistake, world_vectors(&inputs), &frame.lights, point.vertex_light, point.vertex_half);
    let mut lights = [None; MAX_LIGHTS];
    let on = lights.iter_mut().zip(frame.lights.as_slice()).enumerate().filter(|(_, (_, light))| light.enabled);
    for (k, (terms, light)) in on {
        let arriving = incident(light, point.position, n);
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
    let lighting_space = match (bump, tangent_frame, shading_model) {
        (BumpKind::TangentSpace, Some(_), ShadingModel::BlinnPhong) => shading.lighting_space,
        _ => LightingSpace::World,
    };
    let legacy = shading.legacy;
    // Emitted light shows in the bump × colour picture only (not in the legacy looks).
    let emission = match shading.mode {
        _ if legacy.look != LegacyLook::Off => Vec3::ZERO,
        ShadingMode::BumpTimesColour => material.emissive_factor * point.emissive.unwrap_or(Vec3::ONE),
        ShadingMode::BumpOnly | ShadingMode::ColourOnly => Vec3::ZERO,
    };
    let first = frame.lights.first_on().map(|light| (light, incident(light, point.position, n)));
    let dot3_light = (legacy.look == LegacyLook::Dot3).then(|| match legacy.cube_map_in_use() {
        Some(size) => legacy::cube_map_lookup(&legacy::cube_map(size), size, point.vertex_light),
        None => point.vertex_light,
    });
    let lit_color = match (shading.mode, shading_model) {
        (ShadingMode::ColourOnly, _) => albedo,
        // The legacy looks light with the first light that is on (the ambient light alone
        // without one), seen from where it is, whatever the mistake.
        _ if legacy.look == LegacyLook::Dot3 => match first {
            Some((_, arriving)) => {
                legacy::dot3_color(lit_albedo, arriving.radiance, shading_normal, dot3_light.unwrap_or(Vec3::ZERO))
            }
            None => lit_albedo * frame.lights.ambient(),
        },
        _ if legacy.look == LegacyLook::Emboss => match (point.emboss, tangent_frame, first) {
            (Some(sample), Some((t, b, _)), Some((light, arriving))) => {
                let offset = legacy::emboss_light_offset(t, b, legacy::emboss_to_light(light, point.position, n));
                let strength = if shading.bump_enabled { shading.strength } else { 0.0 };
                legacy::emboss_color(lit_albedo, arriving.radiance, &sample, offset, strength)
            }
            _ => lit_albedo * frame.lights.ambient(),
        },
        (_, ShadingModel::BlinnPhong) => {
            let vectors = match lighting_space {
                LightingSpace::World => seen,
                LightingSpace::Tangent => {
                    let own = tangent_frame.map_or(Mat3::IDENTITY, |(t, b, _)| inverse_tbn(t, b, n));
                    let tangent_normal = if shading.bump_enabled { drawn_tangent_normal } else { None };
                    let to_tangent = point.triangle_frame.unwrap_or(own);
                    tangent_lighting_vectors(&seen, to_tangent, tangent_normal.unwrap_or(Vec3::Z))
                }
                LightingSpace::View => view_lighting_vectors(&seen, frame.camera.view_rotation()),
            };
            blinn_phong(&inputs, &vectors)
        }
        (_, ShadingModel::MetallicRoughness) => {
            let occlusion_strength = material.occlusion.as_ref().map_or(0.0, |o| o.strength);
            metallic_roughness(&PbrInputs {
                base_color: lit_albedo,
                metallic: material.metallic * metal_rough.z,
                roughness: mip.roughness.unwrap_or(material.roughness * metal_rough.y),
                occlusion: 1.0 + occlusion_strength * (point.occlusion.unwrap_or(1.0) - 1.0),
                geometric_normal: n,
                shading_normal,
                position: point.position,
                eye,
                lights: frame.lights,
                seen: Some(seen),
                clearcoat: coat.map(|c| ClearcoatInputs {
                    factor: c.factor * point.clearcoat.unwrap_or(1.0),
                    roughness: c.roughness * point.clearcoat_roughness.unwrap_or(1.0),
                    normal: clearcoat_normal,
                }),
            })
        }
    };
    let color_linear = lit_color + emission;
    let lit = color_linear.map(linear_to_srgb);
    let zero = Vec3::ZERO;
    let shown = match shading.view {
        ViewMode::Lit => Some(lit),
        ViewMode::OverTilt if over_tilted(n, shading_normal) => Some(OVER_TILT_COLOR),
        ViewMode::OverTilt => Some(over_tilt_grey(color_linear).map(linear_to_srgb)),
        ViewMode::Tangent => Some(debug_color(tangent_frame.map_or(zero, |f| f.0))),
        ViewMode::Bitangent => Some(debug_color(tangent_frame.map_or(zero, |f| f.1))),
        ViewMode::Normal => Some(debug_color(n)),
        ViewMode::ShadingNormal => Some(debug_color(shading_normal)),
        ViewMode::Handedness => Some(handedness_color(tangent_frame.map(|f| f.2), n, eye - point.position)),
        ViewMode::ClearcoatNormal => Some(debug_color(clearcoat_normal)),
        ViewMode::Difference | ViewMode::UvCheck => None,
    };
    ChainValues {
        march: None,
        texel: match point.bump {
            Some(BumpSample::NormalMap(texel)) => Some(texel),
            _ => None,
        },
        decoded,
        strength,
        after_strength,
        detail,
        tangent: tangent_frame.map(|f| f.0),
        bitangent: tangent_frame.map(|f| f.1),
        w: tangent_frame.map(|f| f.2),
        normal: n,
        shading_normal,
        clearcoat_normal,
        view_dir,
        vertex_light: point.vertex_light,
        dot3_light,
        lights,
        albedo,
        shading_model,
        lighting_space,
        mip,
        color_linear,
        shown,
    }
}
