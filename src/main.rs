//! The `bumpview` command: the viewer (default) and `render`, a headless picture.

#[cfg(feature = "ui")]
mod app;
mod args;
mod inputs;

use std::path::PathBuf;
use std::process::ExitCode;

use bumpview::height::{Border, Kernel};
use bumpview::render::capture::{render_image, write_png_atomically};
use bumpview::render::{BumpSource, Gpu, Renderer, SceneOptions};
use bumpview::scene::builtin::teaching_scene_with_kernel;
use bumpview::scene::{GreenAxis, MaterialOverrides, ShadingModel};
use bumpview::shading::ViewMode;
use bumpview::tangent::TangentMethod;
use bumpview::viewer::ViewerState;
use clap::{Parser, Subcommand};
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
    #[command(flatten)]
    methods: MethodArgs,
    #[command(flatten)]
    inputs: inputs::InputArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Draw the built-in scene or a mesh file offscreen (no window, no display) and write a PNG.
    Render(RenderArgs),
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
    /// Where to write the PNG.
    #[arg(long)]
    out: PathBuf,
    /// Image size in pixels.
    #[arg(long, default_value = "1280x720", value_parser = args::parse_size)]
    size: [u32; 2],
    /// What to show: lit, tangent, bitangent, normal or shading-normal.
    #[arg(long, default_value = "lit", value_parser = parse_view)]
    view: ViewMode,
    /// Bump mapping on or off.
    #[arg(long, default_value = "on", value_parser = args::parse_on_off, action = clap::ArgAction::Set)]
    bump: bool,
    /// Bump strength (0 is flat, negative inverts the relief).
    #[arg(long, default_value = "1", value_parser = args::parse_finite, allow_hyphen_values = true)]
    strength: f32,
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
    #[command(flatten)]
    methods: MethodArgs,
    #[command(flatten)]
    inputs: inputs::InputArgs,
}

/// The numerical methods behind the picture (shared by the viewer and `render`).
#[derive(clap::Args, Clone, Copy)]
struct MethodArgs {
    /// Tangent frames: auto (the mesh's own, else MikkTSpace), mikktspace, per-face,
    /// averaged-uniform, averaged-area, averaged-angle, supplied or analytic.
    #[arg(long, default_value = "auto", value_parser = parse_tangents)]
    tangents: TangentChoice,
    /// Height→normal kernel for the built-in brick normal map: forward, central, sobel3,
    /// scharr3, sobel5 or central4.
    #[arg(long, default_value = "central", value_parser = parse_kernel)]
    kernel: Kernel,
    /// Where the bump comes from: normal-map, or height-in-shader (Blinn's bump from the
    /// height map by screen-space derivatives, no tangents).
    #[arg(long, default_value = "normal-map", value_parser = parse_bump_source)]
    bump_source: BumpSource,
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
    /// pbr for glTF, blinn-phong for OBJ and the built-in scene).
    #[arg(long, default_value = "auto", value_parser = parse_shading)]
    shading: ShadingChoice,
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
    match text {
        "auto" => Ok(ShadingChoice(None)),
        "blinn-phong" => Ok(ShadingChoice(Some(ShadingModel::BlinnPhong))),
        "pbr" => Ok(ShadingChoice(Some(ShadingModel::MetallicRoughness))),
        _ => Err(format!("{text:?}: expected blinn-phong, pbr or auto")),
    }
}

fn parse_green(text: &str) -> Result<GreenAxis, String> {
    match text {
        "opengl" => Ok(GreenAxis::OpenGl),
        "directx" => Ok(GreenAxis::DirectX),
        _ => Err(format!("{text:?}: expected opengl or directx")),
    }
}

impl MethodArgs {
    fn scene_options(&self) -> SceneOptions {
        let materials = self.materials.overrides();
        SceneOptions { tangent_method: self.tangents.0, bump_source: self.bump_source, materials, ..Default::default() }
    }
}

