//! The parallax study's part of the report: a markdown section (the convergence of the
//! displacement reference, one table per specimen, the layers occlusion needs, Blinn's
//! approximation), CSV rows, and a Pareto chart per specimen (image RMSE against frame time,
//! one curve per technique).

use std::fmt::Write;

use super::blinn::BlinnRow;
use plotters::style::RGBColor;

use super::chart::{COLOURS, ChartError, Marker, Series, XAxis, png};
use super::convergence::{REFERENCE_STEP_RMSE, reference_step};
use super::parallax::{DISPLACEMENT, OFF_BY, ParallaxPlan, ParallaxRow};
use crate::frame::Parallax;
use crate::names::Named;

/// RMSE (linear RGB) a picture must come within to count as matching displacement: 1 % of the
/// full range.
pub const WITHIN_RMSE: f64 = 0.01;

/// What the section shows besides the rows.
pub struct ParallaxPage<'a> {
    pub rows: &'a [ParallaxRow],
    pub plan: &'a ParallaxPlan,
    /// The adapter's name, or why the GPU study did not run.
    pub adapter: &'a str,
    /// Frames were timed by GPU timestamps (else wall time with a wait).
    pub timestamps: bool,
    /// Lines about specimens left out.
    pub notes: &'a [String],
    pub blinn: &'a [BlinnRow],
    /// File names of the charts, per specimen.
    pub charts: &'a [(String, String)],
}

/// The chart file of `specimen`.
pub fn chart_name(specimen: &str) -> String {
    format!("parallax-{}.png", specimen.to_lowercase())
}

fn label(row: &ParallaxRow) -> String {
    match (row.layers, row.level) {
        (Some(layers), _) => format!("{} {layers}", row.technique),
        (None, Some(level)) => format!("{} level {level}", row.technique),
        (None, None) => row.technique.to_owned(),
    }
}

/// How many layers `technique` needs on `specimen` at `angle`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayersNeeded {
    /// The fewest layers with an RMSE within [`WITHIN_RMSE`] of displacement.
    pub within_rmse: Option<u32>,
    /// The fewest layers within 1 % of the error at the most layers measured (where the
    /// technique has converged to what it cannot draw).
    pub within_converged: Option<u32>,
    /// The most layers measured and the RMSE there.
    pub most: Option<(u32, f64)>,
}

/// [`LayersNeeded`] from the rows.
pub fn layers_needed(rows: &[ParallaxRow], specimen: &str, angle: f32, technique: Parallax) -> LayersNeeded {
    let mut measured: Vec<(u32, f64)> = rows
        .iter()
        .filter(|r| r.specimen == specimen && r.angle_deg == angle && r.technique == <&str>::from(technique))
        .filter_map(|r| r.layers.map(|n| (n, r.error.rmse)))
        .collect();
    measured.sort_by_key(|m| m.0);
    let most = measured.last().copied();
    let first = |limit: f64| measured.iter().find(|m| m.1 <= limit).map(|m| m.0);
    LayersNeeded {
        within_rmse: first(WITHIN_RMSE),
        within_converged: most.and_then(|(_, rmse)| first(rmse * 1.01)),
        most,
    }
}

/// The angle the face-on floor is measured at.
pub const FACE_ON_DEG: f32 = 0.0;

/// The face-on floor of `specimen`: the smallest RMSE any parallax technique (off excluded)
/// reaches at [`FACE_ON_DEG`], with the same shading as at every other angle. Face-on a
/// search's shift is nearly 0 and the best one removes what perspective leaves, so what
/// remains is the shading difference between the displaced mesh and the normal-mapped plane
/// (exact against kernel normals, brick sides, mip levels) that no UV shift removes. `off`
/// is not the floor: the camera's rays reach 17° at the square's edge, a shift off does not
/// make. `None` where the study did not draw face-on.
pub fn face_on_floor(rows: &[ParallaxRow], specimen: &str) -> Option<f64> {
    let off = Parallax::default().name();
    rows.iter()
        .filter(|r| r.specimen == specimen && r.angle_deg == FACE_ON_DEG)
        .filter(|r| r.technique != DISPLACEMENT && r.technique != off)
        .map(|r| r.error.rmse)
        .min_by(f64::total_cmp)
}

