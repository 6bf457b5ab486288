//! The UV-error study's part of the report ([`super::uv_error`]): one markdown table of every
//! specimen × technique × layers × angle, beside the GPU frame time the image study measured
//! for the same case (where it drew that angle), the layers each search needs for a mean
//! under [`UNDER_TEXELS`], and the charts' links.

use std::fmt::Write;

use super::parallax::ParallaxRow;
use super::uv_error::{BRICK_ABOVE, MORTAR_BELOW, UvError};
use crate::frame::Parallax;

/// The mean UV error (texels) the layer table asks each search to come under.
pub const UNDER_TEXELS: f64 = 0.5;

/// The image study's median frame time of `r`'s case (same specimen, technique, layers, angle).
pub fn gpu_ms(r: &UvError, gpu: &[ParallaxRow]) -> Option<f64> {
    let name: &str = r.technique.into();
    gpu.iter()
        .find(|g| g.specimen == r.specimen && g.technique == name && g.layers == r.layers && g.angle_deg == r.angle_deg)
        .map(|g| g.frame_ms)
}

/// The fewest layers at which `technique`'s mean UV error on `specimen` at `angle_deg` is under
/// [`UNDER_TEXELS`], with that row; `None` if no layer count measured gets there.
pub fn layers_for<'a>(rows: &'a [UvError], specimen: &str, technique: Parallax, angle_deg: f32) -> Option<&'a UvError> {
    rows.iter()
        .filter(|r| r.specimen == specimen && r.technique == technique && r.angle_deg == angle_deg)
        .filter(|r| r.mean < UNDER_TEXELS)
        .min_by_key(|r| r.layers.unwrap_or(0))
}

/// The section: `rows` over a `grid × grid` grid of each relief, `gpu` the image study's rows,
/// `charts` the chart files to link (alt text, file name).
pub fn markdown(rows: &[UvError], gpu: &[ParallaxRow], grid: u32, charts: &[(String, String)]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Parallax: texture-space error against the exact intersection\n");
    let _ = writeln!(
        s,
        "Per surface point of a relief ({grid}×{grid} points of one tile, parallel view rays \
         at each angle about +Y), the distance in height-map texels between the UV a technique reads \
         (the chain's march, the probe's and the GPU's) and the UV of the view ray's exact first \
         intersection with the height field (a fine march then bisection to 1e-6 texel, heights \
         bilinear from level 0 as the GPU's sampler reads them). *Wrong region*: the share of points \
         whose UV lies on the wrong brick: on another brick than the exact hit's, or in a joint where the hit \
         is on a brick or the reverse (the straight UV path between them reads both a brick face, height ≥ \
         {BRICK_ABOVE}, and mortar, ≤ {MORTAR_BELOW}; — on a relief without bricks). \
         GPU ms: the image study's median frame time of the same case at that angle (— where it did \
         not draw the angle). No shading enters these numbers. The torus carries the wall's bricks at \
         the wall's depth and tile, so its tangent-plane error is the wall's (what differs on the torus, its \
         curvature, no technique and not this measure models); it is not repeated.\n"
    );
    for (alt, file) in charts {
        let _ = writeln!(s, "![{alt}]({file})\n");
    }
    let specimens: Vec<&str> = rows.iter().fold(vec![], |mut list, r| {
        if !list.contains(&r.specimen) {
            list.push(r.specimen);
        }
        list
    });
    let angles: Vec<f32> = [45.0, 70.0, 80.0].into_iter().filter(|a| rows.iter().any(|r| r.angle_deg == *a)).collect();
    if !angles.is_empty() {
        let _ = writeln!(s, "Layers for a mean under {UNDER_TEXELS} texel (the image study's GPU ms of that case):\n");
        let _ = write!(s, "| specimen | technique |");
        for angle in &angles {
            let _ = write!(s, " {angle}° |");
        }
        let _ = writeln!(s, "\n|---|---|{}", "---|".repeat(angles.len()));
        for specimen in &specimens {
            for technique in Parallax::shifting() {
                let name: &str = technique.into();
                let _ = write!(s, "| {specimen} | {name} |");
                for &angle in &angles {
                    let cell = match layers_for(rows, specimen, technique, angle) {
                        None => "never".to_owned(),
                        Some(r) => {
                            let layers = r.layers.map_or("no search".to_owned(), |n| format!("{n}"));
                            let ms = gpu_ms(r, gpu).map_or(String::new(), |ms| format!(" · {ms:.1} ms"));
                            format!("{layers} ({:.3}){ms}", r.mean)
                        }
                    };
                    let _ = write!(s, " {cell} |");
                }
                s.push('\n');
            }
        }
        s.push('\n');
    }
    let _ = writeln!(s, "| specimen | technique | layers | angle | mean (texels) | p95 | max | wrong brick | GPU ms |");
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let name: &'static str = r.technique.into();
        let ms = gpu_ms(r, gpu).map_or("—".to_owned(), |ms| format!("{ms:.3}"));
        let _ = writeln!(
            s,
            "| {} | {name} | {} | {}° | {:.3} | {:.3} | {:.3} | {} | {ms} |",
            r.specimen,
            r.layers.map_or("—".to_owned(), |n| n.to_string()),
            r.angle_deg,
            r.mean,
            r.p95,
            r.max,
            r.wrong_brick.map_or("—".to_owned(), |w| format!("{:.1} %", 100.0 * w)),
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::parallax::ImageError;

    /// A row's numbers and the GPU time of the same case at the same angle; none elsewhere.
    #[test]
    fn each_row_sits_beside_its_cases_frame_time() {
        let uv = |angle_deg| UvError {
            specimen: "wall",
            technique: Parallax::Relief,
            layers: Some(32),
            angle_deg,
            mean: 0.0126,
            p95: 0.5,
            max: 2.0,
            wrong_brick: Some(0.25),
        };
        let gpu = ParallaxRow {
            specimen: "wall".into(),
            angle_deg: 70.0,
            technique: Parallax::Relief.into(),
            layers: Some(32),
            level: None,
            error: ImageError { rmse: 0.1, off_share: 0.1 },
            frame_ms: 1.25,
        };
        let page = markdown(&[uv(70.0), uv(75.0)], &[gpu], 8, &[]);
        let name: &str = Parallax::Relief.into();
        assert!(
            page.contains(&format!("| wall | {name} | 32 | 70° | 0.013 | 0.500 | 2.000 | 25.0 % | 1.250 |")),
            "{page}"
        );
        assert!(page.contains(&format!("| wall | {name} | 32 | 75° | 0.013 | 0.500 | 2.000 | 25.0 % | — |")), "{page}");
        // The layer table: relief gets under half a texel with 32 layers at 70°, at 1.25 ms.
        assert!(page.contains(&format!("| wall | {name} | 32 (0.013) · 1.2 ms |")), "{page}");
    }
}
