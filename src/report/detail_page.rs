//! The detail-blend study's part of the report ([`super::detail_study`]): which method is
//! exact for which question, a table per method over base tilt at strength 1, the lit
//! picture's RMSE, GPU frame time per method on the built-in detail-waves scene, CSV rows and
//! a chart of error against base tilt.

use std::fmt::Write;
use std::num::NonZeroU32;

use glam::Vec3;

use super::chart::{COLOURS, ChartError, ERROR_FLOOR_DEGREES, Marker, Series, XAxis, png};
use super::detail_study::{DetailPlan, DetailRow};
use super::gpu_time::gpu_frame_ms;
use crate::error::RenderError;
use crate::frame::{DetailBlend, FrameParams, ShadingSettings};
use crate::names::Named;
use crate::render::Renderer;
use crate::scene::teaching::TeachingScene;
use crate::scene::{Light, Lights, OrbitCamera};

/// The chart's file name.
pub const CHART: &str = "detail-blends.png";
/// The CSV's file name.
pub const CSV: &str = "detail-blends.csv";
/// The strength the tables and the chart show.
pub const SHOWN_STRENGTH: f64 = 1.0;

/// The median GPU frame time (ms, 4× MSAA, `size`) of the built-in detail-waves wall under
/// each method; `None` per method without timestamp queries.
pub fn gpu_ms(renderer: &mut Renderer, size: [u32; 2]) -> Result<Vec<(&'static str, Option<f64>)>, RenderError> {
    let scene = TeachingScene::DetailWaves.build(crate::height::Kernel::default());
    renderer.set_scene(&scene, Default::default());
    let camera =
        OrbitCamera { target: Vec3::new(0.0, 1.5, -1.0), yaw: 0.0, pitch: 0.0, distance: 1.2, ..scene.default_camera };
    let light = Light::point(Vec3::new(-2.0, 2.5, 2.0), Vec3::ONE);
    let mut rows = vec![];
    for &method in DetailBlend::all() {
        let shading = ShadingSettings { show_light_marker: false, detail_blend: Some(method), ..Default::default() };
        let params = FrameParams { camera, lights: Lights::one(light, scene.ambient), shading };
        rows.push((method.name(), gpu_frame_ms(renderer, &params, size, NonZeroU32::new(15).expect("15"))?));
    }
    Ok(rows)
}

fn at<'a>(rows: &'a [DetailRow], method: &str, strength: f64) -> Vec<&'a DetailRow> {
    rows.iter().filter(|r| r.method == method && r.strength == strength).collect()
}

/// Each method's largest error against each reference over the whole study.
fn worst(rows: &[DetailRow], method: &str) -> [f64; 2] {
    rows.iter().filter(|r| r.method == method).fold([0.0, 0.0], |w, r| [w[0].max(r.added[2]), w[1].max(r.rotated[2])])
}

/// The markdown section; `timing` is [`gpu_ms`]'s rows (empty without a GPU), `notes` what
/// was left out.
pub fn markdown(rows: &[DetailRow], plan: &DetailPlan, timing: &[(&str, Option<f64>)], notes: &[String]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Detail normal maps: six blends against the two exact answers\n");
    let _ = writeln!(
        s,
        "A base height field tilted {}–{}° (a plane at {} azimuths) and a detail sine pair \
         `h = (s/k)(sin kx + sin ky)` of strength s ∈ {:?} ({}×{} phases), each a tangent-space normal map \
         from its exact slopes. **(a) added heights**: the normal of h_b + h_d, slopes added. **(b) rotated \
         detail**: the detail's normal turned by the shortest arc from +Z onto the base normal. Angles in \
         degrees (mean / p95 / max); **lit RMSE**: `0.8·max(n·L, 0) + 0.2·max(n·H, 0)^32` with L at 45° \
         elevation, against each reference's. Methods in f32 as the shader runs them.\n",
        plan.tilts_deg.first().unwrap_or(&0.0),
        plan.tilts_deg.last().unwrap_or(&0.0),
        plan.azimuths,
        plan.strengths,
        plan.phases,
        plan.phases,
    );
    for note in notes {
        let _ = writeln!(s, "- {note}");
    }
    let _ = writeln!(s, "\n| method | max error (a) | max error (b) | GPU ms |\n|---|---|---|---|");
    for &method in DetailBlend::all() {
        let [a, b] = worst(rows, method.name());
        let ms = timing
            .iter()
            .find(|t| t.0 == method.name())
            .and_then(|t| t.1)
            .map_or("—".into(), |ms| format!("{ms:.2}"));
        let _ = writeln!(s, "| {} | {a:.5} | {b:.5} | {ms} |", method.name());
    }
    let exact = |reference: usize| -> Vec<&str> {
        DetailBlend::all().iter().map(|m| m.name()).filter(|&m| worst(rows, m)[reference] < 1e-3).collect()
    };
    let _ = writeln!(
        s,
        "\nExact (under 0.001°) for (a): **{}**; for (b): **{}**.\n",
        exact(0).join(", "),
        exact(1).join(", ")
    );
    let _ = writeln!(s, "### By base tilt, strength {SHOWN_STRENGTH}\n");
    let _ =
        writeln!(s, "| method | tilt ° | (a) mean / p95 / max | (b) mean / p95 / max | lit RMSE (a) | lit RMSE (b) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for &method in DetailBlend::all() {
        for r in at(rows, method.name(), SHOWN_STRENGTH) {
            let [a, b] = [r.added, r.rotated].map(|e| format!("{:.3} / {:.3} / {:.3}", e[0], e[1], e[2]));
            let _ = writeln!(
                s,
                "| {} | {} | {a} | {b} | {:.4} | {:.4} |",
                r.method, r.tilt_deg, r.lit_rmse[0], r.lit_rmse[1]
            );
        }
    }
    let _ = writeln!(s, "\nEvery tilt and strength: `{CSV}`; the chart: `{CHART}`.\n");
    s
}

