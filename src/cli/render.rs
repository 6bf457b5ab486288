//! `bumpview render`: the built-in scene or a mesh drawn offscreen (no window, no display)
//! into a PNG, or with `--frames N` timed against the adapter's floor. Its picture flags are
//! the viewer's ([`PictureArgs`]).

use std::num::NonZeroU32;
use std::path::{Path, PathBuf};

use bumpview::atomic::check_outputs;
use bumpview::error::{LoadWarning, escape_controls};
use bumpview::frame::{FrameQuality, SceneUploads, ShadingSettings};
use bumpview::render::capture::{MAX_SUPERSAMPLE, write_png_atomically};
use bumpview::render::export::{MAX_EXPORT_PIXELS, TileGrid, caption, render_grid, render_picture};
use bumpview::render::timing::{TimedPicture, time_turning_frames};
use bumpview::render::{Gpu, Renderer};
use bumpview::state::interactive::InteractiveQuality;
use bumpview::state::preset::{CapturePreset, Preset};
use bumpview::state::{Command, ViewerState};

use super::Failure;
use super::args;
use super::inputs::InputArgs;
use super::methods::MethodArgs;
use super::picture::PictureArgs;
use super::start::{Started, start};

/// `render`'s size when neither `--size` nor the preset gives one.
pub const DEFAULT_RENDER_SIZE: [u32; 2] = [1280, 720];

/// The most frames `--frames` times without `--no-budget`: about 110 s of frame and floor
/// pairs at 1280x720 on lavapipe (58 + 52 ms a pair), well under a second on a desktop GPU.
pub const MAX_FRAMES: u32 = 1000;

/// The most tiles `--grid` draws without `--no-budget`: an 8x8 grid; each tile is a full
/// render (and a caption).
pub const MAX_TILES: usize = 64;

#[derive(clap::Args)]
pub struct RenderArgs {
    /// Where to write the PNG [default with --preset: the preset's path with `.png`].
    #[arg(long, required_unless_present_any = ["preset", "frames"])]
    out: Option<PathBuf>,
    /// Instead of writing a PNG: draw the picture N times at --size and print one line on
    /// stdout, `frame <ms> ms, floor <ms> ms, ratio <r>`: the median time of a frame (drawn
    /// until the adapter finished) and of the adapter's floor (a clear and one full-screen
    /// triangle of one colour, same size, format, depth buffer and MSAA), drawn alternately.
    #[arg(long, value_name = "N", conflicts_with_all = ["out", "transparent", "supersample", "tiles"])]
    frames: Option<NonZeroU32>,
    /// With --frames: time the frames the viewer draws while you drag (1 sample per pixel,
    /// at the render scale it settles on) instead of full-quality ones (4× MSAA).
    #[arg(long, requires = "frames", conflicts_with_all = ["out", "transparent", "supersample", "tiles"])]
    interactive: bool,
    /// With --frames: turn the camera by DEGREES about its target before each frame, as while
    /// dragging, so that what is done once per view (GPU displacement's tessellation) is timed
    /// in every frame [default: 0].
    #[arg(long, value_name = "DEGREES", requires = "frames", value_parser = args::parse_finite)]
    turning: Option<f32>,
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
    #[command(flatten)]
    pub(super) picture: PictureArgs,
    /// A row of tiles of --size side by side: flat │ bumped │ Tangent view.
    #[arg(long, group = "tiles", conflicts_with = "split")]
    row: bool,
    /// A grid of tiles of --size: rows separated by `;`, tiles by `,`, each NAME[@STRENGTH]
    /// with NAME flat, bumped, bump-only, colour-only, a view name, or a parallax technique
    /// with an optional fixed layer count (`steep:8,occlusion:8,relief:8`); without SPEC
    /// `flat,bumped,bump-only;tangent,bitangent,shading-normal`.
    #[arg(long, value_name = "SPEC", num_args = 0..=1, default_missing_value = "", group = "tiles", conflicts_with = "split")]
    grid: Option<String>,
    /// With --row or --grid: a caption strip under each tile (view and mode, strength,
    /// normal-map convention, tangent source).
    #[arg(long, requires = "tiles")]
    captions: bool,
    /// Fail (exit 1, no PNG) when the model opened without a texture it names, instead of
    /// drawing it without and warning on stderr.
    #[arg(long)]
    strict: bool,
    /// Replace --out (and --save-preset) when it exists; without it an existing file is kept
    /// and nothing is drawn. An input is never written over, even with --force.
    #[arg(long)]
    force: bool,
    /// Lift the work budgets: at most 1000 --frames and 64 tiles per --grid. (The pixels of
    /// an export stay limited to 2^28, 1 GiB of RGBA.)
    #[arg(long)]
    no_budget: bool,
    #[command(flatten)]
    pub(super) methods: MethodArgs,
    #[command(flatten)]
    pub(super) inputs: InputArgs,
}

