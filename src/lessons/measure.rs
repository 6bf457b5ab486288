//! Drawing a lesson's sides the way `bumpview render` draws a preset (the same capture path:
//! [`render_capture`] / [`render_capture_split`]) and measuring how much they differ.

use image::RgbaImage;

use super::inset::{self, Inset};
use super::{CHANGED_STEP, Lesson, Side};
use crate::error::RenderError;
use crate::frame::SceneUploads;
use crate::height::Kernel;
use crate::load::SceneFiles;
use crate::render::capture::{CaptureOptions, render_capture, render_capture_split};
use crate::render::{PictureWindow, Renderer};
use crate::scene::{Lights, OrbitCamera, Scene};
use crate::state::preset::{Preset, PresetSceneError};
use crate::state::{Command, ViewerState};

/// Why a lesson could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum LessonRenderError {
    #[error("lesson {0}: {1}")]
    Scene(String, PresetSceneError),
    #[error("lesson {0}: {1}")]
    Render(String, RenderError),
}

/// The scenes lessons were drawn on, kept so that lessons on the same files share one, and
/// what was last uploaded to the one renderer they are drawn with, so that pictures of the same
/// scene and uploads (a split's halves and the split itself) prepare it once.
#[derive(Default)]
pub struct SceneCache {
    scenes: Vec<((SceneFiles, Kernel), Scene)>,
    uploaded: Option<(usize, SceneUploads)>,
}

impl SceneCache {
    /// The index of the scene of `preset`'s files and kernel, made once.
    fn index(&mut self, preset: &Preset) -> Result<usize, PresetSceneError> {
        let key = (preset.files.clone(), preset.kernel()?);
        if let Some(i) = self.scenes.iter().position(|(k, _)| *k == key) {
            return Ok(i);
        }
        let scene = preset.build_scene()?;
        self.scenes.push((key, scene));
        Ok(self.scenes.len() - 1)
    }

    /// Drops every scene that none of `lessons` is drawn on (a deck drawn in order keeps only
    /// what its later slides need; the renderer keeps what it has uploaded).
    pub fn keep_only<'a>(&mut self, lessons: impl IntoIterator<Item = &'a Lesson>) {
        let wanted: Vec<(SceneFiles, Kernel)> = lessons
            .into_iter()
            .flat_map(|lesson| &lesson.sides)
            .filter_map(|side| Some((side.preset.files.clone(), side.preset.kernel().ok()?)))
            .collect();
        let before = self.scenes.len();
        self.scenes.retain(|(key, _)| wanted.contains(key));
        if self.scenes.len() != before {
            // The indices moved: the next draw uploads again.
            self.uploaded = None;
        }
    }

    /// The renderer was replaced by a new one: the next draw uploads its scene again.
    pub fn renderer_replaced(&mut self) {
        self.uploaded = None;
    }

    /// Gives `renderer` scene `index` with `uploads`, unless it has them already.
    fn upload(&mut self, renderer: &mut Renderer, index: usize, uploads: SceneUploads) {
        let wanted = Some((index, uploads));
        if self.uploaded != wanted {
            let (index, uploads) = wanted.as_ref().expect("just made");
            renderer.set_scene_uploads(&self.scenes[*index].1, uploads);
            self.uploaded = wanted;
        }
    }
}

/// A lesson drawn: each side's picture, and the measured share of changed pixels.
pub struct Measured {
    /// One picture per side, in order, `size` pixels each.
    pub sides: Vec<RgbaImage>,
    /// For a split: the split picture itself (divider where the preset puts it).
    pub split: Option<RgbaImage>,
    /// The smallest share of changed pixels between neighbouring sides, percent.
    pub changed_percent: f32,
    /// For a lesson with an inset: the window where the sides differ most, magnified.
    pub inset: Option<Inset>,
}

/// Draws every side of `lesson` at `size` pixels (4× MSAA, no supersampling, as `render`)
/// and measures [`changed_percent`] between neighbouring sides; with `split_picture`, a split
/// lesson's split picture as well; for a lesson with an inset, each side magnified
/// ([`inset`]).
pub fn measure(
    renderer: &mut Renderer,
    scenes: &mut SceneCache,
    lesson: &Lesson,
    size: [u32; 2],
    split_picture: bool,
) -> Result<Measured, LessonRenderError> {
    let sides = lesson
        .sides
        .iter()
        .map(|side| draw(renderer, scenes, lesson, side, size, false, None))
        .collect::<Result<Vec<_>, _>>()?;
    let split = match lesson.sides.first() {
        Some(side) if lesson.split && split_picture => Some(draw(renderer, scenes, lesson, side, size, true, None)?),
        _ => None,
    };
    let changed_percent = sides.windows(2).map(|pair| changed_percent(&pair[0], &pair[1])).fold(100.0, f32::min);
    let inset = match lesson.inset {
        Some(zoom) => {
            let shown = inset::inset_size(lesson, size);
            let window = inset::most_different_window(&sides, inset::window_size(shown, zoom, size));
            // Only the window is drawn, magnified to the inset's size.
            let magnified = lesson.sides.iter().map(|side| {
                renderer.set_window(Some(PictureWindow { picture: size, window }));
                let picture = draw(renderer, scenes, lesson, side, shown, false, None);
                renderer.set_window(None);
                picture
            });
            Some(Inset { window, sides: magnified.collect::<Result<_, LessonRenderError>>()? })
        }
        None => None,
    };
    Ok(Measured { sides, split, changed_percent, inset })
}

