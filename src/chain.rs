//! The one CPU shading chain: the twin of the fragment stage of `shaders/mesh.wgsl`, step by
//! step, returning every intermediate value. [`shade`] takes what the fragment shader reads at
//! one surface point — the interpolated vertex outputs and the filtered texture samples, a
//! [`SurfaceSample`] — and runs the same formulas ([`crate::shading`]) in the same order: the
//! geometric normal, the tangent frame, the bump by the instance's [`BumpKind`], the lighting
//! in the frame's [`ShadingMode`] with the material's (or the overriding) shading model, and
//! the colour the frame's [`ViewMode`] stores. The pixel probe and the CPU reference tests
//! call it; neither holds shading math of its own.
//!
//! Spaces and units follow the crate conventions: positions in metres, world space; vectors
//! unit length, world space unless named tangent space; colours linear RGB 0..1 unless named
//! stored (what the target holds: sRGB-encoded for the lit picture, `0.5·v + 0.5` for
//! vector views).

pub mod legacy;
pub mod mistakes;
pub mod parallax;

use glam::{Mat3, Vec3, Vec4};

use crate::frame::{BumpKind, FrameParams, LegacyLook, ShadingMode, ViewMode};
use crate::math::{linear_to_srgb, normalize_or, smoothstep};
use crate::scene::{Light, Material, ShadingModel};
use crate::shading::pbr::{ClearcoatInputs, PbrInputs, metallic_roughness};
use crate::shading::{
    LightingInputs, NormalTexel, OVER_TILT_COLOR, SELF_SHADOW_FADE, blinn_phong, debug_color, decode_normal,
    handedness_color, object_space_normal, over_tilted, packed_gloss, surface_gradient_normal,
};

/// What the fragment shader reads at one surface point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSample {
    /// World-space position, metres.
    pub position: Vec3,
    /// The interpolated vertex normal taken by the normal matrix (not normalised).
    pub world_normal: Vec3,
    /// Whether the point is on a front face (else a back face of a double-sided material).
    pub front_facing: bool,
    /// The interpolated tangent taken by the model matrix, its `w` times `sign(det(model))`;
    /// `None` where the mesh is drawn without a tangent stream.
    pub world_tangent: Option<Vec4>,
    /// The normal matrix (inverse-transpose of the model matrix): object-space maps need it.
    pub normal_matrix: Mat3,
    /// The filtered base colour texture, linear; `None` without one (white).
    pub base_color: Option<Vec3>,
    /// The bump texture's reading, by the instance's [`BumpKind`]; `None` without a bump.
    pub bump: Option<BumpSample>,
    /// The filtered metallic-roughness texture (B metal, G rough); `None` without one.
    pub metallic_roughness: Option<Vec3>,
    /// The occlusion texture's red; `None` without one.
    pub occlusion: Option<f32>,
    /// The filtered gloss (specular) map; `None` without one.
    pub gloss: Option<Vec3>,
    /// The filtered emissive texture, linear; `None` without one.
    pub emissive: Option<Vec3>,
    /// The clear-coat textures at the layer's coordinates: strength (red), roughness
    /// (green), the normal map's RGB; `None` where the material has none.
    pub clearcoat: Option<f32>,
    pub clearcoat_roughness: Option<f32>,
    pub clearcoat_normal: Option<Vec3>,
    /// The per-vertex light direction and half vector ([`legacy::vertex_vectors`]),
    /// interpolated (perspective-correct) as the vertex stage passes them on.
    pub vertex_light: Vec3,
    pub vertex_half: Vec3,
    /// The height map's neighbours for the emboss look; `None` where no height map is bound
    /// (only normal-mapped surfaces with a height map, uploaded for parallax or emboss).
    pub emboss: Option<legacy::EmbossSample>,
}

/// What the bump texture gives at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BumpSample {
    /// The normal map's filtered texel (and X-Ray's `bump#`), linear (tangent- or
    /// object-space maps).
    NormalMap(NormalTexel),
    /// Screen-space derivatives for Blinn's bump from the height map: of the position
    /// (metres per pixel, world space) and of the decoded height sample ([`crate::shading::height_sample`],
    /// full range per pixel, before the depth flip, range and strength).
    HeightSlopes { dp_dx: Vec3, dp_dy: Vec3, dh_dx: f32, dh_dy: f32 },
}

