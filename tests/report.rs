//! The report's measurements against known numerical behaviour, tangent frames on a mirrored
//! UV layout, and `bumpview report --quick` as a user runs it.

use std::process::Command;

use bumpview::frame::Parallax;
use bumpview::height::{Border, Kernel};
use bumpview::names::Named;
use bumpview::report::measure::{angle_degrees, kernel_normals};
use bumpview::report::surfaces::SineBumps;
use bumpview::scene::Mesh;
use bumpview::tangent::{TangentMethod, bitangent, tangents};
use glam::{DVec3, Vec2, Vec3, Vec4};

/// Mean angle (degrees) between `kernel`'s normals and the exact ones at the texel centres.
fn mean_error(kernel: Kernel, texels_per_period: u32) -> f64 {
    let bumps = SineBumps::new(texels_per_period, 2);
    let normals = kernel_normals(&bumps.field(), kernel, Border::Wrap);
    let side = bumps.side();
    let exact = (0..side).flat_map(|j| (0..side).map(move |i| bumps.normal(i, j)));
    let total: f64 = normals.iter().zip(exact).map(|(n, e)| angle_degrees(n.as_dvec3(), e)).sum();
    total / normals.len() as f64
}

/// `log2(e(N) / e(2N))`: the order seen when the resolution doubles.
fn observed_order(error: impl Fn(u32) -> f64, texels_per_period: u32) -> f64 {
    (error(texels_per_period) / error(2 * texels_per_period)).log2()
}

#[test]
fn central_difference_gain_is_sinc_of_k_delta() {
    for texels_per_period in [6, 8, 16, 32] {
        let bumps = SineBumps::new(texels_per_period, 1);
        let field = bumps.field();
        let side = bumps.side();
        // The texel of maximum exact slope along x (and, separately, along y).
        let slope_at = |i: u32, j: u32| {
            let (x, y) = bumps.texel_centre(i, j);
            bumps.slope(x, y)
        };
        let texels: Vec<(u32, u32)> = (0..side).flat_map(|j| (0..side).map(move |i| (i, j))).collect();
        let steepest_x =
            *texels.iter().max_by(|a, b| slope_at(a.0, a.1).0.abs().total_cmp(&slope_at(b.0, b.1).0.abs())).unwrap();
        let steepest_y =
            *texels.iter().max_by(|a, b| slope_at(a.0, a.1).1.abs().total_cmp(&slope_at(b.0, b.1).1.abs())).unwrap();
        let k_delta = bumps.wavenumber() * bumps.texel_m();
        let sinc = k_delta.sin() / k_delta;
        let (i, j) = steepest_x;
        let gain_x =
            field.slope(Kernel::CentralDifference, Border::Wrap, i as i64, j as i64).0 as f64 / slope_at(i, j).0;
        let (i, j) = steepest_y;
        let gain_y =
            field.slope(Kernel::CentralDifference, Border::Wrap, i as i64, j as i64).1 as f64 / slope_at(i, j).1;
        for gain in [gain_x, gain_y] {
            assert!((gain - sinc).abs() < 2e-6, "{texels_per_period} texels/period: gain {gain}, sinc(kΔ) {sinc}");
        }
    }
}

#[test]
fn kernels_converge_at_their_truncation_order() {
    let expected = [
        (Kernel::ForwardDifference, 1.0),
        (Kernel::CentralDifference, 2.0),
        (Kernel::Sobel3, 2.0),
        (Kernel::Scharr3, 2.0),
        (Kernel::Sobel5, 2.0),
        (Kernel::Central4, 4.0),
    ];
    for (kernel, order) in expected {
        // 16 → 32 texels per period: asymptotic, and central4's error (~0.001°) still far above f32 noise.
        let seen = observed_order(|n| mean_error(kernel, n), 16);
        assert!((seen - order).abs() < 0.1, "{}: order {seen}, expected {order}", kernel.name());
    }
}

