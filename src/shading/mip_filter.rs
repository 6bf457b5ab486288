//! The formulas of normal-map mip filtering, one per method, twins of
//! `shaders/mip_filter.wgsl`: how much a filtered normal map widens the highlight, as a
//! variance added to the GGX/Beckmann `α²` ([`alpha_variance`]), and that variance applied to
//! the classic model's exponent ([`widened_shininess`]) or to a perceptual roughness
//! ([`widened_roughness`]). [`crate::chain::shade`] runs them where the shader does.
//!
//! LEAN mapping reads its own texture instead of `|Na|`: the filtered slope moments
//! `(Bx, By, Bx², By²)` ([`crate::texture::LeanTexels`]); [`lean_normal`] and [`lean_variance`].
//!
//! `|Na|` is the length of the mean of the unit normals a mip texel covers (1 at level 0,
//! shorter where the bumps disagree); the normal map's mip chain stores it
//! ([`crate::texture::TextureImage::mip_chain_filtered`]).

use glam::{Vec3, Vec4};

use crate::texture::MipFilter;

/// Geometric specular AA's screen-space variance `σ²` (Tokuyoshi & Kaplanyan 2019, as
/// Filament's `specularAntiAliasingVariance`, its default 0.15): the kernel's variance per
/// squared change of the unit normal across one pixel.
pub const GSAA_VARIANCE: f32 = 0.15;
/// Geometric specular AA's clamp `κ` on the added `α²` (Filament's
/// `specularAntiAliasingThreshold`, its default 0.2).
pub const GSAA_THRESHOLD: f32 = 0.2;
/// The shortest `|Na|` the formulas take: opposite normals cancelling to nothing would give an
/// infinite variance.
pub const MIN_NORMAL_LENGTH: f32 = 1e-3;

/// The part of each second moment LEAN's variance leaves out as the rounding of its half-float
/// texture (`2⁻⁹`, four times a half float's relative rounding `2⁻¹¹`): `Bx²` and `(Bx)²` each
/// carry up to about `3·2⁻¹¹·Bx²` of it, so a single slope (level 0 read at a texel centre)
/// reads 0, not rounding noise, while a real variance loses `2⁻⁹` of `Bx²` at most.
pub const LEAN_HALF_FLOOR: f32 = 1.0 / 512.0;

/// LEAN's variance added to `α²` from a filtered texel of its moments `(Bx, By, Bx², By²)`: the
/// trace of the slope covariance `Σ = M − B·Bᵀ`, `σxx + σyy`, each term less
/// [`LEAN_HALF_FLOOR`]` × M` and at least 0 (so `Σ`'s diagonal is never negative). A Beckmann
/// lobe of roughness `α` has slope variance `α²/2` per axis, so an isotropic `Σ` adds its
/// trace to `α²` (Olano & Baker add `Σ` to the lobe's own covariance; the isotropic trace is
/// what the classic exponent and the metallic-roughness `α` can take, as the other methods'
/// variances). Before the bump strength: slopes scale by it, so the caller multiplies by
/// `strength²`.
pub fn lean_variance(moments: Vec4) -> f32 {
    let term = |b: f32, m: f32| (m - b * b - LEAN_HALF_FLOOR * m).max(0.0);
    let variance = term(moments.x, moments.z) + term(moments.y, moments.w);
    if variance.is_finite() { variance } else { 0.0 }
}

/// How much of LEAN applies at the normal map's level of detail `lod` (`log2` of
/// the footprint's longer side in level-0 texels): `clamp(lod, 0, 1)` — none under
/// magnification, all from level 1 on, faded in over the first level as the sampler fades
/// level 1 in. Under magnification a pixel sees less than one texel, across which the map's
/// normal is interpolated, not bumpy: the covariance the bilinear blend of level 0's moments
/// has (that of the four texels it mixes, `f(1 − f)·ΔB²` along an axis, 0 at texel centres)
/// is the sampler's interpolation, not a spread of slopes inside the pixel, and widened the
/// close wall's highlight by up to 123 steps (metallic-roughness, roughness 0.3) where plain
/// shading is the reference. The mean-slope normal fades in with it (the blend of the
/// moments' mean slope is another interpolation than the re-normalised blend of the texels'
/// normals: 17 steps apart there). This is a departure from Olano & Baker, who take the
/// moments as filtered at every level. A non-finite `lod` (no footprint) reads as level 0.
pub fn lean_fade(lod: f32) -> f32 {
    if lod.is_finite() { lod.clamp(0.0, 1.0) } else { 0.0 }
}

