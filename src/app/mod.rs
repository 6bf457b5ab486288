//! The eframe/egui viewer: a thin layer over the library in three parts. The windowless
//! [`controller`] holds the state, the scene, the renderer and the files, and is the one place
//! [`Action`]s take effect; the [`view`] shows the 3D view (a texture the controller draws
//! into, only when the picture would change) with its overlays and turns the mouse into
//! actions; the [`panel`] and the keys produce actions too. [`automation`] runs the
//! command line's `--probe`, `--exit-after` and `--capture-window`.

mod action;
mod automation;
#[cfg(target_arch = "wasm32")]
mod browser;
mod controller;
mod dialog;
mod files;
mod panel;
mod probe;
mod view;
mod watch;
#[cfg(target_arch = "wasm32")]
pub mod web;

use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;
use std::time::Duration;

use web_time::Instant;

use bumpview::lessons::Lesson;
use bumpview::load::{SceneFiles, TextureSlot};
use bumpview::render::Renderer;
use bumpview::scene::Scene;
use bumpview::state::ViewerState;
use bumpview::state::preset::CapturePreset;
#[cfg(not(target_arch = "wasm32"))]
pub use controller::last_state_file;

use action::Action;
use automation::Automation;
use controller::{Controller, Start};
use view::View;

/// How the viewer is started.
pub struct Options {
    /// Close after this many presented frames.
    pub exit_after: Option<u64>,
    /// With `exit_after`: save a screenshot of the whole window here before closing.
    pub capture_window: Option<PathBuf>,
    /// Pin the probe at this pixel of the 3D view once it is laid out.
    pub probe: Option<[u32; 2]>,
    /// The scene to start with (the built-in one, or made from `files`).
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
    /// A lesson file to show with its card (`state` is its state).
    pub lesson: Option<Lesson>,
}

/// Longest frame step fed to animations, so a stall does not make the light jump.
const MAX_TICK_SECONDS: f32 = 0.1;
/// After an interactive frame the UI runs again within this long, so the full-quality frame
/// follows when input stops even if no further event arrives.
const INTERACTIVE_RECHECK: Duration = Duration::from_millis(100);

/// Opens the viewer window and runs until it is closed.
#[cfg(not(target_arch = "wasm32"))]
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
/// mode (the wireframe overlay) and BC texture sampling (a file's blocks as they are) where the
/// adapter has them, and the adapter's full texture size (screenshots up to its limit; egui
/// asks for 8192 only).
fn request_device_extras(setup: &mut eframe::egui_wgpu::WgpuSetup) {
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        let base = Arc::clone(&create.device_descriptor);
        create.device_descriptor = Arc::new(move |adapter| {
            let mut descriptor = base(adapter);
            let wanted = wgpu::Features::POLYGON_MODE_LINE | wgpu::Features::TEXTURE_COMPRESSION_BC;
            descriptor.required_features |= adapter.features() & wanted;
            descriptor.required_limits.max_texture_dimension_2d = adapter.limits().max_texture_dimension_2d;
            descriptor
        });
    }
}