/// The viewer's camera and lights now, laid over a lesson's sides so that a grid shown live
/// turns and is lit as one picture ([`draw_sides_live`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiveLook {
    pub camera: OrbitCamera,
    pub lights: Lights,
}

/// Every side of `lesson` drawn at `size` pixels as [`measure`] draws them, with the viewer's
/// `look` laid over each: a side that views or lights the scene as the lesson opens in the
/// viewer ([`Lesson::viewer_preset`]) follows the viewer's camera or lights, one that sets
/// its own (a tile of other lights) keeps them.
pub fn draw_sides_live(
    renderer: &mut Renderer,
    scenes: &mut SceneCache,
    lesson: &Lesson,
    size: [u32; 2],
    look: &LiveLook,
) -> Result<Vec<RgbaImage>, LessonRenderError> {
    let opened = side_state(scenes, lesson, lesson.viewer_preset())?.1;
    let overlay = |state: &mut ViewerState| {
        if state.camera == opened.camera {
            state.camera = look.camera;
        }
        if state.lights == opened.lights {
            state.lights = look.lights;
        }
    };
    lesson.sides.iter().map(|side| draw(renderer, scenes, lesson, side, size, false, Some(&overlay))).collect()
}

/// The index of `preset`'s scene in `scenes` and the viewer state it sets on it.
fn side_state(
    scenes: &mut SceneCache,
    lesson: &Lesson,
    preset: &Preset,
) -> Result<(usize, ViewerState), LessonRenderError> {
    let scene_error = |e| LessonRenderError::Scene(lesson.name.to_owned(), e);
    let index = scenes.index(preset).map_err(scene_error)?;
    let state = preset.to_state(&scenes.scenes[index].1).map_err(|e| scene_error(e.into()))?;
    Ok((index, state))
}

/// One side's picture; with `whole_split`, the preset's split picture instead of one half;
/// `overlay` changes the side's state before it is drawn.
fn draw(
    renderer: &mut Renderer,
    scenes: &mut SceneCache,
    lesson: &Lesson,
    side: &Side,
    size: [u32; 2],
    whole_split: bool,
    overlay: Option<&dyn Fn(&mut ViewerState)>,
) -> Result<RgbaImage, LessonRenderError> {
    let render_error = |e| LessonRenderError::Render(lesson.name.to_owned(), e);
    let (index, mut state) = side_state(scenes, lesson, &side.preset)?;
    if let Some(overlay) = overlay {
        overlay(&mut state);
    }
    match (side.half, whole_split) {
        (_, true) => {}
        // The whole picture of one half: the divider at the far edge.
        (Some(half), false) => state.apply(Command::SetSplitDivider(if half == 0 { 1.0 } else { 0.0 })),
        (None, false) => state.apply(Command::SetSplit(false)),
    }
    scenes.upload(renderer, index, state.scene_uploads());
    let options = CaptureOptions::plain(size);
    let params = state.frame_params();
    match state.split_frame() {
        Some(split) => render_capture_split(renderer, &options, &params, &split),
        None => render_capture(renderer, &options, &params),
    }
    .map_err(render_error)
}

/// The share of pixels, percent, at which some channel of `a` and `b` differs by at least
/// [`CHANGED_STEP`] (images of one size; 100 when the sizes differ).
pub fn changed_percent(a: &RgbaImage, b: &RgbaImage) -> f32 {
    if a.dimensions() != b.dimensions() || a.is_empty() {
        return 100.0;
    }
    let changed = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) >= CHANGED_STEP))
        .count();
    100.0 * changed as f32 / (a.width() * a.height()) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deck drawn in order keeps the scenes its later slides are drawn on, no others.
    #[test]
    fn the_cache_keeps_only_the_scenes_of_the_lessons_named() {
        let all = crate::lessons::catalogue().unwrap();
        let lesson = |name: &str| all.iter().find(|l| l.name == name).unwrap();
        let (wall, mirrored) = (lesson("cg-wall"), lesson("mistake-handedness"));
        let mut cache = SceneCache::default();
        for side in wall.sides.iter().chain(&mirrored.sides) {
            cache.index(&side.preset).unwrap();
        }
        assert_eq!(cache.scenes.len(), 2, "the bricks and the mirrored wall");
        cache.keep_only([mirrored]);
        assert_eq!(cache.scenes.len(), 1);
        assert_eq!(cache.index(&mirrored.sides[0].preset).unwrap(), 0, "kept, not made again");
        cache.keep_only([]);
        assert!(cache.scenes.is_empty());
    }

    #[test]
    fn a_pixel_changes_at_four_steps_of_one_channel() {
        let a = RgbaImage::from_pixel(2, 2, image::Rgba([10, 10, 10, 255]));
        let mut b = a.clone();
        b.put_pixel(0, 0, image::Rgba([10, 13, 10, 255]));
        assert_eq!(changed_percent(&a, &b), 0.0);
        b.put_pixel(1, 1, image::Rgba([10, 10, 6, 255]));
        assert_eq!(changed_percent(&a, &b), 25.0);
    }
}
