//! The `bumpview` command: the viewer (default) and `render`, a headless picture.

#[cfg(feature = "ui")]
mod app;
mod cli;

use std::path::PathBuf;
use std::process::ExitCode;

use bumpview::frame::BumpSource;
use bumpview::frame::ViewMode;
use bumpview::height::{Border, Kernel};
use bumpview::names::{Named, parse_or_auto};
use bumpview::render::capture::{
    CaptureOptions, MAX_SUPERSAMPLE, render_capture, render_capture_split, write_png_atomically,
};
use bumpview::render::export::{TileGrid, caption, render_grid};
use bumpview::render::{Background, Gpu, Renderer};
use bumpview::scene::{GreenAxis, MaterialOverrides, Scene, ShadingModel};
use bumpview::state::preset::{CapturePreset, Preset, PresetFiles};
use bumpview::state::{SplitDifference, ViewerState};
use bumpview::tangent::TangentMethod;
use clap::{Parser, Subcommand};
use cli::args;
use cli::inputs::InputArgs;
use glam::Vec3;

#[derive(Parser)]
#[command(name = "bumpview", version, about = "A viewer and teaching tool for bump and normal mapping")]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Viewer: close after this many frames have been presented (for tests and CI).
    #[arg(long, value_name = "FRAMES")]
    exit_after: Option<u64>,
    /// Viewer: with --exit-after, save a screenshot of the whole window (UI included) here first.
    #[arg(long, value_name = "PATH", requires = "exit_after")]
    capture_window: Option<PathBuf>,
    /// Viewer: start from this preset (files and flags given as well override it). Without
    /// it, files or flags, the viewer restores the state it had when it last closed.
    #[arg(long, value_name = "FILE")]
    preset: Option<PathBuf>,
    #[command(flatten)]
    methods: MethodArgs,
    #[command(flatten)]
    inputs: InputArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Draw the built-in scene or a mesh file offscreen (no window, no display) and write a PNG.
    Render(Box<RenderArgs>),
    /// Measure error against run time of every tangent method and height kernel and write
    /// report.md, report.csv and PNG charts.
    Report(ReportArgs),
    /// Check mesh files for what breaks bump mapping (degenerate or mirrored UVs, seams, bad
    /// tangents, normal-map sanity and green convention). Exit 0 clean, 1 warnings, 2 errors.
    Check {
        /// glTF (.gltf, .glb) or OBJ files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
}

#[derive(clap::Args)]
struct ReportArgs {
    /// Directory for report.md, report.csv and the charts (created if missing).
    #[arg(long, default_value = "report")]
    out: PathBuf,
    /// Fewer resolutions and runs, for tests and CI.
    #[arg(long)]
    quick: bool,
}

/// Prints a check report per file; the exit status is the worst finding (a file that does
/// not load is an error).
fn check(files: &[PathBuf]) -> ExitCode {
    let mut worst = bumpview::check::Severity::Clean;
    for path in files {
        println!("{}", path.display());
        let severity = match bumpview::load::load_scene(path) {
            Ok(scene) => {
                let report = bumpview::check::check_scene(&scene);
                print!("{}", report.to_text());
                report.severity()
            }
            Err(e) => {
                println!("  error: {e}");
                bumpview::check::Severity::Error
            }
        };
        worst = worst.max(severity);
    }
    ExitCode::from(worst.exit_code())
}

fn report(args: ReportArgs) -> Result<(), String> {
    let started = std::time::Instant::now();
    let plan = if args.quick { bumpview::report::Plan::quick() } else { bumpview::report::Plan::full() };
    let files = bumpview::report::run(&args.out, &plan).map_err(|e| e.to_string())?;
    let names: Vec<_> = files.iter().map(|f| f.display().to_string()).collect();
    println!("wrote {} in {:.1} s", names.join(", "), started.elapsed().as_secs_f64());
    Ok(())
}

