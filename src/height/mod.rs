//! Height fields and their conversion to tangent-space normal maps.
//!
//! A height field stores samples in 0..1 (white = high). Its `range_m` says how many metres
//! the full range spans and `texel_size_m` how many metres one texel covers on the surface,
//! so the slope `∂h/∂x` in world units is `Δsample · range_m / texel_size_m`. Derivatives
//! come from one of several finite-difference [`Kernel`]s.
//!
//! [`HeightField::slope`] and [`HeightField::normal`] compute one texel, as written in the
//! formulas; [`rows`] computes whole images the same way, rows in parallel, and [`integrate`]
//! goes back from slopes to heights.

pub mod cone;
pub mod derivative;
pub mod integrate;
pub mod rows;
pub mod spectrum;

use glam::Vec3;

use crate::math::normalize_or;
use crate::texture::{TextureImage, TextureKind};

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

    /// Sample at `(x, y)` with `border` handling outside the field.
    pub fn at_border(&self, x: i64, y: i64, border: Border) -> f32 {
        match border {
            Border::Wrap => self.at(x, y),
            Border::Clamp => self.at(x.clamp(0, self.width as i64 - 1), y.clamp(0, self.height as i64 - 1)),
        }
    }

    /// World-unit slopes `(∂h/∂x, ∂h/∂y_up)` at texel `(x, y)` by `kernel`, metres per
    /// metre. `y_up` points up the image (towards smaller rows), the normal map's +Y.
    pub fn slope(&self, kernel: Kernel, border: Border, x: i64, y: i64) -> (f32, f32) {
        self.slope_with_taps(kernel.taps(), border, x, y)
    }

    fn slope_with_taps(&self, taps: &[Tap], border: Border, x: i64, y: i64) -> (f32, f32) {
        let scale = self.range_m / self.texel_size_m;
        let (mut d_dx, mut d_dy_up) = (0.0, 0.0);
        for &Tap { along, across, weight } in taps {
            d_dx += weight * self.at_border(x + along, y + across, border);
            // Along +y_up is towards smaller rows.
            d_dy_up += weight * self.at_border(x + across, y - along, border);
        }
        (d_dx * scale, d_dy_up * scale)
    }

    /// Tangent-space unit normal `normalize(−∂h/∂x, −∂h/∂y_up, 1)` at a texel.
    pub fn normal(&self, kernel: Kernel, border: Border, x: i64, y: i64) -> Vec3 {
        let (d_dx, d_dy_up) = self.slope(kernel, border, x, y);
        normalize_or(Vec3::new(-d_dx, -d_dy_up, 1.0), Vec3::Z)
    }

    /// The field as a [`rows::HeightGrid`] (float samples, `slope_scale = range_m / texel_size_m`).
    pub fn grid(&self) -> rows::HeightGrid<'_> {
        rows::HeightGrid {
            width: self.width as usize,
            height: self.height as usize,
            samples: rows::Samples::F32(&self.samples),
            slope_scale: self.range_m / self.texel_size_m,
            depth: false,
        }
    }

    /// The tangent-space normal map of this field by `kernel`, OpenGL convention, encoded
    /// `rgb = round(255 · (0.5·n + 0.5))`, alpha 255 (rows in parallel, [`rows`]).
    pub fn to_normal_map(&self, kernel: Kernel, border: Border, name: &str) -> TextureImage {
        let mut rgba = vec![0u8; self.samples.len() * 4];
        let (grid, row_len) = (self.grid(), self.width as usize * 4);
        rows::for_each_normal_row(&grid, kernel, border, 0..grid.height, &mut rgba, row_len, |row, out| {
            for (((texel, &x), &y), &z) in out.chunks_exact_mut(4).zip(row.x).zip(row.y).zip(row.z) {
                texel.copy_from_slice(&[rows::unorm8(x), rows::unorm8(y), rows::unorm8(z), 255]);
            }
        });
        TextureImage::new(name.to_owned(), self.width, self.height, TextureKind::NormalMap, rgba)
    }

    /// The field as a 16-bit [`TextureKind::Height`] texture (red high byte, green low byte).
    pub fn to_height_texture(&self, name: &str) -> TextureImage {
        let rgba = self
            .samples
            .iter()
            .flat_map(|&h| {
                let [high, low] = crate::texture::encode_height(h);
                [high, low, 0, 255]
            })
            .collect();
        TextureImage::new(name.to_owned(), self.width, self.height, TextureKind::Height, rgba)
    }

    /// The field stored with `bits` bits per sample (8 or 16 in image files): every sample
    /// rounded to one of `2^bits` levels.
    pub fn quantized(&self, bits: u32) -> HeightField {
        let levels = ((1u64 << bits.clamp(1, 24)) - 1) as f32;
        let samples = self.samples.iter().map(|&h| (h.clamp(0.0, 1.0) * levels).round() / levels).collect();
        HeightField { samples, ..self.clone() }
    }
}