/// The forward difference `(h[x+1] − h[x]) / Δ` is a centred difference about `x + Δ/2`: against
/// the exact slope there (x-derivative at `(x + Δ/2, y)`, y-derivative at `(x, y + Δ/2)`, a
/// staggered grid) it is second order, with gain `sinc(kΔ/2)`.
#[test]
fn forward_difference_is_second_order_about_the_half_texel_point() {
    let staggered_error = |texels_per_period: u32| {
        let bumps = SineBumps::new(texels_per_period, 2);
        let field = bumps.field();
        let half = bumps.texel_m() / 2.0;
        let side = bumps.side();
        let mut total = 0.0;
        for j in 0..side {
            for i in 0..side {
                let (dx, dy) = field.slope(Kernel::ForwardDifference, Border::Wrap, i as i64, j as i64);
                let (x, y) = bumps.texel_centre(i, j);
                let exact = DVec3::new(-bumps.slope(x + half, y).0, -bumps.slope(x, y + half).1, 1.0);
                total += angle_degrees(DVec3::new(-dx as f64, -dy as f64, 1.0), exact);
            }
        }
        total / (side * side) as f64
    };
    let seen = observed_order(staggered_error, 16);
    assert!((seen - 2.0).abs() < 0.1, "order {seen}");
    assert!(staggered_error(32) < 0.1 * mean_error(Kernel::ForwardDifference, 32));
}

/// A unit-square grid in the XY plane facing +Z, twice: the left square `x ∈ [0, 1]` with
/// `u = x`, the right one `x ∈ [1, 2]` with `u` mirrored (`u = 2 − x`), `v = 1 − y` on both (v
/// down the image, so the image's up is +Y). The mirror column is split, as meshes with mirrored
/// UVs are. Returns the mesh and, per vertex, whether it is on the mirrored half.
fn mirrored_grid(cells: u32) -> (Mesh, Vec<bool>) {
    let mut mesh = Mesh::empty("mirrored grid");
    let mut mirrored = vec![];
    let mut analytic = vec![];
    for half in 0..2 {
        let base = mesh.positions.len() as u32;
        for j in 0..=cells {
            for i in 0..=cells {
                let (x, y) = (half as f32 + i as f32 / cells as f32, j as f32 / cells as f32);
                mesh.positions.push(Vec3::new(x, y, 0.0));
                mesh.normals.push(Vec3::Z);
                mesh.uvs.push(Vec2::new(if half == 0 { x } else { 2.0 - x }, 1.0 - y));
                analytic.push(if half == 0 { Vec4::new(1.0, 0.0, 0.0, 1.0) } else { Vec4::new(-1.0, 0.0, 0.0, -1.0) });
                mirrored.push(half == 1);
            }
        }
        let stride = cells + 1;
        for j in 0..cells {
            for i in 0..cells {
                let a = base + j * stride + i;
                // +x then +y: counter-clockwise seen from +Z.
                mesh.indices.extend([a, a + 1, a + stride + 1, a, a + stride + 1, a + stride]);
            }
        }
    }
    mesh.analytic_tangents = Some(analytic);
    (mesh, mirrored)
}

#[test]
fn every_method_gives_unit_orthogonal_frames_with_the_right_handedness_on_mirrored_uvs() {
    let (mesh, mirrored) = mirrored_grid(4);
    // The generated methods only: supplied and analytic frames come from the mesh itself.
    let methods: Vec<TangentMethod> = TangentMethod::all().iter().copied().filter(|m| m.is_generated()).collect();
    assert_eq!(methods.len(), 6, "{methods:?}");
    for method in methods {
        // Per-face frames are exact on the unwelded mesh, which is how they are drawn.
        let (mesh, mirrored): (Mesh, Vec<bool>) = if method == TangentMethod::PerFace {
            (mesh.unwelded(), mesh.indices.iter().map(|&i| mirrored[i as usize]).collect())
        } else {
            (mesh.clone(), mirrored.clone())
        };
        let frames = tangents(&mesh, method).unwrap();
        for ((frame, &n), &mirror) in frames.iter().zip(&mesh.normals).zip(&mirrored) {
            let name = method.name();
            let t = frame.truncate();
            assert!((t.length() - 1.0).abs() < 1e-5 && t.dot(n).abs() < 1e-5, "{name}: {frame}");
            let expected_w = if mirror { -1.0 } else { 1.0 };
            assert_eq!(
                frame.w,
                expected_w,
                "{name}: handedness on the {} half",
                if mirror { "mirrored" } else { "plain" }
            );
            assert!(bitangent(n, *frame).dot(Vec3::Y) > 0.9999, "{name}: B points up the image");
            assert!(t.dot(if mirror { -Vec3::X } else { Vec3::X }) > 0.9999, "{name}: T along +u");
        }
    }
}

fn markdown_mentions(dir: &std::path::Path, text: &str) -> bool {
    std::fs::read_to_string(dir.join("report.md")).unwrap().contains(text)
}