#[derive(clap::Args)]
struct RenderArgs {
    /// Where to write the PNG [default with --preset: the preset's path with `.png`].
    #[arg(long, required_unless_present = "preset")]
    out: Option<PathBuf>,
    /// Start from this preset (TOML, as the viewer's "Save preset" writes); flags given as well
    /// override it.
    #[arg(long, value_name = "FILE")]
    preset: Option<PathBuf>,
    /// Also write the state of this picture as a preset here.
    #[arg(long, value_name = "FILE")]
    save_preset: Option<PathBuf>,
    /// Image size in pixels [default: the preset's, else 1280x720].
    #[arg(long, value_parser = args::parse_size)]
    size: Option<[u32; 2]>,
    /// Transparent background: alpha 0 where there is no geometry (the PNG keeps alpha).
    #[arg(long)]
    transparent: bool,
    /// Render at K times the size (1 to 4) and downsample with a box filter in linear light.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_SUPERSAMPLE)))]
    supersample: Option<u32>,
    /// What to show: lit, tangent, bitangent, normal or shading-normal [default: lit].
    #[arg(long, value_parser = parse_view)]
    view: Option<ViewMode>,
    /// Bump mapping on or off [default: on].
    #[arg(long, value_parser = args::parse_on_off, action = clap::ArgAction::Set)]
    bump: Option<bool>,
    /// Bump strength (0 is flat, negative inverts the relief) [default: 1].
    #[arg(long, value_parser = args::parse_finite, allow_hyphen_values = true)]
    strength: Option<f32>,
    /// Light position X,Y,Z in metres (world space, +Y up).
    #[arg(long, value_parser = args::parse_vec3, allow_hyphen_values = true)]
    light: Option<Vec3>,
    /// Camera YAW,PITCH,DISTANCE: degrees about +Y (0 looks along −Z), degrees above the
    /// target, metres from it.
    #[arg(long, value_parser = args::parse_triple, allow_hyphen_values = true)]
    camera: Option<[f32; 3]>,
    /// Hide the light marker.
    #[arg(long)]
    no_light_marker: bool,
    /// Draw T/B/N glyphs (red, green, blue lines) at vertices of meshes with tangent frames.
    #[arg(long)]
    glyphs: bool,
    /// Split view, left │ right, as one image: bump (off │ on), view (lit │ shading-normal),
    /// strength (1 │ 3), mode (colour-only │ bump-colour), tangents (per-face │ mikktspace),
    /// convention (opengl │ directx) or bump-source (normal-map │ height-in-shader)
    /// [default: the preset's].
    #[arg(long, value_name = "KIND", value_parser = parse_split, conflicts_with = "tiles")]
    split: Option<SplitDifference>,
    /// With --split: the two sides instead of the defaults above, e.g. `averaged-uniform,mikktspace`
    /// for tangents or `0.5,2` for strength.
    #[arg(long, value_name = "LEFT,RIGHT", requires = "split")]
    split_sides: Option<String>,
    /// With --split: the divider as a fraction of the width [default: 0.5].
    #[arg(long, value_name = "FRACTION", value_parser = args::parse_finite, requires = "split")]
    split_at: Option<f32>,
    /// A row of tiles of --size side by side: flat │ bumped │ Tangent view.
    #[arg(long, group = "tiles")]
    row: bool,
    /// A grid of tiles of --size: rows separated by `;`, tiles by `,`, each NAME[@STRENGTH]
    /// with NAME flat, bumped, bump-only, colour-only or a view name; without SPEC
    /// `flat,bumped,bump-only;tangent,bitangent,shading-normal`.
    #[arg(long, value_name = "SPEC", num_args = 0..=1, default_missing_value = "", group = "tiles")]
    grid: Option<String>,
    /// With --row or --grid: a caption strip under each tile (view and mode, strength,
    /// normal-map convention, tangent source).
    #[arg(long, requires = "tiles")]
    captions: bool,
    #[command(flatten)]
    methods: MethodArgs,
    #[command(flatten)]
    inputs: InputArgs,
}

fn parse_split(text: &str) -> Result<SplitDifference, String> {
    args::parse_named(text)
}