fn parse_bump_source(text: &str) -> Result<BumpSource, String> {
    BumpSource::from_name(text).ok_or_else(|| {
        let names: Vec<_> = BumpSource::ALL.iter().map(|b| b.name()).collect();
        format!("{text:?}: expected one of {}", names.join(", "))
    })
}

fn parse_view(text: &str) -> Result<ViewMode, String> {
    ViewMode::from_name(text).ok_or_else(|| {
        let names: Vec<_> = ViewMode::ALL.iter().map(|m| m.name()).collect();
        format!("{text:?}: expected one of {}", names.join(", "))
    })
}

/// A tangent method, or `None` for auto (clap reads a bare `Option` as "flag may be absent").
#[derive(Clone, Copy)]
struct TangentChoice(Option<TangentMethod>);

/// `auto` or a [`TangentMethod`] name.
fn parse_tangents(text: &str) -> Result<TangentChoice, String> {
    if text == "auto" {
        return Ok(TangentChoice(None));
    }
    TangentMethod::from_name(text).map(|m| TangentChoice(Some(m))).ok_or_else(|| {
        let names: Vec<_> = TangentMethod::ALL.iter().map(|m| m.name()).collect();
        format!("{text:?}: expected auto or one of {}", names.join(", "))
    })
}

fn parse_kernel(text: &str) -> Result<Kernel, String> {
    Kernel::from_name(text).ok_or_else(|| {
        let names: Vec<_> = Kernel::ALL.iter().map(|k| k.name()).collect();
        format!("{text:?}: expected one of {}", names.join(", "))
    })
}

fn parse_border(text: &str) -> Result<Border, String> {
    match text {
        "wrap" => Ok(Border::Wrap),
        "clamp" => Ok(Border::Clamp),
        _ => Err(format!("{text:?}: expected wrap or clamp")),
    }
}

fn render(args: RenderArgs) -> Result<(), String> {
    let kernel = args.methods.kernel;
    let scene = args.inputs.scene(kernel)?.unwrap_or_else(|| teaching_scene_with_kernel(kernel));
    let mut state = ViewerState::new(&scene);
    state.shading.view = args.view;
    state.shading.bump_enabled = args.bump;
    state.shading.strength = args.strength;
    state.shading.show_light_marker = !args.no_light_marker;
    state.shading.shading_override = args.methods.materials.shading.0;
    if let Some(light) = args.light {
        state.light.position = light;
    }
    if let Some([yaw, pitch, distance]) = args.camera {
        if distance <= 0.0 {
            return Err(format!("camera distance {distance} must be positive"));
        }
        state.camera.yaw = yaw.to_radians();
        state.camera.pitch = 0.0;
        state.camera.orbit(0.0, pitch.to_radians());
        state.camera.distance = distance;
    }
    let gpu = Gpu::headless().map_err(|e| e.to_string())?;
    let mut renderer = Renderer::from_gpu(&gpu);
    renderer.set_scene(&scene, args.methods.scene_options());
    let image = render_image(&mut renderer, args.size, &state.frame_params()).map_err(|e| e.to_string())?;
    write_png_atomically(&image, &args.out).map_err(|e| e.to_string())?;
    println!("wrote {} ({}x{}, {})", args.out.display(), args.size[0], args.size[1], gpu.adapter_name());
    Ok(())
}

#[cfg(feature = "ui")]
fn viewer(cli: &Cli) -> Result<(), String> {
    app::run(app::Options {
        exit_after: cli.exit_after,
        capture_window: cli.capture_window.clone(),
        scene_options: cli.methods.scene_options(),
        shading_override: cli.methods.materials.shading.0,
        kernel: cli.methods.kernel,
        scene: cli.inputs.scene(cli.methods.kernel)?,
        inputs: cli.inputs.clone(),
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
        Some(Command::Render(args)) => render(args),
        Some(Command::Report(args)) => report(args),
        Some(Command::Check { files }) => return check(&files),
        None => viewer(&cli),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("bumpview: {message}");
            ExitCode::FAILURE
        }
    }
}
