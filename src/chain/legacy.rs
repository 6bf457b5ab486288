//! The legacy looks ([`LegacyLook`]) as steps of the CPU chain, each the twin of its function
//! in `shaders/legacy.wgsl`: the per-vertex light and half vectors the vertex stage passes on
//! (DOT3 and the per-vertex lighting mistakes read them), the normalization cube map (Cg
//! tutorial 8.1.3) with its lookup, DOT3's colour, and the emboss look's light map and colour.
//!
//! Vectors are world space and colours linear RGB unless stated. The cube map and the light
//! map are built here once and uploaded as they are, so the GPU reads the same bytes.

use glam::{Vec2, Vec3};

use std::sync::OnceLock;

#[cfg(doc)]
use crate::frame::{LegacyLook, Mistake};
use crate::math::normalize_or;
#[cfg(doc)]
use crate::scene::Lights;
use crate::scene::{Light, LightKind};
use crate::shading::lights::incident;

/// At a vertex at `position` (world space) with normal `normal` (not necessarily unit): the
/// unit direction to `light` (the first light that is on, [`Lights::first_on`]; a point or a
/// directional light, [`incident`]; the normal without one) and the unit half vector between
/// it and the direction to the eye. The vertex stage passes both on for interpolation (DOT3,
/// [`Mistake::LightPerVertex`], [`Mistake::HalfVectorPerVertex`]).
pub fn vertex_vectors(position: Vec3, normal: Vec3, light: Option<&Light>, eye: Vec3) -> (Vec3, Vec3) {
    let n = normalize_or(normal, Vec3::Z);
    let l = light.map_or(n, |light| incident(light, position, n).direction);
    let v = normalize_or(eye - position, n);
    (l, normalize_or(l + v, n))
}

/// DOT3's colour: `albedo · radiance · max(N·L, 0)` with `l` as given (unnormalised where it
/// was interpolated) and the radiance arriving from the first light ([`incident`]): no
/// ambient, no specular, no self-shadowing.
pub fn dot3_color(albedo: Vec3, radiance: Vec3, n_shading: Vec3, l: Vec3) -> Vec3 {
    albedo * radiance * n_shading.dot(l).max(0.0)
}

/// The face of a cube map `d` points at and its coordinates on it: the major axis `a`
/// (0 x, 1 y, 2 z) and sign give face `2a` (+) or `2a + 1` (−); `(u, v)` are the next two axes,
/// `d[(a+1)%3]` and `d[(a+2)%3]`, divided by `|d[a]|`, in −1..1.
pub fn cube_face(d: Vec3) -> (usize, Vec2) {
    let a = d.abs();
    let axis = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let c = d.to_array();
    let major = c[axis];
    let face = 2 * axis + usize::from(major < 0.0);
    let scale = if major != 0.0 { major.abs().recip() } else { 0.0 };
    (face, Vec2::new(c[(axis + 1) % 3], c[(axis + 2) % 3]) * scale)
}

/// The unit direction at the centre of texel `(i, j)` of face `face` of a cube map `size`
/// texels a side ([`cube_face`]'s layout).
pub fn cube_texel_direction(face: usize, i: u32, j: u32, size: u32) -> Vec3 {
    let uv = (Vec2::new(i as f32, j as f32) + 0.5) / size as f32 * 2.0 - 1.0;
    let axis = face / 2;
    let mut c = [0.0; 3];
    c[axis] = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    c[(axis + 1) % 3] = uv.x;
    c[(axis + 2) % 3] = uv.y;
    Vec3::from_array(c).normalize()
}

