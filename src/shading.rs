//! The formulas of the shading in the mesh pass (the `shaders/` files of `render::shaders::MESH`),
//! one function each: normal-map decoding, the bump by a normal map, an object-space map or a
//! height field, Blinn-Phong and metallic-roughness ([`pbr`]), and the colours of the debug
//! views. [`crate::chain`] runs them in the shader's order.
//!
//! The GPU and this module implement the same formulas line for line; tests render with the
//! GPU and compare against them. All vectors are world space and unit length unless stated;
//! colours are linear RGB.

pub mod detail_blend;
pub mod lights;
pub mod mip_filter;
pub mod pbr;
pub mod spaces;

use glam::{Mat3, Vec3, Vec4};

use crate::math::{handedness, normalize_or, orthonormalize_tangent, smoothstep};
use crate::scene::{GreenAxis, Lights, MAX_LIGHTS, NormalConvention, NormalLayout, SpecularMode};
use lights::{incident, specular_power};

/// Width of the self-shadow fade in units of `N_geo · L` (a cosine): the light fades in
/// smoothly from grazing (0) to `N_geo · L = 0.1` (about 84° from the normal).
pub const SELF_SHADOW_FADE: f32 = 0.1;

/// What a normal map gives at a point: its filtered RGBA (linear, 0..1) and, in the X-Ray
/// layout, the filtered RGB of its `bump#` texture (`None`: no `bump#`, no correction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalTexel {
    pub rgba: Vec4,
    pub correction: Option<Vec3>,
}

impl NormalTexel {
    /// An RGB texel (alpha 1), no correction.
    pub fn rgb(rgb: Vec3) -> NormalTexel {
        NormalTexel { rgba: rgb.extend(1.0), correction: None }
    }
}

/// The signed vector a texel's channels hold by `layout` ([`NormalLayout`]), before the
/// green convention and normalisation: RGB `2·rgb − 1`; RG and AG `(2·x − 1, 2·y − 1)` with
/// `z = sqrt(max(0, 1 − x² − y²))`, `(x, y)` scaled onto the unit circle where `x² + y² > 1`;
/// X-Ray `bump.agb + bump#.rgb − 1` (a correction of 0.5 without `bump#`).
pub fn unpack_normal(texel: NormalTexel, layout: NormalLayout) -> Vec3 {
    let t = texel.rgba;
    let rebuilt = |x: f32, y: f32| {
        let (x, y) = (x * 2.0 - 1.0, y * 2.0 - 1.0);
        let xy2 = x * x + y * y;
        let shrink = if xy2 > 1.0 { xy2.sqrt().recip() } else { 1.0 };
        Vec3::new(x * shrink, y * shrink, (1.0 - xy2).max(0.0).sqrt())
    };
    match layout {
        NormalLayout::Rgb => t.truncate() * 2.0 - 1.0,
        NormalLayout::Rg => rebuilt(t.x, t.y),
        NormalLayout::Ag => rebuilt(t.w, t.y),
        NormalLayout::Xray => Vec3::new(t.w, t.z, t.y) + texel.correction.unwrap_or(Vec3::splat(0.5)) - 1.0,
    }
}

/// A normal map texel as a unit vector in the map's space: unpacked by the layout
/// ([`unpack_normal`]), green negated for DirectX, then normalised.
pub fn decode_normal(texel: NormalTexel, convention: NormalConvention) -> Vec3 {
    let mut v = unpack_normal(texel, convention.layout);
    if convention.green == GreenAxis::DirectX {
        v.y = -v.y;
    }
    normalize_or(v, Vec3::Z)
}

/// The gloss a normal map carries: X-Ray's `bump` red squared (it scales k_s), else 1.
pub fn packed_gloss(texel: NormalTexel, layout: NormalLayout) -> f32 {
    match layout {
        NormalLayout::Xray => texel.rgba.x * texel.rgba.x,
        NormalLayout::Rgb | NormalLayout::Rg | NormalLayout::Ag => 1.0,
    }
}