/// The numerical methods behind the picture (shared by the viewer and `render`).
#[derive(clap::Args, Clone, Copy)]
struct MethodArgs {
    /// Tangent frames: auto (the mesh's own, else MikkTSpace), mikktspace, per-face,
    /// averaged-uniform, averaged-area, averaged-angle, supplied or analytic [default: auto].
    #[arg(long, value_parser = parse_tangents)]
    tangents: Option<TangentChoice>,
    /// Height→normal kernel for the built-in brick normal map: forward, central, sobel3,
    /// scharr3, sobel5 or central4 [default: central].
    #[arg(long, value_parser = parse_kernel)]
    kernel: Option<Kernel>,
    /// Where the bump comes from: normal-map, or height-in-shader (Blinn's bump from the
    /// height map by screen-space derivatives, no tangents) [default: normal-map].
    #[arg(long, value_parser = parse_bump_source)]
    bump_source: Option<BumpSource>,
    #[command(flatten)]
    materials: MaterialArgs,
}

/// Texture conventions for every material and the shading model (viewer and `render`).
#[derive(clap::Args, Clone, Copy)]
struct MaterialArgs {
    /// Normal maps' green channel: opengl (+Y up the image) or directx (−Y); default: as loaded.
    #[arg(long, value_parser = parse_green)]
    normal_convention: Option<GreenAxis>,
    /// Normal maps store only red and green; blue (z) is reconstructed.
    #[arg(long)]
    two_channel: bool,
    /// Normal maps hold object-space (model-space) normals; no tangents are used.
    #[arg(long)]
    object_space: bool,
    /// Height maps store depth (white = deep).
    #[arg(long)]
    depth_map: bool,
    /// Metres spanned by a height map's full range (world units).
    #[arg(long, value_name = "METRES", value_parser = args::parse_finite)]
    height_range: Option<f32>,
    /// Height→normal kernel for every height map (re-makes its normal map): forward, central,
    /// sobel3, scharr3, sobel5 or central4. `--kernel` only makes the built-in brick map.
    #[arg(long, value_parser = parse_kernel)]
    height_kernel: Option<Kernel>,
    /// Height maps' border when differentiating: wrap (tiling) or clamp (re-makes the normal map).
    #[arg(long, value_parser = parse_border)]
    height_border: Option<Border>,
    /// Shading model: blinn-phong, pbr (glTF metallic-roughness) or auto (each material's own:
    /// pbr for glTF, blinn-phong for OBJ and the built-in scene) [default: auto].
    #[arg(long, value_parser = parse_shading)]
    shading: Option<ShadingChoice>,
}

impl MaterialArgs {
    fn overrides(&self) -> MaterialOverrides {
        MaterialOverrides {
            green: self.normal_convention,
            two_channel: self.two_channel.then_some(true),
            object_space: self.object_space.then_some(true),
            depth_map: self.depth_map.then_some(true),
            height_range_m: self.height_range,
            kernel: self.height_kernel,
            border: self.height_border,
        }
    }
}

/// A shading model, or `None` for auto.
#[derive(Clone, Copy)]
struct ShadingChoice(Option<ShadingModel>);

fn parse_shading(text: &str) -> Result<ShadingChoice, String> {
    parse_or_auto(text).map(ShadingChoice).map_err(|e| e.to_string())
}

fn parse_green(text: &str) -> Result<GreenAxis, String> {
    args::parse_named(text)
}

impl MethodArgs {
    /// Whether no method or convention flag was given.
    fn is_empty(&self) -> bool {
        let m = &self.materials;
        self.tangents.is_none()
            && self.kernel.is_none()
            && self.bump_source.is_none()
            && m.overrides().is_empty()
            && m.shading.is_none()
    }

    /// These flags over the state a preset gave.
    fn apply(&self, state: &mut ViewerState) {
        let options = &mut state.scene_options;
        if let Some(TangentChoice(method)) = self.tangents {
            options.tangent_method = method;
        }
        if let Some(source) = self.bump_source {
            options.bump_source = source;
        }
        options.materials = self.materials.overrides().over(options.materials);
        if let Some(kernel) = self.kernel {
            state.kernel = kernel;
        }
        if let Some(ShadingChoice(model)) = self.materials.shading {
            state.shading.shading_override = model;
        }
    }
}

fn parse_bump_source(text: &str) -> Result<BumpSource, String> {
    args::parse_named(text)
}

fn parse_view(text: &str) -> Result<ViewMode, String> {
    args::parse_named(text)
}

/// A tangent method, or `None` for auto (clap reads a bare `Option` as "flag may be absent").
#[derive(Clone, Copy)]
struct TangentChoice(Option<TangentMethod>);

