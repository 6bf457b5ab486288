//! `report.md`: the references and metrics, the sanity values, the convergence orders, the
//! full tables and links to the charts.

use std::fmt::Write;

use super::convergence::{NOISE_FLOOR_DEGREES, Order};
use super::cube_map::CubeMapRow;
use super::measure::{Row, Study, Vector};
use super::roundtrip::{Agreement, RoundTrip};
use super::spaces::SpaceRow;
use super::stiff::StabilityRow;
use super::surfaces::{POLE_DEGREES, Region};
use super::{LARGE_PLANE, LARGE_TORUS, MIKKTSPACE_SANITY_SPHERE, Machine, Plan};
use crate::height::derivative::Derivative;
use crate::names::Named;

/// Everything the page shows.
pub struct Page<'a> {
    pub rows: &'a [Row],
    pub orders: &'a [Order],
    pub plan: &'a Plan,
    pub machine: &'a Machine,
    /// Wall-clock seconds the measurements took.
    pub seconds: f64,
    /// File names of the tangent and kernel charts, beside report.md.
    pub charts: [&'a str; 2],
    /// The stiff cases: non-finite and invalid frames and the worst error per method.
    pub stability: &'a [StabilityRow],
    /// MikkTSpace's mean interior (T, B) errors on the sanity sphere as the library's
    /// a naive f32 `acos` measures them, when that sphere was measured.
    pub acos_f32: Option<(f32, f32)>,
    /// Heights → normals → heights on the sine plane.
    pub round_trips: &'a [RoundTrip],
    /// meshoptimizer's frames against MikkTSpace's per reference surface.
    pub agreements: &'a [Agreement],
    /// DOT3's normalization cube maps against exact normalisation, per face size.
    pub cube_maps: &'a [CubeMapRow],
    /// Tangent- and view-space lighting against world space per surface of the built-in scene.
    pub lighting_spaces: &'a [SpaceRow],
}

/// Degrees with three significant digits (scientific below 10⁻⁴).
fn degrees(v: f32) -> String {
    let v = v as f64;
    if v == 0.0 {
        "0".into()
    } else if v < 1e-4 {
        format!("{v:.1e}")
    } else {
        let decimals = (2 - v.log10().floor() as i32).clamp(0, 8) as usize;
        format!("{v:.decimals$}")
    }
}

fn duration(seconds: f64) -> String {
    match seconds {
        s if s >= 1.0 => format!("{s:.2} s"),
        s if s >= 1e-3 => format!("{:.2} ms", s * 1e3),
        s => format!("{:.1} µs", s * 1e6),
    }
}

fn throughput(row: &Row) -> String {
    let (value, unit) = (row.throughput(), row.study.unit());
    match value {
        v if v >= 1e9 => format!("{:.2} G {unit}/s", v / 1e9),
        v if v >= 1e6 => format!("{:.2} M {unit}/s", v / 1e6),
        v => format!("{:.1} k {unit}/s", v / 1e3),
    }
}

fn find<'a>(rows: &'a [Row], method: &str, surface: &str, resolution: u32, region: Region) -> Option<&'a Row> {
    rows.iter().find(|r| r.method == method && r.surface == surface && r.resolution == resolution && r.region == region)
}

