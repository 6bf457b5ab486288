//! Detail normal maps: the six blend methods against the two exact answers on an analytic pair
//! of height fields (two sines, slopes known in closed form), and each method's CPU twin
//! (the probe through `chain::shade`) against its WGSL twin on the GPU.

mod common;

use bumpview::frame::{DetailBlend, SceneOptions};
use bumpview::names::Named;
use bumpview::report::detail_study::{added_heights, angle_deg, blended, rotated_detail};
use bumpview::scene::{DetailMap, Scene, sine_pair_normal_map};
use common::*;
use glam::DVec2;

/// The analytic pair: base `h_b = A·sin(k_b·x)·cos(k_b·y / 2)` with `A·k_b = tan 60°`, so its
/// normal tilts 0–60°, and detail `h_d = a·(sin(k_d·x) + sin(k_d·y))` with `a·k_d = 1` (a
/// 45° slope at most), on a 64 × 64 grid over one base period. Slopes are exact.
fn analytic_pairs() -> Vec<(DVec2, DVec2)> {
    let (kb, kd) = (1.0, 23.0);
    let base_slope = 60f64.to_radians().tan();
    let mut pairs = vec![];
    for i in 0..64 {
        for j in 0..64 {
            let (x, y) = (std::f64::consts::TAU * f64::from(i) / 64.0, std::f64::consts::TAU * f64::from(j) / 64.0);
            let base = DVec2::new(
                base_slope * (kb * x).cos() * (kb * y / 2.0).cos(),
                -base_slope * 0.5 * (kb * x).sin() * (kb * y / 2.0).sin(),
            );
            let detail = DVec2::new((kd * x).cos(), (kd * y).cos());
            pairs.push((base, detail));
        }
    }
    pairs
}

/// Partial-derivative addition (and surface gradients, its equal in an orthonormal frame) is
/// exact for reference (a), the heights added; RNM is exact for reference (b), the detail
/// turned onto the base normal: within float precision (0.001°; measured 0.000009° for
/// partial derivatives and surface gradients against (a), 0.000011° for RNM against (b)).
/// Every other method misses each reference by more than a degree somewhere (measured: linear
/// 32.9° / 52.2°, whiteout 19.2° / 28.2°, UDN 19.6° / 33.3°; partial derivatives miss (b) and
/// RNM misses (a) by 35.2°).
#[test]
fn partial_derivatives_answer_added_heights_and_rnm_answers_the_rotated_detail() {
    let pairs = analytic_pairs();
    for &method in DetailBlend::all() {
        let (mut added, mut rotated) = (0.0f64, 0.0f64);
        for &(b, d) in &pairs {
            let n = blended(method, b, d);
            added = added.max(angle_deg(n, added_heights(b, d)));
            rotated = rotated.max(angle_deg(n, rotated_detail(b, d)));
        }
        println!("{:<20} max error: added heights {added:.6}°, rotated detail {rotated:.6}°", method.name());
        match method {
            DetailBlend::PartialDerivative | DetailBlend::SurfaceGradient => {
                assert!(added < 1e-3, "{}: {added}° from reference (a)", method.name());
                assert!(rotated > 1.0, "{}: {rotated}° from reference (b)", method.name());
            }
            DetailBlend::Rnm => {
                assert!(rotated < 1e-3, "rnm: {rotated}° from reference (b)");
                assert!(added > 1.0, "rnm: {added}° from reference (a)");
            }
            _ => assert!(added > 1.0 && rotated > 1.0, "{}: {added}°, {rotated}°", method.name()),
        }
    }
}

/// The built-in scene with a sine-pair detail map (two periods of slope 0.7, tiling 2) on every material.
fn detailed_scene() -> Scene {
    let mut scene = scene();
    scene.textures.push(sine_pair_normal_map(64, 2, 0.7).into());
    let texture = scene.textures.len() - 1;
    for material in &mut scene.materials {
        material.detail_map = Some(DetailMap { tiling: 2.0, ..DetailMap::new(texture, DetailBlend::Rnm) });
    }
    scene
}

