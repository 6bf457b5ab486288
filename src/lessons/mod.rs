//! Lessons: the built-in, ordered course of small TOML files under `assets/lessons/`
//! ([`catalogue`]), each a preset (the whole viewer state, [`crate::state::preset`]) with a
//! title, a caption naming its source, a comparison and the claim the measured number makes.
//!
//! A lesson file holds:
//!
//! - `title`, `caption` (one to three plain sentences), `claim` (a sentence in which
//!   `{changed}` becomes the measured share of changed pixels);
//! - `[preset]`: the preset, written as a preset file's tables (`[preset.shading]`, …);
//! - the comparison: either the preset's split view (`[preset.split] enabled = true`; its two
//!   halves are the sides, labelled by `labels`), or `[[tiles]]`, each a `label` and a
//!   `preset` table laid over the lesson's (a grid of N settings, side by side);
//! - optionally `uv_error_angle_deg`: the claim may then say `{uv_error}`, each side's mean
//!   parallax UV error in texels against the exact intersection at that angle ([`uv_claim`]);
//! - optionally `min_changed` (percent) with `why_fewer`: a lesson whose point shows on fewer
//!   than [`MIN_CHANGED_PERCENT`] of the pixels says why and how many it holds;
//! - optionally `inset = { zoom = N }` (N from 2 to 8): a point small by nature is shown
//!   magnified as well, the window where the sides differ most drawn N times larger from each
//!   side ([`inset`]).
//!
//! The sides "differ" at a pixel when some channel differs by at least [`CHANGED_STEP`] of 255
//! ([`measure`]).

pub mod deck;
pub mod deck_html;
pub mod files;
pub mod grid;
pub mod inset;
pub mod keys;
pub mod measure;
pub mod pdf;
pub mod slide;
pub mod uv_claim;
pub mod visibility;

use serde::Deserialize;

use crate::scene::Scene;
use crate::state::ViewerState;
use crate::state::preset::{Preset, PresetError, one_line};

/// The share of the picture's pixels the two sides of a comparison must differ in, percent.
pub const MIN_CHANGED_PERCENT: f32 = 5.0;
/// The smallest channel difference (of 255) that counts as a changed pixel.
pub const CHANGED_STEP: u8 = 4;

/// The lesson files, in the course's order: name and text.
const FILES: &[(&str, &str)] = &[
    ("cg-wall", include_str!("../../assets/lessons/cg-wall.toml")),
    ("cg-floor", include_str!("../../assets/lessons/cg-floor.toml")),
    ("cg-torus", include_str!("../../assets/lessons/cg-torus.toml")),
    ("cg-mesh", include_str!("../../assets/lessons/cg-mesh.toml")),
    ("cg-decal-gloss", include_str!("../../assets/lessons/cg-decal-gloss.toml")),
    ("bump-off-on", include_str!("../../assets/lessons/bump-off-on.toml")),
    ("strength", include_str!("../../assets/lessons/strength.toml")),
    ("frame-views", include_str!("../../assets/lessons/frame-views.toml")),
    ("tangent-methods", include_str!("../../assets/lessons/tangent-methods.toml")),
    ("kernels", include_str!("../../assets/lessons/kernels.toml")),
    ("blinn-height", include_str!("../../assets/lessons/blinn-height.toml")),
    ("green-convention", include_str!("../../assets/lessons/green-convention.toml")),
    ("mistake-tbn-typo", include_str!("../../assets/lessons/mistake-tbn-typo.toml")),
    ("mistake-srgb", include_str!("../../assets/lessons/mistake-srgb.toml")),
    ("mistake-green", include_str!("../../assets/lessons/mistake-green.toml")),
    ("mistake-handedness", include_str!("../../assets/lessons/mistake-handedness.toml")),
    ("mistake-gram-schmidt", include_str!("../../assets/lessons/mistake-gram-schmidt.toml")),
    ("mistake-renormalization", include_str!("../../assets/lessons/mistake-renormalization.toml")),
    ("mistake-half-vector", include_str!("../../assets/lessons/mistake-half-vector.toml")),
    ("mistake-light-vertex", include_str!("../../assets/lessons/mistake-light-vertex.toml")),
    ("lighting-space", include_str!("../../assets/lessons/lighting-space.toml")),
    ("specular-modes", include_str!("../../assets/lessons/specular-modes.toml")),
    ("coloured-lights", include_str!("../../assets/lessons/coloured-lights.toml")),
    ("dot3-cube-maps", include_str!("../../assets/lessons/dot3-cube-maps.toml")),
    ("emboss", include_str!("../../assets/lessons/emboss.toml")),
    ("xray-packing", include_str!("../../assets/lessons/xray-packing.toml")),
    ("parallax-family", include_str!("../../assets/lessons/parallax-family.toml")),
    ("parallax-uv-error", include_str!("../../assets/lessons/parallax-uv-error.toml")),
    ("relaxed-cone", include_str!("../../assets/lessons/relaxed-cone.toml")),
    ("self-shadowing", include_str!("../../assets/lessons/self-shadowing.toml")),
    ("silhouettes", include_str!("../../assets/lessons/silhouettes.toml")),
    ("over-tilt", include_str!("../../assets/lessons/over-tilt.toml")),
    ("mip-distance", include_str!("../../assets/lessons/mip-distance.toml")),
    ("clearcoat", include_str!("../../assets/lessons/clearcoat.toml")),
    ("detail-blend", include_str!("../../assets/lessons/detail-blend.toml")),
    ("compression", include_str!("../../assets/lessons/compression.toml")),
];

