//! Relaxed cone maps (Policarpo & Oliveira 2007, "Relaxed cone stepping for relief mapping",
//! GPU Gems 3 ch. 18; cone maps after Dummer 2006, "Cone step mapping"): for every texel, how
//! wide a cone standing on the relief's surface there may open upwards so that a view ray
//! coming down from the top above the texel leaves the solid at most once inside it.
//!
//! Coordinates are those of the parallax march: UV horizontally and the depth fraction `t`
//! (0 at the top of the relief, 1 at its bottom) vertically, so a cone ratio is UV units of
//! radius per unit of depth fraction and holds for any relief depth or UV density. A texel of
//! height `h` lies at depth `1 − h`.
//!
//! The map is built on the CPU by scanning [`CONE_DIRECTIONS`] directions from each texel
//! out to the widest cone stored ([`MAX_CONE_RATIO`]). The first [`NEAR_TEXELS`] texels are
//! read one by one, nearest (flat columns): where the relief drops from a column of depth `d`
//! to a deeper one, rays from the top above the source leave the solid over the edge, the
//! highest just under `d`; an edge higher than the source bounds its cone:
//! ratio ≤ `distance / (depth(s) − d)`, as the exit points of the published GPU pass bound it
//! (every exit, not only each ray's first: a little narrower, never wider). Further out the
//! scan steps [`FAR_STEP`] texels over the field's maximum within that many texels and any
//! point higher than the source bounds the cone at its nearest possible distance (Dummer's
//! conservative bound): narrower again, never wider, and a few times faster. Measured build
//! times (`tests` profile, 2 shared cores) are in `docs/parallax.md`.

use rayon::prelude::*;

use super::HeightField;

/// The widest cone stored, UV units per unit of depth fraction: wider cones step no further
/// in practice (a view ray 85° off the normal over the built-in wall's 1 cm on 1 m moves 0.11
/// UV units over the whole depth).
pub const MAX_CONE_RATIO: f32 = 0.25;
/// Directions scanned from each texel, evenly over the circle.
pub const CONE_DIRECTIONS: usize = 16;
/// Texels from the source read one by one for the relaxed bound.
pub const NEAR_TEXELS: f32 = 16.0;
/// The far scan's step and the radius (texels, square) of its maximum filter.
pub const FAR_STEP: i64 = 8;

/// The relaxed cone ratio of every texel of `field` (wrapping), row by row, in
/// `0..=`[`MAX_CONE_RATIO`] UV units per unit of depth fraction.
pub fn relaxed_cone_ratios(field: &HeightField) -> Vec<f32> {
    let (width, height) = (field.width as usize, field.height as usize);
    let highest = maximum_within(field, FAR_STEP);
    let mut ratios = vec![0.0f32; width * height];
    ratios.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
        for (x, ratio) in row.iter_mut().enumerate() {
            *ratio = cone_ratio_at(field, &highest, x as i64, y as i64);
        }
    });
    ratios
}

/// `field` with each sample the largest within `radius` texels on both axes (wrapping).
fn maximum_within(field: &HeightField, radius: i64) -> HeightField {
    let (width, height) = (field.width as usize, field.height as usize);
    let max_along = |at: &dyn Fn(i64) -> f32| (-radius..=radius).map(at).fold(f32::MIN, f32::max);
    let mut rows = vec![0.0f32; width * height];
    rows.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            *out = max_along(&|d| field.at(x as i64 + d, y as i64));
        }
    });
    let across_rows = HeightField { samples: rows, ..field.clone() };
    let mut samples = vec![0.0f32; width * height];
    samples.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            *out = max_along(&|d| across_rows.at(x as i64, y as i64 + d));
        }
    });
    HeightField { samples, ..field.clone() }
}