/// Every value along the chain at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainValues {
    /// The decoded normal-map vector ([`decode_normal`]): tangent space, or model space for an
    /// object-space map. `None` without a normal map.
    pub decoded: Option<Vec3>,
    /// The effective strength: the frame's strength times the material's `normalTexture.scale`
    /// (the height bump uses the frame's strength alone).
    pub strength: f32,
    /// Tangent-space normal after strength, `normalize(x·s, y·s, max(z, 0))` (tangent-space
    /// maps only).
    pub after_strength: Option<Vec3>,
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
    /// Unit directions from the point to the light and the eye, and their half vector.
    pub light_dir: Vec3,
    pub view_dir: Vec3,
    pub half: Vec3,
    /// The per-vertex light direction as interpolated ([`SurfaceSample::vertex_light`]), and
    /// the light vector DOT3 lit with: that one, or it through the normalization cube map;
    /// `None` outside DOT3.
    pub vertex_light: Vec3,
    pub dot3_light: Option<Vec3>,
    /// `N·L` and `N·H` with the shading normal, signed (the shading uses `max(·, 0)`).
    pub n_dot_l: f32,
    pub n_dot_h: f32,
    /// The geometric self-shadow fade `smoothstep(0, SELF_SHADOW_FADE, N_geo·L)`, 0..1.
    pub self_shadow: f32,
    /// Linear albedo: base colour texture times the factor.
    pub albedo: Vec3,
    /// The model the point is lit with (the frame's override, else the material's).
    pub shading_model: ShadingModel,
    /// The lit colour in the frame's shading mode, linear RGB.
    pub color_linear: Vec3,
    /// What the frame's view stores, 0..1; `None` for the Difference and UV check views,
    /// which need screen-space data of a whole triangle.
    pub shown: Option<Vec3>,
}

