//! The UV-error study's charts ([`super::uv_error`]): mean UV error against the image study's
//! GPU frame time at one angle with the Pareto front marked, and mean UV error against the view
//! angle.

use plotters::style::{BLACK, RGBColor};

use super::chart::{COLOURS, ChartError, Marker, Series, XAxis, png};
use super::parallax::ParallaxRow;
use super::uv_error::{self, Relief, UvError};
use super::uv_page::gpu_ms;
use crate::frame::Parallax;

/// Mean errors below this many texels (0 face-on) are drawn at it.
pub const TEXEL_FLOOR: f64 = 1e-3;

/// What [`study_and_charts`] made: the rows, the charts as (caption, file name) for the page
/// and as (file name, PNG bytes) to write.
pub struct UvStudy {
    pub rows: Vec<UvError>,
    pub captions: Vec<(String, String)>,
    pub files: Vec<(String, Vec<u8>)>,
}

/// The UV-error study over `reliefs` at [`uv_error::report_angles`] with the study's layer
/// counts on an `n`×`n` grid of rays: its rows, its charts as (caption, file name) for the page,
/// and their (file name, PNG bytes) to write. `angle` (degrees) is the view the chart of mean
/// error against the GPU's milliseconds is drawn at.
pub fn study_and_charts(
    reliefs: impl Iterator<Item = Relief>,
    gpu: &[ParallaxRow],
    layers: &[u32],
    n: u32,
    angle: f32,
) -> Result<UvStudy, ChartError> {
    let mut rows = vec![];
    let mut captions = vec![];
    let mut files = vec![];
    for relief in reliefs {
        rows.extend(uv_error::study(&relief, &uv_error::report_angles(), layers, n));
        if let Some(bytes) = ms_chart(&rows, gpu, relief.name, angle) {
            let name = ms_chart_name(relief.name, angle);
            let caption = format!("{}: mean UV error against GPU ms at {angle}°, the Pareto front marked", relief.name);
            captions.push((caption, name.clone()));
            files.push((name, bytes?));
        }
        let name = angle_chart_name(relief.name);
        captions.push((format!("{}: mean UV error against the view angle", relief.name), name.clone()));
        files.push((name, angle_chart(&rows, relief.name, layers)?));
    }
    Ok(UvStudy { rows, captions, files })
}

/// The file of [`ms_chart`] for `specimen` at `angle_deg`.
pub fn ms_chart_name(specimen: &str, angle_deg: f32) -> String {
    format!("uv-ms-{}-{angle_deg}.png", specimen.to_lowercase())
}

/// The file of [`angle_chart`] for `specimen`.
pub fn angle_chart_name(specimen: &str) -> String {
    format!("uv-angle-{}.png", specimen.to_lowercase())
}

/// The points of the Pareto front of `(ms, error)` points: those no other point beats in both
/// (no faster point is as accurate), fastest first.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = vec![];
    for p in sorted {
        if front.last().is_none_or(|last| p.1 < last.1) {
            front.push(p);
        }
    }
    front
}

/// Mean UV error against GPU ms on `specimen` at `angle_deg`: a curve per technique through its
/// layer counts, a point for each technique without layers, and the Pareto front over them
/// all. `None` where no case has a GPU time at that angle.
pub fn ms_chart(
    rows: &[UvError],
    gpu: &[ParallaxRow],
    specimen: &str,
    angle_deg: f32,
) -> Option<Result<Vec<u8>, ChartError>> {
    let mut series = vec![];
    for (index, technique) in Parallax::shifting().enumerate() {
        let mut points: Vec<(u32, f64, f64)> = rows
            .iter()
            .filter(|r| r.specimen == specimen && r.technique == technique && r.angle_deg == angle_deg)
            .filter_map(|r| gpu_ms(r, gpu).map(|ms| (r.layers.unwrap_or(0), ms.max(1e-3), r.mean.max(TEXEL_FLOOR))))
            .collect();
        points.sort_by_key(|p| p.0);
        if !points.is_empty() {
            let name: &str = technique.into();
            series.push(Series {
                label: name.to_owned(),
                colour: COLOURS[index % COLOURS.len()],
                marker: Marker::Circle,
                points: points.into_iter().map(|(_, ms, e)| (ms, e)).collect(),
            });
        }
    }
    if series.is_empty() {
        return None;
    }
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.points.iter().copied()).collect();
    series.push(Series {
        label: "Pareto front".into(),
        colour: BLACK,
        marker: Marker::Line,
        points: pareto_front(&all),
    });
    let title = format!("{specimen} at {angle_deg}°: mean UV error vs GPU frame time (a point per layer count)");
    Some(png(
        &title,
        ["median GPU frame time (ms)", "mean UV error against the exact hit (texels)"],
        &series,
        XAxis::Log,
    ))
}

/// Mean UV error against the view angle on `specimen`: offset and offset-limited, and each
/// search at the fewest (triangles) and the most (circles) of `layers`.
pub fn angle_chart(rows: &[UvError], specimen: &str, layers: &[u32]) -> Result<Vec<u8>, ChartError> {
    let counts: Vec<Option<u32>> = match (layers.iter().min(), layers.iter().max()) {
        (Some(&few), Some(&most)) if few < most => vec![Some(few), Some(most)],
        (Some(&n), _) => vec![Some(n)],
        _ => vec![],
    };
    let mut series = vec![];
    for (index, technique) in Parallax::shifting().enumerate() {
        let searches = rows.iter().any(|r| r.technique == technique && r.layers.is_some());
        for (k, &count) in if searches { counts.as_slice() } else { &[None] }.iter().enumerate() {
            let mut points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.specimen == specimen && r.technique == technique && r.layers == count)
                .map(|r| (f64::from(r.angle_deg), r.mean.max(TEXEL_FLOOR)))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let name: &str = technique.into();
            let label = count.map_or(name.to_owned(), |n| format!("{name} {n}"));
            let marker = if counts.len() > 1 && k == 0 && searches { Marker::Triangle } else { Marker::Circle };
            let colour: RGBColor = COLOURS[index % COLOURS.len()];
            if !points.is_empty() {
                series.push(Series { label, colour, marker, points });
            }
        }
    }
    let title = format!("{specimen}: mean UV error vs view angle (0 drawn at {TEXEL_FLOOR})");
    png(
        &title,
        ["view angle from the normal (°)", "mean UV error against the exact hit (texels)"],
        &series,
        XAxis::Linear,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pareto_front_keeps_each_point_no_faster_one_beats() {
        let points = [(3.0, 0.5), (1.0, 2.0), (2.0, 3.0), (2.5, 1.0), (4.0, 0.5), (5.0, 0.1)];
        assert_eq!(pareto_front(&points), vec![(1.0, 2.0), (2.5, 1.0), (3.0, 0.5), (5.0, 0.1)]);
        assert_eq!(pareto_front(&[]), vec![]);
    }
}