/// A decoded tangent-space normal after strength `s`: `normalize(x·s, y·s, max(z, 0))` (a
/// tangent-space normal never points into the surface).
pub fn tangent_space_normal(decoded: Vec3, strength: f32) -> Vec3 {
    normalize_or(Vec3::new(decoded.x * strength, decoded.y * strength, decoded.z.max(0.0)), Vec3::Z)
}

/// The tangent frame `(T, B, w)` from the interpolated world tangent and the unit geometric
/// normal `n`: `T` by Gram-Schmidt against `n`, `w = ±1` from the tangent's `w`,
/// `B = w · (N × T)` (the glTF rule). The twin of `tangent_frame` in `shaders/mesh.wgsl`; the
/// classic mistakes' wrong frames sit beside it in [`crate::chain::mistakes`].
pub fn tangent_frame(world_tangent: Vec4, n: Vec3) -> (Vec3, Vec3, f32) {
    let w = handedness(world_tangent);
    let t = orthonormalize_tangent(world_tangent.truncate(), n);
    (t, w * n.cross(t), w)
}

/// A tangent-space normal `nt` ([`tangent_space_normal`]) in world space through the frame
/// `t`, `b`, `n`: `normalize(T·nt.x + B·nt.y + N·nt.z)`, `n` the fallback. The one right path
/// (`tangent_to_world` in `shaders/mistakes.wgsl` without a mistake); the classic mistakes'
/// wrong ways sit beside it in [`crate::chain::mistakes`].
pub fn tangent_to_world(t: Vec3, b: Vec3, n: Vec3, nt: Vec3) -> Vec3 {
    normalize_or(t * nt.x + b * nt.y + n * nt.z, n)
}

/// The normal after an object-space normal map: the decoded model-space vector goes to world
/// space by `normal_matrix` (inverse-transpose of the model matrix) and is negated on the
/// back faces of double-sided materials (`front_facing` false); the strength `s` blends
/// `normalize(n_geo + s · (n_map − n_geo))` (0 flat, 1 the map, negative mirrors it about
/// `n_geo`). No tangents are involved.
pub fn object_space_normal(
    n_geo: Vec3,
    normal_matrix: Mat3,
    front_facing: bool,
    texel: NormalTexel,
    strength: f32,
    convention: NormalConvention,
) -> Vec3 {
    let facing = if front_facing { 1.0 } else { -1.0 };
    let n_map = facing * normalize_or(normal_matrix * decode_normal(texel, convention), n_geo);
    normalize_or(n_geo + strength * (n_map - n_geo), n_geo)
}

/// Everything the classic model needs at one surface point.
#[derive(Debug, Clone, Copy)]
pub struct LightingInputs {
    /// Linear albedo (base colour texture × factor).
    pub albedo: Vec3,
    /// Unit geometric normal, facing the viewer's side for double-sided back faces.
    pub geometric_normal: Vec3,
    /// Unit normal used for lighting (equals `geometric_normal` without bump).
    pub shading_normal: Vec3,
    /// Point position, metres.
    pub position: Vec3,
    pub eye: Vec3,
    /// Every light (switched-off ones bring nothing) and the ambient light.
    pub lights: Lights,
    /// k_s, linear: the material's specular colour times its gloss map's texel where it has one.
    pub specular: Vec3,
    pub shininess: f32,
    pub specular_mode: SpecularMode,
}

/// The unit vectors the classic model lights with at one point, all in one lighting space
/// ([`spaces`]): world space ([`world_vectors`]), tangent space or view space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightingVectors {
    pub geometric_normal: Vec3,
    pub shading_normal: Vec3,
    /// Towards each light, by the frame's light index (lights that are off: unused).
    pub lights: [Vec3; MAX_LIGHTS],
    /// Towards the eye as each light's highlight sees it, by the frame's light index: the
    /// true direction for every light but where a per-vertex mistake of the chain
    /// ([`crate::chain::mistakes::seen_view_direction`]) replaces the first light's.
    pub views: [Vec3; MAX_LIGHTS],
}