/// `auto` or a [`TangentMethod`] name.
fn parse_tangents(text: &str) -> Result<TangentChoice, String> {
    parse_or_auto(text).map(TangentChoice).map_err(|e| e.to_string())
}

fn parse_kernel(text: &str) -> Result<Kernel, String> {
    args::parse_named(text)
}

fn parse_border(text: &str) -> Result<Border, String> {
    args::parse_named(text)
}

/// The preset, the scene it names and its state, with the command line's files and method
/// flags over them. Errors name the file and the problem.
fn start_state(preset: Preset, inputs: &InputArgs, methods: &MethodArgs) -> Result<Started, String> {
    let mut preset = preset;
    preset.files = inputs.over(preset.files);
    if let Some(kernel) = methods.kernel {
        kernel.name().clone_into(&mut preset.scene.kernel);
    }
    let scene = preset.build_scene()?;
    let mut state = preset.to_state(&scene).map_err(|e| e.to_string())?;
    methods.apply(&mut state);
    Ok(Started { files: preset.files, capture: preset.capture, scene, state })
}

/// What the viewer or `render` starts with.
struct Started {
    files: PresetFiles,
    capture: CapturePreset,
    scene: Scene,
    state: ViewerState,
}

/// Why a command failed: its arguments (exit status 2, as for flags clap rejects) or the
/// work itself (exit status 1).
enum Failure {
    BadArguments(String),
    Failed(String),
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Failed(message)
    }
}

fn render(args: RenderArgs) -> Result<(), Failure> {
    let preset = match &args.preset {
        Some(path) => Preset::load(path).map_err(|e| e.to_string())?,
        None => Preset::default(),
    };
    let Started { files, capture, scene, mut state } = start_state(preset, &args.inputs, &args.methods)?;
    if let Some(view) = args.view {
        state.shading.view = view;
    }
    if let Some(bump) = args.bump {
        state.shading.bump_enabled = bump;
    }
    if let Some(strength) = args.strength {
        state.shading.strength = strength;
    }
    if args.no_light_marker {
        state.shading.show_light_marker = false;
    }
    if args.glyphs {
        state.shading.tbn_glyphs = true;
    }
    if let Some(light) = args.light {
        state.light.position = light;
    }
    if let Some([yaw, pitch, distance]) = args.camera {
        if distance <= 0.0 {
            return Err(Failure::BadArguments(format!("--camera: distance {distance} must be positive")));
        }
        state.camera.yaw = yaw.to_radians();
        state.camera.pitch = 0.0;
        state.camera.orbit(0.0, pitch.to_radians());
        state.camera.distance = distance;
    }
    let capture = CapturePreset {
        size: Some(args.size.or(capture.size).unwrap_or(DEFAULT_RENDER_SIZE)),
        transparent: args.transparent || capture.transparent,
        supersample: args.supersample.unwrap_or(capture.supersample),
        captions: args.captions || capture.captions,
    };
    if let Some(difference) = args.split {
        state.split.enabled = true;
        state.split.difference = difference;
    }
    if let (Some(difference), Some(sides)) = (args.split, &args.split_sides) {
        let sides = args::parse_split_sides(difference, sides);
        state.apply(sides.map_err(|e| Failure::BadArguments(format!("--split-sides {e}")))?);
    }
    if let Some(at) = args.split_at {
        if !(0.0..=1.0).contains(&at) {
            return Err(Failure::BadArguments(format!("--split-at {at}: expected a fraction of the width, 0 to 1")));
        }
        state.split.divider = at;
    }
    let out = match (&args.out, &args.preset) {
        (Some(out), _) => out.clone(),
        (None, Some(preset)) => preset.with_extension("png"),
        (None, None) => unreachable!("clap requires --out without --preset"),
    };
    let grid = match (&args.grid, args.row) {
        (Some(spec), _) if spec.is_empty() => Some(TileGrid::default_grid(&state.shading)),
        (Some(spec), _) => {
            Some(TileGrid::parse(spec, &state.shading).map_err(|e| Failure::BadArguments(format!("--grid {e}")))?)
        }
        (None, true) => Some(TileGrid::default_row(&state.shading)),
        (None, false) => None,
    };
    if grid.is_some() {
        // Tiles are single pictures: a preset's split view does not apply.
        state.split.enabled = false;
    }
    if let Some(path) = &args.save_preset {
        let preset = Preset { capture, ..Preset::from_state(&state, files) };
        preset.save(path).map_err(|e| e.to_string())?;
    }
    let gpu = Gpu::headless().map_err(|e| e.to_string())?;
    let mut renderer = Renderer::from_gpu(&gpu);
    renderer.set_scene_uploads(&scene, &state.scene_uploads());
    let options = capture_options(&capture, DEFAULT_RENDER_SIZE);
    let params = state.frame_params();
    let image = if let Some(grid) = grid {
        let captions: Option<Vec<_>> = capture
            .captions
            .then(|| grid.tiles.iter().map(|s| caption(&renderer, &scene, &state.scene_options, s)).collect());
        render_grid(&mut renderer, &options, &params, &grid, captions.as_deref())
    } else if let Some(split) = state.split_frame() {
        render_capture_split(&mut renderer, &options, &params, &split)
    } else {
        render_capture(&mut renderer, &options, &params)
    }
    .map_err(|e| e.to_string())?;
    write_png_atomically(&image, &out).map_err(|e| e.to_string())?;
    let (width, height) = image.dimensions();
    println!("wrote {} ({width}x{height}, {})", out.display(), gpu.adapter_name());
    Ok(())
}