fn intro(page: &Page, out: &mut String) {
    let plan = page.plan;
    let list = |v: &[(u32, u32)]| v.iter().map(|(a, b)| format!("{a}×{b}")).collect::<Vec<_>>().join(", ");
    let tpp: Vec<String> = plan.texels_per_period.iter().map(u32::to_string).collect();
    let _ = write!(
        out,
        "# bumpview report: error against run time\n\n\
         Every numerical method is compared with an exact reference. Angles are in degrees, computed as \
         `atan2(|a×b|, a·b)` in f64 (exact for tiny angles); mean, RMS and max are over the vertices or texels \
         of a region. Times are the median wall-clock time of one run over the whole surface \
         ({} runs at most, {:.1} s budget per case), throughput is triangles or texels per second.\n\n\
         **References**\n\n\
         - *UV sphere*, radius 1 m: `P = (sinθ cosφ, cosθ, −sinθ sinφ)`, `u = φ/2π`, `v = θ/π`, exact normals, \
         analytic frame `T = (−sinφ, 0, −cosφ)`, `w = +1` (B towards the north pole, up the image). Seam column \
         duplicated, one pole vertex per segment. Resolutions (segments×rings): {}. Regions: *seam* = the \
         u = 0/1 column, *pole* = the pole rows, the rings next to them and any vertex within {POLE_DEGREES}° of a pole, *interior* = the rest.\n\
         - *Torus* (the built-in one, R = 0.45 m, r = 0.18 m, texture 3× around the ring) with its analytic frame. \
         Resolutions (segments×sides): {}. Regions: *seam* = the duplicated first/last column and row, \
         *saddle* = inner half of the tube (cos t < 0), *interior* = outer half.\n\
         - *Sine-bump plane* `h = A·sin(2πx/λ)·sin(2πy/λ)`, `A = λ/2π` so the maximum slope |∇h| is 1, \
         {} periods square, samples (and exact normals) at texel centres `x = (i + ½)Δ`. Texels per period: {}; \
         8-bit, 16-bit and clamped-border variants at {} texels per period (*border* = within two texels of the edge).\n\n\
         Every tangent method is measured except **supplied**, which needs tangents from a mesh \
         file (the references have none). **per-face** is measured on the unwelded mesh, where it is exact per \
         triangle; **analytic** is the reference itself (error ≈ 0, its time is the cost of copying and \
         re-orthogonalising). Convergence orders are least-squares slopes of ln(mean error) against \
         ln(resolution), over resolutions whose mean error is above {NOISE_FLOOR_DEGREES}° (f32 rounding).\n\n",
        plan.repeats.runs,
        plan.repeats.budget.as_secs_f64(),
        list(&plan.spheres),
        list(&plan.tori),
        plan.periods,
        tpp.join(", "),
        plan.quantised_at,
    );
    let m = page.machine;
    let _ = writeln!(
        out,
        "**Machine**: {} logical CPUs ({}), {}; {} build. The measurements took {:.1} s{}.\n",
        m.cpus,
        m.cpu_model,
        m.os,
        m.profile,
        page.seconds,
        if plan.quick { " (--quick: fewer resolutions and runs)" } else { "" },
    );
}

fn sanity(page: &Page, out: &mut String) {
    out.push_str("## Sanity values\n\n| quantity | expected | measured |\n| --- | --- | --- |\n");
    let kernels = [("forward", 2.5), ("central", 0.16), ("central4", 0.001)];
    for (kernel, expected) in kernels {
        let measured = find(page.rows, kernel, "plane", 32, Region::All)
            .and_then(|r| r.error(Vector::Normal))
            .map_or("not measured".into(), |s| format!("{}°", degrees(s.mean)));
        let _ = writeln!(
            out,
            "| {kernel}, plane, 32 texels/period, slope 1, float, wrap: mean N error | ≈ {expected}° | {measured} |"
        );
    }
    let (segments, rings) = MIKKTSPACE_SANITY_SPHERE;
    let mikk = find(page.rows, "mikktspace", "sphere", segments, Region::Interior);
    let measured = mikk
        .and_then(|r| Some((r.error(Vector::Tangent)?, r.error(Vector::Bitangent)?)))
        .map_or("not measured (only in the full run)".into(), |(t, b)| {
            format!("{}° (T), {}° (B)", degrees(t.mean), degrees(b.mean))
        });
    let _ = writeln!(out, "| mikktspace, {segments}×{rings} UV sphere, interior: mean error | ≈ 0.002° | {measured} |");
    if let Some((t, b)) = page.acos_f32 {
        let _ = writeln!(
            out,
            "| the same, measured naively (acos of an f32 dot product) | ≈ 0.002° | {}° (T), {}° (B) |",
            degrees(t),
            degrees(b)
        );
    }
    out.push_str(
        "\n**Kernels.** Slope 1 means max |∇h| = A·k = 1, and every kernel's normal at a texel is compared with the \
         exact normal at the texel's own sample point (its centre, `x = (i + ½)Δ`). The forward difference \
         `h[x+1] − h[x]` is the exact derivative half a texel away (times sinc(kΔ/2)), so against the texel centre \
         it is first order; the centred kernels only lose gain (sinc(kΔ) for the 2-tap central difference), \
         second order; central4 is fourth order. Comparing at a point other than where the samples were taken \
         (e.g. samples at `x = i + ½` but the reference at `x = i`) would add half a texel of shift to every kernel.\n\n\
         **MikkTSpace on the UV sphere.** Its interior error is f32 rounding (≈ 1e-5°), not a truncation error: \
         both triangles of a quad take their u-direction along a chord of a latitude circle (horizontal, at the \
         segment's middle longitude); an interior vertex has three faces on each side, and the corner angles on \
         the two sides add up to the same total (the quads are mirror-symmetric trapezoids). So any angle-weighted \
         average (MikkTSpace, averaged-angle), and the uniform one, lands exactly on the analytic T. Area weights \
         differ between the two sides (the rings above and below have different widths), hence averaged-area's \
         second-order error. The expected ≈ 0.002° could not be reproduced as a truncation error; a naive measurement \
         taking `acos` of an f32 dot product cannot resolve angles below about 0.01° (a vertex reads 0 or \
         acos(1 − 2⁻²⁴) = 0.0198°), so an f32 measurement of this size is rounding, not method error.\n\n",
    );
}

