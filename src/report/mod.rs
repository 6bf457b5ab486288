//! `bumpview report`: angular error against run time for every tangent method and
//! height kernel, from exact references, written as `report.md`, `report.csv` and two PNG
//! charts.
//!
//! [`surfaces`] makes the references, [`mod@measure`] the rows, `convergence` the fitted orders,
//! `markdown`, `csv` and `chart` the files; this module plans the run and writes atomically.

pub mod blinn;
mod chart;
pub mod compression_page;
pub mod compression_study;
pub mod convergence;
mod csv;
pub mod cube_map;
pub mod detail_page;
pub mod detail_study;
pub mod exact_hit;
pub mod gpu_time;
pub mod image_error;
mod markdown;
pub mod measure;
pub mod mip_page;
pub mod mip_specimen;
pub mod mip_study;
pub mod parallax;
pub mod parallax_page;
pub mod roundtrip;
pub mod spaces;
pub mod stiff;
pub mod surfaces;
pub mod timing;
mod uv_chart;
pub mod uv_error;
mod uv_page;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::height::{Border, Kernel};
use crate::names::Named;
use crate::tangent::TangentMethod;
use measure::{Row, Sample, kernel_rows, tangent_rows};
use surfaces::{Region, SineBumps, torus, uv_sphere};
use timing::Repeats;

/// File names inside the output directory.
pub const MARKDOWN: &str = "report.md";
pub const CSV: &str = "report.csv";
pub const TANGENT_CHART: &str = "tangents.png";
pub const KERNEL_CHART: &str = "kernels.png";
pub const PARALLAX_CSV: &str = "parallax.csv";
pub const UV_CSV: &str = "uv-error.csv";

/// The sphere (segments, rings) of the MikkTSpace sanity value.
pub const MIKKTSPACE_SANITY_SPHERE: (u32, u32) = (256, 128);

/// Failures of `bumpview report`.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    #[error("could not write {path}: {reason}")]
    Write { path: PathBuf, reason: String },
    #[error(transparent)]
    Chart(#[from] chart::ChartError),
}

/// What to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// UV spheres as (segments, rings).
    pub spheres: Vec<(u32, u32)>,
    /// Tori as (segments, sides).
    pub tori: Vec<(u32, u32)>,
    /// Sine-bump planes, float heights, wrapped border: texels per period.
    pub texels_per_period: Vec<u32>,
    /// Periods across each plane.
    pub periods: u32,
    /// Texels per period of the 8-bit, 16-bit and clamped-border planes.
    pub quantised_at: u32,
    /// The large plane every kernel is timed on, as (texels per period, periods): the
    /// throughput of whole images.
    pub large_plane: (u32, u32),
    /// The torus (segments, sides) MikkTSpace and meshoptimizer are timed on: 2 · segments ·
    /// sides triangles.
    pub large_torus: (u32, u32),
    /// The sine plane of the round trips, as (texels per period, periods).
    pub round_trip_plane: (u32, u32),
    pub repeats: Repeats,
    /// The reduced plan of `--quick`.
    pub quick: bool,
    /// The parallax family against displacement on the GPU.
    pub parallax: parallax::ParallaxPlan,
    /// Points per side of the wall's grid the UV error is measured over (at the parallax
    /// study's layer counts, [`uv_error::report_angles`]).
    pub uv_grid: u32,
    /// The mip filters against a supersampled reference on the GPU.
    pub mip: mip_study::MipPlan,
    /// The detail blends against the two exact answers (CPU), timed on the GPU.
    pub detail: detail_study::DetailPlan,
    /// Normal maps through each GPU texture format.
    pub compression: compression_study::CompressionPlan,
}

impl Plan {
    pub fn full() -> Plan {
        Plan {
            spheres: vec![(32, 16), (64, 32), (128, 64), (256, 128)],
            tori: vec![(48, 16), (96, 32), (192, 64), (384, 128)],
            texels_per_period: vec![8, 16, 32, 64],
            periods: 4,
            quantised_at: 32,
            large_plane: (64, 32),
            large_torus: (1000, 500),
            round_trip_plane: (32, 16),
            repeats: Repeats { runs: 21, budget: Duration::from_secs(2) },
            quick: false,
            parallax: parallax::ParallaxPlan::full(None),
            uv_grid: 64,
            mip: mip_study::MipPlan::full(),
            detail: detail_study::DetailPlan::full(),
            compression: compression_study::CompressionPlan::full(None),
        }
    }