/// LEAN's shading normal in the normal map's tangent space before the bump strength: from the
/// mean slope, `normalize(Bx, By, 1)` (the slopes are `(nx/nz, ny/nz)`, [`crate::texture::slopes`]);
/// `+z` where the moments are not finite.
pub fn lean_normal(moments: Vec4) -> Vec3 {
    Vec3::new(moments.x, moments.y, 1.0).try_normalize().unwrap_or(Vec3::Z)
}

/// Toksvig's variance `σ² = (1 − |Na|) / |Na|` of the normal distribution whose mean has
/// length `|Na|` (Toksvig 2005, eq. 4): 0 for `|Na| ≥ 1`.
pub fn toksvig_variance(length: f32) -> f32 {
    let r = clamped_length(length);
    (1.0 - r) / r
}

/// The von Mises–Fisher concentration fitted to a mean normal of length `r = |Na|` (Banerjee
/// et al. 2005's approximation, as Neubelt & Pettineo 2013 and Karis 2018 take it):
/// `κ = (3r − r³) / (1 − r²)`; infinite at `r = 1` (all normals agree).
pub fn vmf_kappa(length: f32) -> f32 {
    let r = clamped_length(length);
    (3.0 * r - r * r * r) / (1.0 - r * r)
}

/// The vMF fit's variance added to `α²` (Karis 2018's correction of Neubelt & Pettineo):
/// `2/κ = 2(1 − r²) / (3r − r³)`, written without the division by `1 − r²` so that it is 0,
/// not NaN, at `r = 1`.
pub fn vmf_variance(length: f32) -> f32 {
    let r = clamped_length(length);
    2.0 * (1.0 - r * r) / (3.0 * r - r * r * r)
}

/// Geometric specular AA's added `α²` from the fine screen-space derivatives of the unit
/// shading normal (world space, per pixel): `min(2·σ²·(|∂n/∂x|² + |∂n/∂y|²), κ)` with
/// [`GSAA_VARIANCE`] and [`GSAA_THRESHOLD`] (Tokuyoshi & Kaplanyan 2019, §4; Filament's
/// `normalFiltering`).
pub fn gsaa_variance(dn_dx: Vec3, dn_dy: Vec3) -> f32 {
    let variance = GSAA_VARIANCE * (dn_dx.dot(dn_dx) + dn_dy.dot(dn_dy));
    let added = (2.0 * variance).min(GSAA_THRESHOLD);
    if added.is_finite() { added } else { GSAA_THRESHOLD }
}

/// What `filter` adds to `α²` at a point: from the filtered normal map's `|Na|` (`length`,
/// the texel's alpha) for Toksvig (`2σ²`, since a Blinn-Phong exponent `s` is a Beckmann
/// `α² ≈ 2/s`, Walter et al. 2007) and vMF (`2/κ`), each times `strength²` (the bump strength
/// scales the slopes); from the shading normal's derivatives (`normal_derivatives`, `None`: no
/// quad) for geometric specular AA; 0 for the others (LEAN's is [`lean_variance`] of its own
/// texture), and with the bump off.
pub fn alpha_variance(
    filter: MipFilter,
    length: f32,
    strength: f32,
    bump_enabled: bool,
    normal_derivatives: Option<(Vec3, Vec3)>,
) -> f32 {
    if !bump_enabled {
        return 0.0;
    }
    let s2 = strength * strength;
    match filter {
        MipFilter::Toksvig => s2 * 2.0 * toksvig_variance(length),
        MipFilter::Vmf => s2 * vmf_variance(length),
        MipFilter::GeometricSpecularAa => normal_derivatives.map_or(0.0, |(dx, dy)| gsaa_variance(dx, dy)),
        MipFilter::BaseOnly | MipFilter::RenormalizedBox | MipFilter::Lean => 0.0,
    }
}

