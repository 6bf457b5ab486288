//! The web build's start (wasm32, docs/web.md): the viewer in the page's canvas by eframe's web
//! runner, the page's fragment (`#lesson=NAME`, `#preset=…`, `#backend=webgl|webgpu`), dropped
//! files read and opened, and the marker the page tests wait for. What the rest of the viewer
//! asks of the browser (files held in memory, downloads) is [`super::browser`], a leaf.
//!
//! The page (web/index.html) has a `<canvas id="bumpview">`. Once the first frame of the scene
//! is drawn, the page's `<body>` gets `data-ready` (milliseconds since the page started),
//! `data-backend` (`webgpu` or `webgl`) and `data-view` (the 3D view's rectangle in CSS pixels,
//! `x,y,width,height`), and the title becomes "bumpview ready".

use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;

use bumpview::load::TextureSlot;
use bumpview::read::MEMORY_FOLDER;
use bumpview::scene::Scene;
use bumpview::state::ViewerState;
use bumpview::state::preset::Preset;
use wasm_bindgen::JsCast;

use super::action::Action;
use super::browser::hold;
use super::files::{FileKind, file_kind};
use super::{Options, ViewerApp};

/// The id of the page's canvas.
const CANVAS_ID: &str = "bumpview";

/// Starts the viewer in the page's canvas; what fails is written into the page.
pub fn start() {
    wasm_bindgen_futures::spawn_local(async {
        if let Err(message) = run().await {
            show_failure(&message);
        }
    });
}

/// The page's fragment: `key=value` pairs joined by `&`, the value percent-encoded.
fn fragment() -> Vec<(String, String)> {
    let hash = web_sys::window().and_then(|w| w.location().hash().ok()).unwrap_or_default();
    let decode = |v: &str| percent_encoding::percent_decode_str(v).decode_utf8_lossy().into_owned();
    hash.trim_start_matches('#')
        .split('&')
        .filter_map(|pair| pair.split_once('='))
        .map(|(key, value)| (key.to_owned(), decode(value)))
        .collect()
}

/// The viewer's start from the fragment's lesson (`lesson=NAME`, its whole state) or preset (the
/// defaults without either, or when it does not load: then the notice says why).
fn options(fragment: &[(String, String)]) -> Result<Options, String> {
    let value = |wanted: &str| fragment.iter().find(|(key, _)| key == wanted).map(|(_, value)| value);
    let given = match (value("lesson"), value("preset")) {
        (Some(name), _) => Some(lesson_preset(name).and_then(started).map(|s| (s, format!("lesson {name}")))),
        (None, Some(text)) => Some(
            Preset::from_toml(text)
                .map_err(|e| e.to_string())
                .and_then(started)
                .map(|s| (s, "preset from the page's address".to_owned())),
        ),
        (None, None) => None,
    };
    let ((preset, scene, state), notice) = match given {
        Some(Ok((started, notice))) => (started, Some(notice)),
        Some(Err(e)) => (started(Preset::default())?, Some(format!("the address's state was not used: {e}"))),
        None => (started(Preset::default())?, None),
    };
    Ok(Options {
        exit_after: None,
        capture_window: None,
        probe: None,
        scene,
        files: preset.files,
        state,
        capture: preset.capture,
        last_state: None,
        notice,
        lesson: None,
    })
}

/// The whole state of the built-in lesson `name` (`bumpview lessons` lists them).
fn lesson_preset(name: &str) -> Result<Preset, String> {
    let catalogue = bumpview::lessons::catalogue().map_err(|e| e.to_string())?;
    let lesson = catalogue.iter().find(|l| l.name == name).ok_or(format!("no lesson named {name}"))?;
    Ok(lesson.viewer_preset().clone())
}

/// `preset`, its scene and its state; the error says what did not load.
fn started(preset: Preset) -> Result<(Preset, Scene, ViewerState), String> {
    let scene = preset.build_scene().map_err(|e| e.to_string())?;
    let state = preset.to_state(&scene).map_err(|e| e.to_string())?;
    Ok((preset, scene, state))
}

/// The graphics backends the fragment asks for (`backend=webgl` or `webgpu`); both otherwise,
/// WebGPU first where the browser has it.
fn backends(fragment: &[(String, String)]) -> wgpu::Backends {
    match fragment.iter().find(|(key, _)| key == "backend").map(|(_, value)| value.as_str()) {
        Some("webgl") => wgpu::Backends::GL,
        Some("webgpu") => wgpu::Backends::BROWSER_WEBGPU,
        _ => wgpu::Backends::BROWSER_WEBGPU | wgpu::Backends::GL,
    }
}