impl RenderArgs {
    /// The tile grid asked for, made from the current shading (`None`: a single picture).
    fn grid(&self, state: &ViewerState) -> Result<Option<TileGrid>, Failure> {
        Ok(match (&self.grid, self.row) {
            (Some(spec), _) if spec.is_empty() => Some(TileGrid::default_grid(&state.shading)),
            (Some(spec), _) => {
                let grid = TileGrid::parse(spec, &state.shading);
                Some(grid.map_err(|e| Failure::BadArguments(format!("--grid {e}")))?)
            }
            (None, true) => Some(TileGrid::default_row(&state.shading)),
            (None, false) => None,
        })
    }

    /// The PNG to write: `--out`, else the preset's path with `.png`; `None` with `--frames`.
    fn out_path(&self) -> Option<PathBuf> {
        match (&self.out, &self.preset) {
            _ if self.frames.is_some() => None,
            (Some(out), _) => Some(out.clone()),
            (None, Some(preset)) => Some(preset.with_extension("png")),
            (None, None) => None,
        }
    }

    /// Every file this command writes: the PNG and the `--save-preset` file.
    fn outputs(&self) -> Vec<PathBuf> {
        self.out_path().into_iter().chain(self.save_preset.clone()).collect()
    }

    /// Refuses, before any work, more frames or tiles than the budgets ([`MAX_FRAMES`],
    /// [`MAX_TILES`]; lifted by `--no-budget`) and an export of more than
    /// [`MAX_EXPORT_PIXELS`] pixels drawn (size × supersampling² × tiles), naming the limit.
    fn budget(&self, capture: &CapturePreset) -> Result<(), Failure> {
        let bad = |message: String| Err(Failure::BadArguments(message));
        if let Some(frames) = self.frames.filter(|f| f.get() > MAX_FRAMES && !self.no_budget) {
            return bad(format!("--frames {frames}: at most {MAX_FRAMES} frames are timed (--no-budget lifts this)"));
        }
        // The tile count from the spec alone (tiles' shading is made once the scene is read).
        let tiles = match (&self.grid, self.row) {
            (Some(spec), _) if !spec.is_empty() => {
                let grid = TileGrid::parse(spec, &ShadingSettings::default());
                grid.map_err(|e| Failure::BadArguments(format!("--grid {e}")))?.tiles.len()
            }
            (Some(_), _) => TileGrid::default_grid(&ShadingSettings::default()).tiles.len(),
            (None, true) => TileGrid::default_row(&ShadingSettings::default()).tiles.len(),
            (None, false) => 1,
        };
        if tiles > MAX_TILES && !self.no_budget {
            return bad(format!("--grid of {tiles} tiles: at most {MAX_TILES} are drawn (--no-budget lifts this)"));
        }
        if let Some([width, height]) = capture.size {
            let k = u64::from(capture.supersample);
            let pixels = u64::from(width) * u64::from(height) * k * k * tiles as u64;
            if pixels > MAX_EXPORT_PIXELS {
                let what = format!("{width}x{height}, {tiles} tile(s), supersampled {k}x");
                return bad(format!("{what} is {pixels} pixels to draw, over the limit of {MAX_EXPORT_PIXELS}"));
            }
        }
        Ok(())
    }

    /// The screenshot settings: the flags over the preset's.
    fn capture(&self, preset: CapturePreset) -> CapturePreset {
        CapturePreset {
            size: Some(self.size.or(preset.size).unwrap_or(DEFAULT_RENDER_SIZE)),
            transparent: self.transparent || preset.transparent,
            supersample: self.supersample.unwrap_or(preset.supersample),
            captions: self.captions || preset.captions,
        }
    }
}

