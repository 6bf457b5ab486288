//! The parallax family on the CPU: the twin of `shaders/parallax.wgsl`, formula for formula
//! and in the same order, so the probe marches the same height samples as the GPU.
//!
//! The reference plane is the mesh surface, the top of the relief; a texel of height `h` (0..1)
//! lies `(1 − h) · depth` metres below it. The view ray enters at the pixel's UV and descends
//! along `−V`: at depth `t · depth` metres (`t` 0..1) it is over the texture coordinates
//! `uv + t · depth · S`, where `S = −(∇u·V, ∇v·V) / max(N·V, GRAZING_N_DOT_V)` is the UV shift
//! per metre of depth. `∇u`, `∇v` are the world-space surface gradients of the texture
//! coordinates (UV units per metre), from screen-space derivatives of the position and the UV
//! as in Mikkelsen's surface gradient: the surface's UV density comes from the pixel, not from
//! the tangent frame, so one relief is equally deep under every technique and on every UV
//! layout. The searches (steep, occlusion, relief, relaxed cones) take `ParallaxSettings::layers`
//! layers (cone steps) and relief and relaxed cones `steps` more samples: at most 257 + 16
//! height samples per pixel.

use glam::{Vec2, Vec3};

use crate::frame::{MAX_PARALLAX_STEPS, Parallax, ParallaxSettings};

/// `N·V` is floored here before it divides: at grazing views the shift per metre of depth is
/// at most `1 / GRAZING_N_DOT_V` times the face-on one (finite, no NaN).
pub const GRAZING_N_DOT_V: f32 = 0.05;

/// What the fragment shader knows at one pixel for the march.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchInputs {
    /// The interpolated texture coordinates.
    pub uv: Vec2,
    /// The unit geometric normal (facing the viewer's side) and the unit direction to the eye.
    pub normal: Vec3,
    pub view_dir: Vec3,
    /// Screen-space derivatives of the world position (metres per pixel) and of the UV.
    pub dp_dx: Vec3,
    pub dp_dy: Vec3,
    pub duv_dx: Vec2,
    pub duv_dy: Vec2,
    /// The relief's depth, metres.
    pub depth_m: f32,
    /// The height map's sampler clamps u, v: marched coordinates stay in 0..1 on those axes.
    pub clamp: [bool; 2],
}

/// The march at one pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct March {
    /// Layers of the linear search (0 for techniques without one, or no shift).
    pub layers: u32,
    /// The first layer at or below the relief (0 = the surface itself).
    pub layer_hit: u32,
    /// The texture coordinates the normal map and colour are read at, and their shift.
    pub uv: Vec2,
    pub shift: Vec2,
    /// The depth reached along the ray, 0..1 of the relief's depth.
    pub depth: f32,
}

/// What relaxed cone stepping reads at one UV: the height texture's level 0, filtered.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConeTexel {
    /// Height 0..1, white = high, a depth map already flipped.
    pub height: f32,
    /// The relaxed cone's ratio, UV units per unit of depth fraction
    /// ([`crate::height::cone`]).
    pub ratio: f32,
}

/// The texture coordinates of `inputs` shifted by `settings`' technique, reading heights
/// (0..1, white = high, a depth map already flipped) with `height` (at the pixel's footprint)
/// and, for relaxed cones, the cone map with `cone`. Off, depth 0 or a surface seen edge-on
/// in screen space return the UV unchanged without a sample.
pub fn march(
    settings: &ParallaxSettings,
    inputs: &MarchInputs,
    height: impl Fn(Vec2) -> f32,
    cone: impl Fn(Vec2) -> ConeTexel,
) -> March {
    let unshifted = March { layers: 0, layer_hit: 0, uv: inputs.uv, shift: Vec2::ZERO, depth: 0.0 };
    let (n, v) = (inputs.normal, inputs.view_dir);
    let gradients = uv_gradients(inputs);
    let Some((grad_u, grad_v)) =
        gradients.filter(|_| settings.technique.shifts() && inputs.depth_m != 0.0 && inputs.depth_m.is_finite())
    else {
        return unshifted;
    };
    let n_dot_v = n.dot(v);
    let along = Vec2::new(-grad_u.dot(v), -grad_v.dot(v)) * inputs.depth_m;
    let per_depth = along / n_dot_v.max(GRAZING_N_DOT_V);
    let clamp = |uv: Vec2| clamped(inputs, uv);
    let uv_at = |t: f32| clamp(inputs.uv + per_depth * t);
    let depth_at = |t: f32| 1.0 - height(uv_at(t));
    let done = |layers, layer_hit, uv: Vec2, depth| March { layers, layer_hit, uv, shift: uv - inputs.uv, depth };
    match settings.technique {
        Parallax::Off => unshifted,
        Parallax::Offset => {
            let d = depth_at(0.0);
            done(0, 0, uv_at(d), d)
        }
        Parallax::OffsetLimited => {
            let d = depth_at(0.0);
            done(0, 0, clamp(inputs.uv + along * d), d)
        }
        Parallax::Steep | Parallax::Occlusion | Parallax::Relief => {
            let layers = settings.layers(n_dot_v);
            let (mut i, mut t, mut d) = (0u32, 0.0f32, depth_at(0.0));
            let (mut t_prev, mut d_prev) = (t, d);
            while i < layers && t < d {
                t_prev = t;
                d_prev = d;
                i += 1;
                t = i as f32 / layers as f32;
                d = depth_at(t);
            }
            let t_hit = match settings.technique {
                Parallax::Occlusion if i > 0 => {
                    let after = d - t;
                    let before = d_prev - t_prev;
                    let w = after / (after - before);
                    t_prev * w + t * (1.0 - w)
                }
                Parallax::Relief if i > 0 => binary_search(t_prev, t, settings.steps, depth_at),
                _ => t,
            };
            done(layers, i, uv_at(t_hit), t_hit)
        }
        Parallax::RelaxedCone => {
            let layers = settings.layers(n_dot_v);
            let cone_at = |t: f32| cone(uv_at(t));
            let (i, t_prev, t) = relaxed_cone_steps(layers, per_depth.length(), cone_at);
            let depth_of = |t: f32| 1.0 - cone_at(t).height;
            let t_hit = if i > 0 { binary_search(t_prev, t, settings.steps, depth_of) } else { t };
            done(layers, i, uv_at(t_hit), t_hit)
        }
    }
}

