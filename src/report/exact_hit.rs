//! The exact first intersection of a view ray with a height field: the reference the parallax
//! techniques' texture coordinates are measured against ([`super::uv_error`]).
//!
//! Depths follow [`crate::chain::parallax`]: the surface is the top of the relief, a texel of
//! height `h` (0..1) lies `1 − h` (a fraction of the relief's depth) below it, and the ray
//! entering at `uv` is over `uv + t · shift` at depth `t` (0..1). It is found in `f64` by a
//! fine march (steps of at most [`MARCH_STEP_TEXELS`] texel along the ray's UV path, and at
//! least [`MIN_MARCH_STEPS`]), then by bisection until the bracket spans at most
//! [`BISECTION_TEXELS`] texel (or depth fraction, for a ray without shift).

use glam::DVec2;

use crate::height::HeightField;

/// The fine march's longest step, texels along the ray's UV path.
pub const MARCH_STEP_TEXELS: f64 = 1.0 / 16.0;
/// The fine march takes at least this many steps down the relief's depth.
pub const MIN_MARCH_STEPS: u32 = 256;
/// ... and at most this many (a path over 65 536 texels takes longer steps).
pub const MAX_MARCH_STEPS: u32 = 1 << 20;
/// The bisection stops when the bracket is this short, texels.
pub const BISECTION_TEXELS: f64 = 1e-6;

/// Where a ray meets the height field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactHit {
    /// Depth along the ray, 0..1 of the relief's depth (the first `t` with `t ≥ 1 − h`).
    pub depth: f64,
    /// The texture coordinates under the hit.
    pub uv: DVec2,
}

/// The first intersection of the ray entering at `uv` with UV shift `shift` over the relief's
/// full depth, `texels` texels per UV unit on each axis, heights (0..1) from `height`.
/// A ray whose path leaves the relief's bottom (depth 1) unhit stops there: every height is
/// ≥ 0, so depth 1 is always at or below the surface. A shift that is not finite (a ray
/// along the surface) returns the entry point.
pub fn exact_hit(uv: DVec2, shift: DVec2, texels: DVec2, height: impl Fn(DVec2) -> f64) -> ExactHit {
    let path_texels = (shift * texels).length();
    if !path_texels.is_finite() {
        return ExactHit { depth: 0.0, uv };
    }
    let below = |t: f64| t >= 1.0 - height(uv + shift * t);
    let at = |t: f64| ExactHit { depth: t, uv: uv + shift * t };
    if below(0.0) {
        return at(0.0);
    }
    let steps = ((path_texels / MARCH_STEP_TEXELS).ceil() as u32).clamp(MIN_MARCH_STEPS, MAX_MARCH_STEPS);
    let mut low = 0.0;
    let mut high = 1.0;
    for i in 1..=steps {
        let t = f64::from(i) / f64::from(steps);
        if below(t) {
            high = t;
            break;
        }
        low = t;
    }
    // The bracket's length in texels (or in depth for a ray straight down).
    let scale = path_texels.max(1.0);
    // 64 halvings exhaust an f64 bracket: the cap only ends a path too long to resolve.
    for _ in 0..64 {
        if (high - low) * scale <= BISECTION_TEXELS {
            break;
        }
        let mid = 0.5 * (low + high);
        if below(mid) {
            high = mid;
        } else {
            low = mid;
        }
    }
    at(high)
}