/// One side of a comparison: its label and the whole preset it is drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct Side {
    pub label: String,
    pub preset: Preset,
    /// Which half of the preset's split view this side is (0 left, 1 right), for a split.
    pub half: Option<usize>,
}

/// A lesson, read and checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Lesson {
    /// The file's name without `.toml`: what `--lessons` takes for a built-in lesson.
    pub name: String,
    pub title: String,
    pub caption: String,
    /// The claim with `{changed}` where the measured percentage goes.
    pub claim: String,
    /// The share of changed pixels this lesson holds, percent ([`MIN_CHANGED_PERCENT`] unless
    /// the file says why fewer).
    pub min_changed: f32,
    pub why_fewer: Option<String>,
    /// The lesson's own preset: what the viewer loads for a split comparison.
    pub preset: Preset,
    /// The sides, two for a split, N for a grid.
    pub sides: Vec<Side>,
    /// Whether the sides are the halves of the preset's split view (else a grid).
    pub split: bool,
    /// What the claim's `{uv_error}` says: each side's UV error, measured once when the lesson
    /// is read ([`uv_claim`]).
    pub uv_errors: Option<String>,
    /// The inset's magnification, for a lesson that shows one ([`inset`]).
    pub inset: Option<u32>,
}

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LessonFile {
    title: String,
    caption: String,
    claim: String,
    min_changed: Option<f32>,
    why_fewer: Option<String>,
    labels: Option<[String; 2]>,
    uv_error_angle_deg: Option<f32>,
    inset: Option<InsetFile>,
    preset: toml::Table,
    #[serde(default)]
    tiles: Vec<TileFile>,
}

/// `inset = { zoom = N }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct InsetFile {
    zoom: u32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TileFile {
    label: String,
    #[serde(default)]
    preset: toml::Table,
}

/// Each tile's preset table read as a preset where it stands in the file (a tile sets only
/// what differs, so every key may be missing).
#[derive(Deserialize)]
#[expect(dead_code, reason = "read only to check each tile's keys where they stand in the file")]
struct TilePresets {
    #[serde(default)]
    tiles: Vec<TilePreset>,
}

#[derive(Deserialize)]
#[expect(dead_code, reason = "read only to check the keys")]
struct TilePreset {
    #[serde(default)]
    preset: Preset,
}

/// Why a lesson file is not a lesson.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("lesson {name}: {message}")]
pub struct LessonError {
    pub name: String,
    pub message: String,
}