/// The world-space vectors of `p`: its normals, and the directions to the eye and to each
/// light ([`lights::incident`]); degenerate directions fall back to `N_geo`.
pub fn world_vectors(p: &LightingInputs) -> LightingVectors {
    let n_geo = p.geometric_normal;
    let mut lights = [n_geo; MAX_LIGHTS];
    for (l, light) in lights.iter_mut().zip(p.lights.as_slice()) {
        *l = incident(light, p.position, n_geo).direction;
    }
    LightingVectors {
        geometric_normal: n_geo,
        shading_normal: p.shading_normal,
        lights,
        views: [normalize_or(p.eye - p.position, n_geo); MAX_LIGHTS],
    }
}

/// The classic model with the vectors of one lighting space: `albedo·ambient` plus
/// [`light_term`] of every light that is on, each bringing its radiance
/// ([`lights::incident`], attenuated by its world-space distance).
pub fn blinn_phong(p: &LightingInputs, space: &LightingVectors) -> Vec3 {
    let mut sum = p.albedo * p.lights.ambient();
    let directions = space.lights.iter().zip(&space.views);
    for ((l, v), light) in directions.zip(p.lights.as_slice()).filter(|(_, light)| light.enabled) {
        sum += light_term(p, space, *l, *v, incident(light, p.position, p.geometric_normal).radiance);
    }
    sum
}

/// What one light adds in the classic model from unit direction `l` with `radiance`, seen
/// from unit direction `v`, with geometric self-shadowing: `fade(N_geo·L) · radiance ·
/// (albedo·max(N·L, 0) + k_s·specular)`, where `fade` is `smoothstep(0, SELF_SHADOW_FADE, ·)`
/// and the specular term comes from [`lights::specular_power`] in the frame's mode; the
/// normals from `space`.
pub fn light_term(p: &LightingInputs, space: &LightingVectors, l: Vec3, v: Vec3, radiance: Vec3) -> Vec3 {
    let (n_geo, n) = (space.geometric_normal, space.shading_normal);
    let self_shadow = smoothstep(0.0, SELF_SHADOW_FADE, n_geo.dot(l));
    let n_dot_l = n.dot(l).max(0.0);
    let specular = specular_power(p.specular_mode, n, n_geo, l, v, p.shininess);
    self_shadow * radiance * (p.albedo * n_dot_l + p.specular * specular)
}

/// A height map's filtered texel as a height sample, 0..1 of the full range: 16 bits in red
/// (high byte) and green (low byte), [`crate::scene::TextureKind::Height`].
pub fn height_sample(texel: Vec3) -> f32 {
    (texel.x * 65280.0 + texel.y * 255.0) / 65535.0
}

/// Blinn's bump without tangents: Mikkelsen's surface gradient from screen-space derivatives
/// of the position (`dp_dx`, `dp_dy`, metres per pixel, world space) and of the height
/// (`dh_dx`, `dh_dy`, metres per pixel) around the unit geometric normal `n`. Falls back on `n`
/// where the derivatives are degenerate (the plane seen edge-on).
pub fn surface_gradient_normal(n: Vec3, dp_dx: Vec3, dp_dy: Vec3, dh_dx: f32, dh_dy: f32) -> Vec3 {
    let r1 = dp_dy.cross(n);
    let r2 = n.cross(dp_dx);
    let det = dp_dx.dot(r1);
    let sign = if det > 0.0 {
        1.0
    } else if det < 0.0 {
        -1.0
    } else {
        0.0
    };
    let surface_gradient = sign * (dh_dx * r1 + dh_dy * r2);
    normalize_or(det.abs() * n - surface_gradient, n)
}

/// Over-tilt threshold, degrees between the shading and the geometric normal. A
/// tangent-space normal map can never point exactly below the surface here
/// ([`tangent_space_normal`] clamps `z ≥ 0`, so `N·N_geo ≥ 0`); what breaks the illusion is a
/// normal that lies nearly in the surface plane (facets seen edge-on). The built-in bricks
/// reach 50° at strength 1 and 78° at strength 4. Object-space maps with a large strength can
/// go truly below (`N·N_geo < 0`), which is marked too.
pub const OVER_TILT_LIMIT_DEG: f32 = 75.0;
/// Stored colour of an over-tilted pixel (saturated red).
pub const OVER_TILT_COLOR: Vec3 = Vec3::new(1.0, 0.0, 0.0);