/// The markdown section: the method, each specimen's tables and sentence, Blinn's sphere.
pub fn markdown(page: &ParallaxPage) -> String {
    let mut s = String::new();
    write_method(&mut s, page);
    let specimens: Vec<&str> = page.rows.iter().fold(vec![], |mut list, r| {
        if !list.contains(&r.specimen.as_str()) {
            list.push(&r.specimen);
        }
        list
    });
    for specimen in &specimens {
        let _ = writeln!(s, "### {specimen}\n");
        let converged = write_convergence(&mut s, page, specimen);
        write_technique_table(&mut s, page, specimen);
        if let Some((_, chart)) = page.charts.iter().find(|(name, _)| name == specimen).filter(|_| converged) {
            let angle = page.plan.convergence_angle_deg;
            let _ = writeln!(s, "![{specimen}: RMSE against frame time at {angle}°]({chart})\n");
        }
        write_layers_needed(&mut s, page, specimen);
    }
    write_blinn(&mut s, page.blinn);
    s
}

/// The heading, how the pictures are drawn and measured, and the page's notes.
fn write_method(s: &mut String, page: &ParallaxPage) {
    let plan = page.plan;
    let refining: Vec<&str> = Parallax::shifting().filter(|t| t.refines()).map(Parallax::name).collect();
    let refining = capitalized(&refining.join(" and "));
    let _ = writeln!(s, "## Parallax: image error against frame time\n");
    let _ = writeln!(
        s,
        "Every technique drawn at {}×{} pixels (4× MSAA where the adapter has it) on **{}**, against \
         displacement (the mesh tessellated on the CPU and displaced, its exact normals) at the level \
         where its picture stopped changing (each surface's test below). Error: RMSE of the linear \
         RGB channels, and the share of pixels with a channel off by more than {OFF_BY}/255, over the \
         picture (on the squares over the pixels whose view ray meets the surface within {} m of the \
         centre). Time: median of {} full-quality frame(s), {}. {} take 5 binary-search steps; \
         depth is each material's height range.\n",
        plan.size[0],
        plan.size[1],
        page.adapter,
        super::parallax::MEASURED_HALF_SIZE,
        plan.frames,
        if page.timestamps {
            "GPU time between timestamps written before and after the frame's passes"
        } else {
            "wall time, each submitted alone and waited for (the device has no timestamp queries inside encoders)"
        },
        refining,
    );
    for note in page.notes {
        let _ = writeln!(s, "- {note}");
    }
    if !page.notes.is_empty() {
        s.push('\n');
    }
}

/// Displacement's convergence table and whether its reference level converged.
fn write_convergence(s: &mut String, page: &ParallaxPage, specimen: &str) -> bool {
    let angle = page.plan.convergence_angle_deg;
    let _ = writeln!(s, "Displacement's convergence at {angle}° (RMSE against the reference level):\n");
    let _ = writeln!(s, "| level | RMSE | off > {OFF_BY}/255 | ms |\n|---|---|---|---|");
    let levels = page.rows.iter().filter(|r| r.specimen == specimen && r.technique == DISPLACEMENT);
    for r in levels.filter(|r| r.angle_deg == angle) {
        let level = r.level.unwrap_or(0);
        let (rmse, off) = (r.error.rmse, 100.0 * r.error.off_share);
        let _ = writeln!(s, "| {level} | {rmse:.4} | {off:.2} % | {:.1} |", r.frame_ms);
    }
    s.push('\n');
    let step = reference_step(page.rows, specimen, angle);
    let converged = step.is_some_and(|step| step.converged());
    match step {
        Some(step) => {
            let _ = writeln!(
                s,
                "Reference level {}: **{}** (level {} is {:.4} RMSE from it, {:.1} % of pixels off; the test: at \
                 most {REFERENCE_STEP_RMSE}).{}\n",
                step.level,
                if converged { "converged" } else { "not converged" },
                step.level - 1,
                step.below.rmse,
                100.0 * step.below.off_share,
                if converged { "" } else { " No chart is drawn against it." },
            );
        }
        None => {
            let _ = writeln!(
                s,
                "Reference: **convergence not measured** (no level below it drawn). No chart is drawn against it.\n"
            );
        }
    }
    converged
}