fn orders(page: &Page, out: &mut String) {
    let cell = |o: Option<&Order>| match o {
        Some(Order { order: Some(p), points, .. }) => format!("{p:.2} ({points} pts)"),
        Some(_) => "— (at noise floor)".into(),
        None => "—".into(),
    };
    out.push_str("## Convergence orders (mean error ∝ resolution^−p)\n\n");
    out.push_str("| method | surface | region | p of T | p of B |\n| --- | --- | --- | --- | --- |\n");
    let lookup = |o: &Order, v: Vector| {
        page.orders
            .iter()
            .find(|x| x.method == o.method && x.surface == o.surface && x.region == o.region && x.vector == v)
    };
    for o in page.orders.iter().filter(|o| o.study == Study::Tangents && o.vector == Vector::Tangent) {
        let (t, b) = (cell(Some(o)), cell(lookup(o, Vector::Bitangent)));
        let _ = writeln!(out, "| {} | {} | {} | {t} | {b} |", o.method, o.surface, o.region.name());
    }
    out.push_str("\n| kernel | surface | p of N |\n| --- | --- | --- |\n");
    for o in page.orders.iter().filter(|o| o.study == Study::Kernels) {
        let _ = writeln!(out, "| {} | {} | {} |", o.method, o.surface, cell(Some(o)));
    }
    out.push('\n');
}

fn tables(page: &Page, out: &mut String) {
    let stats = |row: &Row, v: Vector| {
        row.error(v)
            .map_or("| | |".into(), |s| format!("{} | {} | {}", degrees(s.mean), degrees(s.rms), degrees(s.max)))
    };
    out.push_str("## Tangent methods\n\n");
    out.push_str(
        "| method | surface | resolution | region | T mean° | T RMS° | T max° | B mean° | B RMS° | B max° | median time | throughput |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for row in page.rows.iter().filter(|r| r.study == Study::Tangents) {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            row.method,
            row.surface,
            row.resolution_label,
            row.region.name(),
            stats(row, Vector::Tangent),
            stats(row, Vector::Bitangent),
            duration(row.seconds),
            throughput(row)
        );
    }
    out.push_str("\n## Height kernels\n\n");
    out.push_str(
        "| method | surface | resolution | region | mean° | RMS° | max° | median time | throughput |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for row in page.rows.iter().filter(|r| r.study == Study::Kernels) {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            row.method,
            row.surface,
            row.resolution_label,
            row.region.name(),
            stats(row, Vector::Normal),
            duration(row.seconds),
            throughput(row)
        );
    }
}