/// Policarpo & Oliveira's relaxed cone steps along a ray moving `ray_ratio` UV units per unit
/// of depth fraction: from depth `t`, where the cone at the ray's texel (ratio `c`, its apex
/// at depth `d`) meets the ray, `t + c · (d − t) / (ray_ratio + c)`; at most `layers` steps,
/// stopping at or below the relief. Returns the steps taken and the last two depths.
fn relaxed_cone_steps(layers: u32, ray_ratio: f32, cone_at: impl Fn(f32) -> ConeTexel) -> (u32, f32, f32) {
    let (mut i, mut t, mut t_prev) = (0u32, 0.0f32, 0.0f32);
    let mut texel = cone_at(0.0);
    while i < layers && t < 1.0 - texel.height {
        let below = 1.0 - texel.height - t;
        t_prev = t;
        t += texel.ratio * below / (ray_ratio + texel.ratio).max(f32::MIN_POSITIVE);
        i += 1;
        texel = cone_at(t);
    }
    (i, t_prev, t)
}

/// Relief mapping's binary search between depths `low` (above the relief) and `high`:
/// `steps` halvings (at most [`MAX_PARALLAX_STEPS`]), the last depth at or below it.
fn binary_search(mut low: f32, mut high: f32, steps: u32, depth_at: impl Fn(f32) -> f32) -> f32 {
    for _ in 0..steps.min(MAX_PARALLAX_STEPS) {
        let mid = 0.5 * (low + high);
        if mid >= depth_at(mid) {
            high = mid;
        } else {
            low = mid;
        }
    }
    high
}

/// `uv` with the axes `inputs.clamp` names held in 0..1.
fn clamped(inputs: &MarchInputs, uv: Vec2) -> Vec2 {
    Vec2::new(
        if inputs.clamp[0] { uv.x.clamp(0.0, 1.0) } else { uv.x },
        if inputs.clamp[1] { uv.y.clamp(0.0, 1.0) } else { uv.y },
    )
}

/// The world-space gradients `∇u`, `∇v` of the texture coordinates over the surface (UV
/// units per metre), from the pixel's derivatives; `None` where the surface is seen edge-on
/// in screen space.
fn uv_gradients(inputs: &MarchInputs) -> Option<(Vec3, Vec3)> {
    let n = inputs.normal;
    let r1 = inputs.dp_dy.cross(n);
    let r2 = n.cross(inputs.dp_dx);
    let det = inputs.dp_dx.dot(r1);
    if det.abs() < 1e-20 || !det.is_finite() {
        return None;
    }
    let grad_u = (r1 * inputs.duv_dx.x + r2 * inputs.duv_dy.x) / det;
    let grad_v = (r1 * inputs.duv_dx.y + r2 * inputs.duv_dy.y) / det;
    Some((grad_u, grad_v))
}

/// A unit world direction `l` (towards a light) in the march's tangent space:
/// `(∇u·l, ∇v·l, N·l)` — UV units and metres along the normal per metre travelled. Zero where
/// the surface is edge-on in screen space.
pub fn light_in_tangent_space(inputs: &MarchInputs, l: Vec3) -> Vec3 {
    uv_gradients(inputs)
        .map_or(Vec3::ZERO, |(grad_u, grad_v)| Vec3::new(grad_u.dot(l), grad_v.dot(l), inputs.normal.dot(l)))
}

