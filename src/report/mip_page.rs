//! The mip-filter study's part of the report ([`super::mip_study`]): the reference's
//! convergence, one table per specimen, which method comes closest at 16×, CSV rows, and a
//! chart of static error against GPU frame time (a point per method and minification).

use std::fmt::Write;

use super::chart::{COLOURS, ChartError, Marker, Series, XAxis, png};
use super::mip_specimen::{SHININESS, SLOPE_SIGMA, Shape};
use super::mip_study::{MipPlan, MipRow, MipStudy, PAN_PX_PER_FRAME};
use crate::names::Named;
use crate::texture::MipFilter;

/// The chart's file name.
pub const CHART: &str = "mip-filters.png";
/// The CSV's file name.
pub const CSV: &str = "mip-filters.csv";
/// The minification the answer is given at.
pub const ANSWER_AT: u32 = 16;

/// Rows of `shape` at `minification`.
fn at(rows: &[MipRow], shape: Shape, minification: u32) -> Vec<&MipRow> {
    rows.iter().filter(|r| r.shape == shape && r.minification == minification).collect()
}

/// The method with the lowest static error on `shape` at `minification`.
pub fn closest(rows: &[MipRow], shape: Shape, minification: u32) -> Option<&MipRow> {
    at(rows, shape, minification).into_iter().min_by(|a, b| a.rmse.total_cmp(&b.rmse))
}

fn ms(row: &MipRow) -> String {
    row.frame_ms.map_or("—".into(), |ms| format!("{ms:.2}"))
}

/// The markdown section; `adapter` names the GPU, `notes` say what was left out.
pub fn markdown(study: &MipStudy, plan: &MipPlan, adapter: &str, notes: &[String]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Normal maps at a distance: mip filters against a supersampled reference\n");
    let _ = writeln!(
        s,
        "A synthetic normal map of fine bumps (128×128 texels, six sine waves of 10 to 26 texels, slope \
         standard deviation {SLOPE_SIGMA} per axis) on a plane facing the camera and on the built-in torus, \
         Blinn-Phong exponent {SHININESS}, one point light moving with the camera, drawn on **{adapter}** at \
         {0}×{0} pixels, one sample per pixel. *k× minification*: the UVs are tiled so that k texels of \
         level 0 span a pixel (on the torus, at the front of its tube). Reference: the base level only, \
         drawn at {1}× the size and box-filtered in linear radiance ({1}×{1} samples per pixel). \
         **RMSE**: linear RGB against the reference at frame 0. **Energy**: mean highlight radiance \
         (the picture minus the same picture with the highlight off) over the reference's. **Shimmer**: \
         the camera pans {PAN_PX_PER_FRAME} pixel per frame over {2} frames; per pixel and channel the \
         standard deviation over time of (frame − reference frame), averaged. Only pixels the surface \
         covers fully count. **ms**: median GPU frame time at {3}×{3} (4× MSAA); **texture bytes**: every \
         level of the normal map uploaded.\n",
        plan.size, plan.supersample, plan.frames, plan.timing_size,
    );
    for note in notes {
        let _ = writeln!(s, "- {note}");
    }
    if !notes.is_empty() {
        s.push('\n');
    }
    let _ = writeln!(s, "### The reference's convergence\n");
    let _ = writeln!(s, "RMSE of each sample grid against the finest, at frame 0 (mean radiance for scale):\n");
    let grids: Vec<u32> = plan.convergence.clone();
    let _ = write!(s, "| specimen | k× | mean radiance |");
    for g in &grids {
        let _ = write!(s, " {g}×{g} |");
    }
    let _ = writeln!(s, "\n|---|---:|---:|{}", "---:|".repeat(grids.len()));
    for c in &study.convergence {
        let _ = write!(s, "| {} | {} | {:.4} |", c.shape.name(), c.minification, c.mean_radiance);
        for g in &grids {
            match c.rmse_by_grid.iter().find(|(grid, _)| grid == g) {
                Some((_, e)) => {
                    let _ = write!(s, " {e:.5} |");
                }
                None => s.push_str(" — |"),
            }
        }
        s.push('\n');
    }
    s.push('\n');
    for &shape in &plan.shapes {
        let _ = writeln!(s, "### {}\n", shape.name());
        let _ = writeln!(s, "| method | k× | RMSE | energy | shimmer | ms | texture bytes |");
        let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|");
        for &k in &plan.minifications {
            for r in at(&study.rows, shape, k) {
                let _ = writeln!(
                    s,
                    "| {} | {k} | {:.4} | {:.3} | {:.4} | {} | {} |",
                    r.method,
                    r.rmse,
                    r.energy_ratio,
                    r.shimmer,
                    ms(r),
                    r.texture_bytes
                );
            }
        }
        s.push('\n');
        s.push_str(&answer(&study.rows, shape));
    }
    let _ = writeln!(s, "![static error against GPU frame time, a point per method and minification]({CHART})\n");
    s
}