/// The face-on floor and the table of every technique at every angle, displacement last.
fn write_technique_table(s: &mut String, page: &ParallaxPage, specimen: &str) {
    let plan = page.plan;
    let rows: Vec<&ParallaxRow> = page.rows.iter().filter(|r| r.specimen == specimen).collect();
    let floor = face_on_floor(page.rows, specimen);
    if let Some(floor) = floor {
        let _ = writeln!(
            s,
            "Face-on floor: **{floor:.4}** RMSE (the best technique at {FACE_ON_DEG}°: the shading difference no UV \
             shift removes); each cell's (+…) is the part of its RMSE above it.\n"
        );
    }
    let above = |rmse: f64| floor.map_or(String::new(), |f| format!(" (+{:.4})", rmse - f));
    let angles = &plan.angles_deg;
    let _ = write!(s, "| technique |");
    for angle in angles {
        let _ = write!(s, " {angle}°: RMSE · off · ms |");
    }
    let _ = writeln!(s, "\n|---|{}", "---|".repeat(angles.len()));
    let mut labels: Vec<String> = vec![];
    for r in rows.iter().filter(|r| r.technique != DISPLACEMENT) {
        let l = label(r);
        if !labels.contains(&l) {
            labels.push(l);
        }
    }
    for l in &labels {
        let _ = write!(s, "| {l} |");
        for angle in angles {
            match rows.iter().find(|r| r.angle_deg == *angle && label(r) == *l) {
                Some(r) => {
                    let e = r.error;
                    let (off, ms) = (100.0 * e.off_share, r.frame_ms);
                    let _ = write!(s, " {:.4}{} · {off:.1} % · {ms:.1} |", e.rmse, above(e.rmse));
                }
                None => s.push_str(" – |"),
            }
        }
        s.push('\n');
    }
    let _ = write!(s, "| displacement (reference) |");
    for angle in angles {
        match rows.iter().find(|r| r.angle_deg == *angle && r.technique == DISPLACEMENT) {
            Some(r) => {
                let _ = write!(s, " level {} · {:.1} ms |", r.level.unwrap_or(0), r.frame_ms);
            }
            None => s.push_str(" – |"),
        }
    }
    s.push_str("\n\n");
}

/// The sentence on the layers [`Parallax::headline`] needs at the convergence angle.
fn write_layers_needed(s: &mut String, page: &ParallaxPage, specimen: &str) {
    let angle = page.plan.convergence_angle_deg;
    let technique = Parallax::headline();
    let needed = layers_needed(page.rows, specimen, angle, technique);
    let Some((most, rmse)) = needed.most else {
        return;
    };
    let name = capitalized(technique.name());
    match needed.within_rmse {
        Some(n) => {
            let _ = write!(
                s,
                "{name} comes within {WITHIN_RMSE} RMSE (1 %) of displacement at {angle}° with **{n} layers**"
            );
        }
        None => {
            let _ = write!(
                s,
                "{name} does not come within {WITHIN_RMSE} RMSE (1 %) of displacement at {angle}° with up to \
                 {most} layers (RMSE {rmse:.4} at {most})"
            );
        }
    }
    if let Some(n) = needed.within_converged {
        let _ = write!(s, "; it comes within 1 % of its error at {most} layers with **{n} layers**");
    }
    s.push_str(".\n\n");
}

/// `text` with its first letter upper-case.
fn capitalized(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or(String::new(), |first| first.to_uppercase().chain(chars).collect())
}

/// Blinn's approximation against the exact normal of a displaced sphere.
fn write_blinn(s: &mut String, blinn: &[BlinnRow]) {
    let _ = writeln!(s, "### Blinn's approximation on a sphere\n");
    let _ = writeln!(
        s,
        "A unit sphere displaced by `F = h · ½ (1 + sin 8φ sin 8θ)`; Blinn's 1978 normal (the `F · ∂n/∂u` \
         terms dropped) against the exact normal of the displaced sphere, over θ in 0.1π..0.9π (CPU):\n"
    );
    let _ = writeln!(s, "| h/R | mean tilt (°) | mean error (°) | max error (°) |\n|---|---|---|---|");
    for r in blinn {
        let _ = writeln!(
            s,
            "| {} | {:.3} | {:.5} | {:.5} |",
            r.h_over_r, r.mean_tilt_deg, r.mean_error_deg, r.max_error_deg
        );
    }
    s.push('\n');
}

/// CSV rows (header first): one per picture measured.
pub fn csv(rows: &[ParallaxRow]) -> String {
    let mut s =
        String::from("specimen,angle_deg,technique,layers,displacement_level,rmse_linear_rgb,share_off_5,frame_ms\n");
    for r in rows {
        let layers = r.layers.map_or(String::new(), |n| n.to_string());
        let level = r.level.map_or(String::new(), |n| n.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{layers},{level},{:.6},{:.6},{:.3}",
            r.specimen, r.angle_deg, r.technique, r.error.rmse, r.error.off_share, r.frame_ms
        );
    }
    s
}

/// Errors below this RMSE are drawn at it.
const RMSE_FLOOR: f64 = 1e-5;

