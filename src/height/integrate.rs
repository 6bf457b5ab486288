//! From slopes back to heights: the height field whose derivatives are closest, in the
//! least-squares sense, to a given slope field — a Poisson equation, solved in the Fourier
//! domain.
//!
//! Frankot & Chellappa (1988), "A method for enforcing integrability in shape from shading
//! algorithms", IEEE PAMI 10(4): project the slope field `(p, q)` onto the integrable fields,
//! `Ĥ = (conj(D̂x)·P̂ + conj(D̂y)·Q̂) / (|D̂x|² + |D̂y|²)`, where `D̂x`, `D̂y` are the Fourier
//! symbols of the derivative ([`super::derivative`]). They used the continuous `iω`
//! ([`Derivative::Spectral`]); here the symbol may also be that of the finite-difference
//! [`super::Kernel`] that made the normal map ([`Derivative::Kernel`]), which inverts that
//! kernel exactly: a central-difference map of the sine plane comes back within f32 rounding,
//! while `iω` leaves the kernel's gain `sinc(kΔ)` in the amplitude (0.64% at 32 texels per
//! period; the tests and the report measure both). The mean height is not determined by slopes and comes out 0; so do the modes both
//! symbols are blind to (for the central difference the Nyquist rows and columns' joint mode).
//!
//! The solve assumes the field tiles ([`Border::Wrap`]). With [`Border::Clamp`] the slopes are
//! first mirrored into a field twice as wide and tall, which tiles, and the solution cropped
//! (the even extension, i.e. Neumann boundary conditions), at four times the work and twice
//! the memory ([`super::spectrum`] stores only the upper half).

use rustfft::num_complex::Complex32;

use super::Border;
use super::derivative::Derivative;
use super::spectrum::PackedSlopes;

/// `width × height` slopes: `dx[i]` = ∂h/∂x and `dy_up[i]` = ∂h/∂y_up (y up the image) at
/// texel `i` (rows top to bottom), in height units per texel.
#[derive(Debug, Clone, PartialEq)]
pub struct Slopes {
    pub width: usize,
    pub height: usize,
    pub dx: Vec<f32>,
    pub dy_up: Vec<f32>,
}

/// The least-squares heights of `slopes` (same units, mean 0), rows top to bottom. Holds the
/// slopes, the packed field ([`PackedSlopes::bytes`]) and the result; the bake fills a
/// [`PackedSlopes`] itself and streams the [`super::spectrum::Heights`] out instead.
pub fn integrate(slopes: &Slopes, derivative: Derivative, border: Border) -> Vec<f32> {
    let (w, h) = (slopes.width, slopes.height);
    let mut packed = PackedSlopes::new(w, h, border);
    packed.fill(|y, out| {
        let (dx, dy_up) = (&slopes.dx[y * w..][..w], &slopes.dy_up[y * w..][..w]);
        for ((out, &p), &q) in out.iter_mut().zip(dx).zip(dy_up) {
            *out = Complex32::new(p, q);
        }
    });
    packed.solve(derivative).to_vec()
}

#[cfg(test)]
mod tests {
    use std::f32::consts::TAU;

    use super::*;
    use crate::height::{HeightField, Kernel};
    use crate::names::Named;

