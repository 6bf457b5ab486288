//! The mip-filter study (report::mip_study) on lavapipe at a small size: at 16× minification
//! the methods that widen the highlight from the filtered normal map beat re-normalised mips
//! on both static error and shimmer, and at 1× every method draws what plain shading draws.

use bumpview::names::Named;
use bumpview::render::{Gpu, Renderer};
use bumpview::report::mip_specimen::Shape;
use bumpview::report::mip_study::{MipPlan, MipRow, measure};
use bumpview::texture::MipFilter;

fn renderer() -> Renderer {
    let gpu =
        Gpu::headless().unwrap_or_else(|e| panic!("GPU tests need an adapter (install mesa-vulkan-drivers): {e}"));
    Renderer::from_gpu(&gpu)
}

/// 32×32 pictures, 16 frames of the pan, the 16×16 reference.
fn plan() -> MipPlan {
    MipPlan { convergence: vec![16], ..MipPlan::quick() }
}

fn row(rows: &[MipRow], filter: MipFilter) -> Option<&MipRow> {
    rows.iter().find(|r| r.method == filter.name())
}

/// Measured on lavapipe (32×32, 16 frames): on the plane re-normalised mips have RMSE 0.124
/// and shimmer 0.034, Toksvig 0.033 and 0.0147, vMF 0.031 and 0.0146 (torus: 0.108/0.041
/// against 0.035/0.017 and 0.033/0.016). The bounds ask for a factor of 2.5 on static error
/// and 1.6 on shimmer: below what was measured, far above what a method that widens nothing
/// gets (1.0). LEAN is held to the same bounds once the renderer draws it.
#[test]
fn at_16x_toksvig_lean_and_vmf_beat_renormalised_mips_on_static_error_and_shimmer() {
    let mut renderer = renderer();
    for shape in [Shape::Plane, Shape::Torus] {
        let (rows, _) = measure(&mut renderer, &plan(), shape, 16).unwrap();
        let plain = row(&rows, MipFilter::RenormalizedBox).expect("re-normalised mips are drawn");
        // Plain mips are too shiny: a third more highlight than the reference at least.
        assert!(plain.energy_ratio > 1.3, "{plain:?}");
        let mut beaten = 0;
        for filter in [MipFilter::Toksvig, MipFilter::Lean, MipFilter::Vmf] {
            let Some(r) = row(&rows, filter) else {
                assert_eq!(filter, MipFilter::Lean, "{} is drawn", filter.name());
                continue;
            };
            assert!(r.rmse * 2.5 < plain.rmse, "{shape:?}: {r:?} against {plain:?}");
            assert!(r.shimmer * 1.6 < plain.shimmer, "{shape:?}: {r:?} against {plain:?}");
            assert!((r.energy_ratio - 1.0).abs() < 0.15, "{shape:?}: {r:?}");
            beaten += 1;
        }
        assert!(beaten >= 2);
    }
}

/// At 1× on the plane (a texel a pixel: level 0 is what the sampler reads) every method but
/// geometric specular AA (it widens from the normal's screen derivatives at any distance)
/// draws exactly what base-level-only sampling draws, to the last bit of the float target.
/// LEAN within 1e-5 relative: it fades its variance in over `clamp(lod, 0, 1)`, and at a texel
/// a pixel the lod is 0 only up to rounding (measured: 1.1e-6 relative on the RMSE).
#[test]
fn at_1x_every_method_draws_the_base_level() {
    let mut renderer = renderer();
    let (rows, _) = measure(&mut renderer, &plan(), Shape::Plane, 1).unwrap();
    let base = row(&rows, MipFilter::BaseOnly).unwrap();
    for r in rows.iter().filter(|r| r.method != MipFilter::GeometricSpecularAa.name()) {
        let measured = [r.rmse, r.energy_ratio, r.shimmer];
        let expected = [base.rmse, base.energy_ratio, base.shimmer];
        if r.method == MipFilter::Lean.name() {
            let close = measured.iter().zip(expected).all(|(m, e)| (m - e).abs() <= 1e-5 * e.abs());
            assert!(close, "{r:?} against {base:?}");
        } else {
            assert_eq!(measured, expected, "{r:?}");
        }
    }
}
