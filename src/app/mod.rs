//! The eframe/egui viewer: a thin layer over the library. The panel ([`panel`]), the keyboard
//! and mouse ([`input`]), dropped files, the file dialog ([`dialog`]), file changes on disk
//! ([`watch`]) and finished loads ([`files`]) only produce [`Action`]s; [`ViewerApp::apply`] is
//! the one place they take effect. The 3D view is drawn by [`Renderer`] into an offscreen texture
//! that egui shows as an image, and only when the picture would change.

mod dialog;
mod files;
mod files_panel;
mod input;
mod legend;
mod panel;
mod probe;
mod watch;

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::{Arc, mpsc};
use std::time::Instant;

use bumpview::check::{CheckReport, check_scene};
use bumpview::frame::SceneUploads;
use bumpview::frame::SplitFrame;
use bumpview::frame::ViewMode;
use bumpview::height::Kernel;
use bumpview::load::{SceneFiles, TextureSlot};
use bumpview::names::Named;
use bumpview::render::capture::{MAX_SUPERSAMPLE, render_capture, render_capture_split, write_png_atomically};
use bumpview::render::export::{self, TileGrid};
use bumpview::render::{Background, RenderTarget, Renderer};
use bumpview::scene::Scene;
use bumpview::state::preset::{CapturePreset, Preset};
use bumpview::state::{Command, RedrawTracker, ViewerState};
use bumpview::tangent::{MethodMeasurement, TangentMethod, measure};
use eframe::egui_wgpu::RenderState;
use files::{Files, Finished, Purpose, Status};

/// How the viewer is started; see `--exit-after` and `--capture-window`.
pub struct Options {
    /// Close after this many presented frames.
    pub exit_after: Option<u64>,
    /// With `exit_after`: save a screenshot of the whole window here before closing.
    pub capture_window: Option<PathBuf>,
    /// The scene to start with (the built-in one, or made from `inputs`).
    pub scene: Scene,
    /// The files `scene` was made from, watched for changes.
    pub files: SceneFiles,
    /// Camera, light, settings and scene options to start with.
    pub state: ViewerState,
    /// Screenshot size, background and supersampling to start with.
    pub capture: CapturePreset,
    /// Where the state is saved on exit ([`last_state_file`]); `None`: not saved.
    pub last_state: Option<PathBuf>,
    /// Shown in the panel at start (e.g. why the last state was not restored).
    pub notice: Option<String>,
}

/// Something the user asked for or that arrived: a library [`Command`] or an app-only action.
#[derive(Debug, Clone, PartialEq)]
enum Action {
    /// A change to the viewer state.
    Viewer(Command),
    /// Save a PNG of the 3D view (F12 or the panel button).
    Screenshot,
    /// Save a PNG of the tile export (the form's spec, else flat │ bumped │ Tangent view),
    /// captions as the form says.
    ExportTiles,
    /// Write the whole state as a preset file.
    SavePreset(PathBuf),
    /// Read a preset file and show its files and state.
    LoadPreset(PathBuf),
    /// Open files (dropped, chosen in the dialog or the recent list): a mesh replaces the
    /// scene; images go into `slot` (dropped on it or chosen for it) or the one their name
    /// suggests.
    Open { paths: Vec<PathBuf>, slot: Option<TextureSlot> },
    /// Show the file dialog for a mesh or texture (`None`) or for one slot's texture.
    ShowDialog(Option<TextureSlot>),
    /// The file dialog closed with a file, or without one (`None`).
    DialogClosed { slot: Option<TextureSlot>, path: Option<PathBuf> },
    /// Files of the scene changed on disk and have settled: re-make it, keeping the view.
    Reload,
    /// A load finished on the worker thread.
    Loaded(Box<Finished>),
    /// Pin the pixel probe at `pixel` of a view `size` pixels (P + click).
    PinProbe { pixel: [u32; 2], size: [u32; 2] },
    /// Remove the pixel probe.
    ClearProbe,
}

impl From<Command> for Action {
    fn from(command: Command) -> Self {
        Action::Viewer(command)
    }
}

/// Format of the view texture; egui samples it as gamma-encoded colour.
const VIEW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Format the renderer draws through: the same bytes, sRGB-encoded on write.
const VIEW_RENDER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Longest frame step fed to animations, so a stall does not make the light jump.
const MAX_TICK_SECONDS: f32 = 0.1;
/// How close to the split view's divider (points) a drag must begin to move it.
const DIVIDER_GRAB_POINTS: f32 = 8.0;
/// Frames to wait for a requested window screenshot before giving up.
const CAPTURE_TIMEOUT_FRAMES: u32 = 600;