/// The Over-tilt view's picture under the marks: the lit colour (linear RGB) in grey, its
/// Rec. 709 luminance in every channel, so the red marks cannot be taken for red bricks. The
/// twin of the `VIEW_OVER_TILT` case in `shaders/surface_color.wgsl`.
pub fn over_tilt_grey(linear: Vec3) -> Vec3 {
    Vec3::splat(linear.dot(Vec3::new(0.2126, 0.7152, 0.0722)))
}

/// `cos(OVER_TILT_LIMIT_DEG)`, the `frame.over_tilt_cos` uniform.
pub fn over_tilt_cos() -> f32 {
    OVER_TILT_LIMIT_DEG.to_radians().cos()
}

/// True where the Over-tilt view marks the pixel: `N·N_geo < cos(OVER_TILT_LIMIT_DEG)`.
pub fn over_tilted(n_geo: Vec3, n_shading: Vec3) -> bool {
    n_geo.dot(n_shading) < over_tilt_cos()
}

/// Stored colours of the Handedness view before shading: `w = +1`, `w = −1`, no tangents.
pub const HANDEDNESS_POSITIVE: Vec3 = Vec3::new(0.25, 0.85, 0.3);
pub const HANDEDNESS_NEGATIVE: Vec3 = Vec3::new(0.9, 0.2, 0.8);
pub const HANDEDNESS_NONE: Vec3 = Vec3::new(0.5, 0.5, 0.5);

/// The stored colour of the Handedness view: by the sign of tangent `w` (`None`: drawn
/// without tangents), shaded by `0.35 + 0.65·|N_geo·V|` so the shape stays readable. The
/// twin of `handedness_color` in `shaders/surface_color.wgsl`.
pub fn handedness_color(w: Option<f32>, n_geo: Vec3, to_eye: Vec3) -> Vec3 {
    let base = match w {
        None => HANDEDNESS_NONE,
        Some(w) if w < 0.0 => HANDEDNESS_NEGATIVE,
        Some(_) => HANDEDNESS_POSITIVE,
    };
    base * (0.35 + 0.65 * n_geo.dot(normalize_or(to_eye, n_geo)).abs())
}

/// Stops of the Difference view's colour scale (a viridis-like ramp, display values).
const DIFFERENCE_STOPS: [[f32; 3]; 5] =
    [[0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551], [0.369, 0.789, 0.383], [0.993, 0.906, 0.144]];

/// The stored colour of the Difference view for `t` = angle / range (clamped to 0..1); the
/// twin of `difference_color` in `shaders/difference.wgsl`, for legends.
pub fn difference_color(t: f32) -> [f32; 3] {
    let x = t.clamp(0.0, 1.0) * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f32;
    std::array::from_fn(|c| DIFFERENCE_STOPS[i][c] + (DIFFERENCE_STOPS[i + 1][c] - DIFFERENCE_STOPS[i][c]) * f)
}