/// The whole page.
pub fn render(page: &Page) -> String {
    let mut out = String::new();
    intro(page, &mut out);
    sanity(page, &mut out);
    let [tangent_chart, kernel_chart] = page.charts;
    let _ = write!(
        out,
        "## Charts\n\nMean error (all vertices or texels) against median run time, log-log, one point per \
         resolution; errors below 1e-6° (the analytic frame) are drawn at 1e-6°.\n\n\
         ![tangent methods]({tangent_chart})\n\n![height kernels]({kernel_chart})\n\n"
    );
    speed(page, &mut out);
    round_trips(page, &mut out);
    cube_maps(page, &mut out);
    lighting_spaces(page, &mut out);
    orders(page, &mut out);
    stability(page, &mut out);
    tables(page, &mut out);
    out
}

/// The stability table: every generated tangent method on every stiff case.
fn stability(page: &Page, out: &mut String) {
    out.push_str(
        "## Stability (stiff and extreme cases)\n\n\
         Non-finite: frames with a NaN or infinite component. Invalid: frames not unit or not orthogonal to \
         their normal (beyond 1e-4). Max error: the largest angle of T or B to the exact frame, where one \
         exists (— where none does: degenerate UVs have no frame, a valid fallback is all that is asked); \
         measured away from a sphere's poles and seams, a zero-area triangle's corners and the triangles that \
         touch non-finite data.\n\n\
         | case | method | non-finite | invalid | max error |\n| --- | --- | --- | --- | --- |\n",
    );
    for row in page.stability {
        let error = row
            .max_error_deg
            .map_or("—".to_owned(), |e| if e.is_finite() { format!("{}°", degrees(e)) } else { "NaN".into() });
        let _ = writeln!(out, "| {} | {} | {} | {} | {error} |", row.case, row.method, row.non_finite, row.invalid);
    }
    out.push('\n');
}

/// Whole-image and large-mesh throughput: the rows the speed goals are about.
fn speed(page: &Page, out: &mut String) {
    out.push_str(
        "## Throughput on large inputs\n\n\
         The kernels on the large sine plane (rows in parallel on every CPU, into a buffer allocated once), and \
         MikkTSpace (bevy_mikktspace) against meshoptimizer's MikkTSpace-compatible generator (what \"auto\" uses \
         for meshes without tangents) on the large torus, with their mean error against the exact frame or \
         normal.\n\n| method | surface | resolution | mean error | median time | throughput |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    let large =
        page.rows.iter().filter(|r| (r.surface == LARGE_TORUS || r.surface == LARGE_PLANE) && r.region == Region::All);
    for row in large {
        let vector = if row.study == Study::Kernels { Vector::Normal } else { Vector::Tangent };
        let error = row.error(vector).map_or("".into(), |s| format!("{}°", degrees(s.mean)));
        let _ = writeln!(
            out,
            "| {} | {} | {} | {error} | {} | {} |",
            row.method,
            row.surface,
            row.resolution_label,
            duration(row.seconds),
            throughput(row)
        );
    }
    out.push_str(
        "\n**meshoptimizer against MikkTSpace** (the same frames, as meshoptimizer's option promises): angles \
         between the two methods' T and B at every vertex.\n\n\
         | surface | T mean° | T max° | B mean° | B max° |\n| --- | --- | --- | --- | --- |\n",
    );
    for a in page.agreements {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} |",
            a.surface,
            degrees(a.tangent.mean),
            degrees(a.tangent.max),
            degrees(a.bitangent.mean),
            degrees(a.bitangent.max)
        );
    }
    out.push('\n');
}

/// Heights → normals → heights (`bumpview bake --to-height`).
/// Tangent- and view-space lighting against world space, per surface.
fn lighting_spaces(page: &Page, out: &mut String) {
    out.push_str(
        "## Lighting spaces\n\n\
         The built-in scene from its default camera and light, the classic model, the brick map at strength 1, \
         MikkTSpace frames; three points per triangle, the normal map's nearest texel (the CPU chain, which the \
         GPU matches: tests/lighting_spaces.rs). Tangent space (as the ARB-era shaders light): light and view vectors through the \
         inverse of each triangle's frame (T = ∂P/∂u, B = −∂P/∂v, N the face normal). View space (as the GLSL practicum lights): the world vectors rotated by the \
         camera. Angle: between the light direction a space lights with and the exact one in the pixel's frame \
         (for the diffuse term, the angle between that space's shading normal and world space's). ΔRGB: the \
         largest channel difference from world space, 8-bit sRGB steps.\n\n\
         | surface | space | points | angle mean | angle max | ΔRGB mean | ΔRGB max |\n\
         | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for row in page.lighting_spaces {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.3}° | {:.3}° | {:.3} | {:.2} |",
            row.surface,
            row.space.name(),
            row.points,
            row.mean_angle_deg,
            row.max_angle_deg,
            row.mean_delta,
            row.max_delta
        );
    }
    out.push('\n');
}