/// Opens the viewer window and runs until it is closed.
pub fn run(options: Options) -> Result<(), String> {
    let mut native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("bumpview")
            .with_inner_size([1280.0, 800.0])
            .with_min_inner_size([480.0, 320.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    // lavapipe and most drivers support FIFO; the default `AutoVsync` may pick otherwise.
    native.wgpu_options.surface.present_mode = wgpu::PresentMode::Fifo;
    request_device_extras(&mut native.wgpu_options.wgpu_setup);

    let failure = Rc::new(RefCell::new(None));
    let app_failure = Rc::clone(&failure);
    eframe::run_native("bumpview", native, Box::new(move |cc| Ok(Box::new(ViewerApp::new(cc, options, app_failure)?))))
        .map_err(|e| format!("viewer: {e}"))?;
    failure.take().map_or(Ok(()), Err)
}

/// Asks eframe's device for what the renderer can use beyond egui's defaults: line polygon
/// mode (the wireframe overlay) where the adapter has it, and the adapter's full texture size
/// (screenshots up to its limit; egui asks for 8192 only).
fn request_device_extras(setup: &mut eframe::egui_wgpu::WgpuSetup) {
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        let base = Arc::clone(&create.device_descriptor);
        create.device_descriptor = Arc::new(move |adapter| {
            let mut descriptor = base(adapter);
            descriptor.required_features |= adapter.features() & wgpu::Features::POLYGON_MODE_LINE;
            descriptor.required_limits.max_texture_dimension_2d = adapter.limits().max_texture_dimension_2d;
            descriptor
        });
    }
}

/// The offscreen texture the 3D view is drawn into, registered with egui.
struct ViewTexture {
    /// The `Rgba8UnormSrgb` view the renderer draws through.
    render_view: wgpu::TextureView,
    /// egui's handle of the plain `Rgba8Unorm` view.
    id: egui::TextureId,
    /// Width and height in pixels.
    size: [u32; 2],
}

/// The screenshot size field, its options and the outcome of the last screenshot.
struct ScreenshotForm {
    /// "WxH", or empty for the view's current pixel size.
    size_text: String,
    /// Alpha 0 where there is no geometry.
    transparent: bool,
    /// Render at this many times the size and downsample (1..=[`MAX_SUPERSAMPLE`]).
    supersample: u32,
    /// Tile exports get a caption strip under each tile.
    captions: bool,
    /// The tile export's spec ([`TileGrid::parse`]); empty: the default row.
    tiles_text: String,
    /// Where the last PNG went, or why it failed.
    message: Option<Result<String, String>>,
}

impl ScreenshotForm {
    fn new(capture: &CapturePreset) -> ScreenshotForm {
        ScreenshotForm {
            size_text: capture.size.map_or_else(String::new, |[w, h]| format!("{w}x{h}")),
            transparent: capture.transparent,
            supersample: capture.supersample,
            captions: capture.captions,
            tiles_text: String::new(),
            message: None,
        }
    }

    /// The settings as a preset stores them (a size field that does not parse is left out).
    fn capture(&self) -> CapturePreset {
        let size = crate::cli::args::parse_size(&self.size_text).ok();
        CapturePreset { size, transparent: self.transparent, supersample: self.supersample, captions: self.captions }
    }
}

/// The preset path field and the outcome of the last save or load.
#[derive(Default)]
struct PresetForm {
    /// The file "Save preset" and "Load preset" use.
    path_text: String,
    /// What the last save or load did, or why it failed.
    message: Option<Result<String, String>>,
}

/// The eframe app: viewer state, the renderer on eframe's device, and the view texture.
struct ViewerApp {
    state: ViewerState,
    scene: Scene,
    /// The scene's files, the loader, the recent list and the last outcome.
    files: Files,
    dialog: dialog::Dialog,
    watcher: watch::Watcher,
    /// Why hot reload does not work, when it does not.
    watch_error: Option<String>,
    /// Where the panel's slot buttons were last drawn, for files dropped on them.
    slot_targets: Vec<(TextureSlot, egui::Rect)>,
    /// To wake the UI from worker threads.
    ctx: egui::Context,
    /// The options the renderer's scene uploads were made with.
    uploaded: SceneUploads,
    /// Per mesh: the chosen tangent method timed and compared with the reference.
    measurements: Vec<(String, MethodMeasurement)>,
    /// The tangent method `measurements` are of.
    measurements_method: Option<TangentMethod>,
    /// What `bumpview check` finds in the current scene.
    check: CheckReport,
    /// `check`'s warnings, made once per scene rather than per drawn panel.
    check_warnings: Vec<String>,
    renderer: Renderer,
    render_state: RenderState,
    adapter_name: String,
    view: Option<ViewTexture>,
    tracker: RedrawTracker,
    /// The split view the view texture was last drawn with (`None`: not split).
    drawn_split: Option<SplitFrame>,
    /// The divider is being dragged (the drag began near it).
    dragging_divider: bool,
    screenshot: ScreenshotForm,
    preset: PresetForm,
    /// Where the state is saved on exit; `None`: not saved.
    last_state: Option<PathBuf>,
    render_error: Option<String>,
    exit: Option<ExitAfter>,
    /// The pinned pixel probe and its readout.
    probe: probe::Probe,
}

impl ViewerApp {
    fn new(
        cc: &eframe::CreationContext<'_>,
        options: Options,
        failure: Rc<RefCell<Option<String>>>,
    ) -> Result<Self, String> {
        let render_state = cc
            .wgpu_render_state
            .clone()
            .ok_or("eframe started without a wgpu render state (the viewer needs the wgpu renderer)")?;
        let mut renderer =
            Renderer::new(render_state.device.clone(), render_state.queue.clone(), render_state.adapter.clone());
        let scene = options.scene;
        let state = options.state;
        renderer.set_scene_uploads(&scene, &state.scene_uploads());
        let adapter_name = renderer.adapter_name();
        let mut files =
            Files::new(options.files.absolute(), state.kernel, Arc::new(SceneFiles::build), files::recent_file());
        files.remember_scene_files();
        if let Some(notice) = options.notice {
            files.status = Some(Status::Failed(notice));
        }
        let ctx = cc.egui_ctx.clone();
        let wake = ctx.clone();
        let (mut watcher, watching) = watch::Watcher::new(move || wake.request_repaint());
        let watch_error = watching.and_then(|()| watcher.watch(&watched_files(&files.scene_files, &scene))).err();
        let check = check_scene(&scene);
        Ok(ViewerApp {
            measurements: measure_all(&scene, state.scene_options.tangent_method),
            measurements_method: state.scene_options.tangent_method,
            check_warnings: check.warnings(),
            check,
            uploaded: state.scene_uploads(),
            scene,
            files,
            dialog: dialog::Dialog::default(),
            watcher,
            watch_error,
            slot_targets: Vec::new(),
            ctx,
            state,
            renderer,
            adapter_name,
            render_state,
            view: None,
            tracker: RedrawTracker::default(),
            drawn_split: None,
            dragging_divider: false,
            screenshot: ScreenshotForm::new(&options.capture),
            preset: PresetForm::default(),
            last_state: options.last_state,
            render_error: None,
            exit: options.exit_after.map(|frames| ExitAfter::new(frames, options.capture_window, failure)),
            probe: probe::Probe::default(),
        })
    }

    /// The one place actions take effect.
    fn apply(&mut self, actions: Vec<Action>) {
        for action in actions {
            match action {
                Action::Viewer(command) => {
                    self.state.apply(command);
                    if let Command::SetKernel(kernel) = command {
                        self.rebuild_builtin(kernel);
                    }
                }
                Action::Screenshot => self.screenshot.message = Some(self.save_screenshot()),
                Action::ExportTiles => self.screenshot.message = Some(self.export_tiles()),
                Action::SavePreset(path) => {
                    let saved = self.current_preset().save(&path).map_err(|e| e.to_string());
                    self.preset.message = Some(saved.map(|()| format!("saved {}", path.display())));
                }
                Action::LoadPreset(path) => self.preset.message = Some(self.load_preset(&path)),
                Action::Open { paths, slot } => self.files.open(&paths, slot, self.waker()),
                Action::ShowDialog(slot) => {
                    let folder = self.files.scene_files.paths().first().and_then(|f| f.parent()).map(Path::to_owned);
                    if let Err(message) = self.dialog.show(slot, folder, self.waker()) {
                        self.files.status = Some(Status::Failed(message));
                    }
                }
                Action::DialogClosed { slot, path: Some(path) } => self.files.open(&[path], slot, self.waker()),
                Action::DialogClosed { path: None, .. } => {
                    self.files.status = Some(Status::Done(
                        "no file chosen (if no dialog appeared: this desktop has no file-chooser portal or zenity)"
                            .into(),
                    ));
                }
                Action::Reload => {
                    let name = self
                        .files
                        .scene_files
                        .paths()
                        .first()
                        .map_or_else(|| "built-in scene".into(), |p| files::file_name(p));
                    let done = format!("reloaded {name}");
                    let (scene_files, kernel) = (self.files.scene_files.clone(), self.files.kernel);
                    self.files.reload(scene_files, kernel, done, self.waker());
                }
                Action::PinProbe { pixel, size } => {
                    self.probe.pin(pixel, size);
                    self.ctx.request_repaint();
                }
                Action::ClearProbe => self.probe.clear(),
                Action::Loaded(finished) => {
                    if let Some((scene, purpose)) = self.files.finish(*finished) {
                        self.install_scene(scene, purpose);
                    }
                }
            }
        }
    }

    /// A function for worker threads that makes the UI run a frame (to pick up their result).
    fn waker(&self) -> impl Fn() + Send + 'static {
        let ctx = self.ctx.clone();
        move || ctx.request_repaint()
    }

    /// Re-makes the built-in scene with a new brick-map kernel (in the background, keeping
    /// the view and any textures in its slots); loaded meshes do not use the kernel.
    fn rebuild_builtin(&mut self, kernel: Kernel) {
        if self.files.scene_files.mesh.is_none() && self.files.kernel != kernel {
            let done = format!("brick normal map made with {}", kernel.name());
            self.files.reload(self.files.scene_files.clone(), kernel, done, self.waker());
        }
    }

    /// Shows a newly loaded scene. A new mesh is framed by its default camera and light; a
    /// reload keeps camera, light and settings.
    fn install_scene(&mut self, scene: Scene, purpose: Purpose) {
        if purpose == Purpose::Open {
            // Per-material overrides name materials by index: they belong to the old mesh.
            self.state.scene_options.per_material.clear();
        }
        self.uploaded = self.state.scene_uploads();
        self.renderer.set_scene_uploads(&scene, &self.uploaded);
        self.measurements = measure_all(&scene, self.state.scene_options.tangent_method);
        self.measurements_method = self.state.scene_options.tangent_method;
        self.check = check_scene(&scene);
        self.check_warnings = self.check.warnings();
        self.state.default_camera = scene.default_camera;
        if purpose == Purpose::Open {
            self.state.camera = scene.default_camera;
            self.state.light = scene.default_light;
        }
        self.scene = scene;
        self.probe.scene_changed();
        self.tracker.invalidate();
        self.watch_error = self.watcher.watch(&watched_files(&self.files.scene_files, &self.scene)).err();
    }

    /// What arrived from other threads this frame: dropped files, the dialog's answer, settled
    /// file changes and finished loads.
    fn arrivals(&mut self, ctx: &egui::Context) -> Vec<Action> {
        let mut actions = Vec::new();
        let (dropped, pointer) = ctx.input(|i| {
            (i.raw.dropped_files.iter().map(|f| f.path().to_owned()).collect::<Vec<_>>(), i.pointer.latest_pos())
        });
        if !dropped.is_empty() {
            let slot =
                pointer.and_then(|p| self.slot_targets.iter().find(|(_, rect)| rect.contains(p))).map(|(s, _)| *s);
            actions.push(Action::Open { paths: dropped, slot });
        }
        if let Some((slot, path)) = self.dialog.poll() {
            actions.push(Action::DialogClosed { slot, path });
        }
        let now = Instant::now();
        // Scene files are relative where the mesh path was (a command-line argument); the
        // watcher reports absolute paths.
        let referred =
            |path: &PathBuf| self.scene.files.iter().any(|f| std::path::absolute(f).is_ok_and(|f| f == *path));
        if self.watcher.changes().iter().any(|path| files::affects(&self.files.scene_files, path) || referred(path)) {
            self.files.debouncer.changed(now);
        }
        if let Some(finished) = self.files.loader.poll() {
            actions.push(Action::Loaded(Box::new(finished)));
        }
        // A reload waits for a load in flight (which wakes the UI when done), so that it does
        // not replace a mesh the user is opening.
        if self.files.loader.busy().is_none() {
            if self.files.debouncer.fire(now) {
                actions.push(Action::Reload);
            } else if let Some(wait) = self.files.debouncer.remaining(now) {
                ctx.request_repaint_after(wait);
            }
        }
        actions
    }

    /// Shows the 3D view filling `ui` and returns what the mouse did to it.
    fn view_area(&mut self, ui: &mut egui::Ui) -> Vec<Action> {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, egui::Sense::drag());
        let Some(size) = self.pixel_size(rect.size() * ui.ctx().pixels_per_point()) else {
            return Vec::new();
        };
        let id = self.ensure_view(size);
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        ui.painter().image(id, rect, uv, egui::Color32::WHITE);
        if self.state.shading.view == ViewMode::Difference {
            legend::difference(ui.painter(), rect, self.state.shading.difference_range_deg);
        }
        if self.state.split.enabled {
            if let Some(actions) = self.split_divider(ui, &response, rect) {
                return actions;
            }
        } else {
            self.dragging_divider = false;
        }
        self.probe.paint(ui.painter(), rect, size, &self.state.frame_params());
        let mut actions = input::viewport(&response, ui.ctx(), size);
        actions.extend(probe::clicked(ui.ctx(), rect, size));
        actions
    }

    /// Draws the split view's divider and labels over the view at `rect`; a drag that began
    /// within [`DIVIDER_GRAB_POINTS`] of the divider moves it (returned as the frame's actions,
    /// instead of orbiting), elsewhere the view's gestures work as usual (`None`).
    fn split_divider(&mut self, ui: &egui::Ui, response: &egui::Response, rect: egui::Rect) -> Option<Vec<Action>> {
        let split = self.state.split;
        let x = rect.left() + rect.width() * split.divider;
        let painter = ui.painter();
        painter.vline(x, rect.y_range(), egui::Stroke::new(2.0, egui::Color32::WHITE));
        let [left, right] = split.labels();
        let font = egui::FontId::proportional(15.0);
        let label_y = rect.top() + 8.0;
        for (text, anchor, pos) in [
            (left, egui::Align2::RIGHT_TOP, egui::pos2(x - 10.0, label_y)),
            (right, egui::Align2::LEFT_TOP, egui::pos2(x + 10.0, label_y)),
        ] {
            let galley = painter.layout_no_wrap(text, font.clone(), egui::Color32::WHITE);
            let text_rect = anchor.anchor_size(pos, galley.size());
            painter.rect_filled(text_rect.expand(4.0), 4.0, egui::Color32::from_black_alpha(170));
            painter.galley(text_rect.min, galley, egui::Color32::WHITE);
        }
        let near = |p: egui::Pos2| (p.x - x).abs() <= DIVIDER_GRAB_POINTS && rect.y_range().contains(p.y);
        if response.hover_pos().is_some_and(near) || self.dragging_divider {
            ui.ctx().set_cursor_icon(egui::CursorIcon::ResizeHorizontal);
        }
        if response.drag_started() {
            self.dragging_divider = ui.ctx().input(|i| i.pointer.press_origin()).is_some_and(near);
        }
        if !response.dragged() {
            self.dragging_divider = false;
            return None;
        }
        if !self.dragging_divider {
            return None;
        }
        let pointer = response.interact_pointer_pos()?;
        let fraction = ((pointer.x - rect.left()) / rect.width()).clamp(0.0, 1.0);
        Some(vec![Command::SetSplitDivider(fraction).into()])
    }

    /// Whole pixels for a view of `pixels`, within the adapter's limit; `None` when empty.
    fn pixel_size(&self, pixels: egui::Vec2) -> Option<[u32; 2]> {
        let limit = self.renderer.max_target_size();
        let side = |v: f32| (v.round() as u32).min(limit);
        let size = [side(pixels.x), side(pixels.y)];
        (size[0] > 0 && size[1] > 0).then_some(size)
    }

    /// Makes the view texture `size` pixels, recreating it only when the size changed.
    fn ensure_view(&mut self, size: [u32; 2]) -> egui::TextureId {
        if let Some(view) = self.view.as_ref().filter(|v| v.size == size) {
            return view.id;
        }
        let device = &self.render_state.device;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("3d view"),
            size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: VIEW_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[VIEW_RENDER_FORMAT],
        });
        let egui_view = texture.create_view(&Default::default());
        let render_view = texture
            .create_view(&wgpu::TextureViewDescriptor { format: Some(VIEW_RENDER_FORMAT), ..Default::default() });
        let mut egui_renderer = self.render_state.renderer.write();
        let id = match &self.view {
            Some(old) => {
                egui_renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    &egui_view,
                    wgpu::FilterMode::Linear,
                    old.id,
                );
                old.id
            }
            None => egui_renderer.register_native_texture(device, &egui_view, wgpu::FilterMode::Linear),
        };
        self.view = Some(ViewTexture { render_view, id, size });
        id
    }

    /// Advances the light orbit by the frame time and keeps frames coming while it runs.
    fn animate(&mut self, ctx: &egui::Context) {
        if self.state.is_animating() {
            let dt = ctx.input(|i| i.stable_dt).min(MAX_TICK_SECONDS);
            self.state.apply(Command::Tick(dt));
            ctx.request_repaint();
        }
    }

    /// Re-makes the GPU data whose options changed: the tangent method, bump source or
    /// conventions, or the split view's halves. (A kernel change re-makes the built-in scene:
    /// [`Self::rebuild_builtin`].)
    fn apply_methods(&mut self) {
        let wanted = self.state.scene_uploads();
        if wanted == self.uploaded {
            return;
        }
        if wanted.main != self.uploaded.main {
            self.renderer.set_scene(&self.scene, wanted.main.clone());
        }
        if wanted.split_right != self.uploaded.split_right {
            self.renderer.set_split_scene(&self.scene, wanted.split_right.clone());
        }
        let method = self.state.scene_options.tangent_method;
        if self.measurements_method != method {
            self.measurements = measure_all(&self.scene, method);
            self.measurements_method = method;
        }
        self.uploaded = wanted;
        self.tracker.invalidate();
    }

    /// Draws the 3D view into its texture, only when the picture or its size changed.
    fn draw_view(&mut self) {
        let Some(view) = &self.view else { return };
        let params = self.state.frame_params();
        let split = self.state.split_frame();
        if split != self.drawn_split {
            self.drawn_split = split;
            self.tracker.invalidate();
        }
        if !self.tracker.needs_redraw(&params, view.size) {
            return;
        }
        let target = RenderTarget { view: &view.render_view, format: VIEW_RENDER_FORMAT, size: view.size };
        let mut encoder = self.render_state.device.create_command_encoder(&Default::default());
        let drawn = match &split {
            Some(split) => self.renderer.render_split(&mut encoder, &target, &params, split, Background::Opaque),
            None => self.renderer.render(&mut encoder, &target, &params),
        };
        self.render_error = match drawn {
            Ok(()) => {
                self.render_state.queue.submit([encoder.finish()]);
                None
            }
            Err(e) => Some(e.to_string()),
        };
    }

    /// Renders the 3D view offscreen at the requested size (with the form's background and
    /// supersampling) and writes a fresh PNG in the current directory. Returns where it went,
    /// or why it failed.
    fn save_screenshot(&mut self) -> Result<String, String> {
        let view_size = match self.screenshot.size_text.trim() {
            "" => self.view.as_ref().map(|v| v.size).ok_or("the view has no size yet")?,
            text => crate::cli::args::parse_size(text)?,
        };
        let capture = CapturePreset { size: Some(view_size), ..self.screenshot.capture() };
        let options = capture.options(view_size);
        let params = self.state.frame_params();
        let image = match self.state.split_frame() {
            Some(split) => render_capture_split(&mut self.renderer, &options, &params, &split),
            None => render_capture(&mut self.renderer, &options, &params),
        }
        .map_err(|e| e.to_string())?;
        let path = unused_screenshot_path();
        write_png_atomically(&image, &path).map_err(|e| e.to_string())?;
        let shown = std::path::absolute(&path).unwrap_or(path);
        Ok(format!("wrote {} ({}x{})", shown.display(), view_size[0], view_size[1]))
    }

    /// Renders the tile export (the form's spec, else flat │ bumped │ Tangent view) with tiles
    /// of the screenshot size (else the view's) and writes a fresh PNG; captions as the form says.
    fn export_tiles(&mut self) -> Result<String, String> {
        let tile = match self.screenshot.size_text.trim() {
            "" => self.view.as_ref().map(|v| v.size).ok_or("the view has no size yet")?,
            text => crate::cli::args::parse_size(text)?,
        };
        let capture = CapturePreset { size: Some(tile), ..self.screenshot.capture() };
        let options = capture.options(tile);
        let grid = match self.screenshot.tiles_text.trim() {
            "" => TileGrid::default_row(&self.state.shading),
            spec => TileGrid::parse(spec, &self.state.shading)?,
        };
        // Tiles are single pictures: while a split view's left half has its own upload, the
        // current settings' upload stands in for the export.
        let current = &self.state.scene_options;
        let swapped = self.uploaded.main != *current;
        if swapped {
            self.renderer.set_scene(&self.scene, current.clone());
        }
        let captions: Option<Vec<_>> = capture.captions.then(|| {
            let caption = |s| export::caption(&self.renderer, &self.scene, current, s);
            grid.tiles.iter().map(caption).collect()
        });
        let params = self.state.frame_params();
        let image = export::render_grid(&mut self.renderer, &options, &params, &grid, captions.as_deref());
        if swapped {
            self.renderer.set_scene(&self.scene, self.uploaded.main.clone());
        }
        let image = image.map_err(|e| e.to_string())?;
        let path = unused_screenshot_path();
        write_png_atomically(&image, &path).map_err(|e| e.to_string())?;
        let shown = std::path::absolute(&path).unwrap_or(path);
        Ok(format!("wrote {} ({}x{}, {} tiles)", shown.display(), image.width(), image.height(), grid.tiles.len()))
    }

    /// The whole state, the scene's files and the screenshot settings as a preset.
    fn current_preset(&self) -> Preset {
        let files = self.files.scene_files.clone();
        Preset { capture: self.screenshot.capture(), ..Preset::from_state(&self.state, files) }
    }

    /// Shows a preset's state at once and loads its files in the background when they differ
    /// from the scene's (a reload: the preset's camera and light stay).
    fn load_preset(&mut self, path: &Path) -> Result<String, String> {
        let preset = Preset::load(path).map_err(|e| e.to_string())?;
        let mut state = preset.to_state(&self.scene).map_err(|e| e.to_string())?;
        state.default_camera = self.state.default_camera;
        let wanted = preset.files.absolute();
        let kernel = state.kernel;
        self.state = state;
        self.screenshot = ScreenshotForm::new(&preset.capture);
        self.tracker.invalidate();
        if (&wanted, kernel) != (&self.files.scene_files, self.files.kernel) {
            let done = format!("opened the files of {}", path.display());
            self.files.reload(wanted, kernel, done, self.waker());
        }
        Ok(format!("loaded {}", path.display()))
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Keys first, so the panel below already shows their effect.
        let keys = input::keyboard(&ctx);
        self.apply(keys);
        let arrivals = self.arrivals(&ctx);
        self.apply(arrivals);
        // The probe follows the picture where its point shows now: in the split view, that half's.
        if let (Some(size), true) = (self.view.as_ref().map(|v| v.size), self.probe.is_pinned()) {
            let column = self.probe.shown_at(&self.state.camera, size).map_or(0, |p| p.x.max(0.0) as u32);
            let (probe_params, probe_options, half) = self.state.picture_at(column, size[0]);
            let half = half.map(|i| format!("{}: {}", ["left", "right"][i], self.state.split.labels()[i]));
            self.probe.update(&self.scene, &probe_options, &probe_params, size, half);
        }
        let notices = self.renderer.notices();
        let stats = panel::Stats {
            measurements: &self.measurements,
            adapter: &self.adapter_name,
            view_size: self.view.as_ref().map(|v| v.size),
            counters: self.renderer.counters(),
            render_error: self.render_error.as_deref(),
            materials: &self.scene.materials,
            check: &self.check,
            check_warnings: &self.check_warnings,
            notices: &notices,
            probe: &self.probe,
        };
        let files = files_panel::FilesView {
            files: &self.files,
            dialog_open: self.dialog.is_open(),
            watch_error: self.watch_error.as_deref(),
            scene: &self.scene,
            tangents: &self.renderer.tangent_methods(),
        };
        let slot_targets = &mut self.slot_targets;
        let mut actions = egui::Panel::left("controls")
            .default_size(270.0)
            .show(ui, |ui| {
                let files_section = |ui: &mut egui::Ui, actions: &mut Vec<Action>| {
                    *slot_targets = files_panel::show(ui, &files, actions);
                };
                let forms = panel::Forms { screenshot: &mut self.screenshot, preset: &mut self.preset };
                panel::show(ui, &self.state, forms, &stats, files_section)
            })
            .inner;
        actions.extend(egui::CentralPanel::no_frame().show(ui, |ui| self.view_area(ui)).inner);
        files_panel::drop_hint(&ctx);
        self.apply(actions);
        self.apply_methods();
        self.animate(&ctx);
        self.draw_view();
        if let Some(exit) = &mut self.exit {
            exit.on_frame(&ctx, &self.render_state.device);
        }
    }

    /// Saves the state for the next start (see [`last_state_file`]).
    fn on_exit(&mut self) {
        if let Some(path) = &self.last_state {
            let saved = path.parent().map_or(Ok(()), std::fs::create_dir_all).map_err(|e| e.to_string());
            if let Err(e) = saved.and_then(|()| self.current_preset().save(path).map_err(|e| e.to_string())) {
                eprintln!("bumpview: last state not saved: {e}");
            }
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        // Opaque, so a window screenshot has no see-through pixels.
        visuals.panel_fill.to_normalized_gamma_f32()
    }
}

