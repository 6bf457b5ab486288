//! Detail normal blending: a base and a detail tangent-space normal (unit, `z ≥ 0`, each after
//! its strength, [`super::tangent_space_normal`]) made into one tangent-space normal, one
//! function per [`DetailBlend`] method. The WGSL twins are `shaders/detail.wgsl`, held equal by
//! tests/detail_blend.rs; `crate::chain` runs [`blend`] between the normal map's strength and
//! the step to world space. docs/detail-normals.md gives the sources and the measured errors.

use glam::{Vec2, Vec3};

use crate::math::normalize_or;
use crate::scene::sample::sample_bilinear;
use crate::scene::{DetailBlend, NormalConvention, SamplerWrap, TextureImage};
use crate::shading::{NormalTexel, decode_normal, tangent_space_normal};

/// The smallest `z` the surface-gradient method divides by (a normal at the horizon has no
/// finite slope): `z` below it counts as this.
pub const MIN_GRADIENT_Z: f32 = 1e-3;

/// `base` and `detail` (tangent space, unit, `z ≥ 0`) blended by `method`; unit length,
/// `base` the fallback.
pub fn blend(method: DetailBlend, base: Vec3, detail: Vec3) -> Vec3 {
    match method {
        DetailBlend::Linear => linear(base, detail),
        DetailBlend::PartialDerivative => partial_derivative(base, detail),
        DetailBlend::Whiteout => whiteout(base, detail),
        DetailBlend::Udn => udn(base, detail),
        DetailBlend::Rnm => rnm(base, detail),
        DetailBlend::SurfaceGradient => surface_gradient(base, detail),
    }
}

/// `normalize(b + d)`.
pub fn linear(b: Vec3, d: Vec3) -> Vec3 {
    normalize_or(b + d, b)
}

/// The slopes add: `normalize(bx·dz + dx·bz, by·dz + dy·bz, bz·dz)`, which is
/// `normalize(bx/bz + dx/dz, by/bz + dy/dz, 1)` without the divisions.
pub fn partial_derivative(b: Vec3, d: Vec3) -> Vec3 {
    normalize_or(Vec3::new(b.x * d.z + d.x * b.z, b.y * d.z + d.y * b.z, b.z * d.z), b)
}

/// Whiteout: `normalize(bx + dx, by + dy, bz·dz)`.
pub fn whiteout(b: Vec3, d: Vec3) -> Vec3 {
    normalize_or(Vec3::new(b.x + d.x, b.y + d.y, b.z * d.z), b)
}

/// UDN: `normalize(bx + dx, by + dy, bz)`.
pub fn udn(b: Vec3, d: Vec3) -> Vec3 {
    normalize_or(Vec3::new(b.x + d.x, b.y + d.y, b.z), b)
}

/// Reoriented normal mapping (Barré-Brisebois & Hill 2012, unpacked form):
/// `t = b + (0, 0, 1)`, `u = (−dx, −dy, dz)`, `r = t·(t·u)/t.z − u`; `r` is `d` rotated by the
/// shortest arc that takes `+Z` to `b`.
pub fn rnm(b: Vec3, d: Vec3) -> Vec3 {
    let t = b + Vec3::Z;
    let u = Vec3::new(-d.x, -d.y, d.z);
    normalize_or(t * (t.dot(u) / t.z) - u, b)
}

/// Mikkelsen's surface gradient of a perturbed normal `v` against the unperturbed unit normal
/// `n` ("Surface Gradient–Based Bump Mapping Framework", JCGT 2020, `surfgradFromPerturbedNormal`):
/// `(k·n − v) / k` with `k = n·v` (at least [`MIN_GRADIENT_Z`]).
pub fn gradient_of_normal(n: Vec3, v: Vec3) -> Vec3 {
    let k = n.dot(v).max(MIN_GRADIENT_Z);
    (k * n - v) / k
}

/// The normal of the surface gradient `gradient` over the unit normal `n`
/// (`resolveNormalFromSurfaceGradient`): `normalize(n − gradient)`.
pub fn resolve_gradient(n: Vec3, gradient: Vec3) -> Vec3 {
    normalize_or(n - gradient, n)
}

