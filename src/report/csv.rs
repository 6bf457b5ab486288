//! `report.csv`: one row per (method, surface, resolution, region), angles in degrees,
//! times in seconds.

use super::convergence::Order;
use super::measure::{Row, Study, Vector};

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