/// `field` at `uv` as the GPU's linear sampler reads level 0 with repeat wrapping: texel
/// centres at `(i + ½) / width`, the four nearest texels weighted bilinearly.
pub fn bilinear(field: &HeightField, uv: DVec2) -> f64 {
    let x = uv.x * f64::from(field.width) - 0.5;
    let y = uv.y * f64::from(field.height) - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (ix, iy) = (x0 as i64, y0 as i64);
    let h = |dx: i64, dy: i64| f64::from(field.at(ix + dx, iy + dy));
    let top = h(0, 0) + (h(1, 0) - h(0, 0)) * fx;
    let bottom = h(0, 1) + (h(1, 1) - h(0, 1)) * fx;
    top + (bottom - top) * fy
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXELS: DVec2 = DVec2::splat(512.0);

    /// A step: height 0.2 for u < 0.5, 0.9 beyond. A ray from u = 0.45 shifting +0.1 over the
    /// depth passes the step at t = 0.5 (depth 0.5 is above the 0.1 of the high side): the
    /// hit is on the step's wall, u = 0.5.
    #[test]
    fn a_step_is_hit_on_its_wall() {
        let step = |uv: DVec2| if uv.x < 0.5 { 0.2 } else { 0.9 };
        let hit = exact_hit(DVec2::new(0.45, 0.3), DVec2::new(0.1, 0.0), TEXELS, step);
        assert!(((hit.uv.x - 0.5) * 512.0).abs() < 1e-4, "{hit:?}");
        assert!((hit.depth - 0.5).abs() < 1e-6 && hit.uv.y == 0.3, "{hit:?}");
        // Starting on the high side: the ray meets its floor at depth 0.1.
        let high = exact_hit(DVec2::new(0.6, 0.3), DVec2::new(0.1, 0.0), TEXELS, step);
        assert!(((high.uv.x - 0.61) * 512.0).abs() < 1e-4, "{high:?}");
    }

    /// A sine `h = ½ + ½ sin(2π u / P)`, the hit chosen first: on the rising flank at `u*`
    /// (depth `1 − h(u*)`), the ray entering `shift · depth` before it. The fine march finds it
    /// to 1e-4 texel, and the ray is above the surface all the way there (checked densely).
    #[test]
    fn a_sine_is_hit_where_it_was_placed() {
        let period = 0.05;
        let sine = |uv: DVec2| 0.5 + 0.5 * (std::f64::consts::TAU * uv.x / period).sin();
        for (u_hit, shift) in [(0.3101, 0.04), (0.5033, -0.004), (0.71, 0.01)] {
            let depth = 1.0 - sine(DVec2::new(u_hit, 0.0));
            let start = DVec2::new(u_hit - shift * depth, 0.25);
            let clear = (0..100_000)
                .map(|i| depth * f64::from(i) / 100_000.0)
                .all(|t| t < 1.0 - sine(start + DVec2::new(shift * t, 0.0)));
            assert!(clear, "{u_hit} {shift}: the ray meets the sine before the placed hit");
            let hit = exact_hit(start, DVec2::new(shift, 0.0), TEXELS, sine);
            assert!(((hit.uv.x - u_hit) * 512.0).abs() < 1e-4, "{u_hit} {shift}: {hit:?}");
        }
    }

    /// Rays almost or exactly along the surface, and a height field of NaN, end with a finite
    /// hit within the relief's depth.
    #[test]
    fn grazing_rays_and_nan_heights_end_finite() {
        let sine = |uv: DVec2| 0.5 + 0.5 * (uv.x * 300.0).sin();
        for shift in [1e12, f64::INFINITY, f64::NAN] {
            let hit = exact_hit(DVec2::splat(0.5), DVec2::new(shift, 0.0), TEXELS, sine);
            assert!(hit.uv.is_finite() && (0.0..=1.0).contains(&hit.depth), "{shift}: {hit:?}");
        }
        let hit = exact_hit(DVec2::splat(0.5), DVec2::new(0.1, 0.0), TEXELS, |_| f64::NAN);
        assert!(hit.uv.is_finite() && hit.depth == 1.0, "{hit:?}");
    }

    /// Bilinear reads: a texel centre returns the texel, halfway between two their mean, and
    /// the border wraps.
    #[test]
    fn bilinear_reads_like_a_linear_sampler() {
        let field = HeightField {
            width: 4,
            height: 2,
            samples: vec![0.0, 1.0, 0.5, 0.25, 1.0, 1.0, 1.0, 1.0],
            range_m: 1.0,
            texel_size_m: 1.0,
        };
        assert_eq!(bilinear(&field, DVec2::new(0.375, 0.25)), 1.0);
        assert_eq!(bilinear(&field, DVec2::new(0.25, 0.25)), 0.5);
        assert_eq!(bilinear(&field, DVec2::new(0.0, 0.25)), 0.125);
        assert_eq!(bilinear(&field, DVec2::new(1.125, 0.5)), 0.5);
    }
}