/// The relaxed cone ratio at texel `(x, y)`; `highest` is the field's [`maximum_within`]
/// [`FAR_STEP`] texels.
fn cone_ratio_at(field: &HeightField, highest: &HeightField, x: i64, y: i64) -> f32 {
    let depth_at = |x: i64, y: i64| 1.0 - field.at(x, y);
    let source_depth = depth_at(x, y);
    let texel_uv = (1.0 / field.width.max(1) as f32, 1.0 / field.height.max(1) as f32);
    let mut best = MAX_CONE_RATIO;
    for direction in 0..CONE_DIRECTIONS {
        let angle = std::f32::consts::TAU * direction as f32 / CONE_DIRECTIONS as f32;
        let (sin, cos) = angle.sin_cos();
        let step_uv = ((cos * texel_uv.0).powi(2) + (sin * texel_uv.1).powi(2)).sqrt();
        let texel = |k: f32| (x + (cos * k).round() as i64, y + (sin * k).round() as i64);
        // Column k (texels along the scan, nearest sampling) is solid below `inside`; where the
        // next one drops away, a ray from the top above the source leaves the relief over the
        // boundary at k + ½, the highest such exit just under depth `inside`.
        let mut inside = source_depth;
        let mut k = 0.0f32;
        // An exit further than best · depth(s) bounds no cone narrower than `best`.
        while k < NEAR_TEXELS && (k + 0.5) * step_uv < best * source_depth {
            let (nx, ny) = texel(k + 1.0);
            let next = depth_at(nx, ny);
            if next > inside && inside < source_depth {
                best = best.min((k + 0.5) * step_uv / (source_depth - inside));
            }
            inside = next;
            k += 1.0;
        }
        // Further out: the highest point within FAR_STEP texels of each step, at its nearest.
        let reach = FAR_STEP as f32 * std::f32::consts::SQRT_2 + 0.5;
        let mut k = NEAR_TEXELS + FAR_STEP as f32;
        while (k - reach) * step_uv < best * source_depth {
            let (fx, fy) = texel(k);
            let top = 1.0 - highest.at(fx, fy);
            if top < source_depth {
                best = best.min((k - reach).max(0.0) * step_uv / (source_depth - top));
            }
            k += FAR_STEP as f32;
        }
    }
    best
}

/// A cone ratio as the height texture's blue channel stores it: `⌊255 · √(ratio / max)⌋`,
/// rounded down so a stored cone is never wider than the one built.
pub fn encode_cone_ratio(ratio: f32) -> u8 {
    (255.0 * (ratio / MAX_CONE_RATIO).clamp(0.0, 1.0).sqrt()).floor() as u8
}

/// The cone ratio of a (filtered) blue channel `b` in 0..1: `max · b²`.
pub fn decode_cone_ratio(b: f32) -> f32 {
    MAX_CONE_RATIO * b * b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(width: u32, samples: Vec<f32>) -> HeightField {
        HeightField { width, height: samples.len() as u32 / width, samples, range_m: 0.01, texel_size_m: 0.01 }
    }

    /// A flat field bounds no cone; a pit's walls bound none within [`NEAR_TEXELS`] (every ray
    /// into a pit meets its wall or floor once), only the far scan's conservative bound; a
    /// one-texel spike bounds the cone of the floor beside it by its far edge, 1.5 texels away
    /// and the whole depth above.
    #[test]
    fn flat_fields_and_pits_open_and_spikes_bound_their_neighbours() {
        assert!(relaxed_cone_ratios(&field(8, vec![0.5; 64])).iter().all(|&r| r == MAX_CONE_RATIO));
        let mut pit = vec![1.0; 64 * 64];
        pit[32 * 64 + 32] = 0.0;
        let ratios = relaxed_cone_ratios(&field(64, pit));
        let far_bound = (NEAR_TEXELS + FAR_STEP as f32 - FAR_STEP as f32 * std::f32::consts::SQRT_2 - 0.5) / 64.0;
        assert!((ratios[32 * 64 + 32] - far_bound).abs() < 1e-6, "{}", ratios[32 * 64 + 32]);
        assert_eq!(ratios.iter().filter(|&&r| r == MAX_CONE_RATIO).count(), 64 * 64 - 1);
        let mut spike = vec![0.0; 64 * 64];
        spike[32 * 64 + 32] = 1.0;
        let ratios = relaxed_cone_ratios(&field(64, spike));
        assert!((ratios[32 * 64 + 31] - 1.5 / 64.0).abs() < 1e-6, "{}", ratios[32 * 64 + 31]);
        assert_eq!(ratios[32 * 64 + 32], MAX_CONE_RATIO, "the top bounds nothing");
    }

    #[test]
    fn stored_ratios_round_down_and_decode() {
        for ratio in [0.0, 0.001, 0.02, 0.1, MAX_CONE_RATIO] {
            let stored = decode_cone_ratio(f32::from(encode_cone_ratio(ratio)) / 255.0);
            assert!(stored <= ratio + 1e-7 && stored > ratio * 0.9 - 1e-3, "{ratio}: {stored}");
        }
    }
}