    /// Slopes of `field` by `kernel` in samples per texel (scale 1).
    fn kernel_slopes(field: &HeightField, kernel: Kernel, border: Border) -> Slopes {
        let (w, h) = (field.width as usize, field.height as usize);
        let (mut dx, mut dy_up) = (vec![], vec![]);
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                let (a, b) = field.slope(kernel, border, x, y);
                dx.push(a);
                dy_up.push(b);
            }
        }
        Slopes { width: w, height: h, dx, dy_up }
    }

    fn field(width: u32, height: u32) -> HeightField {
        let samples = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x as f32, y as f32)))
            .map(|(x, y)| (x * TAU / width as f32).sin() * 0.3 + (2.0 * y * TAU / height as f32).cos() * 0.2)
            .collect();
        HeightField { width, height, samples, range_m: 1.0, texel_size_m: 1.0 }
    }

    fn max_error_after_mean(a: &[f32], b: &[f32]) -> f32 {
        let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
        let (ma, mb) = (mean(a), mean(b));
        a.iter().zip(b).map(|(x, y)| ((x - ma) - (y - mb)).abs()).fold(0.0, f32::max)
    }

    /// Every kernel's own symbol undoes it on a tiling field of odd and even sizes, within f32
    /// rounding; 100 and 75 texels across take more than one batch of columns.
    #[test]
    fn the_kernel_symbol_inverts_the_kernel() {
        for (w, h) in [(32, 24), (27, 15), (100, 66), (75, 40)] {
            let field = field(w, h);
            for &kernel in Kernel::all() {
                let heights =
                    integrate(&kernel_slopes(&field, kernel, Border::Wrap), Derivative::Kernel(kernel), Border::Wrap);
                let error = max_error_after_mean(&heights, &field.samples);
                assert!(error < 1e-5, "{kernel:?} {w}x{h}: {error}");
            }
        }
    }

    /// The spectral symbol leaves the central difference's gain `sin θ / θ`: the x wave (one
    /// period across 32 texels, amplitude 0.3) comes back 0.3·(1 − 0.99359) short and the y
    /// wave (two periods, 0.2) 0.2·(1 − 0.97450); their peaks meet, so the errors add.
    #[test]
    fn the_spectral_symbol_keeps_the_kernel_gain() {
        let field = field(32, 32);
        let slopes = kernel_slopes(&field, Kernel::CentralDifference, Border::Wrap);
        let heights = integrate(&slopes, Derivative::Spectral, Border::Wrap);
        let shortfall = |theta: f32| 1.0 - theta.sin() / theta;
        let expected = 0.3 * shortfall(TAU / 32.0) + 0.2 * shortfall(TAU / 16.0);
        let error = max_error_after_mean(&heights, &field.samples);
        assert!((error - expected).abs() < 1e-4, "{error} vs {expected}");
    }

    /// The clamped solve (the upper half of the even extension stored, the lower half read as
    /// conjugates) equals the wrapped solve of the whole extension built by hand, cropped and
    /// its mean removed; 70 texels across are 140 in the extension, three batches of columns.
    #[test]
    fn the_clamped_solve_equals_the_wrapped_solve_of_the_mirrored_slopes() {
        let (w, h) = (70usize, 45usize);
        let texel = |i: usize| ((i * 7919 % 1000) as f32 / 1000.0 - 0.5) * 0.1;
        let slopes = Slopes {
            width: w,
            height: h,
            dx: (0..w * h).map(texel).collect(),
            dy_up: (0..w * h).map(|i| texel(i + 17)).collect(),
        };
        let (mut dx, mut dy_up) = (vec![], vec![]);
        for y in 0..2 * h {
            let (source_y, flip_y) = if y < h { (y, 1.0) } else { (2 * h - 1 - y, -1.0) };
            for x in 0..2 * w {
                let (source_x, flip_x) = if x < w { (x, 1.0) } else { (2 * w - 1 - x, -1.0) };
                dx.push(flip_x * slopes.dx[source_y * w + source_x]);
                dy_up.push(flip_y * slopes.dy_up[source_y * w + source_x]);
            }
        }
        let derivative = Derivative::Kernel(Kernel::Sobel3);
        let extended = integrate(&Slopes { width: 2 * w, height: 2 * h, dx, dy_up }, derivative, Border::Wrap);
        let cropped: Vec<f32> = extended.chunks_exact(2 * w).take(h).flat_map(|row| row[..w].to_vec()).collect();
        let clamped = integrate(&slopes, derivative, Border::Clamp);
        let error = max_error_after_mean(&clamped, &cropped);
        let relief = cropped.iter().fold(0.0f32, |m, &v| m.max(v.abs()));
        assert!(error < 1e-5 * relief.max(1.0), "{error} of {relief}");
    }

    /// A bowl that does not tile comes back with a clamped border (mirrored solve) close to
    /// exact away from the edge, where the clamped kernel's one-sided slopes differ.
    #[test]
    fn a_clamped_field_is_integrated_through_its_mirror_image() {
        let (w, h) = (24u32, 20u32);
        let samples = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x as f32 - 9.0, y as f32 - 12.0)))
            .map(|(x, y)| 0.002 * (x * x + 0.5 * y * y))
            .collect();
        let field = HeightField { width: w, height: h, samples, range_m: 1.0, texel_size_m: 1.0 };
        let slopes = kernel_slopes(&field, Kernel::CentralDifference, Border::Clamp);
        let heights = integrate(&slopes, Derivative::Kernel(Kernel::CentralDifference), Border::Clamp);
        let inner = |v: &[f32]| -> Vec<f32> {
            v.chunks_exact(w as usize)
                .skip(2)
                .take(h as usize - 4)
                .flat_map(|r| r[2..w as usize - 2].to_vec())
                .collect()
        };
        let error = max_error_after_mean(&inner(&heights), &inner(&field.samples));
        let relief = field.samples.iter().fold(0.0f32, |m, &v| m.max(v));
        assert!(error < 0.02 * relief, "{error} of {relief}");
    }
}