    /// Fewer resolutions and runs: well under a minute even unoptimised (tests, CI).
    pub fn quick() -> Plan {
        Plan {
            spheres: vec![(16, 8), (32, 16), (64, 32)],
            tori: vec![(24, 8), (48, 16), (96, 32)],
            texels_per_period: vec![8, 16, 32],
            periods: 2,
            quantised_at: 32,
            large_plane: (32, 8),
            large_torus: (96, 32),
            round_trip_plane: (32, 2),
            repeats: Repeats { runs: 3, budget: Duration::from_millis(50) },
            quick: true,
            parallax: parallax::ParallaxPlan::quick(),
            uv_grid: 32,
            mip: mip_study::MipPlan::quick(),
            detail: detail_study::DetailPlan { phases: 8, azimuths: 4, ..detail_study::DetailPlan::full() },
            compression: compression_study::CompressionPlan::quick(),
        }
    }
}

/// Where the timings ran.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    pub cpus: usize,
    pub cpu_model: String,
    pub os: String,
    /// `release` or `debug`: timings of a debug build are not representative.
    pub profile: &'static str,
}

impl Machine {
    pub fn this() -> Machine {
        let cpu_model = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(str::trim)
                    .map(str::to_owned)
            })
            .unwrap_or_else(|| "model unknown".into());
        Machine {
            cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
            cpu_model,
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
            profile: if cfg!(debug_assertions) { "debug (unoptimised: timings not representative)" } else { "release" },
        }
    }
}

/// Directions the normalization cube maps are measured over (a tenth with `--quick`).
pub const CUBE_MAP_DIRECTIONS: usize = 400_000;

/// The surface name of the large torus's rows.
pub const LARGE_TORUS: &str = "large torus";
/// The surface name of the large plane's rows.
pub const LARGE_PLANE: &str = "large plane";

/// Every row of `plan`: tangent methods on spheres then tori, MikkTSpace and meshoptimizer on
/// the large torus, kernels on the planes and the large plane. `progress(done, total)` hears
/// of each case measured.
pub fn measure(plan: &Plan, progress: &mut dyn FnMut(usize, usize)) -> Vec<Row> {
    let mut rows = vec![];
    let methods: Vec<TangentMethod> =
        TangentMethod::all().iter().copied().filter(|&m| m != TangentMethod::Supplied).collect();
    let references = plan
        .spheres
        .iter()
        .map(|&(s, r)| ("sphere", s, format!("{s}x{r}"), uv_sphere(s, r)))
        .chain(plan.tori.iter().map(|&(s, r)| ("torus", s, format!("{s}x{r}"), torus(s, r))))
        .collect::<Vec<_>>();
    let fast_methods = [TangentMethod::MikkTSpace, TangentMethod::Meshopt];
    let planes_per_kernel = plan.texels_per_period.len() + 4;
    let total = methods.len() * references.len() + fast_methods.len() + Kernel::all().len() * planes_per_kernel;
    let mut done = 0;
    let mut step = |progress: &mut dyn FnMut(usize, usize)| {
        done += 1;
        progress(done, total);
    };
    for &method in &methods {
        for (surface, resolution, label, reference) in &references {
            let sample = Sample { surface, resolution: *resolution, resolution_label: label };
            rows.extend(tangent_rows(method, reference, sample, plan.repeats));
            step(progress);
        }
    }
    let (segments, sides) = plan.large_torus;
    let large_torus = torus(segments, sides);
    let label = format!("{segments}x{sides} ({} triangles)", large_torus.mesh.indices.len() / 3);
    for method in fast_methods {
        let sample = Sample { surface: LARGE_TORUS, resolution: segments, resolution_label: &label };
        // One run of MikkTSpace here takes seconds: the fastest of three is enough.
        let repeats = Repeats { runs: plan.repeats.runs.min(3), ..plan.repeats };
        rows.extend(
            tangent_rows(method, &large_torus, sample, repeats).into_iter().filter(|r| r.region == Region::All),
        );
        step(progress);
    }
    for &kernel in Kernel::all() {
        for &tpp in &plan.texels_per_period {
            let bumps = SineBumps::new(tpp, plan.periods);
            let label = format!("{tpp} texels/period");
            let sample = Sample { surface: "plane", resolution: tpp, resolution_label: &label };
            rows.extend(kernel_rows(kernel, &bumps, &bumps.field(), Border::Wrap, sample, plan.repeats));
            step(progress);
        }
        let bumps = SineBumps::new(plan.quantised_at, plan.periods);
        let label = format!("{} texels/period", plan.quantised_at);
        let float = bumps.field();
        let variants = [
            ("plane 8-bit", float.quantized(8), Border::Wrap),
            ("plane 16-bit", float.quantized(16), Border::Wrap),
            ("plane clamp", float, Border::Clamp),
        ];
        for (surface, field, border) in variants {
            let sample = Sample { surface, resolution: plan.quantised_at, resolution_label: &label };
            rows.extend(kernel_rows(kernel, &bumps, &field, border, sample, plan.repeats));
            step(progress);
        }
        let (tpp, periods) = plan.large_plane;
        let bumps = SineBumps::new(tpp, periods);
        let label = format!("{0}x{0} ({tpp} texels/period)", bumps.side());
        let sample = Sample { surface: LARGE_PLANE, resolution: tpp, resolution_label: &label };
        rows.extend(kernel_rows(kernel, &bumps, &bumps.field(), Border::Wrap, sample, plan.repeats));
        step(progress);
    }
    rows
}

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename, so
/// readers never see a half-written file ([`crate::atomic::write_bytes_atomically`]: the
/// temporary is created exclusively, and an existing `path` that is not a regular file is
/// refused).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), ReportError> {
    crate::atomic::write_bytes_atomically(path, bytes)
        .map_err(|e| ReportError::Write { path: path.to_owned(), reason: e.to_string() })
}