/// The shading chain at one point of an instance bumped by `bump`, drawn with `material`
/// under `frame` in a scene with `ambient` light.
pub fn shade(
    bump: BumpKind,
    material: &Material,
    ambient: Vec3,
    point: &SurfaceSample,
    frame: &FrameParams,
) -> ChainValues {
    let shading = &frame.shading;
    let facing = if point.front_facing { 1.0 } else { -1.0 };
    let n = normalize_or(point.world_normal, Vec3::Z) * facing;
    let mistake = shading.mistake;
    let tangent_frame = point.world_tangent.map(|world| mistakes::tangent_frame(mistake, world, n));
    let base = mistakes::base_normal(mistake, point.world_normal, facing, n);

    let map = material.normal_map.as_ref().filter(|_| matches!(bump, BumpKind::TangentSpace | BumpKind::ObjectSpace));
    let strength = shading.strength * map.map_or(1.0, |m| m.scale);
    let texel = match point.bump {
        Some(BumpSample::NormalMap(texel)) => map.map(|_| mistakes::texel_read(mistake, texel)),
        _ => None,
    };
    let convention = map.map(|m| mistakes::convention_read(mistake, m.convention));
    let decoded = texel.zip(convention).map(|(texel, c)| decode_normal(texel, c));
    let after_strength = decoded
        .filter(|_| bump == BumpKind::TangentSpace)
        .map(|d| normalize_or(Vec3::new(d.x * strength, d.y * strength, d.z.max(0.0)), Vec3::Z));
    let slopes = point.bump;
    let shading_normal = match (shading.bump_enabled, bump, tangent_frame, after_strength, texel, convention, slopes) {
        (true, BumpKind::TangentSpace, Some((t, b, _)), Some(nt), ..) => mistakes::to_world(mistake, t, b, base, nt),
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
            let s = shading.strength * map.scale;
            let nt = normalize_or(Vec3::new(decoded.x * s, decoded.y * s, decoded.z.max(0.0)), Vec3::Z);
            mistakes::to_world(mistake, t, b, n, nt)
        }
        _ => n,
    };

    // X-Ray's bump carries a gloss that scales k_s (1 for the other layouts).
    let gloss = match point.bump {
        Some(BumpSample::NormalMap(raw)) => map.map_or(1.0, |m| packed_gloss(raw, m.convention.layout)),
        _ => 1.0,
    };
    let (light_position, eye) = mistakes::seen_positions(
        mistake,
        frame.light.position,
        frame.camera.eye(),
        point.position,
        point.vertex_light,
        point.vertex_half,
        n,
    );
    let light = Light { position: light_position, ..frame.light };
    let light_dir = normalize_or(light.position - point.position, n);
    let view_dir = normalize_or(eye - point.position, n);
    let half = normalize_or(light_dir + view_dir, n);
    let albedo = point.base_color.unwrap_or(Vec3::ONE) * material.base_color_factor.truncate();
    let shading_model = shading.shading_override.unwrap_or(material.shading_model);
    let lit_albedo = if shading.mode == ShadingMode::BumpOnly { Vec3::ONE } else { albedo };
    let legacy = shading.legacy;
    // Emitted light shows in the bump × colour picture only (not in the legacy looks).
    let emission = match shading.mode {
        _ if legacy.look != LegacyLook::Off => Vec3::ZERO,
        ShadingMode::BumpTimesColour => material.emissive_factor * point.emissive.unwrap_or(Vec3::ONE),
        ShadingMode::BumpOnly | ShadingMode::ColourOnly => Vec3::ZERO,
    };
    let dot3_light = (legacy.look == LegacyLook::Dot3).then(|| match legacy.cube_map_in_use() {
        Some(size) => legacy::cube_map_lookup(&legacy::cube_map(size), size, point.vertex_light),
        None => point.vertex_light,
    });
    let lit_color = match (shading.mode, shading_model) {
        (ShadingMode::ColourOnly, _) => albedo,
        _ if legacy.look == LegacyLook::Dot3 => {
            legacy::dot3_color(lit_albedo, light.color, shading_normal, dot3_light.unwrap_or(Vec3::ZERO))
        }
        _ if legacy.look == LegacyLook::Emboss => match (point.emboss, tangent_frame) {
            (Some(sample), Some((t, b, _))) => {
                let offset = legacy::emboss_light_offset(t, b, light.position - point.position);
                let strength = if shading.bump_enabled { shading.strength } else { 0.0 };
                legacy::emboss_color(lit_albedo, light.color, &sample, offset, strength)
            }
            _ => lit_albedo * ambient,
        },
        (_, ShadingModel::BlinnPhong) => blinn_phong(&LightingInputs {
            albedo: lit_albedo,
            geometric_normal: n,
            shading_normal,
            position: point.position,
            eye,
            light,
            ambient,
            specular: material.specular * point.gloss.unwrap_or(Vec3::ONE) * gloss,
            shininess: material.shininess.max(1.0),
        }),
        (_, ShadingModel::MetallicRoughness) => {
            let metal_rough = point.metallic_roughness.unwrap_or(Vec3::ONE);
            let occlusion_strength = material.occlusion.as_ref().map_or(0.0, |o| o.strength);
            metallic_roughness(&PbrInputs {
                base_color: lit_albedo,
                metallic: material.metallic * metal_rough.z,
                roughness: material.roughness * metal_rough.y,
                occlusion: 1.0 + occlusion_strength * (point.occlusion.unwrap_or(1.0) - 1.0),
                geometric_normal: n,
                shading_normal,
                position: point.position,
                eye,
                light,
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
        ViewMode::OverTilt => Some(lit),
        ViewMode::Tangent => Some(debug_color(tangent_frame.map_or(zero, |f| f.0))),
        ViewMode::Bitangent => Some(debug_color(tangent_frame.map_or(zero, |f| f.1))),
        ViewMode::Normal => Some(debug_color(n)),
        ViewMode::ShadingNormal => Some(debug_color(shading_normal)),
        ViewMode::Handedness => Some(handedness_color(tangent_frame.map(|f| f.2), n, eye - point.position)),
        ViewMode::ClearcoatNormal => Some(debug_color(clearcoat_normal)),
        ViewMode::Difference | ViewMode::UvCheck => None,
    };
    ChainValues {
        decoded,
        strength,
        after_strength,
        tangent: tangent_frame.map(|f| f.0),
        bitangent: tangent_frame.map(|f| f.1),
        w: tangent_frame.map(|f| f.2),
        normal: n,
        shading_normal,
        clearcoat_normal,
        light_dir,
        view_dir,
        half,
        vertex_light: point.vertex_light,
        dot3_light,
        n_dot_l: shading_normal.dot(light_dir),
        n_dot_h: shading_normal.dot(half),
        self_shadow: smoothstep(0.0, SELF_SHADOW_FADE, n.dot(light_dir)),
        albedo,
        shading_model,
        color_linear,
        shown,
    }
}