/// The classic model's exponent `s` widened by `variance` (added to `α²`) and the factor on
/// `k_s` that keeps the lobe's energy, `(1 + s′)/(1 + s)` (Toksvig 2005, eq. 7). Toksvig:
/// `s′ = s / (1 + s·σ²)` with `σ² = variance/2` — at strength 1 exactly
/// `|Na|·s / (|Na| + s·(1 − |Na|))`; the others through Beckmann's `α² = 2/(s + 2)`:
/// `s′ = 2/min(α² + variance, 1) − 2`. Unchanged (factor 1) where `variance` is 0.
pub fn widened_shininess(filter: MipFilter, shininess: f32, variance: f32) -> (f32, f32) {
    if !(variance > 0.0) {
        return (shininess, 1.0);
    }
    let s = shininess.max(0.0);
    let widened = if filter == MipFilter::Toksvig {
        s / (1.0 + s * 0.5 * variance)
    } else {
        2.0 / (2.0 / (s + 2.0) + variance).min(1.0) - 2.0
    };
    let widened = widened.max(0.0);
    (widened, (1.0 + widened) / (1.0 + s))
}

/// A perceptual roughness `r` (`α = r²`) widened by `variance`: `r′ = (min(r⁴ + variance,
/// 1))^¼`; unchanged where `variance` is 0 (`α′² = α² + variance` is the vMF bake of Karis
/// 2018 and Filament's, and Toksvig's `2σ²`).
pub fn widened_roughness(roughness: f32, variance: f32) -> f32 {
    if !(variance > 0.0) {
        return roughness;
    }
    let alpha = roughness * roughness;
    (alpha * alpha + variance).min(1.0).sqrt().sqrt()
}

/// What a baked mip level's alpha holds for `filter`, as a function of the level's `|Na|`:
/// Toksvig's exponent ratio `s′/s` at `shininess`, vMF's widened roughness from `roughness`
/// (at most 1), 1 for the methods that widen nothing. `Err` says why a method has nothing per
/// level to bake.
pub fn baked_alpha(filter: MipFilter, shininess: f32, roughness: f32) -> Result<Box<dyn Fn(f32) -> f32>, &'static str> {
    match filter {
        MipFilter::BaseOnly | MipFilter::RenormalizedBox => Ok(Box::new(|_| 1.0)),
        MipFilter::Toksvig => Ok(Box::new(move |length| {
            widened_shininess(filter, shininess, 2.0 * toksvig_variance(length)).0 / shininess
        })),
        MipFilter::Vmf => {
            let roughness = roughness.min(1.0);
            Ok(Box::new(move |length| widened_roughness(roughness, vmf_variance(length))))
        }
        MipFilter::Lean => Err("lean keeps its slope moments in two textures of their own, not one image per level"),
        MipFilter::GeometricSpecularAa => Err(
            "geometric-specular-aa widens from screen-space derivatives while drawing: its mips are renormalized-box's",
        ),
    }
}