/// How samples outside the height field are read. Named `wrap`, `clamp`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum Border {
    /// The field tiles (texture repeat).
    #[default]
    Wrap,
    /// The edge sample repeats outwards.
    Clamp,
}

/// One tap of a derivative kernel for ∂/∂x: the sample `along` texels in the derivative's
/// direction and `across` texels perpendicular to it, times `weight`.
#[derive(Debug, Clone, Copy)]
struct Tap {
    along: i64,
    across: i64,
    weight: f32,
}

const fn tap(along: i64, across: i64, weight: f32) -> Tap {
    Tap { along, across, weight }
}

/// Finite-difference kernels for height→normal conversion. Each is normalised so that a
/// linear ramp gives its exact slope. Named on the command line, in the panel and in reports
/// `forward`, `central`, `sobel3`, `scharr3`, `sobel5`, `central4`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "lowercase")]
pub enum Kernel {
    /// `h[x+1] − h[x]` (the Cg Tutorial's): first order, shifted by half a texel.
    #[strum(serialize = "forward")]
    ForwardDifference,
    /// `(h[x+1] − h[x−1]) / 2`: second order, gain `sinc(kΔ)` at wavenumber `k`.
    #[default]
    #[strum(serialize = "central")]
    CentralDifference,
    /// Sobel 3×3: central difference smoothed `[1 2 1] / 4` across.
    Sobel3,
    /// Scharr 3×3: central difference smoothed `[3 10 3] / 16` across.
    Scharr3,
    /// Sobel 5×5: `[−1 −2 0 2 1] / 8` along, `[1 4 6 4 1] / 16` across.
    Sobel5,
    /// `(−h[x+2] + 8h[x+1] − 8h[x−1] + h[x−2]) / 12`: fourth order.
    Central4,
}

