//! The eframe/egui viewer: a thin layer over the library. The panel ([`panel`]) and the
//! keyboard and mouse ([`input`]) only produce [`Action`]s; [`ViewerApp::apply`] is the one
//! place they take effect. The 3D view is drawn by [`Renderer`] into an offscreen texture
//! that egui shows as an image, and only when the picture would change.

mod input;
mod legend;
mod panel;

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::{Arc, mpsc};

use bumpview::height::Kernel;
use bumpview::render::capture::{render_image, write_png_atomically};
use bumpview::render::{RenderTarget, Renderer, SceneOptions};
use bumpview::scene::Scene;
use bumpview::scene::builtin::teaching_scene_with_kernel;
use bumpview::shading::ViewMode;
use bumpview::tangent::{MethodMeasurement, TangentMethod, measure};
use bumpview::viewer::{Command, RedrawTracker, ViewerState};
use eframe::egui_wgpu::RenderState;

/// How the viewer is started; see `--exit-after` and `--capture-window`.
pub struct Options {
    /// Close after this many presented frames.
    pub exit_after: Option<u64>,
    /// With `exit_after`: save a screenshot of the whole window here before closing.
    pub capture_window: Option<PathBuf>,
    /// Tangent method and bump source to start with.
    pub scene_options: SceneOptions,
    /// Height→normal kernel of the built-in brick normal map to start with.
    pub kernel: Kernel,
    /// A loaded scene (mesh and/or textures from files); `None`: the built-in scene.
    pub scene: Option<Scene>,
}

/// Something the user asked for: a library [`Command`] or an app-only action.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Action {
    /// A change to the viewer state.
    Viewer(Command),
    /// Save a PNG of the 3D view (F12 or the panel button).
    Screenshot,
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

    let failure = Rc::new(RefCell::new(None));
    let app_failure = Rc::clone(&failure);
    eframe::run_native("bumpview", native, Box::new(move |cc| Ok(Box::new(ViewerApp::new(cc, options, app_failure)?))))
        .map_err(|e| format!("viewer: {e}"))?;
    failure.take().map_or(Ok(()), Err)
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

/// The screenshot size field and the outcome of the last screenshot.
#[derive(Default)]
struct ScreenshotForm {
    /// "WxH", or empty for the view's current pixel size.
    size_text: String,
    /// Where the last PNG went, or why it failed.
    message: Option<Result<String, String>>,
}

/// The eframe app: viewer state, the renderer on eframe's device, and the view texture.
struct ViewerApp {
    state: ViewerState,
    scene: Scene,
    /// The scene is the built-in one, re-made when the kernel changes.
    builtin: bool,
    /// The options and kernel the renderer's scene was made with.
    uploaded: (SceneOptions, Kernel),
    /// Per mesh: the chosen tangent method timed and compared with the reference.
    measurements: Vec<(String, MethodMeasurement)>,
    renderer: Renderer,
    render_state: RenderState,
    adapter_name: String,
    view: Option<ViewTexture>,
    tracker: RedrawTracker,
    screenshot: ScreenshotForm,
    render_error: Option<String>,
    exit: Option<ExitAfter>,
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
        let builtin = options.scene.is_none();
        let scene = options.scene.unwrap_or_else(|| teaching_scene_with_kernel(options.kernel));
        renderer.set_scene(&scene, options.scene_options);
        let adapter_name = renderer.adapter_name();
        let mut state = ViewerState::new(&scene);
        state.scene_options = options.scene_options;
        state.kernel = options.kernel;
        Ok(ViewerApp {
            measurements: measure_all(&scene, options.scene_options.tangent_method),
            uploaded: (options.scene_options, options.kernel),
            scene,
            builtin,
            state,
            renderer,
            adapter_name,
            render_state,
            view: None,
            tracker: RedrawTracker::default(),
            screenshot: ScreenshotForm::default(),
            render_error: None,
            exit: options.exit_after.map(|frames| ExitAfter::new(frames, options.capture_window, failure)),
        })
    }

    /// The one place actions take effect.
    fn apply(&mut self, actions: Vec<Action>) {
        for action in actions {
            match action {
                Action::Viewer(command) => self.state.apply(command),
                Action::Screenshot => self.screenshot.message = Some(self.save_screenshot()),
            }
        }
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
        input::viewport(&response, ui.ctx(), size)
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

    /// Re-makes the normal map (built-in scene only) and the tangent frames when their method
    /// changed.
    fn apply_methods(&mut self) {
        let wanted = (self.state.scene_options, self.state.kernel);
        if wanted == self.uploaded {
            return;
        }
        if self.builtin && wanted.1 != self.uploaded.1 {
            self.scene = teaching_scene_with_kernel(wanted.1);
        }
        self.renderer.set_scene(&self.scene, wanted.0);
        self.measurements = measure_all(&self.scene, wanted.0.tangent_method);
        self.uploaded = wanted;
        self.tracker.invalidate();
    }

    /// Draws the 3D view into its texture, only when the picture or its size changed.
    fn draw_view(&mut self) {
        let Some(view) = &self.view else { return };
        let params = self.state.frame_params();
        if !self.tracker.needs_redraw(&params, view.size) {
            return;
        }
        let target = RenderTarget { view: &view.render_view, format: VIEW_RENDER_FORMAT, size: view.size };
        let mut encoder = self.render_state.device.create_command_encoder(&Default::default());
        self.render_error = match self.renderer.render(&mut encoder, &target, &params) {
            Ok(()) => {
                self.render_state.queue.submit([encoder.finish()]);
                None
            }
            Err(e) => Some(e.to_string()),
        };
    }

    /// Renders the 3D view offscreen at the requested size and writes a fresh PNG in the
    /// current directory. Returns where it went, or why it failed.
    fn save_screenshot(&mut self) -> Result<String, String> {
        let size = match self.screenshot.size_text.trim() {
            "" => self.view.as_ref().map(|v| v.size).ok_or("the view has no size yet")?,
            text => crate::args::parse_size(text)?,
        };
        let image = render_image(&mut self.renderer, size, &self.state.frame_params()).map_err(|e| e.to_string())?;
        let path = unused_screenshot_path();
        write_png_atomically(&image, &path).map_err(|e| e.to_string())?;
        let shown = std::path::absolute(&path).unwrap_or(path);
        Ok(format!("wrote {} ({}x{})", shown.display(), size[0], size[1]))
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Keys first, so the panel below already shows their effect.
        let keys = input::keyboard(&ctx);
        self.apply(keys);
        let stats = panel::Stats {
            measurements: &self.measurements,
            adapter: &self.adapter_name,
            view_size: self.view.as_ref().map(|v| v.size),
            counters: self.renderer.counters(),
            render_error: self.render_error.as_deref(),
        };
        let mut actions = egui::Panel::left("controls")
            .default_size(270.0)
            .show(ui, |ui| panel::show(ui, &self.state, &mut self.screenshot, &stats))
            .inner;
        actions.extend(egui::CentralPanel::no_frame().show(ui, |ui| self.view_area(ui)).inner);
        self.apply(actions);
        self.apply_methods();
        self.animate(&ctx);
        self.draw_view();
        if let Some(exit) = &mut self.exit {
            exit.on_frame(&ctx, &self.render_state.device);
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        // Opaque, so a window screenshot has no see-through pixels.
        visuals.panel_fill.to_normalized_gamma_f32()
    }
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
