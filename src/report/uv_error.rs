//! The parallax family's texture-space error: at each surface point, the UV a technique reads
//! the normal map and colour at ([`crate::chain::parallax::march`], the function the probe and
//! the GPU twin run) against the UV of the view ray's exact first intersection with the height
//! field ([`super::exact_hit`]), in texels of the height map. This is the error the techniques
//! are about, free of the shading differences the image comparison carries.
//!
//! The specimens are the built-in wall's brick height map (one 1 m tile, its 1 cm relief, u along
//! +x and v down as on [`super::parallax::square_mesh`]) and, where the shared assets are,
//! Rock058's displacement (2 cm), each seen from `angle` degrees about +Y
//! (the direction to the eye `(sin θ, 0, cos θ)`, the GPU study's cameras) by parallel rays:
//! every point sees the same direction. Heights (16 bits, as the GPU's texture holds them) are
//! read bilinearly from level 0 with repeat wrapping ([`bilinear`]) by both the technique and
//! the exact hit: the mip level the GPU's footprint picks is left out, so the error is the
//! technique's alone. Relaxed cone stepping reads the cone map the prepare stage packs
//! beside the heights ([`crate::height::cone`], 8 bits as the texture holds it), bilinearly too.

use glam::{DVec2, Vec2, Vec3};

use super::exact_hit::{ExactHit, bilinear, exact_hit};
use super::parallax::{Specimen, cases, settings};
use crate::chain::parallax::{ConeTexel, MarchInputs, march};
use crate::frame::{Parallax, ParallaxSettings};
use crate::height::HeightField;
use crate::height::cone::{decode_cone_ratio, encode_cone_ratio, relaxed_cone_ratios};
use crate::scene::bricks::brick_height_field;
use crate::scene::builtin::BRICK_TILE_M;
use crate::scene::material::TEXTURE_SPAN_M;

/// A height at or above this (0..1) is a brick face, at or below [`MORTAR_BELOW`] mortar:
/// the wall's faces lie at 0.8..1 and its mortar at about 0..0.06, joined by a 6-texel bevel
/// that counts as neither (a small shift across the bevel is a shift, not a wrong brick).
pub const BRICK_ABOVE: f64 = 0.7;
pub const MORTAR_BELOW: f64 = 0.3;
/// The path between two UVs is checked for a region change at this spacing, texels.
const REGION_STEP_TEXELS: f64 = 0.25;

/// A height field and the relief's depth: what the rays are traced through.
#[derive(Debug, Clone)]
pub struct Relief {
    /// The specimen's name (as in the image study).
    pub name: &'static str,
    /// The field is bricks and joints: the wrong-brick share applies ([`Self::crosses_region`]).
    pub bricks: bool,
    pub field: HeightField,
    /// The relaxed cone map's stored blue channel (0..1) of `field`, as the height texture
    /// holds it ([`cone_channel`]).
    pub cones: HeightField,
    /// The relief's depth, metres (0: no parallax).
    pub depth_m: f32,
    /// Metres of surface per UV unit.
    pub tile_m: f32,
}

impl Relief {
    /// The built-in wall's bricks at their own depth, stored with 16 bits a sample as its
    /// height texture is ([`crate::texture::encode_height`]).
    pub fn wall() -> Relief {
        Relief::wall_with_cones(true)
    }

    /// [`Self::wall`], its cone map made only `with_cones` (else the heights stand in: the
    /// techniques that do not read cones never look).
    pub fn wall_with_cones(with_cones: bool) -> Relief {
        let field = brick_height_field(BRICK_TILE_M).quantized(16);
        let cones = if with_cones { cone_channel(&field) } else { field.clone() };
        Relief { name: "wall", bricks: true, depth_m: field.range_m, field, cones, tile_m: BRICK_TILE_M }
    }