impl Kernel {
    fn taps(self) -> &'static [Tap] {
        const FORWARD: [Tap; 2] = [tap(1, 0, 1.0), tap(0, 0, -1.0)];
        const CENTRAL: [Tap; 2] = [tap(1, 0, 0.5), tap(-1, 0, -0.5)];
        const SOBEL3: [Tap; 6] = [
            tap(1, -1, 1.0 / 8.0),
            tap(1, 0, 2.0 / 8.0),
            tap(1, 1, 1.0 / 8.0),
            tap(-1, -1, -1.0 / 8.0),
            tap(-1, 0, -2.0 / 8.0),
            tap(-1, 1, -1.0 / 8.0),
        ];
        const SCHARR3: [Tap; 6] = [
            tap(1, -1, 3.0 / 32.0),
            tap(1, 0, 10.0 / 32.0),
            tap(1, 1, 3.0 / 32.0),
            tap(-1, -1, -3.0 / 32.0),
            tap(-1, 0, -10.0 / 32.0),
            tap(-1, 1, -3.0 / 32.0),
        ];
        const SOBEL5: [Tap; 20] = {
            const ALONG: [(i64, f32); 4] = [(-2, -1.0), (-1, -2.0), (1, 2.0), (2, 1.0)];
            const ACROSS: [f32; 5] = [1.0, 4.0, 6.0, 4.0, 1.0];
            let mut taps = [tap(0, 0, 0.0); 20];
            let mut i = 0;
            while i < 20 {
                let (along, w) = ALONG[i / 5];
                taps[i] = tap(along, (i % 5) as i64 - 2, w * ACROSS[i % 5] / 128.0);
                i += 1;
            }
            taps
        };
        const CENTRAL4: [Tap; 4] =
            [tap(2, 0, -1.0 / 12.0), tap(1, 0, 8.0 / 12.0), tap(-1, 0, -8.0 / 12.0), tap(-2, 0, 1.0 / 12.0)];
        match self {
            Kernel::ForwardDifference => &FORWARD,
            Kernel::CentralDifference => &CENTRAL,
            Kernel::Sobel3 => &SOBEL3,
            Kernel::Scharr3 => &SCHARR3,
            Kernel::Sobel5 => &SOBEL5,
            Kernel::Central4 => &CENTRAL4,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    /// A ramp rising to the right (and, in a second field, up the image) by one full range
    /// over the field: every kernel gives the exact slope `range_m / (width · texel_size_m)`
    /// away from the wrap.
    #[test]
    fn every_kernel_is_exact_on_a_linear_ramp() {
        let n = 16u32;
        let ramp = |f: &dyn Fn(u32, u32) -> f32| HeightField {
            width: n,
            height: n,
            samples: (0..n).flat_map(|y| (0..n).map(move |x| (x, y))).map(|(x, y)| f(x, y)).collect(),
            range_m: 0.02,
            texel_size_m: 0.01,
        };
        let rising_right = ramp(&|x, _| x as f32 / n as f32);
        let rising_up = ramp(&|_, y| (n - 1 - y) as f32 / n as f32);
        let expected = 0.02 / (16.0 * 0.01);
        for &kernel in Kernel::all() {
            let (d_dx, d_dy_up) = rising_right.slope(kernel, Border::Wrap, 7, 7);
            assert!((d_dx - expected).abs() < 1e-5 && d_dy_up.abs() < 1e-5, "{kernel:?}: {d_dx} {d_dy_up}");
            let (d_dx, d_dy_up) = rising_up.slope(kernel, Border::Clamp, 7, 7);
            assert!(d_dx.abs() < 1e-5 && (d_dy_up - expected).abs() < 1e-5, "{kernel:?}: {d_dx} {d_dy_up}");
        }
    }

    #[test]
    fn quantizing_rounds_to_the_levels_of_the_bit_depth() {
        let field = HeightField { width: 2, height: 1, samples: vec![0.5, 0.1234], range_m: 1.0, texel_size_m: 1.0 };
        assert_eq!(field.quantized(8).samples, vec![128.0 / 255.0, 31.0 / 255.0]);
        assert!((field.quantized(16).samples[1] - 0.1234).abs() < 1.0 / 65535.0);
    }

    /// Rows are top to bottom; a field that rises towards the top of the image has a positive
    /// slope up the image, so its normal leans to −Y (green below 128).
    #[test]
    fn rising_towards_the_top_tilts_the_normal_down() {
        let samples = (0..8).flat_map(|y| (0..8).map(move |_| 1.0 - y as f32 / 8.0)).collect();
        let field = HeightField { width: 8, height: 8, samples, range_m: 1.0, texel_size_m: 1.0 };
        assert!(field.normal(Kernel::CentralDifference, Border::Wrap, 3, 3).y < -0.05);
        assert!(field.to_normal_map(Kernel::CentralDifference, Border::Wrap, "n").texel(3, 3)[1] < 128);
    }

    /// The baker's 8-bit encoding ([`rows::unorm8`]) read back by the shader's decode
    /// ([`crate::shading::decode_normal`]) gives the vector back.
    #[test]
    fn decode_inverts_encode() {
        let v = Vec3::new(0.3, -0.5, 0.81).normalize();
        let e = v.to_array().map(rows::unorm8);
        let texel = crate::shading::NormalTexel::rgb(Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32) / 255.0);
        let d = crate::shading::decode_normal(texel, Default::default());
        assert!(d.angle_between(v) < 0.01);
    }
}
