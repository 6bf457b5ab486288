//! The procedural brick texture of the built-in scene: a height field with recessed mortar
//! and slightly uneven bricks, and a matching sRGB colour texture. One tile is square and
//! holds [`ROWS`] courses of [`BRICKS_PER_ROW`] bricks, every other course offset by half a brick.

use glam::Vec3;

use crate::height::HeightField;
use crate::math::smoothstep;
use crate::scene::{TextureImage, TextureKind};

/// Texels per tile side (a power of two, so the mip chain halves cleanly).
pub const TILE_TEXELS: u32 = 512;
pub const ROWS: u32 = 8;
pub const BRICKS_PER_ROW: u32 = 4;
/// Half the mortar joint width, texels.
pub const MORTAR_HALF_WIDTH: f32 = 5.0;
/// Width of the rounded brick edge, texels.
pub const BEVEL_WIDTH: f32 = 6.0;
/// Depth of the mortar below the brick faces, metres per full height range.
pub const RELIEF_DEPTH_M: f32 = 0.01;

/// Where a texel lies in the brick pattern.
struct BrickSample {
    /// Unique per brick in the tile.
    brick_id: u32,
    /// Distance to the nearest brick edge (joint centre line), texels.
    edge_distance: f32,
    /// Horizontal position across the brick, 0..1.
    across: f32,
}

fn brick_sample(x: u32, y: u32) -> BrickSample {
    let brick_w = (TILE_TEXELS / BRICKS_PER_ROW) as f32;
    let brick_h = (TILE_TEXELS / ROWS) as f32;
    let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
    let row = (py / brick_h).floor();
    let shifted = (px + if row as u32 % 2 == 1 { brick_w * 0.5 } else { 0.0 }).rem_euclid(TILE_TEXELS as f32);
    let column = (shifted / brick_w).floor();
    let (lx, ly) = (shifted - column * brick_w, py - row * brick_h);
    BrickSample {
        brick_id: row as u32 * BRICKS_PER_ROW + column as u32,
        edge_distance: lx.min(brick_w - lx).min(ly).min(brick_h - ly),
        across: lx / brick_w,
    }
}

/// A deterministic hash of `(n, salt)` to 0..1.
fn hash01(n: u32, salt: u32) -> f32 {
    let mut h = n.wrapping_mul(0x9E37_79B9) ^ salt.wrapping_mul(0x85EB_CA6B);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^= h >> 16;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Smooth value noise in 0..1 on a `cell`-texel lattice that wraps with the tile.
fn value_noise(x: u32, y: u32, cell: u32, salt: u32) -> f32 {
    let cells = TILE_TEXELS / cell;
    let (fx, fy) = (x as f32 / cell as f32, y as f32 / cell as f32);
    let (ix, iy) = (fx.floor() as u32, fy.floor() as u32);
    let (tx, ty) = (smoothstep(0.0, 1.0, fx.fract()), smoothstep(0.0, 1.0, fy.fract()));
    let corner = |cx: u32, cy: u32| hash01((cy % cells) * cells + (cx % cells), salt);
    let top = corner(ix, iy) + (corner(ix + 1, iy) - corner(ix, iy)) * tx;
    let bottom = corner(ix, iy + 1) + (corner(ix + 1, iy + 1) - corner(ix, iy + 1)) * tx;
    top + (bottom - top) * ty
}

/// 0 in the mortar joint, 1 on a brick face, a smooth bevel between.
fn brick_mask(sample: &BrickSample) -> f32 {
    smoothstep(MORTAR_HALF_WIDTH, MORTAR_HALF_WIDTH + BEVEL_WIDTH, sample.edge_distance)
}

/// The brick height field for a tile `tile_size_m` metres wide: mortar at about 0, each
/// brick face between 0.8 and 1.0 with a slight tilt and a little surface noise.
pub fn brick_height_field(tile_size_m: f32) -> HeightField {
    let mut samples = Vec::with_capacity((TILE_TEXELS * TILE_TEXELS) as usize);
    for y in 0..TILE_TEXELS {
        for x in 0..TILE_TEXELS {
            let sample = brick_sample(x, y);
            let id = sample.brick_id;
            let tilt = (hash01(id, 2) - 0.5) * 0.12 * (sample.across - 0.5);
            let face = 0.8 + 0.15 * hash01(id, 1) + tilt + 0.04 * value_noise(x, y, 16, 3);
            let mortar = 0.06 * value_noise(x, y, 8, 4);
            let mask = brick_mask(&sample);
            samples.push(mortar + (face - mortar) * mask);
        }
    }
    HeightField {
        width: TILE_TEXELS,
        height: TILE_TEXELS,
        samples,
        range_m: RELIEF_DEPTH_M,
        texel_size_m: tile_size_m / TILE_TEXELS as f32,
    }
}

/// The matching sRGB colour texture: red-brown bricks, each a little different, grey mortar.
pub fn brick_color_texture() -> TextureImage {
    let mortar = Vec3::new(0.66, 0.64, 0.60);
    let mut rgba = Vec::with_capacity((TILE_TEXELS * TILE_TEXELS * 4) as usize);
    for y in 0..TILE_TEXELS {
        for x in 0..TILE_TEXELS {
            let sample = brick_sample(x, y);
            let id = sample.brick_id;
            let brick =
                Vec3::new(0.62, 0.27, 0.18) * (0.8 + 0.35 * hash01(id, 5)) + Vec3::new(0.05, 0.03, 0.0) * hash01(id, 6);
            let grain = 0.88 + 0.12 * value_noise(x, y, 4, 7);
            let color = (mortar + (brick - mortar) * brick_mask(&sample)) * grain;
            rgba.extend(color.to_array().map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8));
            rgba.push(255);
        }
    }
    TextureImage::new("bricks (colour)", TILE_TEXELS, TILE_TEXELS, TextureKind::Color, rgba)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mortar_is_recessed_and_bricks_are_raised() {
        let field = brick_height_field(1.0);
        let brick_h = (TILE_TEXELS / ROWS) as i64;
        // Row 0 joint line is at y = 0; the middle of the first brick is well inside it.
        assert!(field.at(10, 0) < 0.1, "mortar");
        assert!(field.at(64, brick_h / 2) > 0.75, "brick face");
    }

    #[test]
    fn the_pattern_tiles_seamlessly() {
        let field = brick_height_field(1.0);
        let n = TILE_TEXELS as i64;
        // Across the wrap the step is no larger than inside the tile.
        for y in (0..n).step_by(37) {
            let across = (field.at(0, y) - field.at(n - 1, y)).abs();
            let inside = (field.at(1, y) - field.at(0, y)).abs();
            assert!(across < inside + 0.2, "row {y}: {across} vs {inside}");
        }
    }
}