/// The stored colour of a debug view for unit vector `v`.
pub fn debug_color(v: Vec3) -> Vec3 {
    v * 0.5 + 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, NormalSpace};

    const GL: NormalConvention =
        NormalConvention { green: GreenAxis::OpenGl, layout: NormalLayout::Rgb, space: NormalSpace::Tangent };
    const RGB: fn(Vec3) -> NormalTexel = NormalTexel::rgb;

    fn inputs() -> LightingInputs {
        LightingInputs {
            albedo: Vec3::new(0.5, 0.4, 0.3),
            geometric_normal: Vec3::Z,
            shading_normal: Vec3::Z,
            position: Vec3::ZERO,
            eye: Vec3::new(0.0, 0.0, 2.0),
            lights: Lights::one(Light::point(Vec3::new(0.0, 0.0, 3.0), Vec3::ONE), Vec3::splat(0.1)),
            specular: Vec3::splat(0.2),
            shininess: 16.0,
            specular_mode: SpecularMode::Blinn,
        }
    }

    #[test]
    fn head_on_light_gives_ambient_plus_full_diffuse_and_specular() {
        let p = inputs();
        let expected = p.albedo * 0.1 + p.albedo + Vec3::splat(0.2);
        assert!((blinn_phong(&p, &world_vectors(&p)) - expected).length() < 1e-6);
    }

    #[test]
    fn light_below_the_geometric_surface_leaves_only_ambient_even_if_bumped_towards_it() {
        let mut p = inputs();
        p.lights[0].position = Vec3::new(3.0, 0.0, -0.1);
        p.shading_normal = Vec3::new(1.0, 0.0, 0.2).normalize();
        assert!((blinn_phong(&p, &world_vectors(&p)) - p.albedo * 0.1).length() < 1e-7);
    }

    /// The right path of a tangent-space normal map, as the chain runs it: decode, strength,
    /// the frame from `tangent` against `n`, to world space.
    fn perturbed_normal(
        n: Vec3,
        tangent: Vec4,
        texel: NormalTexel,
        strength: f32,
        convention: NormalConvention,
    ) -> Vec3 {
        let (t, b, _) = tangent_frame(tangent, n);
        tangent_to_world(t, b, n, tangent_space_normal(decode_normal(texel, convention), strength))
    }

    #[test]
    fn flat_texel_or_zero_strength_keeps_the_geometric_normal() {
        let n = Vec3::new(0.0, 1.0, 0.0);
        let t = Vec4::new(1.0, 0.0, 0.0, 1.0);
        let bumpy = RGB(Vec3::new(0.8, 0.3, 0.7));
        assert!((perturbed_normal(n, t, RGB(Vec3::new(0.5, 0.5, 1.0)), 3.0, GL) - n).length() < 1e-6);
        assert!((perturbed_normal(n, t, bumpy, 0.0, GL) - n).length() < 1e-6);
        let inverted = perturbed_normal(n, t, bumpy, -1.0, GL);
        let plain = perturbed_normal(n, t, bumpy, 1.0, GL);
        assert!((inverted.x + plain.x).abs() < 1e-6 && (inverted.y - plain.y).abs() < 1e-6);
    }

    #[test]
    fn extreme_strength_stays_finite_and_unit() {
        let n = Vec3::Z;
        let t = Vec4::new(1.0, 0.0, 0.0, -1.0);
        for s in [-1000.0, 1000.0, f32::MAX] {
            let v = perturbed_normal(n, t, RGB(Vec3::new(0.6, 0.45, 0.9)), s, GL);
            assert!(v.is_finite() && (v.length() - 1.0).abs() < 1e-5, "{s}: {v}");
        }
    }

    #[test]
    fn directx_decode_of_a_flipped_texel_equals_opengl_decode() {
        let texel = Vec3::new(0.7, 0.2, 0.9);
        let flipped = Vec3::new(0.7, 0.8, 0.9);
        let dx = NormalConvention { green: GreenAxis::DirectX, ..GL };
        assert!((decode_normal(RGB(flipped), dx) - decode_normal(RGB(texel), GL)).length() < 1e-6);
    }

    #[test]
    fn two_channel_outside_the_unit_disc_gives_finite_unit_normals() {
        let two = NormalConvention { layout: NormalLayout::Rg, ..GL };
        for texel in [Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, Vec3::new(0.5, 0.5, 0.0)] {
            let v = decode_normal(RGB(texel), two);
            assert!(v.is_finite() && (v.length() - 1.0).abs() < 1e-6 && v.z >= 0.0, "{texel}: {v}");
        }
        assert!((decode_normal(RGB(Vec3::new(0.5, 0.5, 0.0)), two) - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn object_space_map_turns_with_the_model() {
        let rotation = Mat3::from_rotation_y(std::f32::consts::FRAC_PI_2);
        let texel = RGB(Vec3::new(0.5, 0.5, 1.0)); // model +Z
        let object = NormalConvention { space: NormalSpace::Object, ..GL };
        let n = object_space_normal(Vec3::X, rotation, true, texel, 1.0, object);
        assert!((n - Vec3::X).length() < 1e-6, "{n}");
        assert!((object_space_normal(Vec3::Y, rotation, true, texel, 0.0, object) - Vec3::Y).length() < 1e-6);
    }
}
