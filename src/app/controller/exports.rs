//! Screenshots of the 3D view and tile exports: rendered offscreen at any size the adapter
//! allows, written atomically as fresh PNGs (`bumpview-<unix seconds>.png`). Not in the web build,
//! whose page cannot wait for the GPU read-back ([`crate::app::browser::NO_CAPTURE`]): there only the
//! form is kept (presets carry its settings).

#[cfg(not(target_arch = "wasm32"))]
use std::path::{Path, PathBuf};

#[cfg(not(target_arch = "wasm32"))]
use bumpview::render::capture::write_png_atomically;
use bumpview::render::export::parse_size;
#[cfg(not(target_arch = "wasm32"))]
use bumpview::render::export::{self, TileGrid};
use bumpview::state::preset::CapturePreset;

#[cfg(not(target_arch = "wasm32"))]
use super::Controller;

/// The screenshot size field, its options, the tile export's spec and the outcome of the last
/// screenshot or export.
pub struct ScreenshotForm {
    /// "WxH", or empty for the view's current pixel size.
    pub size_text: String,
    /// Alpha 0 where there is no geometry.
    pub transparent: bool,
    /// Render at this many times the size and downsample (1..=[`bumpview::render::capture::MAX_SUPERSAMPLE`]).
    pub supersample: u32,
    /// Tile exports get a caption strip under each tile.
    pub captions: bool,
    /// The tile export's spec ([`TileGrid::parse`]); empty: the default row.
    pub tiles_text: String,
    /// Where the last PNG went, or why it failed.
    pub message: Option<Result<String, String>>,
}

impl ScreenshotForm {
    pub fn new(capture: &CapturePreset) -> ScreenshotForm {
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
    pub fn capture(&self) -> CapturePreset {
        let size = parse_size(&self.size_text).ok();
        CapturePreset { size, transparent: self.transparent, supersample: self.supersample, captions: self.captions }
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl Controller {
    /// The form's size, else the view's.
    fn capture_size(&self) -> Result<[u32; 2], String> {
        match self.screenshot.size_text.trim() {
            "" => self.view_size.ok_or_else(|| "the view has no size yet".to_owned()),
            text => parse_size(text),
        }
    }

    /// Renders the 3D view offscreen at the requested size (with the form's background and
    /// supersampling) and writes a fresh PNG. Returns where it went, or why it failed.
    pub(super) fn save_screenshot(&mut self) -> Result<String, String> {
        let size = self.capture_size()?;
        let options = CapturePreset { size: Some(size), ..self.screenshot.capture() }.options(size);
        let params = self.state.frame_params();
        let split = self.state.split_frame();
        let labels = self.state.split.labels();
        let split = split.as_ref().map(|s| (s, [labels[0].as_str(), labels[1].as_str()]));
        let image = export::render_picture(&mut self.renderer, &options, &params, split).map_err(|e| e.to_string())?;
        let path = unused_screenshot_path(&self.screenshot_dir);
        write_png_atomically(&image, &path).map_err(|e| e.to_string())?;
        let shown = std::path::absolute(&path).unwrap_or(path);
        Ok(format!("wrote {} ({}x{})", shown.display(), size[0], size[1]))
    }

    /// Renders the tile export (the form's spec, else flat │ bumped │ Tangent view) with tiles
    /// of the screenshot size (else the view's) and writes a fresh PNG; captions as the form says.
    pub(super) fn export_tiles(&mut self) -> Result<String, String> {
        let tile = self.capture_size()?;
        let capture = CapturePreset { size: Some(tile), ..self.screenshot.capture() };
        let options = capture.options(tile);
        let grid = match self.screenshot.tiles_text.trim() {
            "" => TileGrid::default_row(&self.state.shading),
            spec => TileGrid::parse(spec, &self.state.shading).map_err(|e| e.to_string())?,
        };
        // Tiles are single pictures: while a split view's left half has its own upload, the
        // current settings' upload stands in for the export, and the held one comes back after.
        let current = self.state.scene_options_drawing(&grid.tiles);
        let held = self.renderer.prepared(false).filter(|p| p.options != current).cloned();
        if held.is_some() {
            self.renderer.set_scene(&self.scene, current.clone());
        }
        let captions: Option<Vec<_>> = capture.captions.then(|| {
            let caption = |s| export::caption(&self.renderer, &self.scene, &current, s);
            grid.tiles.iter().map(caption).collect()
        });
        let params = self.state.frame_params();
        let image = export::render_grid(&mut self.renderer, &options, &params, &grid, captions.as_deref());
        if let Some(held) = held {
            self.renderer.set_prepared(held);
        }
        let image = image.map_err(|e| e.to_string())?;
        let path = unused_screenshot_path(&self.screenshot_dir);
        write_png_atomically(&image, &path).map_err(|e| e.to_string())?;
        let shown = std::path::absolute(&path).unwrap_or(path);
        Ok(format!("wrote {} ({}x{}, {} tiles)", shown.display(), image.width(), image.height(), grid.tiles.len()))
    }

    /// Screenshots and exports go to `dir` instead of the current directory.
    #[cfg(test)]
    pub(super) fn set_screenshot_dir(&mut self, dir: PathBuf) {
        self.screenshot_dir = dir;
    }
}

/// `bumpview-<unix seconds>.png` in `dir` (empty: the current directory), with `-1`, `-2`…
/// added while such a file exists.
#[cfg(not(target_arch = "wasm32"))]
fn unused_screenshot_path(dir: &Path) -> PathBuf {
    let seconds = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let stem = format!("bumpview-{seconds}");
    let mut path = dir.join(format!("{stem}.png"));
    let mut n = 0;
    while path.exists() {
        n += 1;
        path = dir.join(format!("{stem}-{n}.png"));
    }
    path
}
