//! LEAN mapping's moments of a normal map (Olano & Baker, "LEAN mapping", I3D 2010): per texel
//! the slopes `B = (nx/nz, ny/nz)` and their second moments `M = (Bx², By², Bx·By)`, box-filtered
//! down the mip chain. Both are linear in the texels, so a mip texel's moments are exactly the
//! means over the base texels it covers and `M − B·Bᵀ` is their covariance. Stored in floats
//! (the GPU would take `Rgba16Float`): in 8 bits the cancellation in `M − B·Bᵀ` loses the
//! variance (Olano & Baker scale `B` by a per-map factor for that; floats need none).

use glam::{Vec2, Vec3};

use super::{TextureImage, decode_unit_normal};

/// The smallest `nz` a slope is taken at: steeper normals are read as 20:1 slopes (a normal
/// map's z is positive; at the horizon the slope is infinite).
pub const MIN_LEAN_NZ: f32 = 0.05;

/// One level of LEAN's moments, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct LeanLevel {
    pub width: u32,
    pub height: u32,
    /// Mean slopes `B = (nx/nz, ny/nz)` (tangent space, per unit of the surface).
    pub first: Vec<Vec2>,
    /// Mean second moments `(Bx², By², Bx·By)`.
    pub second: Vec<Vec3>,
}

impl LeanLevel {
    /// The slope covariance `M − B·Bᵀ` at texel `index`: `(σxx, σyy, σxy)`.
    pub fn covariance(&self, index: usize) -> Vec3 {
        let (b, m) = (self.first[index], self.second[index]);
        Vec3::new(m.x - b.x * b.x, m.y - b.y * b.y, m.z - b.x * b.y)
    }
}

/// The slopes of a unit tangent-space normal, `(nx/nz, ny/nz)` with `nz ≥` [`MIN_LEAN_NZ`].
pub fn slopes(n: Vec3) -> Vec2 {
    Vec2::new(n.x, n.y) / n.z.max(MIN_LEAN_NZ)
}

impl TextureImage {
    /// LEAN's moments of this RGB normal map, level 0 first down to 1×1, by the same 2×2 boxes
    /// as [`TextureImage::downsampled`].
    pub fn lean_moments(&self) -> Vec<LeanLevel> {
        let (first, second) = self
            .rgba
            .chunks_exact(4)
            .map(|t| {
                let b = slopes(decode_unit_normal([t[0], t[1], t[2]]));
                (b, Vec3::new(b.x * b.x, b.y * b.y, b.x * b.y))
            })
            .unzip();
        let mut levels = vec![LeanLevel { width: self.width, height: self.height, first, second }];
        while let Some(last) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
            let (w, h) = (last.width as usize, last.height as usize);
            let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
            let corners = |x: usize, y: usize| {
                [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| ((2 * y + dy).min(h - 1)) * w + (2 * x + dx).min(w - 1))
            };
            let cells: Vec<[usize; 4]> =
                (0..nh).flat_map(|y| (0..nw).map(move |x| (x, y))).map(|(x, y)| corners(x, y)).collect();
            let first = cells.iter().map(|c| c.iter().map(|&i| last.first[i]).sum::<Vec2>() / 4.0).collect();
            let second = cells.iter().map(|c| c.iter().map(|&i| last.second[i]).sum::<Vec3>() / 4.0).collect();
            levels.push(LeanLevel { width: nw as u32, height: nh as u32, first, second });
        }
        levels
    }
}