/// A normalization cube map of face size `size`: per face (in face order), per row `j`, per
/// column `i`, the texel centre's unit direction stored as `0.5·d + 0.5` in 8-bit RGB, alpha
/// 255. Uploaded as a six-layer 2D array texture.
pub fn normalization_cube_map(size: u32) -> Vec<[u8; 4]> {
    let mut texels = Vec::with_capacity(6 * (size * size) as usize);
    for face in 0..6 {
        for j in 0..size {
            for i in 0..size {
                let d = cube_texel_direction(face, i, j, size) * 0.5 + 0.5;
                let [r, g, b] = d.to_array().map(|c| (c * 255.0).round() as u8);
                texels.push([r, g, b, 255]);
            }
        }
    }
    texels
}

/// The normalization cube map of face size `size` ([`normalization_cube_map`]), made once
/// per size (sizes outside [`crate::frame::CUBE_MAP_SIZES`] are made each call).
pub fn cube_map(size: u32) -> std::borrow::Cow<'static, [[u8; 4]]> {
    static MADE: [OnceLock<Vec<[u8; 4]>>; 4] = [const { OnceLock::new() }; 4];
    match crate::frame::CUBE_MAP_SIZES.iter().position(|&s| s == size) {
        Some(i) => std::borrow::Cow::Borrowed(MADE[i].get_or_init(|| normalization_cube_map(size))),
        None => std::borrow::Cow::Owned(normalization_cube_map(size)),
    }
}

/// `d` through the cube map `texels` ([`normalization_cube_map`] of face size `size`): on its
/// face, bilinear between the four nearest texel centres (clamped at the face's edges), each
/// decoded `2·rgb − 1`; not re-normalised, as the classic pipelines used it.
pub fn cube_map_lookup(texels: &[[u8; 4]], size: u32, d: Vec3) -> Vec3 {
    let (face, uv) = cube_face(d);
    let texel = ((uv + 1.0) * 0.5 * size as f32 - 0.5).clamp(Vec2::ZERO, Vec2::splat(size as f32 - 1.0));
    let (i0, j0) = (texel.x.floor() as u32, texel.y.floor() as u32);
    let (i1, j1) = ((i0 + 1).min(size - 1), (j0 + 1).min(size - 1));
    let f = texel - Vec2::new(i0 as f32, j0 as f32);
    let at = |i: u32, j: u32| {
        let t = texels[(face as u32 * size * size + j * size + i) as usize];
        Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 255.0 * 2.0 - 1.0
    };
    let top = at(i0, j0).lerp(at(i1, j0), f.x);
    let bottom = at(i0, j1).lerp(at(i1, j1), f.x);
    top.lerp(bottom, f.y)
}

/// The emboss light map's side, texels; its centre is the light.
pub const LIGHT_MAP_SIZE: u32 = 256;

/// The emboss look's precomputed light map: a round spot, `1 − r / 128` (r in texels from the
/// centre, 0 beyond), stored in 8 bits (grey, alpha 255), row by row.
pub fn emboss_light_map() -> Vec<[u8; 4]> {
    let half = LIGHT_MAP_SIZE as f32 / 2.0;
    (0..LIGHT_MAP_SIZE * LIGHT_MAP_SIZE)
        .map(|k| {
            let offset = Vec2::new((k % LIGHT_MAP_SIZE) as f32, (k / LIGHT_MAP_SIZE) as f32) - half;
            let value = ((1.0 - offset.length() / half).max(0.0) * 255.0).round() as u8;
            [value, value, value, 255]
        })
        .collect()
}

/// The emboss light map ([`emboss_light_map`]), made once.
pub fn light_map() -> &'static [[u8; 4]] {
    static MADE: OnceLock<Vec<[u8; 4]>> = OnceLock::new();
    MADE.get_or_init(emboss_light_map)
}