/// `render`'s size when neither `--size` nor the preset gives one.
const DEFAULT_RENDER_SIZE: [u32; 2] = [1280, 720];

/// The capture a preset's settings describe, at `size` when they give none.
fn capture_options(capture: &CapturePreset, size: [u32; 2]) -> CaptureOptions {
    let background = if capture.transparent { Background::Transparent } else { Background::Opaque };
    CaptureOptions { size: capture.size.unwrap_or(size), background, supersample: capture.supersample }
}

#[cfg(feature = "ui")]
fn viewer(cli: &Cli) -> Result<(), String> {
    // `--exit-after` runs (scripts, tests) neither restore nor save the last state.
    let last_state = app::last_state_file().filter(|_| cli.exit_after.is_none());
    let command_line = cli.preset.is_some() || !cli.inputs.is_empty() || !cli.methods.is_empty();
    let mut notice = None;
    let restored = match (&cli.preset, &last_state) {
        (Some(path), _) => Some(Preset::load(path).map_err(|e| e.to_string())?),
        (None, Some(path)) if !command_line && path.exists() => {
            Preset::load(path).map_err(|e| notice = Some(format!("last state not restored: {e}"))).ok()
        }
        _ => None,
    };
    let from_last = restored.is_some() && cli.preset.is_none();
    let started = match start_state(restored.unwrap_or_default(), &cli.inputs, &cli.methods) {
        Err(e) if from_last => {
            notice = Some(format!("last state not restored: {e}"));
            start_state(Preset::default(), &cli.inputs, &cli.methods)?
        }
        started => started?,
    };
    app::run(app::Options {
        exit_after: cli.exit_after,
        capture_window: cli.capture_window.clone(),
        inputs: InputArgs::from_files(&started.files),
        capture: started.capture,
        scene: started.scene,
        state: started.state,
        last_state,
        notice,
    })
}

#[cfg(not(feature = "ui"))]
fn viewer(_cli: &Cli) -> Result<(), String> {
    Err("this build has no viewer (built without the `ui` feature); use `bumpview render`".into())
}

fn main() -> ExitCode {
    let mut cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // One line: the first line of clap's message names the bad flag or value.
            let message = e.to_string();
            eprintln!("bumpview: {}", message.lines().next().unwrap_or("bad arguments").trim_start_matches("error: "));
            return ExitCode::from(2);
        }
    };
    let result = match cli.command.take() {
        Some(Command::Render(args)) => render(*args),
        Some(Command::Report(args)) => report(args).map_err(Failure::Failed),
        Some(Command::Check { files }) => return check(&files),
        None => viewer(&cli).map_err(Failure::Failed),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::BadArguments(message)) => {
            eprintln!("bumpview: {message}");
            ExitCode::from(2)
        }
        Err(Failure::Failed(message)) => {
            eprintln!("bumpview: {message}");
            ExitCode::FAILURE
        }
    }
}