/// The files hot reload watches: the scene's (mesh, slot textures) and those the mesh file
/// referred to (buffers, material libraries, textures, also in other folders).
fn watched_files<'a>(scene_files: &'a SceneFiles, scene: &'a Scene) -> Vec<&'a Path> {
    let mut files = scene_files.paths();
    files.extend(scene.files.iter().map(PathBuf::as_path));
    files
}

/// Where the viewer keeps its state between runs: `last.toml`, a preset, next to the recent
/// list ([`files::recent_file`]).
pub fn last_state_file() -> Option<PathBuf> {
    files::recent_file().map(|recent| recent.with_file_name("last.toml"))
}

/// The chosen tangent method timed and compared with the reference on every mesh.
fn measure_all(scene: &Scene, method: Option<TangentMethod>) -> Vec<(String, MethodMeasurement)> {
    scene.meshes.iter().map(|mesh| (mesh.name.clone(), measure(mesh, method))).collect()
}

/// `bumpview-<unix seconds>.png` in the current directory, with `-1`, `-2`… added while
/// such a file exists.
fn unused_screenshot_path() -> PathBuf {
    let seconds = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let stem = format!("bumpview-{seconds}");
    let mut path = PathBuf::from(format!("{stem}.png"));
    let mut n = 0;
    while path.exists() {
        n += 1;
        path = PathBuf::from(format!("{stem}-{n}.png"));
    }
    path
}

