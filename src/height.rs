//! Height fields and their conversion to tangent-space normal maps.
//!
//! A height field stores samples in 0..1 (white = high). Its `range_m` says how many metres
//! the full range spans and `texel_size_m` how many metres one texel covers on the surface,
//! so the slope `∂h/∂x` in world units is `Δsample · range_m / texel_size_m`.

use glam::Vec3;

use crate::math::normalize_or;
use crate::scene::{TextureImage, TextureKind};

/// A wrapping (tileable) height field, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightField {
    pub width: u32,
    pub height: u32,
    /// `width · height` samples in 0..1.
    pub samples: Vec<f32>,
    /// Metres per full sample range (0 → 1).
    pub range_m: f32,
    /// Metres per texel on the surface.
    pub texel_size_m: f32,
}

impl HeightField {
    /// Sample at `(x, y)`, wrapped into the field.
    pub fn at(&self, x: i64, y: i64) -> f32 {
        let x = x.rem_euclid(self.width as i64) as usize;
        let y = y.rem_euclid(self.height as i64) as usize;
        self.samples[y * self.width as usize + x]
    }

    /// World-unit slopes `(∂h/∂x, ∂h/∂y_up)` at texel `(x, y)` by central differences
    /// with wrapping: `∂h/∂x ≈ (h[x+1] − h[x−1]) / 2`, scaled to metres per metre.
    /// `y_up` points up the image (towards smaller rows), the normal map's +Y.
    pub fn slope_central(&self, x: i64, y: i64) -> (f32, f32) {
        let scale = self.range_m / self.texel_size_m;
        let d_dx = (self.at(x + 1, y) - self.at(x - 1, y)) * 0.5 * scale;
        let d_dy_up = (self.at(x, y - 1) - self.at(x, y + 1)) * 0.5 * scale;
        (d_dx, d_dy_up)
    }

    /// Tangent-space unit normal `normalize(−∂h/∂x, −∂h/∂y_up, 1)` at a texel (central differences).
    pub fn normal_central(&self, x: i64, y: i64) -> Vec3 {
        let (d_dx, d_dy_up) = self.slope_central(x, y);
        normalize_or(Vec3::new(-d_dx, -d_dy_up, 1.0), Vec3::Z)
    }

    /// The tangent-space normal map of this field (central-difference kernel, wrapped
    /// borders), OpenGL convention, encoded `rgb = round(255 · (0.5·n + 0.5))`.
    pub fn to_normal_map(&self, name: &str) -> TextureImage {
        let mut rgba = Vec::with_capacity(self.samples.len() * 4);
        for y in 0..self.height as i64 {
            for x in 0..self.width as i64 {
                let n = self.normal_central(x, y);
                rgba.extend(encode_unit_vector(n));
                rgba.push(255);
            }
        }
        TextureImage {
            name: name.to_owned(),
            width: self.width,
            height: self.height,
            kind: TextureKind::NormalMap,
            rgba,
        }
    }
}

/// `round(255 · (0.5·v + 0.5))` per component.
pub fn encode_unit_vector(v: Vec3) -> [u8; 3] {
    (v * 0.5 + 0.5).to_array().map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// `normalize(2·rgb − 1)` for RGB values in 0..1; a zero vector decodes to +Z.
pub fn decode_normal(rgb: Vec3) -> Vec3 {
    normalize_or(rgb * 2.0 - 1.0, Vec3::Z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ramp rising to the right by one full range over the field: every interior slope is
    /// `range_m / (width · texel_size_m)`.
    #[test]
    fn central_difference_is_exact_on_a_linear_ramp() {
        let (width, height) = (16u32, 4u32);
        let samples = (0..height).flat_map(|_| (0..width).map(|x| x as f32 / width as f32)).collect();
        let field = HeightField { width, height, samples, range_m: 0.02, texel_size_m: 0.01 };
        let (d_dx, d_dy_up) = field.slope_central(5, 2);
        let expected = 0.02 / (16.0 * 0.01);
        assert!((d_dx - expected).abs() < 1e-6 && d_dy_up.abs() < 1e-6);
        let n = field.normal_central(5, 2);
        assert!((n - Vec3::new(-expected, 0.0, 1.0).normalize()).length() < 1e-6);
    }

    /// Rows are top to bottom; a field that rises towards the top of the image has a positive
    /// slope up the image, so its normal leans to −Y (green below 128).
    #[test]
    fn rising_towards_the_top_tilts_the_normal_down() {
        let samples = (0..8).flat_map(|y| (0..8).map(move |_| 1.0 - y as f32 / 8.0)).collect();
        let field = HeightField { width: 8, height: 8, samples, range_m: 1.0, texel_size_m: 1.0 };
        assert!(field.normal_central(3, 3).y < -0.05);
        assert!(field.to_normal_map("n").texel(3, 3)[1] < 128);
    }

    #[test]
    fn decode_inverts_encode() {
        let v = Vec3::new(0.3, -0.5, 0.81).normalize();
        let e = encode_unit_vector(v);
        let d = decode_normal(Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32) / 255.0);
        assert!(d.angle_between(v) < 0.01);
    }
}