/// Measures `plan` and writes the report into `out` (created if missing), telling
/// `progress(done, total)` of each case measured. Fails before measuring when `out` cannot be
/// written. Returns the files written.
pub fn run(out: &Path, plan: &Plan, progress: &mut dyn FnMut(usize, usize)) -> Result<Vec<PathBuf>, ReportError> {
    let started = Instant::now();
    std::fs::create_dir_all(out).map_err(|e| ReportError::Write { path: out.to_owned(), reason: e.to_string() })?;
    write_atomically(&out.join(".write-test"), b"")?;
    let _ = std::fs::remove_file(out.join(".write-test"));
    let rows = measure(plan, progress);
    let (tpp, periods) = plan.round_trip_plane;
    let round_trips = roundtrip::round_trips(&SineBumps::new(tpp, periods), plan.repeats);
    let agreements: Vec<_> = plan
        .spheres
        .iter()
        .map(|&(s, r)| roundtrip::agreement(format!("sphere {s}x{r}"), &uv_sphere(s, r)))
        .chain(plan.tori.iter().map(|&(s, r)| roundtrip::agreement(format!("torus {s}x{r}"), &torus(s, r))))
        .collect();
    let orders = convergence::orders(&rows);
    let tangent_png = chart::tangent_chart(&rows).map_err(ReportError::Chart)?;
    let kernel_png = chart::kernel_chart(&rows).map_err(ReportError::Chart)?;
    let machine = Machine::this();
    let (segments, rings) = MIKKTSPACE_SANITY_SPHERE;
    let acos_f32 = plan.spheres.contains(&MIKKTSPACE_SANITY_SPHERE).then(|| {
        measure::acos_f32_means(TangentMethod::MikkTSpace, &uv_sphere(segments, rings), surfaces::Region::Interior)
    });
    let cube_maps = cube_map::cube_map_rows(if plan.quick { CUBE_MAP_DIRECTIONS / 10 } else { CUBE_MAP_DIRECTIONS });
    let page = markdown::Page {
        rows: &rows,
        orders: &orders,
        plan,
        machine: &machine,
        seconds: started.elapsed().as_secs_f64(),
        charts: [TANGENT_CHART, KERNEL_CHART],
        acos_f32: acos_f32.flatten(),
        stability: &stiff::stability_rows(),
        round_trips: &round_trips,
        agreements: &agreements,
        cube_maps: &cube_maps,
        lighting_spaces: &spaces::space_rows(&crate::scene::builtin::teaching_scene()),
    };
    let study = parallax_study(&plan.parallax, progress);
    let blinn = blinn::blinn_rows(if plan.quick { 64 } else { 256 });
    let angle = plan.parallax.convergence_angle_deg;
    let (charts, mut chart_files) = parallax_page::charts(&study.rows, angle)?;
    let parallax_section = parallax_page::markdown(&parallax_page::ParallaxPage {
        rows: &study.rows,
        plan: &plan.parallax,
        adapter: &study.adapter,
        timestamps: study.timestamps,
        notes: &study.notes,
        blinn: &blinn,
        charts: &charts,
    });
    let rock = study.specimens.iter().filter(|s| s.name == "Rock058");
    let reliefs = std::iter::once(uv_error::Relief::wall())
        .chain(rock.filter_map(|s| uv_error::Relief::of_specimen("Rock058", s)));
    let uv = uv_chart::study_and_charts(reliefs, &study.rows, &plan.parallax.layers, plan.uv_grid, angle)?;
    chart_files.extend(uv.files);
    let uv_section = uv_page::markdown(&uv.rows, &study.rows, plan.uv_grid, &uv.captions);
    let (mip, mip_adapter, mip_notes) = mip_filter_study(&plan.mip, progress);
    let mip_section = mip_page::markdown(&mip, &plan.mip, &mip_adapter, &mip_notes);
    let (detail_rows, detail_timing, detail_notes) = detail_page::study(&plan.detail);
    let detail_section = detail_page::markdown(&detail_rows, &plan.detail, &detail_timing, &detail_notes);
    let (compression, compression_notes) = compression_page::study(&plan.compression);
    let compression_section = compression_page::markdown(&compression, &compression_notes);
    let sections =
        [markdown::render(&page), parallax_section, uv_section, mip_section, detail_section, compression_section];
    let files = [
        (MARKDOWN.to_owned(), sections.join("\n").into_bytes()),
        (CSV.to_owned(), csv::render(&rows, &orders).into_bytes()),
        (PARALLAX_CSV.to_owned(), parallax_page::csv(&study.rows).into_bytes()),
        (UV_CSV.to_owned(), csv::uv_rows(&uv.rows, &study.rows).into_bytes()),
        (TANGENT_CHART.to_owned(), tangent_png),
        (KERNEL_CHART.to_owned(), kernel_png),
        (mip_page::CSV.to_owned(), mip_page::csv(&mip.rows).into_bytes()),
        (mip_page::CHART.to_owned(), mip_page::chart(&mip.rows)?),
        (detail_page::CSV.to_owned(), detail_page::csv(&detail_rows).into_bytes()),
        (detail_page::CHART.to_owned(), detail_page::chart(&detail_rows)?),
        (compression_page::CSV.to_owned(), compression_page::csv(&compression).into_bytes()),
    ]
    .into_iter()
    .chain(chart_files)
    .chain(compression_page::charts(&compression)?);
    let mut written = vec![];
    for (name, bytes) in files {
        let path = out.join(&name);
        write_atomically(&path, &bytes)?;
        written.push(path);
    }
    Ok(written)
}