/// Where `--exit-after` stands.
enum ExitStage {
    /// Counting presented frames.
    Counting,
    /// A window screenshot was requested; it arrives through the channel.
    Capturing { image: mpsc::Receiver<Arc<egui::ColorImage>>, path: PathBuf, frames_waited: u32 },
    /// Close was sent.
    Closing,
}

/// `--exit-after N [--capture-window PATH]`: keeps frames coming, closes after frame N,
/// optionally saving a screenshot of the whole window first.
struct ExitAfter {
    after: u64,
    presented: u64,
    capture: Option<PathBuf>,
    stage: ExitStage,
    /// Read by [`run`] after the window closed: why the capture failed.
    failure: Rc<RefCell<Option<String>>>,
}

impl ExitAfter {
    fn new(after: u64, capture: Option<PathBuf>, failure: Rc<RefCell<Option<String>>>) -> Self {
        ExitAfter { after, presented: 0, capture, stage: ExitStage::Counting, failure }
    }

    /// Called once per presented frame (each call to `App::ui`).
    fn on_frame(&mut self, ctx: &egui::Context, device: &wgpu::Device) {
        ctx.request_repaint();
        self.presented += 1;
        self.stage = match std::mem::replace(&mut self.stage, ExitStage::Closing) {
            ExitStage::Counting if self.presented >= self.after => match self.capture.take() {
                Some(path) => request_capture(ctx, path),
                None => self.close(ctx, None),
            },
            ExitStage::Capturing { image, path, frames_waited } => {
                self.poll_capture(ctx, device, image, path, frames_waited)
            }
            stage => stage,
        };
    }