    /// The height map of `specimen`'s first material as the GPU reads it (16-bit samples
    /// decoded, `1 − h` for a depth map), at its depth, one UV unit per [`TEXTURE_SPAN_M`];
    /// `None` where the material has no height map.
    pub fn of_specimen(name: &'static str, specimen: &Specimen) -> Option<Relief> {
        let slot = specimen.scene.materials.first()?.height_map.clone()?;
        let texture = specimen.scene.textures.get(slot.texture)?;
        let field = slot.height_field(texture, TEXTURE_SPAN_M);
        let cones = cone_channel(&field);
        Some(Relief { name, bricks: false, depth_m: slot.range_m, field, cones, tile_m: TEXTURE_SPAN_M })
    }

    /// Texels per UV unit on each axis.
    pub fn texels(&self) -> DVec2 {
        DVec2::new(f64::from(self.field.width), f64::from(self.field.height))
    }

    /// What the fragment shader knows at `uv` seen from `angle_deg`: a flat surface facing +Z,
    /// derivatives of a millimetre a pixel.
    pub fn inputs(&self, uv: Vec2, angle_deg: f32) -> MarchInputs {
        let (sin, cos) = angle_deg.to_radians().sin_cos();
        let pixel_m = 1e-3;
        MarchInputs {
            uv,
            normal: Vec3::Z,
            view_dir: Vec3::new(sin, 0.0, cos),
            dp_dx: Vec3::X * pixel_m,
            dp_dy: Vec3::NEG_Y * pixel_m,
            duv_dx: Vec2::new(pixel_m / self.tile_m, 0.0),
            duv_dy: Vec2::new(0.0, pixel_m / self.tile_m),
            depth_m: self.depth_m,
            clamp: [false; 2],
        }
    }

    /// The exact hit of the ray entering at `uv` from `angle_deg` (under 90°): its UV moves
    /// `−tan θ · depth / tile` along u over the relief's depth.
    pub fn exact(&self, uv: Vec2, angle_deg: f32) -> ExactHit {
        let shift = -f64::from(angle_deg).to_radians().tan() * f64::from(self.depth_m) / f64::from(self.tile_m);
        exact_hit(uv.as_dvec2(), DVec2::new(shift, 0.0), self.texels(), |p| bilinear(&self.field, p))
    }

    /// Whether the straight UV path from `a` to `b` (both ends included) reads both a brick
    /// face ([`BRICK_ABOVE`]) and mortar ([`MORTAR_BELOW`]): the technique's UV in or out of a
    /// joint, or on another brick across one.
    pub fn crosses_region(&self, a: DVec2, b: DVec2) -> bool {
        let steps = (((b - a) * self.texels()).length() / REGION_STEP_TEXELS).ceil() as u32;
        let (mut brick, mut mortar) = (false, false);
        for i in 0..=steps {
            let h = bilinear(&self.field, a + (b - a) * (f64::from(i) / f64::from(steps.max(1))));
            brick |= h >= BRICK_ABOVE;
            mortar |= h <= MORTAR_BELOW;
        }
        brick && mortar
    }
}

/// The relaxed cone map of `field` as the height texture's blue channel holds it: each ratio
/// stored in 8 bits ([`encode_cone_ratio`]), as 0..1.
pub fn cone_channel(field: &HeightField) -> HeightField {
    let stored = relaxed_cone_ratios(field).iter().map(|&r| f32::from(encode_cone_ratio(r)) / 255.0).collect();
    HeightField { samples: stored, ..field.clone() }
}

/// The angles the report measures the wall from: 0° to 85° in 5° steps.
pub fn report_angles() -> Vec<f32> {
    (0..=17).map(|i| 5.0 * i as f32).collect()
}

/// `n × n` surface points over the tile, at the centres of an `n × n` grid.
pub fn grid(n: u32) -> Vec<Vec2> {
    let cell = 1.0 / n as f32;
    (0..n).flat_map(|y| (0..n).map(move |x| Vec2::new((x as f32 + 0.5) * cell, (y as f32 + 0.5) * cell))).collect()
}