/// What the GPU study measured, on which adapter, and what it left out.
struct ParallaxStudy {
    /// The specimens drawn (or meant to be, with no GPU).
    specimens: Vec<parallax::Specimen>,
    rows: Vec<parallax::ParallaxRow>,
    adapter: String,
    /// The device has timestamp queries inside encoders: frames are timed on the GPU.
    timestamps: bool,
    notes: Vec<String>,
}

/// Runs the parallax study of `plan` on a headless GPU; a missing GPU or a failed picture
/// becomes a note on the page, not a failed report.
fn parallax_study(plan: &parallax::ParallaxPlan, progress: &mut dyn FnMut(usize, usize)) -> ParallaxStudy {
    let (specimens, skipped) = parallax::specimens(plan);
    let mut notes: Vec<String> = skipped.into_iter().collect();
    let gpu = match crate::render::Gpu::headless() {
        Ok(gpu) => gpu,
        Err(e) => {
            notes.push(format!("no GPU: {e}"));
            return ParallaxStudy { specimens, rows: vec![], adapter: "no adapter".into(), timestamps: false, notes };
        }
    };
    let mut renderer = crate::render::Renderer::from_gpu(&gpu);
    let total: usize = specimens.iter().map(|s| parallax::case_count(plan, s.reference_level)).sum();
    let mut done = 0;
    let mut rows = vec![];
    for specimen in &specimens {
        let mut step = || {
            done += 1;
            progress(done, total);
        };
        match parallax::measure_specimen(&mut renderer, specimen, plan, &mut step) {
            Ok(measured) => rows.extend(measured),
            Err(e) => notes.push(format!("{} left out: {e}", specimen.name)),
        }
    }
    let timestamps = gpu.device.features().contains(gpu_time::FEATURES);
    ParallaxStudy { specimens, rows, adapter: gpu.adapter_name(), timestamps, notes }
}

/// Runs the mip-filter study of `plan` on a headless GPU: what it measured, the adapter's
/// name, and notes (a missing GPU or a failed picture becomes a note, not a failed report).
fn mip_filter_study(
    plan: &mip_study::MipPlan,
    progress: &mut dyn FnMut(usize, usize),
) -> (mip_study::MipStudy, String, Vec<String>) {
    let gpu = match crate::render::Gpu::headless() {
        Ok(gpu) => gpu,
        Err(e) => return (Default::default(), "no adapter".into(), vec![format!("no GPU: {e}")]),
    };
    let mut renderer = crate::render::Renderer::from_gpu(&gpu);
    let total = mip_study::case_count(plan);
    let mut done = 0;
    let mut step = || {
        done += 1;
        progress(done, total);
    };
    let mut notes = vec![];
    let study = mip_study::study(&mut renderer, plan, &mut step).unwrap_or_else(|e| {
        notes.push(format!("the mip-filter study stopped: {e}"));
        Default::default()
    });
    let drawn: Vec<&str> = study.rows.iter().map(|r| r.method).collect();
    for filter in <crate::texture::MipFilter as strum::VariantArray>::VARIANTS {
        if !study.rows.is_empty() && !drawn.contains(&filter.name()) {
            notes.push(format!(
                "{} left out: the renderer does not draw it yet (it falls back to another method)",
                filter.name()
            ));
        }
    }
    (study, gpu.adapter_name(), notes)
}