    /// Saves the window screenshot once it has arrived, then closes; gives up after a while.
    fn poll_capture(
        &mut self,
        ctx: &egui::Context,
        device: &wgpu::Device,
        image: mpsc::Receiver<Arc<egui::ColorImage>>,
        path: PathBuf,
        frames_waited: u32,
    ) -> ExitStage {
        // The read-back completes on a device poll; make sure one happens.
        let _ = device.poll(wgpu::PollType::Poll);
        match image.try_recv() {
            Ok(image) => {
                let failure = save_window_image(&image, &path).err();
                self.close(ctx, failure)
            }
            Err(mpsc::TryRecvError::Empty) if frames_waited < CAPTURE_TIMEOUT_FRAMES => {
                ExitStage::Capturing { image, path, frames_waited: frames_waited + 1 }
            }
            Err(_) => self.close(ctx, Some(format!("the window screenshot for {} never arrived", path.display()))),
        }
    }

    /// Records the outcome for [`run`] and asks the window to close.
    fn close(&mut self, ctx: &egui::Context, failure: Option<String>) -> ExitStage {
        *self.failure.borrow_mut() = failure;
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        ExitStage::Closing
    }
}

/// Asks eframe for a screenshot of the next painted frame, delivered through a channel.
fn request_capture(ctx: &egui::Context, path: PathBuf) -> ExitStage {
    let (sender, image) = mpsc::channel();
    let callback = egui::ScreenshotCallback::new(move |image| {
        let _ = sender.send(image);
    });
    ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(callback));
    ExitStage::Capturing { image, path, frames_waited: 0 }
}

/// Writes a window screenshot from eframe as a PNG.
fn save_window_image(image: &egui::ColorImage, path: &Path) -> Result<(), String> {
    let [width, height] = image.size;
    let bytes = image.pixels.iter().flat_map(|p| p.to_srgba_unmultiplied()).collect();
    let rgba = image::RgbaImage::from_raw(width as u32, height as u32, bytes)
        .ok_or("window screenshot has the wrong number of pixels")?;
    write_png_atomically(&rgba, path).map_err(|e| e.to_string())
}