/// One technique at one layer count and angle, over the points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvError {
    /// The relief's name ([`Relief::name`]).
    pub specimen: &'static str,
    pub technique: Parallax,
    /// Layers of the search (`None` for the techniques without one).
    pub layers: Option<u32>,
    pub angle_deg: f32,
    /// Distance from the exact hit's UV, texels: mean, 95th percentile, largest.
    pub mean: f64,
    pub p95: f64,
    pub max: f64,
    /// Share of points (0..1) whose UV lies on another brick than the exact hit's, or in a
    /// joint where the hit is on a brick (or the reverse): the UV path between them reads both
    /// a face and mortar ([`Relief::crosses_region`]). `None` for a relief without bricks.
    pub wrong_brick: Option<f64>,
}

/// `technique` at `layers` from `angle_deg` over `points`, against their exact hits `hits`.
pub fn uv_error(
    relief: &Relief,
    points: &[Vec2],
    hits: &[ExactHit],
    angle_deg: f32,
    (technique, layers): (Parallax, Option<u32>),
) -> UvError {
    let parallax = settings(technique, layers);
    let reads = reads(relief, points, angle_deg, &parallax);
    let mut errors = Vec::with_capacity(points.len());
    let mut wrong = 0usize;
    for (read, hit) in reads.zip(hits) {
        errors.push(((read - hit.uv) * relief.texels()).length());
        wrong += usize::from(relief.bricks && relief.crosses_region(hit.uv, read));
    }
    errors.sort_by(f64::total_cmp);
    let n = errors.len().max(1);
    let p95 = errors.get(((n as f64 * 0.95).ceil() as usize).saturating_sub(1)).copied().unwrap_or(0.0);
    UvError {
        specimen: relief.name,
        technique,
        layers,
        angle_deg,
        mean: errors.iter().sum::<f64>() / n as f64,
        p95,
        max: errors.last().copied().unwrap_or(0.0),
        wrong_brick: relief.bricks.then_some(wrong as f64 / n as f64),
    }
}

/// The UV `parallax` reads at each of `points` seen from `angle_deg`.
fn reads<'a>(
    relief: &'a Relief,
    points: &'a [Vec2],
    angle_deg: f32,
    parallax: &'a ParallaxSettings,
) -> impl Iterator<Item = DVec2> + 'a {
    let height = |uv: Vec2| bilinear(&relief.field, uv.as_dvec2()) as f32;
    let cone = move |uv: Vec2| ConeTexel {
        height: height(uv),
        ratio: decode_cone_ratio(bilinear(&relief.cones, uv.as_dvec2()) as f32),
    };
    points.iter().map(move |&uv| march(parallax, &relief.inputs(uv, angle_deg), height, cone).uv.as_dvec2())
}

/// [`uv_error`]'s mean, texels, for any settings (a search's own layer range and refinement
/// steps) over an `n × n` grid of `relief` seen from `angle_deg`.
pub fn mean_uv_error(relief: &Relief, angle_deg: f32, parallax: &ParallaxSettings, n: u32) -> f64 {
    let points = grid(n);
    let hits = points.iter().map(|&uv| relief.exact(uv, angle_deg));
    let total: f64 = reads(relief, &points, angle_deg, parallax)
        .zip(hits)
        .map(|(read, hit)| ((read - hit.uv) * relief.texels()).length())
        .sum();
    total / points.len().max(1) as f64
}

/// Every technique but off (each search at each of `layers`) at each of `angles_deg`, over an
/// `n × n` grid of `relief`.
pub fn study(relief: &Relief, angles_deg: &[f32], layers: &[u32], n: u32) -> Vec<UvError> {
    let points = grid(n);
    let mut rows = Vec::new();
    for &angle in angles_deg {
        let hits: Vec<ExactHit> = points.iter().map(|&uv| relief.exact(uv, angle)).collect();
        for case in cases(layers).into_iter().filter(|(t, _)| t.shifts()) {
            rows.push(uv_error(relief, &points, &hits, angle, case));
        }
    }
    rows
}
