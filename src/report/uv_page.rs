//! The UV-error study's part of the report ([`super::uv_error`]): one markdown table of every
//! technique × layers × angle on the wall, beside the GPU frame time the image study measured
//! for the same case (where it drew that angle).

use std::fmt::Write;

use super::parallax::ParallaxRow;
use super::uv_error::{BRICK_ABOVE, MORTAR_BELOW, UvError};

/// The section: `rows` over a `grid × grid` grid of the wall, `gpu` the image study's rows.
pub fn markdown(rows: &[UvError], gpu: &[ParallaxRow], grid: u32) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Parallax: texture-space error against the exact intersection\n");
    let _ = writeln!(
        s,
        "Per surface point of the wall's bricks ({grid}×{grid} points of one tile, parallel view rays \
         at each angle about +Y), the distance in height-map texels between the UV a technique reads \
         (the chain's march, the probe's and the GPU's) and the UV of the view ray's exact first \
         intersection with the height field (a fine march then bisection to 1e-6 texel, heights \
         bilinear from level 0 as the GPU's sampler reads them). *Wrong region*: the share of points \
         whose UV lies across a brick/mortar boundary from the exact hit's (the straight UV path between \
         them reads both a brick face, height ≥ {BRICK_ABOVE}, and mortar, ≤ {MORTAR_BELOW}). \
         GPU ms: the image study's median frame time of the same case at that angle (— where it did \
         not draw the angle). No shading enters these numbers.\n"
    );
    let _ = writeln!(s, "| technique | layers | angle | mean (texels) | p95 | max | wrong region | GPU ms |");
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let name: &'static str = r.technique.into();
        let ms = gpu
            .iter()
            .find(|g| g.specimen == "wall" && g.technique == name && g.layers == r.layers && g.angle_deg == r.angle_deg)
            .map_or("—".to_owned(), |g| format!("{:.3}", g.frame_ms));
        let _ = writeln!(
            s,
            "| {name} | {} | {}° | {:.3} | {:.3} | {:.3} | {:.1} % | {ms} |",
            r.layers.map_or("—".to_owned(), |n| n.to_string()),
            r.angle_deg,
            r.mean,
            r.p95,
            r.max,
            100.0 * r.wrong_region,
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Parallax;
    use crate::report::parallax::ImageError;

    /// A row's numbers and the GPU time of the same case at the same angle; none elsewhere.
    #[test]
    fn each_row_sits_beside_its_cases_frame_time() {
        let uv = |angle_deg| UvError {
            technique: Parallax::Relief,
            layers: Some(32),
            angle_deg,
            mean: 0.0126,
            p95: 0.5,
            max: 2.0,
            wrong_region: 0.25,
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
        let page = markdown(&[uv(70.0), uv(75.0)], &[gpu], 8);
        let name: &str = Parallax::Relief.into();
        assert!(page.contains(&format!("| {name} | 32 | 70° | 0.013 | 0.500 | 2.000 | 25.0 % | 1.250 |")), "{page}");
        assert!(page.contains(&format!("| {name} | 32 | 75° | 0.013 | 0.500 | 2.000 | 25.0 % | — |")), "{page}");
    }
}
