//! `report.csv`: one row per (method, surface, resolution, region), angles in degrees,
//! times in seconds; `uv-error.csv`: one row per UV-error case.

use std::fmt::Write;

use super::convergence::Order;
use super::measure::{Row, Study, Vector};
use super::parallax::ParallaxRow;
use super::uv_error::UvError;
use super::uv_page::gpu_ms;

const HEADER: &str = "study,method,surface,resolution,resolution_label,region,count,\
t_mean_deg,t_rms_deg,t_max_deg,t_order,b_mean_deg,b_rms_deg,b_max_deg,b_order,\
n_mean_deg,n_rms_deg,n_max_deg,n_order,median_time_s,throughput_per_s,throughput_unit";

/// The CSV text: a header line, then one line per row; cells that do not apply are empty.
pub fn render(rows: &[Row], orders: &[Order]) -> String {
    let mut text = format!("{HEADER}\n");
    for row in rows {
        let study = match row.study {
            Study::Tangents => "tangents",
            Study::Kernels => "kernels",
        };
        let count = row.errors.first().map_or(0, |(_, s)| s.count);
        let mut cells = vec![
            study.to_owned(),
            row.method.to_owned(),
            row.surface.clone(),
            row.resolution.to_string(),
            row.resolution_label.clone(),
            row.region.name().to_owned(),
            count.to_string(),
        ];
        for vector in [Vector::Tangent, Vector::Bitangent, Vector::Normal] {
            let order = orders
                .iter()
                .find(|o| {
                    o.method == row.method && o.surface == row.surface && o.region == row.region && o.vector == vector
                })
                .and_then(|o| o.order);
            match row.error(vector) {
                Some(s) => cells.extend([s.mean, s.rms, s.max].map(|v| format!("{v:e}"))),
                None => cells.extend([""; 3].map(String::from)),
            }
            cells.push(order.map_or(String::new(), |p| format!("{p:.3}")));
        }
        cells.extend([format!("{:e}", row.seconds), format!("{:e}", row.throughput()), row.study.unit().to_owned()]);
        text += &cells.join(",");
        text.push('\n');
    }
    text
}

/// The UV-error study's CSV text: a header line, then one line per row (texels; the share
/// 0..1; the image study's GPU ms of the same case). Empty cells: no layers, no bricks, no GPU
/// time at that angle.
pub fn uv_rows(rows: &[UvError], gpu: &[ParallaxRow]) -> String {
    let mut text = String::from(
        "specimen,technique,layers,angle_deg,mean_texels,p95_texels,max_texels,wrong_brick_share,gpu_ms\n",
    );
    for r in rows {
        let name: &str = r.technique.into();
        let layers = r.layers.map_or(String::new(), |n| n.to_string());
        let wrong = r.wrong_brick.map_or(String::new(), |w| format!("{w:.6}"));
        let ms = gpu_ms(r, gpu).map_or(String::new(), |ms| format!("{ms:.3}"));
        let _ = writeln!(
            text,
            "{},{name},{layers},{},{:.6},{:.6},{:.6},{wrong},{ms}",
            r.specimen, r.angle_deg, r.mean, r.p95, r.max
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Parallax;

    #[test]
    fn a_uv_row_leaves_empty_what_it_lacks() {
        let row = UvError {
            specimen: "Rock058",
            technique: Parallax::Offset,
            layers: None,
            angle_deg: 45.0,
            mean: 0.25,
            p95: 0.5,
            max: 1.0,
            wrong_brick: None,
        };
        let text = uv_rows(&[row], &[]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2);
        assert_eq!(lines[0].split(',').count(), lines[1].split(',').count());
        assert_eq!(lines[1], "Rock058,offset,,45,0.250000,0.500000,1.000000,,");
    }
}