fn round_trips(page: &Page, out: &mut String) {
    let Some(first) = page.round_trips.first() else { return };
    let side = (first.texels as f64).sqrt().round();
    let _ = write!(
        out,
        "## Round trip: height → normal → height\n\n\
         The sine plane ({side}×{side} texels, float heights, slope 1) made into central-difference normals, stored \
         as float, 16-bit or 8-bit, then integrated back by least squares in the Fourier domain (Frankot & \
         Chellappa 1988) with the central difference's own symbol or the continuous derivative `iω` they used. \
         Errors are in full height ranges (1 = the whole range), mean removed (slopes do not fix it). The kernel's \
         symbol undoes the kernel; `iω` leaves its gain `sinc(kΔ)` in the amplitude.\n\n\
         | normals | derivative | RMS | max | solve time | throughput |\n| --- | --- | --- | --- | --- | --- |\n"
    );
    for trip in page.round_trips {
        let derivative = match trip.derivative {
            Derivative::Spectral => "spectral (iω)".to_owned(),
            Derivative::Kernel(k) => format!("{} (its symbol)", k.name()),
        };
        let _ = writeln!(
            out,
            "| {} | {derivative} | {:.2e} | {:.2e} | {} | {:.1} M texels/s |",
            trip.normals,
            trip.rms,
            trip.max,
            duration(trip.seconds),
            trip.texels as f64 / trip.seconds.max(1e-12) / 1e6
        );
    }
    out.push('\n');
}

/// The normalization cube maps: error against exact normalisation per face size, and whether
/// the tutorial's "32×32 is enough for 8-bit colour" holds, taken as: `N·L` off by less than
/// one step of 1/255 everywhere.
fn cube_maps(page: &Page, out: &mut String) {
    let Some(first) = page.cube_maps.first() else { return };
    let directions = if page.plan.quick { super::CUBE_MAP_DIRECTIONS / 10 } else { super::CUBE_MAP_DIRECTIONS };
    let _ = write!(
        out,
        "## Normalization cube map (DOT3)\n\n\
         Directions evenly over the sphere ({directions}, a Fibonacci lattice) looked up in the cube map as the \
         shader does (bilinear within a face, clamped at its edges, 8-bit texels, not re-normalised), against \
         exact normalisation. `N·L` can change by at most `|L_cube − L̂|` (N along the difference), given in \
         steps of 1/255. Away from edges: where the lookup has four texels of its face (hardware with seamless \
         cube filtering blends the next face in within half a texel of an edge instead of clamping).\n\n\
         | face size | mean angle | max angle | max length error | N·L error, 99.9% | N·L error, max | away from edges, max |\n\
         | --- | --- | --- | --- | --- | --- | --- |\n"
    );
    for row in page.cube_maps {
        let _ = writeln!(
            out,
            "| {0}×{0} | {1:.3}° | {2:.3}° | {3:.4} | {4:.2} steps | {5:.2} steps | {6:.2} steps |",
            row.size,
            row.mean_deg,
            row.max_deg,
            row.max_length_error,
            row.p999_steps,
            row.max_steps,
            row.interior_max_steps
        );
    }
    let thirty_two = page.cube_maps.iter().find(|r| r.size == 32).unwrap_or(first);
    let claim = if thirty_two.max_steps < 1.0 { "holds" } else { "does not hold" };
    let _ = writeln!(
        out,
        "\nThe tutorial's \"32×32 is enough for 8-bit colour\" (N·L off by less than one step everywhere) {claim}: \
         at 32×32 N·L is off by up to {:.2} steps, {:.2} away from the faces' edges, where the texels' own 8 bits \
         set the floor that no face size removes.\n",
        thirty_two.max_steps, thirty_two.interior_max_steps
    );
}