/// `|Na|` within [`MIN_NORMAL_LENGTH`]..1 (a non-finite length reads as 1).
fn clamped_length(length: f32) -> f32 {
    if length.is_finite() { length.clamp(MIN_NORMAL_LENGTH, 1.0) } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At strength 1 the Toksvig exponent is Toksvig's `|Na|·s / (|Na| + s(1 − |Na|))`, its
    /// energy factor `(1 + s′)/(1 + s)`; the vMF and Toksvig variances agree to first order in
    /// `1 − |Na|`; nothing widens at `|Na| = 1`.
    #[test]
    fn the_methods_agree_with_their_papers_and_leave_unit_normals_alone() {
        for (r, s) in [(0.9f32, 64.0f32), (0.5, 16.0), (0.99, 200.0)] {
            let v = alpha_variance(MipFilter::Toksvig, r, 1.0, true, None);
            let (widened, energy) = widened_shininess(MipFilter::Toksvig, s, v);
            let toksvig = r * s / (r + s * (1.0 - r));
            assert!((widened - toksvig).abs() <= 1e-4 * toksvig, "{r} {s}: {widened} {toksvig}");
            assert!((energy - (1.0 + toksvig) / (1.0 + s)).abs() < 1e-5);
        }
        let e = 1e-3;
        let (toksvig, vmf) = (2.0 * toksvig_variance(1.0 - e), vmf_variance(1.0 - e));
        assert!((toksvig / vmf - 1.0).abs() < 2e-3, "{toksvig} {vmf}");
        assert!((vmf_variance(0.8) - 2.0 / vmf_kappa(0.8)).abs() < 1e-6);
        for filter in [MipFilter::Toksvig, MipFilter::Vmf] {
            assert_eq!(alpha_variance(filter, 1.0, 3.0, true, None), 0.0);
            assert_eq!(alpha_variance(filter, 0.5, 1.0, false, None), 0.0);
        }
        assert_eq!(widened_shininess(MipFilter::Vmf, 32.0, 0.0), (32.0, 1.0));
        assert_eq!(widened_roughness(0.3, 0.0), 0.3);
        // α′² = α² + v: perceptual 0.5 (α² = 1/16) plus 0.1.
        assert!((widened_roughness(0.5, 0.1).powi(4) - (0.0625 + 0.1)).abs() < 1e-6);
        assert_eq!(vmf_variance(f32::NAN), 0.0);
    }

    /// LEAN's variance is the trace of `M − B·Bᵀ`: 0 for one slope read back from half floats,
    /// `σ²` per axis for a texel mixing slopes ±σ; its normal is the mean slope's.
    #[test]
    fn lean_takes_the_trace_of_the_covariance_and_the_mean_slope() {
        use crate::texture::round_to_half;
        for b in [0.0f32, 0.3, -1.7, 19.9] {
            let one = glam::Vec4::new(b, -b, b * b, b * b).map(round_to_half);
            assert_eq!(lean_variance(one), 0.0, "{b}");
        }
        let (sx, sy) = (0.2f32, 0.5f32);
        let mixed = glam::Vec4::new(0.1, 0.0, 0.01 + sx * sx, sy * sy);
        let expected = (sx * sx - LEAN_HALF_FLOOR * (0.01 + sx * sx)) + sy * sy * (1.0 - LEAN_HALF_FLOOR);
        assert!((lean_variance(mixed) - expected).abs() < 1e-6);
        assert!((lean_normal(mixed) - Vec3::new(0.1, 0.0, 1.0).normalize()).length() < 1e-6);
        assert_eq!(lean_variance(glam::Vec4::splat(f32::NAN)), 0.0);
        assert_eq!(lean_normal(glam::Vec4::splat(f32::INFINITY)), Vec3::Z);
        assert_eq!([-2.0, 0.0, 0.25, 1.0, 3.0, f32::NEG_INFINITY].map(lean_fade), [0.0, 0.0, 0.25, 1.0, 1.0, 0.0]);
    }

    /// Filament's clamp: a steep change of the normal adds at most κ = 0.2 to α².
    #[test]
    fn geometric_specular_aa_grows_with_the_derivatives_and_is_clamped() {
        let small = gsaa_variance(Vec3::new(0.1, 0.0, 0.0), Vec3::ZERO);
        assert!((small - 2.0 * 0.15 * 0.01).abs() < 1e-7);
        assert_eq!(gsaa_variance(Vec3::X, Vec3::Y), GSAA_THRESHOLD);
        assert_eq!(gsaa_variance(Vec3::splat(f32::INFINITY), Vec3::ZERO), GSAA_THRESHOLD);
    }
}