/// How much a blocker above the light ray darkens, per unit of shadow strength and of the
/// relief's depth: at strength 1, a blocker an eighth of the depth above the ray next to the
/// point shadows fully.
pub const SHADOW_SHARPNESS: f32 = 8.0;

/// Tatarchuk's soft self-shadow for the searches (steep, occlusion, relief): from the relief's
/// surface at the UV the view ray hit, a ray rises towards one light given in
/// tangent space (`light_ts`, [`light_in_tangent_space`]) and is sampled at
/// `settings.layers(N·L)` points up to the top of the relief. Where the relief stands above
/// the ray by `b` (a fraction of the depth) at step `i` of `n`, it blocks `b · (1 − i/n)`
/// (nearer blockers cast darker shadows); the light arrives times
/// `1 − clamp(strength · SHADOW_SHARPNESS · max blocked, 0, 1)`. 1 for other techniques, a
/// strength of 0, a point at the top, or a light below the surface (the geometric term
/// darkens that). At most 1 + [`crate::frame::MAX_PARALLAX_LAYERS`] height samples.
pub fn soft_shadow(
    settings: &ParallaxSettings,
    inputs: &MarchInputs,
    hit: &March,
    light_ts: Vec3,
    height: impl Fn(Vec2) -> f32,
) -> f32 {
    if !settings.technique.marches() || !settings.shadows_on() || light_ts.z <= 0.0 {
        return 1.0;
    }
    // From the relief's surface at the hit's UV: steep's hit lies up to a layer below it,
    // and a ray starting there would shadow the point by its own layer.
    let start = 1.0 - height(hit.uv);
    if start <= 0.0 {
        return 1.0;
    }
    let per_depth = light_ts.truncate() * inputs.depth_m / light_ts.z.max(GRAZING_N_DOT_V);
    let samples = settings.layers(light_ts.z);
    let mut blocked = 0.0f32;
    for i in 1..=samples {
        let f = i as f32 / samples as f32;
        let ray_depth = start * (1.0 - f);
        let surface_depth = 1.0 - height(clamped(inputs, hit.uv + per_depth * (start * f)));
        blocked = blocked.max((ray_depth - surface_depth) * (1.0 - f));
    }
    1.0 - (settings.shadow_strength * SHADOW_SHARPNESS * blocked).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::height::cone::MAX_CONE_RATIO;
    use crate::names::Named;

    /// A flat surface in the z = 0 plane, u along +x and v along −y, one UV unit per metre,
    /// seen from direction `view_dir`.
    fn inputs(view_dir: Vec3) -> MarchInputs {
        MarchInputs {
            uv: Vec2::new(0.5, 0.5),
            normal: Vec3::Z,
            view_dir,
            dp_dx: Vec3::X * 0.01,
            dp_dy: Vec3::NEG_Y * 0.01,
            duv_dx: Vec2::new(0.01, 0.0),
            duv_dy: Vec2::new(0.0, 0.01),
            depth_m: 0.1,
            clamp: [false; 2],
        }
    }

    /// The widest cones stored, over `height` (a flat floor's own relaxed cones).
    fn open_cones(height: impl Fn(Vec2) -> f32) -> impl Fn(Vec2) -> ConeTexel {
        move |uv| ConeTexel { height: height(uv), ratio: MAX_CONE_RATIO }
    }

    fn settings(technique: Parallax, layers: u32) -> ParallaxSettings {
        ParallaxSettings { technique, layers_min: layers, layers_max: layers, steps: 8, ..Default::default() }
    }

    /// Over a flat floor at half depth (h = 0.5) every technique finds the ray at depth
    /// 0.05 m: seen at 45° along +x, the shift is 0.05 UV units towards −u.
    #[test]
    fn a_flat_floor_is_found_at_its_depth_by_every_technique() {
        let v = Vec3::new(1.0, 0.0, 1.0).normalize();
        for technique in [Parallax::Offset, Parallax::Occlusion, Parallax::Relief, Parallax::RelaxedCone] {
            let m = march(&settings(technique, 16), &inputs(v), |_| 0.5, open_cones(|_| 0.5));
            assert!((m.shift - Vec2::new(-0.05, 0.0)).length() < 1e-5, "{technique:?}: {:?}", m.shift);
        }
        let steep = march(&settings(Parallax::Steep, 16), &inputs(v), |_| 0.5, open_cones(|_| 0.5));
        assert_eq!(steep.layer_hit, 8);
        assert!((steep.shift.x + 0.05).abs() < 1e-5, "{:?}", steep.shift);
        let limited = march(&settings(Parallax::OffsetLimited, 16), &inputs(v), |_| 0.5, open_cones(|_| 0.5));
        assert!((limited.shift.x + 0.05 * v.x).abs() < 1e-5, "{:?}", limited.shift);
    }

    #[test]
    fn face_on_off_and_depth_zero_do_not_shift() {
        for &technique in Parallax::all() {
            let m = march(&settings(technique, 8), &inputs(Vec3::Z), |uv| uv.x.fract(), open_cones(|uv| uv.x.fract()));
            assert_eq!(m.uv, Vec2::new(0.5, 0.5), "{technique:?}");
            let flat = MarchInputs { depth_m: 0.0, ..inputs(Vec3::new(1.0, 0.0, 0.2).normalize()) };
            assert_eq!(
                march(&settings(technique, 8), &flat, |_| 0.0, open_cones(|_| 0.0)).shift,
                Vec2::ZERO,
                "{technique:?}"
            );
        }
    }

    /// Grazing, below the surface, 1 and 256 layers, a clamped border: finite, bounded, in range.
    #[test]
    fn grazing_and_below_stay_finite_and_clamped_stays_in_range() {
        let views = [Vec3::X, Vec3::new(1.0, 0.0, -0.3).normalize(), Vec3::new(0.0, 1.0, 1e-4).normalize()];
        for view in views {
            for layers in [1, 256] {
                for technique in Parallax::shifting() {
                    let clamped = MarchInputs { clamp: [true; 2], ..inputs(view) };
                    let wavy = |uv: Vec2| 0.5 + 0.5 * (uv.x * 40.0).sin();
                    let m = march(&settings(technique, layers), &clamped, wavy, open_cones(wavy));
                    assert!(m.uv.is_finite() && m.depth.is_finite(), "{technique:?} {view} {layers}: {m:?}");
                    assert!(m.uv.cmpge(Vec2::ZERO).all() && m.uv.cmple(Vec2::ONE).all(), "{m:?}");
                    assert!(m.layer_hit <= layers);
                }
            }
        }
    }

    fn shadowed(technique: Parallax, layers: u32) -> ParallaxSettings {
        ParallaxSettings { shadow_strength: 1.0, ..settings(technique, layers) }
    }

    /// A flat floor casts no shadow; a ridge between the point and a low light does, fully at
    /// strength 1; lights grazing, below the surface, 1 and 256 samples stay in 0..1.
    #[test]
    fn soft_shadows_fall_behind_ridges_only_and_stay_in_range() {
        let face_on = inputs(Vec3::Z);
        // A floor at half depth; a ridge up to the top at u in 0.52..0.56 (the point is at 0.5).
        let floor = |_: Vec2| 0.5;
        let ridge = |uv: Vec2| if (0.52..0.56).contains(&uv.x) { 1.0 } else { 0.5 };
        let low_light = Vec3::new(1.0, 0.0, 0.3).normalize();
        for technique in Parallax::shifting().filter(|t| t.marches()) {
            let hit = march(&shadowed(technique, 16), &face_on, floor, open_cones(floor));
            let light_ts = light_in_tangent_space(&face_on, low_light);
            assert_eq!(soft_shadow(&shadowed(technique, 16), &face_on, &hit, light_ts, floor), 1.0);
            assert_eq!(soft_shadow(&shadowed(technique, 16), &face_on, &hit, light_ts, ridge), 0.0, "{technique:?}");
            let away = light_in_tangent_space(&face_on, Vec3::new(-1.0, 0.0, 0.3).normalize());
            assert_eq!(
                soft_shadow(&shadowed(technique, 16), &face_on, &hit, away, ridge),
                1.0,
                "lit from the other side"
            );
            let off = ParallaxSettings { shadow_strength: 0.0, ..shadowed(technique, 16) };
            assert_eq!(soft_shadow(&off, &face_on, &hit, light_ts, ridge), 1.0);
            for light in [Vec3::X, Vec3::new(1.0, 0.0, -0.5).normalize(), Vec3::new(0.0, 1.0, 1e-5).normalize()] {
                for layers in [1, 256] {
                    let settings = shadowed(technique, layers);
                    let light_ts = light_in_tangent_space(&face_on, light);
                    let v = soft_shadow(&settings, &face_on, &hit, light_ts, |uv| 0.5 + 0.5 * (uv.x * 40.0).sin());
                    assert!((0.0..=1.0).contains(&v), "{technique:?} {light} {layers}: {v}");
                }
            }
        }
        let offset = march(&shadowed(Parallax::Offset, 16), &face_on, floor, open_cones(floor));
        let light_ts = light_in_tangent_space(&face_on, low_light);
        assert_eq!(soft_shadow(&shadowed(Parallax::Offset, 16), &face_on, &offset, light_ts, ridge), 1.0);
    }
}