/// Surface gradients: each map's normal made a surface gradient against the unperturbed
/// normal (`+Z` in tangent space), the two added and resolved. In an orthonormal frame, as
/// the chain's, this is the slopes' sum ([`partial_derivative`]) by another road.
pub fn surface_gradient(b: Vec3, d: Vec3) -> Vec3 {
    resolve_gradient(Vec3::Z, gradient_of_normal(Vec3::Z, b) + gradient_of_normal(Vec3::Z, d))
}

/// The blended normal at every texel of `base`: the detail map read bilinearly (wrapping) at
/// the texel centre's UV times `tiling`, scaled by `strength`, blended by `method`; unit
/// tangent-space vectors, row by row from the top.
pub fn blend_maps(
    base: &TextureImage,
    detail: &TextureImage,
    tiling: f32,
    strength: f32,
    method: DetailBlend,
) -> Vec<Vec3> {
    let convention = NormalConvention::default();
    let size = Vec2::new(base.width as f32, base.height as f32);
    let mut out = Vec::with_capacity((base.width * base.height) as usize);
    for y in 0..base.height {
        for x in 0..base.width {
            let texel = base.texel(i64::from(x), i64::from(y)).map(|c| f32::from(c) / 255.0);
            let b = decode_normal(NormalTexel::rgb(Vec3::new(texel[0], texel[1], texel[2])), convention);
            let uv = (Vec2::new(x as f32, y as f32) + 0.5) / size * tiling;
            let d_texel = sample_bilinear(detail, uv, SamplerWrap::default()).truncate();
            let d = tangent_space_normal(decode_normal(NormalTexel::rgb(d_texel), convention), strength);
            out.push(blend(method, tangent_space_normal(b, 1.0), d));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    /// A flat detail leaves the base as it is for every method but the linear mix (which
    /// halves the tilt); a flat base gives the detail for every method but the linear mix and
    /// UDN (which keeps only the detail's `x`, `y` over `z = 1`).
    #[test]
    fn a_flat_partner_changes_nothing() {
        let n = Vec3::new(0.3, -0.2, 0.9).normalize();
        for &method in DetailBlend::all() {
            if method == DetailBlend::Linear {
                continue;
            }
            let on_flat_detail = blend(method, n, Vec3::Z);
            assert!(on_flat_detail.abs_diff_eq(n, 1e-6), "{}: {on_flat_detail}", method.name());
            if method != DetailBlend::Udn {
                let on_flat_base = blend(method, Vec3::Z, n);
                assert!(on_flat_base.abs_diff_eq(n, 1e-6), "{}: {on_flat_base}", method.name());
            }
        }
    }

    /// Every method gives a unit vector, also for normals at the horizon.
    #[test]
    fn every_method_gives_a_unit_vector() {
        let grazing = [Vec3::X, Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.6, 0.0, 0.8), Vec3::Z];
        for &method in DetailBlend::all() {
            for b in grazing {
                for d in grazing {
                    let r = blend(method, b, d);
                    assert!((r.length() - 1.0).abs() < 1e-5, "{} of {b} and {d}: {r}", method.name());
                }
            }
        }
    }

    /// A flat detail map leaves the base's normals as they are (every method but the linear
    /// mix, which halves the tilt), to the 8-bit base's decoding.
    #[test]
    fn a_flat_detail_map_gives_the_base_back() {
        let base = crate::scene::sine_pair_normal_map(16, 1, 0.8);
        let flat = TextureImage { rgba: [128, 128, 255, 255].repeat(4), width: 2, height: 2, ..base.clone() };
        for &method in DetailBlend::all().iter().filter(|&&m| m != DetailBlend::Linear) {
            let normals = blend_maps(&base, &flat, 3.0, 1.0, method);
            for (i, n) in normals.iter().enumerate() {
                let t = base.texel((i % 16) as i64, (i / 16) as i64).map(|c| f32::from(c) / 255.0);
                let b = Vec3::new(t[0], t[1], t[2]) * 2.0 - 1.0;
                assert!(n.angle_between(b.normalize()) < 0.01, "{}: texel {i}", method.name());
            }
        }
    }
}