/// The charts of every specimen whose reference converged at `angle` (in degrees; no curve
/// against one that has not, the page says so): their (specimen, file name) for the page and
/// their (file name, PNG bytes) to write.
pub fn charts(rows: &[ParallaxRow], angle: f32) -> Result<ChartFiles, ChartError> {
    let specimens: std::collections::BTreeSet<_> = rows.iter().map(|r| r.specimen.clone()).collect();
    let mut named = vec![];
    let mut files = vec![];
    for specimen in specimens {
        if !reference_step(rows, &specimen, angle).is_some_and(|step| step.converged()) {
            continue;
        }
        let bytes = chart(rows, &specimen, angle)?;
        let name = chart_name(&specimen);
        named.push((specimen, name.clone()));
        files.push((name, bytes));
    }
    Ok((named, files))
}

/// Charts as [`charts`] returns them: (specimen, file name) and (file name, PNG bytes).
pub type ChartFiles = (Vec<(String, String)>, Vec<(String, Vec<u8>)>);

/// The Pareto chart of `specimen` at `angle`: RMSE against frame time, a curve per technique
/// through its layer counts (displacement through its levels), a point for each technique
/// without layers, and the face-on floor ([`face_on_floor`]) as a line across.
pub fn chart(rows: &[ParallaxRow], specimen: &str, angle: f32) -> Result<Vec<u8>, ChartError> {
    // The reference against itself (error 0) has no place on a log scale.
    let at: Vec<&ParallaxRow> =
        rows.iter().filter(|r| r.specimen == specimen && r.angle_deg == angle && r.error.rmse > 0.0).collect();
    let mut techniques: Vec<&str> = Parallax::all().iter().map(|&t| t.name()).chain([DISPLACEMENT]).collect();
    techniques.retain(|t| at.iter().any(|r| r.technique == *t));
    let series: Vec<Series> = techniques
        .iter()
        .enumerate()
        .map(|(index, technique)| {
            let mut points: Vec<(u32, f64, f64)> = at
                .iter()
                .filter(|r| r.technique == *technique)
                .map(|r| (r.layers.or(r.level).unwrap_or(0), r.frame_ms.max(1e-3), r.error.rmse.max(RMSE_FLOOR)))
                .collect();
            points.sort_by_key(|p| p.0);
            Series {
                label: technique.to_string(),
                colour: COLOURS[index % COLOURS.len()],
                marker: if *technique == DISPLACEMENT { Marker::Triangle } else { Marker::Circle },
                points: points.into_iter().map(|(_, ms, e)| (ms, e)).collect(),
            }
        })
        .collect();
    let mut series = series;
    let times = || series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
    let (first, last) = times().fold((f64::MAX, f64::MIN), |(lo, hi), ms| (lo.min(ms), hi.max(ms)));
    if let Some(floor) = face_on_floor(rows, specimen).filter(|_| first <= last) {
        series.push(Series {
            label: format!("face-on floor {floor:.4}"),
            colour: RGBColor(128, 128, 128),
            marker: Marker::Line,
            points: vec![(first, floor.max(RMSE_FLOOR)), (last, floor.max(RMSE_FLOOR))],
        });
    }
    let title = format!("{specimen} at {angle}°: image RMSE vs frame time (a point per layer count / level)");
    png(&title, ["median frame time (ms)", "RMSE against displacement, linear RGB"], &series, XAxis::Log)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::parallax::ImageError;

    fn row(technique: &'static str, layers: u32, rmse: f64) -> ParallaxRow {
        ParallaxRow {
            specimen: "wall".into(),
            angle_deg: 70.0,
            technique,
            layers: Some(layers),
            level: None,
            error: ImageError { rmse, off_share: 0.0 },
            frame_ms: 1.0,
        }
    }

    #[test]
    fn layers_needed_finds_the_first_count_within_each_limit() {
        let rows = [
            row("occlusion", 16, 0.0164),
            row("occlusion", 4, 0.019),
            row("occlusion", 64, 0.0163),
            row("steep", 4, 0.001),
        ];
        let needed = layers_needed(&rows, "wall", 70.0, Parallax::Occlusion);
        assert_eq!(needed, LayersNeeded { within_rmse: None, within_converged: Some(16), most: Some((64, 0.0163)) });
        let close = [row("occlusion", 8, 0.02), row("occlusion", 32, 0.009)];
        assert_eq!(layers_needed(&close, "wall", 70.0, Parallax::Occlusion).within_rmse, Some(32));
        assert_eq!(layers_needed(&close, "torus", 70.0, Parallax::Occlusion).most, None);
    }
}
