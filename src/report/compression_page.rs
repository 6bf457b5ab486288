//! The compression study's part of the report ([`super::compression_study`]): a table per map
//! (angle to the source normal, lit picture's RMSE, bits per texel, encode time), CSV rows and
//! a chart per map of angle error against the file's bits per texel.

use std::fmt::Write;

use super::chart::{COLOURS, ChartError, ERROR_FLOOR_DEGREES, Marker, Series, XAxis, png};
use super::compression_study::{CompressionPlan, CompressionRow, maps, measure_map, stored_lengths};
use crate::names::Named;

/// The CSV's file name.
pub const CSV: &str = "compression.csv";

/// The study of `plan`: every map through every format, lit pictures on a headless GPU (a
/// missing GPU or a failed picture becomes a note, not a failed report); rows and notes.
pub fn study(plan: &CompressionPlan) -> (Vec<CompressionRow>, Vec<String>) {
    let (maps, mut notes) = maps(plan);
    let gpu = crate::render::Gpu::headless().map_err(|e| notes.push(format!("no GPU, no lit RMSE: {e}"))).ok();
    let mut renderer = gpu.as_ref().map(crate::render::Renderer::from_gpu);
    if let Some(gpu) = &gpu {
        let [w, h] = plan.picture;
        notes.push(format!("lit pictures: the built-in scene's opening view, {w}×{h}, on {}", gpu.adapter_name()));
    }
    for (name, map) in &maps {
        let [low, high, off] = stored_lengths(map);
        notes.push(format!(
            "{name}: {}×{} texels, stored vectors {low:.3}–{high:.3} long (mean |1 − length| {off:.4})",
            map.width, map.height
        ));
    }
    let mut rows = vec![];
    for (name, map) in &maps {
        match measure_map(name, map, renderer.as_mut(), plan.picture) {
            Ok(measured) => rows.extend(measured),
            Err(e) => notes.push(format!("{name} left out: a picture failed: {e}")),
        }
    }
    (rows, notes)
}

/// The markdown section; `notes` say what was left out and where the pictures were drawn.
pub fn markdown(rows: &[CompressionRow], notes: &[String]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Texture compression: what each format does to a normal map\n");
    let _ = writeln!(
        s,
        "Each map is written by `bake --format`'s encoders (intel_tex_2 for BCn, Binomial's Basis Universal \
         for UASTC and ETC1S, one thread) and read back by the loader's decoder; the decoded texels are read \
         as the renderer reads them (two-channel layouts rebuild z) and compared with the source texels read as \
         RGB. **Angle**: between the two normals, degrees (mean / p99 / max over texels). **Lit RMSE**: the \
         built-in scene with the map as every material's normal map, against the same picture with the \
         source map, 8-bit sRGB values (0–255). **GPU bits**: per texel once uploaded; **file bits**: per \
         texel in the file (header and Zstandard or BasisLZ included). **Encode ms**: one run, wall clock, in \
         this report's build. Two-channel layouts (BC5, RG8: rg; DXT5nm: ag) rebuild z for a vector of length \
         1, so a map whose stored vectors are not unit reads differently there even uncompressed; and the \
         renderer averages their mips as data rather than renormalising RGB, so their lit RMSE includes a \
         different mip chain (the RG8 row shows how much).\n"
    );
    for note in notes {
        let _ = writeln!(s, "- {note}");
    }
    let _ =
        writeln!(s, "\n| map | format | angle mean / p99 / max (°) | lit RMSE | GPU bits | file bits | encode ms |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for r in rows {
        match &r.outcome {
            Ok(m) => {
                let [mean, p99, max] = m.angle_deg;
                let lit = m.lit_rmse.map_or("—".into(), |v| format!("{v:.3}"));
                let _ = writeln!(
                    s,
                    "| {} | {} | {mean:.3} / {p99:.3} / {max:.3} | {lit} | {} | {:.2} | {:.1} |",
                    r.map,
                    r.format.name(),
                    m.gpu_bits,
                    m.file_bits,
                    m.encode_ms
                );
            }
            Err(why) => {
                let _ = writeln!(s, "| {} | {} | {why} | | | | |", r.map, r.format.name());
            }
        }
    }
    let mut charts: Vec<String> = rows.iter().map(|r| format!("`{}`", chart_name(&r.map))).collect();
    charts.dedup();
    let _ = writeln!(s, "\nEvery row: `{CSV}`; the charts: {}.\n", charts.join(", "));
    s
}

/// One line per measured row: map, format, the three angles, the RMSE (empty without a GPU),
/// the bits and the encode time.
pub fn csv(rows: &[CompressionRow]) -> String {
    let mut s = String::from("map,format,angle_mean,angle_p99,angle_max,lit_rmse,gpu_bits,file_bits,encode_ms\n");
    for r in rows {
        if let Ok(m) = &r.outcome {
            let [mean, p99, max] = m.angle_deg;
            let lit = m.lit_rmse.map_or(String::new(), |v| format!("{v:.6}"));
            let _ = writeln!(
                s,
                "{},{},{mean:.6},{p99:.6},{max:.6},{lit},{},{:.4},{:.3}",
                r.map,
                r.format.name(),
                m.gpu_bits,
                m.file_bits,
                m.encode_ms
            );
        }
    }
    s
}

/// The chart file of `map`.
pub fn chart_name(map: &str) -> String {
    format!("compression-{}.png", map.to_lowercase())
}

/// A chart per map ([`chart_name`]): each format's mean angle against the file's bits per
/// texel (both logarithmic), a dot per format.
pub fn charts(rows: &[CompressionRow]) -> Result<Vec<(String, Vec<u8>)>, ChartError> {
    let mut names: Vec<&str> = vec![];
    rows.iter().for_each(|r| {
        if !names.contains(&r.map.as_str()) {
            names.push(&r.map)
        }
    });
    let mut charts = vec![];
    for name in names {
        let mut series = vec![];
        for (index, row) in rows.iter().filter(|r| r.map == name).enumerate() {
            if let Ok(m) = &row.outcome {
                series.push(Series {
                    label: row.format.name().to_owned(),
                    colour: COLOURS[index % COLOURS.len()],
                    marker: Marker::Dots,
                    points: vec![(m.file_bits, m.angle_deg[0].max(ERROR_FLOOR_DEGREES))],
                });
            }
        }
        let title = format!("{name}: mean angle to the source normal against the file's bits per texel");
        let png =
            png(&title, ["bits per texel in the file", "mean angle to the source normal (°)"], &series, XAxis::Log)?;
        charts.push((chart_name(name), png));
    }
    Ok(charts)
}