/// The eframe app: the controller, the 3D view and the automation, wired to egui's frames.
struct ViewerApp {
    controller: Controller,
    view: View,
    automation: Automation,
    /// Where the panel's slot buttons were last drawn, for files dropped on them.
    slot_targets: Vec<(TextureSlot, egui::Rect)>,
    /// Whether the window was last asked to be full-screen (the controller's wish, sent once).
    fullscreen: bool,
    /// The web page's ready marker.
    #[cfg(target_arch = "wasm32")]
    page: web::Page,
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
        let renderer =
            Renderer::new(render_state.device.clone(), render_state.queue.clone(), render_state.adapter.clone());
        cc.egui_ctx.set_fonts(fonts());
        let ctx = cc.egui_ctx.clone();
        #[cfg(target_arch = "wasm32")]
        let wake_page = {
            let ctx = ctx.clone();
            move || ctx.request_repaint()
        };
        let wake = Arc::new(move || ctx.request_repaint());
        let start = Start {
            scene: options.scene,
            state: options.state,
            files: options.files,
            capture: options.capture,
            last_state: options.last_state,
            recent_file: files::recent_file(),
            notice: options.notice,
            lesson: options.lesson,
        };
        Ok(ViewerApp {
            controller: Controller::new(start, renderer, wake),
            view: View::new(render_state.clone()),
            automation: Automation::new(options.probe, options.exit_after, options.capture_window, failure),
            slot_targets: Vec::new(),
            fullscreen: false,
            #[cfg(target_arch = "wasm32")]
            page: web::Page::new(render_state.adapter.get_info().backend, wake_page),
        })
    }

    /// Files dropped on the window this frame: into the slot button they were dropped on, if
    /// any.
    #[cfg(not(target_arch = "wasm32"))]
    fn dropped_files(&self, ctx: &egui::Context) -> Option<Action> {
        let (paths, pointer) = ctx.input(|i| {
            (i.raw.dropped_files.iter().map(|f| f.path().to_owned()).collect::<Vec<_>>(), i.pointer.latest_pos())
        });
        if paths.is_empty() {
            return None;
        }
        Some(Action::Open { paths, slot: self.slot_at(pointer) })
    }

    /// Files dropped on the page this frame: the browser gives bytes to read, no paths, so they
    /// are opened once read ([`web::Page::arrived`]).
    #[cfg(target_arch = "wasm32")]
    fn dropped_files(&mut self, ctx: &egui::Context) -> Option<Action> {
        let (files, pointer) = ctx.input(|i| (i.raw.dropped_files.clone(), i.pointer.latest_pos()));
        if !files.is_empty() {
            self.page.read_dropped(files, self.slot_at(pointer));
        }
        None
    }

    /// The slot button at `pointer`, if any.
    fn slot_at(&self, pointer: Option<egui::Pos2>) -> Option<TextureSlot> {
        pointer.and_then(|p| self.slot_targets.iter().find(|(_, rect)| rect.contains(p))).map(|(s, _)| *s)
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Keys and arrivals first, so the panel below already shows their effect.
        self.controller.apply(view::input::keyboard(&ctx));
        let dropped = self.dropped_files(&ctx);
        self.controller.apply(dropped);
        #[cfg(target_arch = "wasm32")]
        self.controller.apply(self.page.arrived());
        self.controller.apply(self.automation.pending_probe(self.view.size()));
        if let Some(wait) = self.controller.poll_background(Instant::now()) {
            ctx.request_repaint_after(wait);
        }
        self.controller.refresh_probe();
        self.controller.tell_budget();
        let fullscreen = self.controller.lessons.fullscreen;
        if fullscreen != self.fullscreen {
            ctx.send_viewport_cmd(egui::ViewportCommand::Fullscreen(fullscreen));
            self.fullscreen = fullscreen;
        }
        let (mut actions, slot_targets) = if self.controller.lessons.panel_hidden {
            (vec![], vec![])
        } else {
            egui::Panel::left("controls")
                .default_size(290.0)
                .show(ui, |ui| panel::show(ui, &mut self.controller, self.view.render_error()))
                .inner
        };
        self.slot_targets = slot_targets;
        let central = egui::CentralPanel::no_frame().show(ui, |ui| self.view.show(ui, &self.controller));
        #[cfg(target_arch = "wasm32")]
        self.page.set_view(central.response.rect);
        actions.extend(central.inner);
        self.controller.set_view_size(self.view.size());
        panel::drop_hint(&ctx);
        self.controller.apply(actions);
        if self.controller.animate(ctx.input(|i| i.stable_dt).min(MAX_TICK_SECONDS)) {
            ctx.request_repaint();
        }
        // Interactive frames while a widget or the view is dragged, the view zoomed or the
        // light orbits; the frame after one is drawn again (at full quality once input stops).
        let active = ctx.dragged_id().is_some()
            || ctx.input(|i| i.smooth_scroll_delta != egui::Vec2::ZERO)
            || self.controller.state.is_animating();
        if self.view.draw(&mut self.controller, active) {
            ctx.request_repaint_after(INTERACTIVE_RECHECK);
        }
        // The scene asked for, and a lesson's number and grid tiles, are all drawn.
        let settled = self.controller.busy().is_none() && !self.controller.lessons.pending();
        self.automation.on_frame(&ctx, self.controller.renderer().device(), settled);
        #[cfg(target_arch = "wasm32")]
        self.page.on_frame(settled);
    }

    /// Saves the state for the next start (see [`last_state_file`]).
    fn on_exit(&mut self) {
        self.controller.save_last_state();
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        // Opaque, so a window screenshot has no see-through pixels.
        visuals.panel_fill.to_normalized_gamma_f32()
    }
}

/// egui's default fonts with Hack behind the proportional face: Ubuntu Light has no "│" or "→"
/// (lesson titles such as "Bump mapping off │ on" and "Height → normal"), Hack draws both.
fn fonts() -> egui::FontDefinitions {
    let mut fonts = egui::FontDefinitions::default();
    fonts.families.entry(egui::FontFamily::Proportional).or_default().push("Hack".to_owned());
    fonts
}

#[cfg(test)]
mod tests {
    /// Every character of the built-in lessons' titles, captions, claims and labels has a glyph in the panel's
    /// proportional face (without the fallback, "│" and "→" were drawn as boxes).
    #[test]
    fn lesson_texts_have_glyphs_in_the_panel_font() {
        let ctx = egui::Context::default();
        ctx.set_fonts(super::fonts());
        ctx.run_ui(Default::default(), |_| {}).textures_delta.clear();
        let font = egui::FontId::proportional(14.0);
        for lesson in bumpview::lessons::catalogue().expect("the built-in lessons read") {
            let labels = lesson.sides.iter().map(|side| side.label.as_str());
            let text: String =
                [&lesson.title, &lesson.caption, &lesson.claim].map(String::as_str).into_iter().chain(labels).collect();
            let missing: String = text.chars().filter(|&c| !ctx.fonts_mut(|f| f.has_glyph(&font, c))).collect();
            assert!(missing.is_empty(), "{:?}: no glyph for {missing:?}", lesson.title);
        }
    }
}