/// Which method comes closest at [`ANSWER_AT`]× on `shape`, at what cost, and by how much
/// it beats re-normalised mips.
pub fn answer(rows: &[MipRow], shape: Shape) -> String {
    let Some(best) = closest(rows, shape, ANSWER_AT) else {
        return String::new();
    };
    let plain = at(rows, shape, ANSWER_AT).into_iter().find(|r| r.method == MipFilter::RenormalizedBox.name());
    let mut s = format!(
        "At {ANSWER_AT}× on the {}, **{}** comes closest to the reference: RMSE {:.4}, energy {:.3}, shimmer {:.4}, \
         {} ms, {} texture bytes",
        shape.name(),
        best.method,
        best.rmse,
        best.energy_ratio,
        best.shimmer,
        ms(best),
        best.texture_bytes
    );
    if let Some(plain) = plain.filter(|p| p.method != best.method) {
        let _ = write!(
            s,
            " — against re-normalised mips' RMSE {:.4} and shimmer {:.4} ({:.1}× and {:.1}× lower), {} ms, {} bytes",
            plain.rmse,
            plain.shimmer,
            plain.rmse / best.rmse.max(1e-12),
            plain.shimmer / best.shimmer.max(1e-12),
            ms(plain),
            plain.texture_bytes
        );
    }
    s.push_str(".\n\n");
    s
}

/// CSV rows (header first), one per method, specimen and minification.
pub fn csv(rows: &[MipRow]) -> String {
    let mut s =
        String::from("specimen,minification,method,rmse_linear_rgb,energy_ratio,shimmer,frame_ms,texture_bytes\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{:.6},{:.6},{:.6},{},{}",
            r.shape.name(),
            r.minification,
            r.method,
            r.rmse,
            r.energy_ratio,
            r.shimmer,
            r.frame_ms.map_or(String::new(), |ms| format!("{ms:.4}")),
            r.texture_bytes
        );
    }
    s
}

/// RMSE against frame time: a curve per method and specimen (circles the plane, triangles
/// the torus) through its minifications.
pub fn chart(rows: &[MipRow]) -> Result<Vec<u8>, ChartError> {
    let mut methods: Vec<&str> = vec![];
    rows.iter().for_each(|r| {
        if !methods.contains(&r.method) {
            methods.push(r.method);
        }
    });
    let mut series = vec![];
    for (index, method) in methods.iter().enumerate() {
        for shape in [Shape::Plane, Shape::Torus] {
            let mut points: Vec<(u32, f64, f64)> = rows
                .iter()
                .filter(|r| r.method == *method && r.shape == shape)
                .filter_map(|r| r.frame_ms.map(|ms| (r.minification, ms.max(1e-3), r.rmse.max(1e-5))))
                .collect();
            if points.is_empty() {
                continue;
            }
            points.sort_by_key(|p| p.0);
            series.push(Series {
                label: format!("{method} · {}", shape.name()),
                colour: COLOURS[index % COLOURS.len()],
                marker: if shape == Shape::Torus { Marker::Triangle } else { Marker::Circle },
                points: points.into_iter().map(|(_, ms, e)| (ms, e)).collect(),
            });
        }
    }
    png(
        "Mip filters: RMSE against the reference vs GPU frame time (a point per minification)",
        ["median GPU frame time (ms)", "RMSE against the 16×16 reference, linear RGB"],
        &series,
        XAxis::Log,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(method: &'static str, rmse: f64, shimmer: f64) -> MipRow {
        MipRow {
            shape: Shape::Plane,
            minification: ANSWER_AT,
            method,
            rmse,
            energy_ratio: 1.0,
            shimmer,
            frame_ms: Some(1.5),
            texture_bytes: 100,
        }
    }

    #[test]
    fn the_answer_names_the_closest_method_and_its_gain() {
        let rows = [row("renormalized-box", 0.12, 0.03), row("toksvig", 0.03, 0.015), row("x", 0.05, 0.01)];
        let text = answer(&rows, Shape::Plane);
        assert!(text.contains("**toksvig** comes closest"), "{text}");
        assert!(text.contains("(4.0× and 2.0× lower)"), "{text}");
        assert_eq!(answer(&rows, Shape::Torus), "");
        assert_eq!(csv(&rows[1..2]), format!("{}plane,16,toksvig,0.030000,1.000000,0.015000,1.5000,100\n", csv(&[])));
    }
}