async fn run() -> Result<(), String> {
    let document = web_sys::window().and_then(|w| w.document()).ok_or("no document")?;
    let canvas = document
        .get_element_by_id(CANVAS_ID)
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        .ok_or(format!("the page has no <canvas id=\"{CANVAS_ID}\">"))?;
    let fragment = fragment();
    let options = options(&fragment)?;
    let mut web_options = eframe::WebOptions::default();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = &mut web_options.wgpu_options.wgpu_setup {
        create.instance_descriptor.backends = backends(&fragment);
    }
    super::request_device_extras(&mut web_options.wgpu_options.wgpu_setup);
    let failure = Rc::new(RefCell::new(None));
    eframe::WebRunner::new()
        .start(canvas, web_options, Box::new(move |cc| Ok(Box::new(ViewerApp::new(cc, options, failure)?))))
        .await
        .map_err(|e| format!("the viewer did not start: {e:?}"))
}

/// Writes `message` into the page (its `#status` element, else the body's text).
fn show_failure(message: &str) {
    let Some(document) = web_sys::window().and_then(|w| w.document()) else { return };
    if let Some(status) = document.get_element_by_id("status") {
        status.set_text_content(Some(message));
    }
    if let Some(body) = document.body() {
        let _ = body.set_attribute("data-failed", message);
    }
}

/// What to do with the files held at `paths`, dropped into `slot`: a preset (`.toml`) is loaded;
/// a glTF dropped with its `.bin` and textures is opened alone (its relative URIs find the
/// others beside it); without a mesh, the images are opened into the slots.
fn to_open(paths: Vec<PathBuf>, slot: Option<TextureSlot>) -> Action {
    if let Some(preset) = paths.iter().find(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"))) {
        return Action::LoadPreset(preset.clone());
    }
    let meshes: Vec<PathBuf> = paths.iter().filter(|p| file_kind(p) == Some(FileKind::Mesh)).cloned().collect();
    Action::Open { paths: if meshes.is_empty() { paths } else { meshes }, slot }
}

/// Where the page stands: the backend the browser gave, the view's place, files being read, the
/// ready marker.
pub struct Page {
    backend: wgpu::Backend,
    /// The 3D view's rectangle last laid out (points, which are CSS pixels).
    view: Option<egui::Rect>,
    ready: bool,
    /// Asks for a frame (when dropped files have been read).
    wake: Rc<dyn Fn()>,
    /// Dropped files read, to open.
    arrived: Rc<RefCell<Vec<Action>>>,
}

impl Page {
    /// The page drawing through `backend`; `wake` asks for a frame.
    pub fn new(backend: wgpu::Backend, wake: impl Fn() + 'static) -> Page {
        Page { backend, view: None, ready: false, wake: Rc::new(wake), arrived: Rc::default() }
    }

    /// Reads dropped `files` (asynchronously, as browsers do), holds them in memory and then
    /// has them opened ([`Page::arrived`]), into `slot` if they were dropped on its button. A
    /// file that cannot be read is named in the panel's status by the loader's "could not
    /// read" (it is opened without bytes held).
    pub fn read_dropped(&self, files: Vec<egui::DroppedFileHandle>, slot: Option<TextureSlot>) {
        let (arrived, wake) = (Rc::clone(&self.arrived), Rc::clone(&self.wake));
        wasm_bindgen_futures::spawn_local(async move {
            let mut paths = Vec::new();
            for file in files {
                let name = file.path().to_string_lossy().into_owned();
                match file.bytes_async().await {
                    Ok(bytes) => paths.push(hold(&name, bytes)),
                    Err(_) => paths.push(PathBuf::from(MEMORY_FOLDER).join(name)),
                }
            }
            arrived.borrow_mut().push(to_open(paths, slot));
            wake();
        });
    }

    /// The dropped files read since the last call, to open.
    pub fn arrived(&self) -> Vec<Action> {
        std::mem::take(&mut *self.arrived.borrow_mut())
    }

    /// Where the 3D view was laid out this frame.
    pub fn set_view(&mut self, rect: egui::Rect) {
        self.view = Some(rect);
    }

    /// The backend's name in the page's marker and the panel.
    pub fn backend(&self) -> &'static str {
        if self.backend == wgpu::Backend::BrowserWebGpu { "webgpu" } else { "webgl" }
    }

    /// After a frame: once the scene asked for is drawn (`settled`), marks the page ready (see
    /// the module doc).
    pub fn on_frame(&mut self, settled: bool) {
        let (false, true, Some(view)) = (self.ready, settled, self.view) else { return };
        let Some(window) = web_sys::window() else { return };
        let Some(document) = window.document() else { return };
        let Some(body) = document.body() else { return };
        let since_start = window.performance().map_or(0.0, |p| p.now());
        let rect = format!("{},{},{},{}", view.min.x, view.min.y, view.width(), view.height());
        let _ = body.set_attribute("data-view", &rect);
        let _ = body.set_attribute("data-backend", self.backend());
        let _ = body.set_attribute("data-ready", &format!("{since_start:.0}"));
        document.set_title("bumpview ready");
        self.ready = true;
    }
}