/// One line per row: method, tilt, strength, the six angles, the two RMSEs.
pub fn csv(rows: &[DetailRow]) -> String {
    let mut s = String::from("method,tilt_deg,strength,a_mean,a_p95,a_max,b_mean,b_p95,b_max,lit_rmse_a,lit_rmse_b\n");
    for r in rows {
        let [a, b] = [r.added, r.rotated];
        let _ = writeln!(
            s,
            "{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}",
            r.method, r.tilt_deg, r.strength, a[0], a[1], a[2], b[0], b[1], b[2], r.lit_rmse[0], r.lit_rmse[1]
        );
    }
    s
}

/// Mean error against each reference over base tilt at [`SHOWN_STRENGTH`]: a line per method
/// and reference (circles (a), triangles (b)); exact values drawn at the chart's floor.
pub fn chart(rows: &[DetailRow]) -> Result<Vec<u8>, ChartError> {
    let mut series = vec![];
    for (index, &method) in DetailBlend::all().iter().enumerate() {
        let shown = at(rows, method.name(), SHOWN_STRENGTH);
        for (reference, marker, name) in [(0, Marker::Circle, "(a) added"), (1, Marker::Triangle, "(b) rotated")] {
            let error = |r: &DetailRow| if reference == 0 { r.added[0] } else { r.rotated[0] };
            series.push(Series {
                label: format!("{} · {name}", method.name()),
                colour: COLOURS[index % COLOURS.len()],
                marker,
                points: shown.iter().map(|r| (r.tilt_deg, error(r).max(ERROR_FLOOR_DEGREES))).collect(),
            });
        }
    }
    png(
        "Detail blends: mean angle to each exact answer against the base's tilt (strength 1)",
        ["base tilt (°)", "mean angle to the reference (°)"],
        &series,
        XAxis::Linear,
    )
}

/// The detail-blend study of `plan` (CPU) and each method's GPU frame time on a headless GPU
/// (512×512); a missing GPU or a failed frame becomes a note, not a failed report.
pub fn study(plan: &DetailPlan) -> (Vec<DetailRow>, Vec<(&'static str, Option<f64>)>, Vec<String>) {
    let rows = super::detail_study::study(plan);
    let timing = crate::render::Gpu::headless().map_err(|e| format!("no GPU: {e}")).and_then(|gpu| {
        let mut renderer = crate::render::Renderer::from_gpu(&gpu);
        let timing = gpu_ms(&mut renderer, [512, 512]).map_err(|e| format!("GPU timing stopped: {e}"))?;
        Ok((timing, gpu.adapter_name()))
    });
    match timing {
        Ok((timing, adapter)) => {
            let note = format!("GPU ms: the built-in detail-waves wall at 512×512, 4× MSAA, on {adapter}");
            (rows, timing, vec![note])
        }
        Err(note) => (rows, vec![], vec![note]),
    }
}