/// Each method's CPU chain through the probe equals the GPU at a grid of probe points on the
/// wall at 0.5 m (the detail map magnified, so both read its level 0): lit within 3 steps of
/// 8 bits (the tolerance of tests/probe.rs), shading normal within 2; and every point read a
/// detail texel and blended it by the method drawn. Measured on lavapipe at 289 points: lit
/// within 1.39–2.31 steps, shading normal within 1.05–1.71 steps, by method.
#[test]
fn each_methods_cpu_blend_equals_its_wgsl_twin_at_probe_points() {
    let scene = detailed_scene();
    for &method in DetailBlend::all() {
        let mut params = close_wall_params(&scene, 0.5);
        params.shading.detail_blend = Some(method);
        let readouts = gpu_against_probe(&scene, &SceneOptions::default(), &params, [192, 192], 11, [3.0, 2.0]);
        println!("{}: {} points", method.name(), readouts.len());
        for (pixel, readout) in &readouts {
            let detail = readout.chain.detail.unwrap_or_else(|| panic!("{pixel:?}: no detail step"));
            assert_eq!(detail.method, method);
        }
    }
}

/// The report's section on the full plan: partial derivatives and surface gradients are the
/// exact answer to (a) at every tilt and strength, RNM to (b), and the page says so; the
/// section is printed with each method's GPU frame time (for docs/detail-normals.md).
#[test]
fn the_report_names_the_exact_method_for_each_question() {
    use bumpview::report::detail_page::{chart, csv, gpu_ms, markdown};
    use bumpview::report::detail_study::{DetailPlan, study};
    let plan = DetailPlan::full();
    let rows = study(&plan);
    assert_eq!(rows.len(), plan.tilts_deg.len() * plan.strengths.len() * DetailBlend::all().len());
    for row in &rows {
        match row.method {
            "partial-derivative" | "surface-gradient" => assert!(row.added[2] < 1e-3, "{row:?}"),
            "rnm" => assert!(row.rotated[2] < 1e-3, "{row:?}"),
            _ => {}
        }
    }
    let mut renderer = renderer_for(&scene());
    let timing = gpu_ms(&mut renderer, [512, 512]).unwrap();
    let page = markdown(&rows, &plan, &timing, &[]);
    println!("{page}");
    assert!(page.contains("Exact (under 0.001°) for (a): **partial-derivative, surface-gradient**; for (b): **rnm**"));
    assert_eq!(csv(&rows).lines().count(), rows.len() + 1);
    let png = chart(&rows).unwrap();
    std::fs::write(std::env::temp_dir().join("detail-blends.png"), &png).unwrap();
}

/// `bake BASE --detail FLAT --blend M` writes a 16-bit map equal to the base for every method
/// but the linear mix (a flat detail changes nothing), within the base's 8-bit decoding.
#[test]
fn bake_blends_two_maps_into_a_16_bit_png() {
    let dir = std::env::temp_dir().join(format!("bumpview-detail-bake-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = sine_pair_normal_map(32, 1, 0.8);
    let to_png = |t: &bumpview::scene::TextureImage, name: &str| {
        let path = dir.join(name);
        image::RgbaImage::from_raw(t.width, t.height, t.rgba.clone()).unwrap().save(&path).unwrap();
        path
    };
    let base_path = to_png(&base, "base.png");
    let flat =
        bumpview::scene::TextureImage { rgba: [128, 128, 255, 255].repeat(4), width: 2, height: 2, ..base.clone() };
    let flat_path = to_png(&flat, "flat.png");
    for &method in DetailBlend::all().iter().filter(|&&m| m != DetailBlend::Linear) {
        let out = dir.join(format!("{}.png", method.name()));
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_bumpview"))
            .args(["bake"])
            .arg(&base_path)
            .arg("--detail")
            .arg(&flat_path)
            .args(["--blend", method.name(), "--out"])
            .arg(&out)
            .status()
            .unwrap();
        assert!(status.success());
        let written = image::open(&out).unwrap();
        assert_eq!(written.color(), image::ColorType::Rgb16, "{}", method.name());
        let written = written.to_rgb16();
        for (x, y, p) in written.enumerate_pixels() {
            let n = glam::Vec3::from(p.0.map(|c| f32::from(c) / 65535.0)) * 2.0 - 1.0;
            let t = base.texel(i64::from(x), i64::from(y));
            let b = glam::Vec3::new(f32::from(t[0]), f32::from(t[1]), f32::from(t[2])) / 127.5 - 1.0;
            assert!(n.angle_between(b.normalize()) < 0.01, "{} at ({x}, {y})", method.name());
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
