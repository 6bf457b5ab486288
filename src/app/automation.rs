//! The viewer driven by its command line for scripts, tests and screenshots: `--probe X,Y`
//! pins the probe once the view has a size, `--exit-after N [--capture-window PATH]` closes
//! after N presented frames of the scene (frames while its scene job runs, or a lesson's number
//! or grid tiles are on their way, do not count),
//! optionally saving a screenshot of the whole window first.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::{Arc, mpsc};

use bumpview::render::capture::write_png_atomically;

use super::action::Action;

/// Frames to wait for a requested window screenshot before giving up.
const CAPTURE_TIMEOUT_FRAMES: u32 = 600;

/// What the command line asked the window to do by itself.
pub struct Automation {
    /// `--probe`: the view pixel to pin the probe at, until the view has a size.
    probe: Option<[u32; 2]>,
    exit: Option<ExitAfter>,
}

impl Automation {
    /// `probe`: pin the probe at this view pixel; `exit_after`: close after that many frames,
    /// saving the window to `capture_window` first; why a capture failed goes to `failure`.
    pub fn new(
        probe: Option<[u32; 2]>,
        exit_after: Option<u64>,
        capture_window: Option<PathBuf>,
        failure: Rc<RefCell<Option<String>>>,
    ) -> Automation {
        Automation { probe, exit: exit_after.map(|frames| ExitAfter::new(frames, capture_window, failure)) }
    }

    /// The probe to pin once the view is `view_size` pixels (the pixel clamped into it).
    pub fn pending_probe(&mut self, view_size: Option<[u32; 2]>) -> Option<Action> {
        let size = view_size?;
        let [x, y] = self.probe.take()?;
        Some(Action::PinProbe { pixel: [x.min(size[0] - 1), y.min(size[1] - 1)], size })
    }

    /// Called once per presented frame (each call to `App::ui`); `settled`: no scene job is
    /// in flight, so the frame shows the scene asked for.
    pub fn on_frame(&mut self, ctx: &egui::Context, device: &wgpu::Device, settled: bool) {
        if let Some(exit) = &mut self.exit {
            exit.on_frame(ctx, device, settled);
        }
    }
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

/// `--exit-after N [--capture-window PATH]`: keeps frames coming, closes after the N-th frame
/// showing the scene, optionally saving a screenshot of the whole window first.
struct ExitAfter {
    after: u64,
    presented: u64,
    capture: Option<PathBuf>,
    stage: ExitStage,
    /// Read by [`super::run`] after the window closed: why the capture failed.
    failure: Rc<RefCell<Option<String>>>,
}

impl ExitAfter {
    fn new(after: u64, capture: Option<PathBuf>, failure: Rc<RefCell<Option<String>>>) -> Self {
        ExitAfter { after, presented: 0, capture, stage: ExitStage::Counting, failure }
    }

    fn on_frame(&mut self, ctx: &egui::Context, device: &wgpu::Device, settled: bool) {
        ctx.request_repaint();
        if !settled && matches!(self.stage, ExitStage::Counting) {
            return;
        }
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

    /// Records the outcome for [`super::run`] and asks the window to close.
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