/// Draws the picture and writes the PNG (and the preset, with `--save-preset`). The work
/// asked for and the outputs are checked before any file but the preset is read
/// ([`RenderArgs::budget`], [`RenderArgs::outputs`]).
pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    let preset = match &args.preset {
        Some(path) => Preset::load(path)?,
        None => Preset::default(),
    };
    args.budget(&args.capture(preset.capture))?;
    let outputs = args.outputs();
    let outputs: Vec<&Path> = outputs.iter().map(PathBuf::as_path).collect();
    let given = args.inputs.files().over(preset.files.clone());
    let inputs: Vec<&Path> = given.paths().into_iter().chain(args.preset.as_deref()).collect();
    check_outputs(&inputs, &outputs, args.force).map_err(|e| Failure::BadArguments(e.to_string()))?;
    let Started { files, capture, scene, mut state } = start(preset, args.inputs.files(), &args.methods)?;
    // The files the model refers to (its buffers and textures), known once it is read.
    let referred: Vec<&Path> = scene.files.iter().map(PathBuf::as_path).collect();
    check_outputs(&referred, &outputs, true).map_err(|e| Failure::BadArguments(e.to_string()))?;
    for warning in &scene.warnings {
        eprintln!("bumpview: warning: {}", escape_controls(&warning.to_string()));
    }
    let unreadable = scene.warnings.iter().filter(|w| matches!(w, LoadWarning::UnreadableTexture { .. })).count();
    if args.strict && unreadable > 0 {
        return Err(Failure::Failed(format!("--strict: the model opened without {unreadable} texture(s)")));
    }
    args.picture.apply(&mut state)?;
    let capture = args.capture(capture);
    let grid = args.grid(&state)?;
    if grid.is_some() {
        // Tiles are single pictures: a preset's split view does not apply.
        state.apply(Command::SetSplit(false));
    }
    if let Some(path) = &args.save_preset {
        Preset { capture, ..Preset::from_state(&state, files) }.save(path)?;
    }
    if let Some(frames) = args.frames {
        let size = capture.size.unwrap_or(DEFAULT_RENDER_SIZE);
        return time(&scene, &state, size, frames, args.interactive, args.turning.unwrap_or(0.0));
    }
    let Some(out) = args.out_path() else {
        unreachable!("clap requires --out without --preset or --frames");
    };
    let gpu = Gpu::headless()?;
    let mut renderer = Renderer::from_gpu(&gpu);
    let uploads = match &grid {
        // Tiles are single pictures, some perhaps marching the height maps.
        Some(grid) => SceneUploads { main: state.scene_options_drawing(&grid.tiles), split_right: None },
        None => state.scene_uploads(),
    };
    renderer.set_scene_uploads(&scene, &uploads);
    let options = capture.options(DEFAULT_RENDER_SIZE);
    let params = state.frame_params();
    let image = if let Some(grid) = grid {
        let captions: Option<Vec<_>> = capture
            .captions
            .then(|| grid.tiles.iter().map(|s| caption(&renderer, &scene, &state.scene_options, s)).collect());
        render_grid(&mut renderer, &options, &params, &grid, captions.as_deref())
    } else {
        let split = state.split_frame();
        let labels = state.split.labels();
        let split = split.as_ref().map(|s| (s, [labels[0].as_str(), labels[1].as_str()]));
        render_picture(&mut renderer, &options, &params, split)
    }?;
    // After drawing: GPU displacement tessellates, and says what it drew, as it draws.
    report_displacement(&renderer);
    report_notices(&renderer, &scene);
    write_png_atomically(&image, &out)?;
    let (width, height) = image.dimensions();
    println!("wrote {} ({width}x{height}, {})", out.display(), gpu.adapter_name());
    Ok(())
}

/// Tells stderr what displacement drew, the level asked for and why it was lowered (per half
/// of a split view drawn from two uploads; a right half without its own upload is drawn from
/// the main one and not named).
fn report_displacement(renderer: &Renderer) {
    let split_upload = renderer.uploads().is_some_and(|u| u.split_right.is_some());
    for (half, name) in [(false, ""), (true, " (split right)")] {
        if half && !split_upload {
            continue;
        }
        if let Some(stats) = renderer.prepared(half).and_then(|p| p.displacement) {
            eprintln!("bumpview: displacement{name}: {}", stats.asked_and_drawn());
        }
        if let Some(stats) = renderer.gpu_displacement(half) {
            eprintln!("bumpview: displacement{name}: {}", stats.summary());
        }
    }
}

/// Tells stderr what the renderer could not do as asked (a texture downscaled or drawn without,
/// LEAN past its size, geometry the device refused), one line each; the load's warnings, which
/// the renderer repeats, were printed when the model was read.
fn report_notices(renderer: &Renderer, scene: &bumpview::scene::Scene) {
    let warnings: Vec<String> = scene.warnings.iter().map(ToString::to_string).collect();
    for notice in renderer.notices().iter().filter(|n| !warnings.contains(n)) {
        eprintln!("bumpview: notice: {}", escape_controls(notice));
    }
}

/// `--frames`: times `frames` frames of the picture at `size` (full quality, or as the viewer
/// draws them while dragging) against the adapter's floor and prints the line.
fn time(
    scene: &bumpview::scene::Scene,
    state: &ViewerState,
    size: [u32; 2],
    frames: NonZeroU32,
    interactive: bool,
    turning_degrees: f32,
) -> Result<(), Failure> {
    let gpu = Gpu::headless()?;
    let mut renderer = Renderer::from_gpu(&gpu);
    renderer.set_scene_uploads(scene, &state.scene_uploads());
    let params = state.frame_params();
    let split = state.split_frame();
    let mut picture =
        TimedPicture { params: &params, split: split.as_ref(), view_size: size, quality: FrameQuality::FULL };
    if interactive {
        picture.quality = InteractiveQuality::default().settle(&mut renderer, &picture)?;
    }
    let timing = time_turning_frames(&mut renderer, &picture, frames, turning_degrees)?;
    report_displacement(&renderer);
    report_notices(&renderer, scene);
    let [width, height] = picture.quality.render_size(size);
    let samples = renderer.samples(bumpview::render::capture::IMAGE_FORMAT, picture.quality.msaa);
    eprintln!(
        "bumpview: timed {frames} frames of {width}x{height} pixels, {samples} sample(s) each, on {}",
        gpu.adapter_name()
    );
    println!("{timing}");
    Ok(())
}