impl Lesson {
    /// Reads and checks the lesson file `text` named `name`. A mistake TOML or the preset's
    /// reading sees is reported with its line in `text` and the key.
    pub fn parse(name: &str, text: &str) -> Result<Lesson, LessonError> {
        let fail = |message: String| LessonError { name: name.to_owned(), message };
        let file: LessonFile = toml::from_str(text).map_err(|e| fail(one_line(&e.to_string())))?;
        // The preset part and each tile's, read in place first so that their mistakes carry
        // their lines; the tiles are then laid over the lesson's table.
        let preset = Preset::from_toml(text).map_err(|e| fail(e.0))?;
        toml::from_str::<TilePresets>(text).map_err(|e| fail(one_line(&e.to_string())))?;
        let split = preset.split.enabled;
        let sides = match (split, file.tiles.is_empty(), file.labels) {
            (true, true, Some(labels)) => {
                let [left, right] = labels;
                vec![(left, preset.clone(), Some(0)), (right, preset.clone(), Some(1))]
            }
            (true, true, None) => {
                return Err(fail("a split comparison names its sides: labels = [LEFT, RIGHT]".into()));
            }
            (false, false, None) => file
                .tiles
                .iter()
                .map(|tile| {
                    let mut table = file.preset.clone();
                    lay_over(&mut table, &tile.preset);
                    let preset = to_preset(&table).map_err(|e| fail(format!("tile {}: {}", tile.label, e.0)))?;
                    Ok((tile.label.clone(), preset, None))
                })
                .collect::<Result<_, LessonError>>()?,
            _ => return Err(fail("the comparison is a split view with labels or [[tiles]] without one".into())),
        };
        if sides.len() < 2 {
            return Err(fail("a comparison has at least two sides".into()));
        }
        let min_changed = match (file.min_changed, &file.why_fewer) {
            (None, None) => MIN_CHANGED_PERCENT,
            (Some(min), Some(_)) if min.is_finite() && (0.0..MIN_CHANGED_PERCENT).contains(&min) => min,
            _ => return Err(fail(format!("min_changed (below {MIN_CHANGED_PERCENT} %) comes with why_fewer"))),
        };
        if !file.claim.contains("{changed}") {
            return Err(fail("the claim says {changed} where the measured number goes".into()));
        }
        let inset = match file.inset {
            Some(InsetFile { zoom }) if !inset::ZOOMS.contains(&zoom) => {
                let [low, high] = [inset::ZOOMS.start(), inset::ZOOMS.end()];
                return Err(fail(format!("inset.zoom = {zoom}: a magnification from {low} to {high}")));
            }
            inset_file => inset_file.map(|i| i.zoom),
        };
        let sides = sides.into_iter().map(|(label, preset, half)| Side { label, preset, half }).collect();
        let lesson = Lesson {
            name: name.to_owned(),
            title: file.title,
            caption: file.caption,
            claim: file.claim,
            min_changed,
            why_fewer: file.why_fewer,
            preset,
            sides,
            split: split && file.tiles.is_empty(),
            uv_errors: None,
            inset,
        };
        let uv_errors = uv_claim::measured(&lesson, file.uv_error_angle_deg).map_err(fail)?;
        Ok(Lesson { uv_errors, ..lesson })
    }

    /// The preset the viewer shows: the split view itself, or a grid's last tile (the
    /// technique the grid arrives at).
    pub fn viewer_preset(&self) -> &Preset {
        if self.split { &self.preset } else { &self.sides.last().expect("two sides or more").preset }
    }

    /// The viewer state this lesson sets on `scene` (the scene its preset's files make,
    /// [`Preset::build_scene`]): the whole state of [`Self::viewer_preset`].
    pub fn apply(&self, scene: &Scene) -> Result<ViewerState, PresetError> {
        self.viewer_preset().to_state(scene)
    }

    /// The claim with the measured percentage in it, and each side's UV error where it says
    /// `{uv_error}` ([`uv_claim`]).
    pub fn claim_with(&self, changed_percent: f32) -> String {
        let claim = self.claim.replace("{changed}", &format!("{changed_percent:.1} %"));
        match &self.uv_errors {
            Some(errors) => claim.replace("{uv_error}", errors),
            None => claim,
        }
    }
}