fn temporary_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn quick_report_writes_a_row_for_every_method_and_kernel_and_valid_charts() {
    let dir = temporary_dir("quick");
    let output =
        Command::new(env!("CARGO_BIN_EXE_bumpview")).args(["report", "--quick", "--out"]).arg(&dir).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let csv = std::fs::read_to_string(dir.join("report.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    let has = |study: &str, method: &str| rows.iter().any(|r| r[0] == study && r[1] == method);
    for &method in TangentMethod::all() {
        assert_eq!(has("tangents", method.name()), method != TangentMethod::Supplied, "{}", method.name());
    }
    for &kernel in Kernel::all() {
        assert!(has("kernels", kernel.name()), "{}", kernel.name());
    }
    let header_cells = csv.lines().next().unwrap().split(',').count();
    assert!(rows.iter().all(|r| r.len() == header_cells));
    // The parallax study (wall at 0° and 70°): a row per technique and layer count per angle,
    // displacement's reference and its convergence, and the chart.
    let parallax = std::fs::read_to_string(dir.join("parallax.csv")).unwrap();
    let parallax_rows: Vec<Vec<&str>> = parallax.lines().skip(1).map(|l| l.split(',').collect()).collect();
    for angle in ["0", "70"] {
        for technique in ["off", "offset", "offset-limited", "steep", "occlusion", "relief", "displacement"] {
            let found = parallax_rows.iter().any(|r| r[0] == "wall" && r[1] == angle && r[2] == technique);
            assert!(found, "wall {angle}° {technique}");
        }
    }
    let rmse = |technique: &str, layers: &str| {
        let row = parallax_rows.iter().find(|r| r[1] == "70" && r[2] == technique && r[3] == layers).unwrap();
        row[5].parse::<f64>().unwrap()
    };
    // Occlusion beats steep at equal layers, and any search beats no parallax, at 70°.
    assert!(rmse("occlusion", "8") < rmse("steep", "8") && rmse("steep", "8") < rmse("off", ""), "{parallax}");
    assert!(markdown_mentions(&dir, "## Parallax: image error against frame time"));
    // The UV error against the exact intersection: every angle 0°–85°, the GPU time beside
    // the angles the image study drew.
    assert!(markdown_mentions(&dir, "## Parallax: texture-space error against the exact intersection"));
    for angle in (0..=85).step_by(5) {
        assert!(markdown_mentions(&dir, &format!("| wall | relief | 32 | {angle}° |")), "relief 32 at {angle}°");
    }
    let uv_line = |angle: &str| {
        let markdown = std::fs::read_to_string(dir.join("report.md")).unwrap();
        markdown.lines().find(|l| l.starts_with(&format!("| wall | relief | 32 | {angle}° |"))).unwrap().to_owned()
    };
    assert!(!uv_line("70").ends_with("| — |") && uv_line("75").ends_with("| — |"), "{}", uv_line("70"));
    // The mip filters at 16× on the plane and the torus: a row per method the renderer draws,
    // the section with its answer, and the chart.
    let mip = std::fs::read_to_string(dir.join("mip-filters.csv")).unwrap();
    for specimen in ["plane", "torus"] {
        for method in ["base-only", "renormalized-box", "toksvig", "lean", "vmf"] {
            let row = format!("{specimen},16,{method},");
            assert!(mip.lines().any(|l| l.starts_with(&row)), "{row} in {mip}");
        }
    }
    assert!(markdown_mentions(&dir, "## Normal maps at a distance: mip filters against a supersampled reference"));
    assert!(markdown_mentions(&dir, "At 16× on the plane, **"));
    // The compression study (64² bricks and noise): a row per map and format (ETC1S with its
    // feature), the section and a chart per map.
    let compression = std::fs::read_to_string(dir.join("compression.csv")).unwrap();
    for map in ["bricks", "noise"] {
        for &format in bumpview::bake::compressed_format::CompressedFormat::all() {
            let row = format!("{map},{},", format.name());
            assert!(compression.lines().any(|l| l.starts_with(&row)), "{row} in {compression}");
        }
    }
    assert!(markdown_mentions(&dir, "## Texture compression: what each format does to a normal map"));
    // The UV rows' CSV: a row per technique, layer count (the quick plan's two) and angle (the
    // techniques without a search once), every line as long as the header.
    let uv = std::fs::read_to_string(dir.join("uv-error.csv")).unwrap();
    let uv_rows: Vec<Vec<&str>> = uv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    let per_angle: usize = Parallax::shifting().map(|t| if t.marches() { 2 } else { 1 }).sum();
    assert_eq!(uv_rows.len(), 18 * per_angle, "{uv}");
    assert!(uv_rows.iter().all(|r| r.len() == uv.lines().next().unwrap().split(',').count()));
    let relief_70 = uv_rows.iter().find(|r| r[1] == "relief" && r[2] == "32" && r[3] == "70").unwrap();
    assert!(uv_line("70").contains(&format!("| {:.3} |", relief_70[4].parse::<f64>().unwrap())), "{relief_70:?}");
    // The face-on floor: the best technique at 0°, and each 70° cell's part above it.
    let floor = parallax_rows
        .iter()
        .filter(|r| r[1] == "0" && !["off", "displacement"].contains(&r[2]))
        .map(|r| r[5].parse::<f64>().unwrap())
        .fold(f64::MAX, f64::min);
    assert!(markdown_mentions(&dir, &format!("Face-on floor: **{floor:.4}** RMSE")), "floor {floor}");
    let occlusion = rmse("occlusion", "32");
    assert!(markdown_mentions(&dir, &format!(" {occlusion:.4} (+{:.4}) ·", occlusion - floor)), "{occlusion}");
    for chart in [
        "tangents.png",
        "kernels.png",
        "parallax-wall.png",
        "uv-ms-wall-70.png",
        "uv-angle-wall.png",
        "mip-filters.png",
        "compression-bricks.png",
        "compression-noise.png",
    ] {
        let image = image::open(dir.join(chart)).unwrap_or_else(|e| panic!("{chart}: {e}"));
        let rgb = image.to_rgb8();
        let first = *rgb.get_pixel(0, 0);
        assert!(rgb.pixels().any(|p| *p != first), "{chart} is blank");
    }
    let markdown = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(markdown.contains("](tangents.png)") && markdown.contains("](kernels.png)"));
    for size in bumpview::frame::CUBE_MAP_SIZES {
        assert!(markdown.contains(&format!("| {size}×{size} |")), "the cube map row of {size}");
    }
    assert!(!std::fs::read_dir(&dir).unwrap().any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".tmp")));
    the_quick_runs_reference_passes_the_full_runs_convergence_test(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The quick run's displacement reference passes the full run's convergence test: its picture
/// at 70° one level coarser is within `REFERENCE_STEP_RMSE` of it, and the page says so.
/// (Called from the quick report's test, which runs `report --quick` once for both.)
fn the_quick_runs_reference_passes_the_full_runs_convergence_test(dir: &std::path::Path) {
    use bumpview::report::convergence::{REFERENCE_STEP_RMSE, ReferenceStep, reference_step};
    use bumpview::report::parallax::{DISPLACEMENT, ImageError, ParallaxRow};
    let parallax = std::fs::read_to_string(dir.join("parallax.csv")).unwrap();
    let rows: Vec<ParallaxRow> = parallax
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[2] == DISPLACEMENT)
        .map(|r| ParallaxRow {
            specimen: r[0].to_owned(),
            angle_deg: r[1].parse().unwrap(),
            technique: DISPLACEMENT,
            layers: None,
            level: r[4].parse().ok(),
            error: ImageError { rmse: r[5].parse().unwrap(), off_share: r[6].parse().unwrap() },
            frame_ms: r[7].parse().unwrap(),
        })
        .collect();
    let step: ReferenceStep = reference_step(&rows, "wall", 70.0).expect("the level below the reference drawn");
    assert!(step.converged() && step.below.rmse <= REFERENCE_STEP_RMSE, "{step:?}");
    assert!(markdown_mentions(dir, &format!("Reference level {}: **converged**", step.level)), "{step:?}");
}

#[test]
fn an_unwritable_directory_fails_with_one_line() {
    let dir = temporary_dir("unwritable");
    std::fs::create_dir_all(&dir).unwrap();
    // A directory inside a regular file cannot be made, not even by root.
    std::fs::write(dir.join("file"), b"").unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_bumpview"))
        .args(["report", "--quick", "--out"])
        .arg(dir.join("file").join("report"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    let ours: Vec<&str> = stderr.lines().filter(|l| l.starts_with("bumpview:")).collect();
    assert_eq!(ours.len(), 1, "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}