/// The emboss brightness 0..1: the light map ([`emboss_light_map`]) at
/// `(slope.x − light.x, slope.y − light.y)` from its centre, the nearest texel, 0 off the map.
/// `slope` is the height difference of the texels right and left, below and above (in steps
/// of 1/255 of the full range), `light` the light's offset from the point in the demo's
/// pixels ([`emboss_light_offset`]).
pub fn emboss_brightness(light_map: &[[u8; 4]], slope: Vec2, light: Vec2) -> f32 {
    let at = (slope - light + LIGHT_MAP_SIZE as f32 / 2.0).floor();
    let inside = at.cmpge(Vec2::ZERO).all() && at.cmplt(Vec2::splat(LIGHT_MAP_SIZE as f32)).all();
    if !inside {
        return 0.0;
    }
    light_map[(at.y as u32 * LIGHT_MAP_SIZE + at.x as u32) as usize][0] as f32 / 255.0
}

/// What the emboss look reads at a point: the height map's samples (mip 0, bilinear) one
/// texel left, right, above and below (0..1 of the full range, after the depth flip).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmbossSample {
    pub left: f32,
    pub right: f32,
    pub up: f32,
    pub down: f32,
}

/// The 2D demo's pixels per metre of surface: positions `x, y` are centimetres, so the light
/// map's spot (128 of its texels) spans 1.28 m around the light.
pub const EMBOSS_PIXELS_PER_M: f32 = 100.0;

/// The vector from `position` towards `light` the emboss look places its light map with: to
/// a point light's position (metres); a directional light's unit direction ([`incident`],
/// `n` the fallback), as if it were 1 m away.
pub fn emboss_to_light(light: &Light, position: Vec3, n: Vec3) -> Vec3 {
    match light.kind {
        LightKind::Point => light.position - position,
        LightKind::Directional => incident(light, position, n).direction,
    }
}

/// The light's offset from the point in the 2D demo's pixels ([`EMBOSS_PIXELS_PER_M`]), x
/// right and y down the image: `(T·to_light, −B·to_light) · 100` (B points up the image).
pub fn emboss_light_offset(t: Vec3, b: Vec3, to_light: Vec3) -> Vec2 {
    Vec2::new(t.dot(to_light), -b.dot(to_light)) * EMBOSS_PIXELS_PER_M
}

/// The emboss colour: `albedo · radiance · brightness` ([`emboss_brightness`]) with the
/// radiance arriving from the first light ([`incident`]), the slope in steps of 1/255 times
/// `strength` (the bump strength, 0 with bump off).
pub fn emboss_color(albedo: Vec3, radiance: Vec3, sample: &EmbossSample, light: Vec2, strength: f32) -> Vec3 {
    let slope = Vec2::new(sample.right - sample.left, sample.down - sample.up) * 255.0 * strength;
    albedo * radiance * emboss_brightness(light_map(), slope, light)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every texel centre's direction finds its own face and texel again, and the lookup of
    /// a texel centre is its stored vector.
    #[test]
    fn texel_centres_round_trip_through_the_cube_map() {
        for size in crate::frame::CUBE_MAP_SIZES {
            let texels = normalization_cube_map(size);
            for face in 0..6 {
                for (i, j) in [(0, 0), (size - 1, 3 % size), (size / 2, size - 1)] {
                    let d = cube_texel_direction(face, i, j, size);
                    assert_eq!(cube_face(d).0, face);
                    let stored = texels[(face as u32 * size * size + j * size + i) as usize];
                    let decoded = Vec3::new(stored[0] as f32, stored[1] as f32, stored[2] as f32) / 255.0 * 2.0 - 1.0;
                    assert!((cube_map_lookup(&texels, size, d * 3.0) - decoded).length() < 1e-5);
                }
            }
        }
    }

    #[test]
    fn the_light_map_is_brightest_at_the_light_and_dark_off_the_map() {
        let map = emboss_light_map();
        assert_eq!(emboss_brightness(&map, Vec2::ZERO, Vec2::ZERO), 1.0);
        assert_eq!(emboss_brightness(&map, Vec2::ZERO, Vec2::new(500.0, 0.0)), 0.0);
        let half_way = emboss_brightness(&map, Vec2::new(64.0, 0.0), Vec2::ZERO);
        assert!((half_way - 0.5).abs() < 0.01, "{half_way}");
    }
}