/// Every lesson, in order. The files are part of the binary; a file that does not read is a
/// bug the tests catch, so it is an error here, not a panic.
pub fn catalogue() -> Result<Vec<Lesson>, LessonError> {
    FILES.iter().map(|(name, text)| Lesson::parse(name, text)).collect()
}

/// Every lesson's name, in order (without reading the files).
pub fn names() -> Vec<&'static str> {
    FILES.iter().map(|f| f.0).collect()
}

/// The lessons named in `names` (in that order), or every one for an empty list; an unknown
/// name is an error listing the names.
pub fn select(wanted: &[String]) -> Result<Vec<Lesson>, LessonError> {
    let all = catalogue()?;
    if wanted.is_empty() {
        return Ok(all);
    }
    wanted
        .iter()
        .map(|wanted| {
            all.iter().find(|l| l.name == *wanted).cloned().ok_or_else(|| LessonError {
                name: wanted.clone(),
                message: format!("no such lesson; the lessons are {}", names().join(", ")),
            })
        })
        .collect()
}

/// The preset a lesson's table describes, checked as a preset file is.
fn to_preset(table: &toml::Table) -> Result<Preset, PresetError> {
    let text = toml::to_string(table).map_err(|e| PresetError(e.to_string()))?;
    Preset::from_toml(&text)
}

/// Lays `over` onto `base` key by key, tables merged, other values replaced.
fn lay_over(base: &mut toml::Table, over: &toml::Table) {
    for (key, value) in over {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(inner)), toml::Value::Table(value)) => lay_over(inner, value),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_lay_their_tables_over_the_lessons() {
        let text = r#"
            title = "t"
            caption = "c"
            claim = "{changed}"
            [preset.shading]
            strength = 2.0
            view = "lit"
            [[tiles]]
            label = "flat"
            preset.shading.bump = false
            [[tiles]]
            label = "bumped"
        "#;
        let lesson = Lesson::parse("x", text).unwrap();
        assert!(!lesson.split);
        assert_eq!(lesson.sides.len(), 2);
        assert!(!lesson.sides[0].preset.shading.bump && lesson.sides[1].preset.shading.bump);
        assert_eq!(lesson.sides[0].preset.shading.strength, 2.0);
        assert_eq!(lesson.claim_with(12.345), "12.3 %");
    }

    #[test]
    fn bad_lessons_say_what_is_wrong() {
        let base = "title = \"t\"\ncaption = \"c\"\nclaim = \"{changed}\"\n";
        let split = format!("{base}[preset.split]\nenabled = true\n");
        assert!(Lesson::parse("x", &split).unwrap_err().message.contains("labels"));
        let fewer = format!("min_changed = 1.0\nlabels = [\"a\", \"b\"]\n{split}");
        assert!(Lesson::parse("x", &fewer).is_err(), "min_changed without why_fewer");
        let unknown =
            format!("{base}[preset.shading]\nstrenght = 1.0\n[[tiles]]\nlabel = \"a\"\n[[tiles]]\nlabel = \"b\"\n");
        assert!(Lesson::parse("x", &unknown).unwrap_err().message.contains("strenght"));
        assert!(select(&["no-such".into()]).unwrap_err().message.contains("cg-wall"));
        let labelled = format!("labels = [\"a\", \"b\"]\n{split}");
        let zoomed = |zoom: &str| Lesson::parse("x", &format!("inset = {{ zoom = {zoom} }}\n{labelled}"));
        assert_eq!(zoomed("4").unwrap().inset, Some(4));
        assert!(zoomed("1").unwrap_err().message.contains("inset.zoom = 1"));
        assert!(zoomed("\"big\"").is_err());
    }

    #[test]
    fn every_lesson_reads() {
        let lessons = catalogue().unwrap();
        assert_eq!(lessons.len(), FILES.len());
        for lesson in &lessons {
            let scene = lesson.viewer_preset().build_scene().unwrap();
            lesson.apply(&scene).unwrap();
        }
    }
}
