//! Comparison exports: a grid of tiles (a row is a grid of one row), each the same camera and
//! light under other shading settings, with an optional caption strip under each tile stating
//! view, mode, strength, normal-map convention and tangent source, wrapped to the tile's width
//! ([`text::wrap`]); and single pictures ([`render_picture`]) with what the viewer draws over
//! them ([`annotate`]). Text is drawn on the CPU ([`text`]).

use super::capture::{CaptureOptions, render_capture, render_capture_split};
use super::{Renderer, annotate, text};
use crate::error::RenderError;
use crate::frame::{
    BumpSource, FrameParams, LegacyLook, LightingSpace, MAX_PARALLAX_LAYERS, Mistake, Parallax, STRENGTH_RANGE,
    SceneOptions, ShadingMode, ShadingSettings, SplitFrame, ViewMode,
};
use crate::names::Named;
use crate::scene::Scene;

/// The most pixels a tile export may hold (1 GiB of RGBA8).
pub const MAX_EXPORT_PIXELS: u64 = 1 << 28;

/// The caption strip's background and text colours (sRGB).
pub const CAPTION_BACKGROUND: [u8; 3] = [24, 26, 30];
const CAPTION_TEXT: [u8; 3] = [235, 235, 235];

/// `"WxH"` → `[W, H]` in pixels (each at least 1).
pub fn parse_size(text: &str) -> Result<[u32; 2], String> {
    let (w, h) =
        text.trim().split_once(['x', 'X']).ok_or_else(|| format!("size {text:?}: expected WxH, e.g. 1280x720"))?;
    let side = |s: &str| s.trim().parse::<u32>().ok().filter(|&v| v > 0);
    match (side(w), side(h)) {
        (Some(w), Some(h)) => Ok([w, h]),
        _ => Err(format!("size {text:?}: width and height must be whole numbers of pixels, at least 1")),
    }
}

/// Tiles in rows of `columns`, left to right, then top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct TileGrid {
    pub columns: usize,
    pub tiles: Vec<ShadingSettings>,
}

/// How [`TileGrid::parse`] names a tile, beside the view names.
const TILE_NAMES: [&str; 4] = ["flat", "bumped", "bump-only", "colour-only"];

/// A tile spec ([`TileGrid::parse`]) that does not parse.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TileSpecError {
    #[error("{spec:?}: every row needs {columns} tiles, one has {found}")]
    RowLength { spec: String, columns: usize, found: usize },
    #[error("tile {tile:?}: expected NAME@STRENGTH, e.g. bumped@2")]
    Strength { tile: String },
    #[error("tile {tile:?}: expected one of {expected}")]
    Name { tile: String, expected: String },
    #[error(
        "tile {tile:?}: expected a parallax technique and its layers, 1 to {MAX_PARALLAX_LAYERS}, e.g. occlusion:8"
    )]
    Layers { tile: String },
}

impl TileGrid {
    /// The default row: flat │ bumped │ Tangent view, from `current` (lit pictures in its mode,
    /// at its strength).
    pub fn default_row(current: &ShadingSettings) -> TileGrid {
        TileGrid::parse("flat,bumped,tangent", current).expect("a valid spec")
    }

    /// The default grid: flat │ bumped │ bump only over Tangent │ Bitangent │ Shading normal.
    pub fn default_grid(current: &ShadingSettings) -> TileGrid {
        TileGrid::parse("flat,bumped,bump-only;tangent,bitangent,shading-normal", current).expect("a valid spec")
    }

    /// Tiles from a spec: rows separated by `;`, tiles by `,`, each `NAME[@STRENGTH]`. A name
    /// is `flat` (lit, bump off), `bumped` (lit, bump on), `bump-only` or `colour-only` (lit in
    /// that mode), a view name (`tangent`, `shading-normal`, `difference`, ...: that view,
    /// bump on), or a parallax technique (`off`, `offset`, `steep`, ...: lit, bump on),
    /// optionally with a fixed layer count, `occlusion:8`. Lit tiles keep `current`'s mode unless named otherwise; every tile keeps its
    /// strength unless `@STRENGTH` gives one (clamped to the strength slider's range). Every
    /// row must have as many tiles.
    pub fn parse(spec: &str, current: &ShadingSettings) -> Result<TileGrid, TileSpecError> {
        let rows: Vec<Vec<&str>> = spec.split(';').map(|row| row.split(',').map(str::trim).collect()).collect();
        let columns = rows[0].len();
        if let Some(row) = rows.iter().find(|r| r.len() != columns) {
            return Err(TileSpecError::RowLength { spec: spec.to_owned(), columns, found: row.len() });
        }
        let tiles = rows.iter().flatten().map(|tile| parse_tile(tile, current)).collect::<Result<_, _>>()?;
        Ok(TileGrid { columns, tiles })
    }

    pub fn rows(&self) -> usize {
        self.tiles.len().div_ceil(self.columns.max(1))
    }
}

/// One tile of a [`TileGrid::parse`] spec.
fn parse_tile(text: &str, current: &ShadingSettings) -> Result<ShadingSettings, TileSpecError> {
    let (name, strength) = match text.split_once('@') {
        Some((name, s)) => {
            let strength = s.trim().parse::<f32>().ok().filter(|s| s.is_finite());
            (name.trim(), Some(strength.ok_or_else(|| TileSpecError::Strength { tile: text.to_owned() })?))
        }
        None => (text, None),
    };
    let lit = ShadingSettings { view: ViewMode::Lit, bump_enabled: true, ..*current };
    // A parallax technique, with a fixed layer count after a colon: `occlusion:8`.
    let (name, layers) = match name.split_once(':') {
        Some((name, layers)) => {
            let count = layers.trim().parse::<u32>().ok().filter(|n| (1..=MAX_PARALLAX_LAYERS).contains(n));
            (name.trim(), Some(count.ok_or_else(|| TileSpecError::Layers { tile: text.to_owned() })?))
        }
        None => (name, None),
    };
    if let Some(technique) = Parallax::from_name(name) {
        let mut tile = lit;
        tile.parallax.technique = technique;
        if let Some(n) = layers {
            (tile.parallax.layers_min, tile.parallax.layers_max) = (n, n);
        }
        if let Some(strength) = strength {
            tile.strength = strength.clamp(*STRENGTH_RANGE.start(), *STRENGTH_RANGE.end());
        }
        return Ok(tile);
    }
    if layers.is_some() {
        return Err(TileSpecError::Layers { tile: text.to_owned() });
    }
    let mut tile = match name {
        "flat" => ShadingSettings { bump_enabled: false, ..lit },
        "bumped" => lit,
        "bump-only" => ShadingSettings { mode: ShadingMode::BumpOnly, ..lit },
        "colour-only" => ShadingSettings { mode: ShadingMode::ColourOnly, ..lit },
        other => match ViewMode::from_name(other) {
            Some(view) => ShadingSettings { view, ..lit },
            None => {
                let names: Vec<&str> =
                    TILE_NAMES.iter().copied().chain(ViewMode::names()).chain(Parallax::names()).collect();
                return Err(TileSpecError::Name { tile: other.to_owned(), expected: names.join(", ") });
            }
        },
    };
    if let Some(strength) = strength {
        tile.strength = strength.clamp(*STRENGTH_RANGE.start(), *STRENGTH_RANGE.end());
    }
    Ok(tile)
}

/// What a tile's caption says of the scene as the renderer drew it, beside the tile's shading.
#[derive(Debug, Clone, PartialEq)]
pub struct CaptionScene {
    /// The normal-map conventions of the scene's materials, e.g. `OpenGL (+Y)`, or `none`.
    pub convention: String,
    /// The tangent frames drawn with, e.g. `auto: meshopt`.
    pub tangents: String,
    /// What displacement drew ([`crate::prepare::displace::DisplacementStats::summary`]), if it drew.
    pub displacement: Option<String>,
}

impl CaptionScene {
    /// The scene facts of `renderer`'s current scene, made from `scene` with `options`: the
    /// normal-map convention of the scene's materials (after `options`' overrides), the
    /// tangent frames the renderer drew with, and the displacement it drew.
    pub fn of(renderer: &Renderer, scene: &Scene, options: &SceneOptions) -> CaptionScene {
        let mut greens: Vec<&str> = Vec::new();
        for (index, material) in scene.materials.iter().enumerate() {
            let Some(map) = &material.normal_map else { continue };
            let green = options.overrides_in_use(index).green.unwrap_or(map.convention.green);
            let name = green.label();
            if !greens.contains(&name) {
                greens.push(name);
            }
        }
        let convention = if greens.is_empty() { "none".to_owned() } else { greens.join(", ") };
        let tangents = if options.bump_source == BumpSource::HeightInShader {
            "none (height in shader)".to_owned()
        } else {
            let mut names: Vec<&str> = Vec::new();
            for method in renderer.tangent_methods().into_iter().flatten() {
                if !names.contains(&method.name()) {
                    names.push(method.name());
                }
            }
            let used = if names.is_empty() { "none".to_owned() } else { names.join(", ") };
            match options.tangent_method {
                None => format!("auto: {used}"),
                Some(_) => used,
            }
        };
        let displacement = renderer.prepared(false).and_then(|p| p.displacement).map(|stats| stats.summary());
        CaptionScene { convention, tangents, displacement }
    }
}

/// The caption of a tile ([`caption_lines`] with [`CaptionScene::of`]).
pub fn caption(renderer: &Renderer, scene: &Scene, options: &SceneOptions, shading: &ShadingSettings) -> Vec<String> {
    caption_lines(shading, &CaptionScene::of(renderer, scene, options))
}

/// The caption of a tile, one line each: view (and mode), bump and strength, the normal-map
/// convention and the tangent frames; a lighting space other than world; with parallax on,
/// the technique, its layers and a changed depth; what displacement drew; with a legacy
/// look, the look (emboss: what its disc is); with a classic mistake, the mistake and what it
/// breaks. Techniques are named by their [`Named`] names, as on the command line.
pub fn caption_lines(shading: &ShadingSettings, scene: &CaptionScene) -> Vec<String> {
    let view = match shading.view {
        ViewMode::Lit | ViewMode::OverTilt => format!("{}: {}", shading.view.label(), shading.mode.label()),
        other => format!("{} view", other.label()),
    };
    let bump = if shading.bump_enabled {
        format!("bump on, strength {:.2}", shading.strength)
    } else {
        format!("bump off (strength {:.2})", shading.strength)
    };
    let mut lines =
        vec![view, bump, format!("normal map: {}", scene.convention), format!("tangents: {}", scene.tangents)];
    if shading.lighting_space != LightingSpace::World {
        lines.push(format!("lighting space: {}", shading.lighting_space.name()));
    }
    if shading.parallax.technique.shifts() {
        lines.push(shading.parallax.caption());
    }
    if let Some(summary) = &scene.displacement {
        lines.push(format!("displacement {summary}"));
    }
    if shading.legacy.look != LegacyLook::Off && shading.view.is_lit() {
        lines.push(format!("legacy look: {}", shading.legacy.caption()));
    }
    if shading.mistake != Mistake::None {
        lines.push(format!("mistake: {}: {}", shading.mistake.name(), shading.mistake.explanation()));
    }
    lines
}

/// `lines` as drawn under a tile `tile_width` pixels wide: each wrapped ([`text::wrap`]) to
/// the tile's width less a margin of half the text size on either side.
pub fn wrap_caption(lines: &[String], tile_width: u32) -> Vec<String> {
    let px = caption_px(tile_width);
    lines.iter().flat_map(|line| text::wrap(line, px, tile_width as f32 - px)).collect()
}

/// Text size of captions under tiles `tile_width` pixels wide, pixels.
pub fn caption_px(tile_width: u32) -> f32 {
    (tile_width as f32 / 30.0).clamp(11.0, 32.0)
}

/// Height of a caption strip of `lines` lines (as drawn: [`wrap_caption`]) under tiles `tile_width` pixels wide.
pub fn caption_strip_height(tile_width: u32, lines: usize) -> u32 {
    let px = caption_px(tile_width);
    (lines as f32 * px * 1.25 + px).ceil() as u32
}

/// Renders the tiles of `grid` (each a capture as `options` say, with `params`' camera and
/// light) in rows with no gap: tile `i` is the pixels `[c·w, (c+1)·w) × [r·(h+s), r·(h+s)+h)`
/// with `c = i mod columns`, `r = i div columns`, and `s` the caption strip's height: with
/// `captions` (one list of lines per tile) [`caption_strip_height`] of the most lines a tile's
/// caption wraps to ([`wrap_caption`]), else 0. The strip under a tile holds its wrapped
/// lines; a Difference or Over-tilt tile carries its key ([`annotate::legend`]).
pub fn render_grid(
    renderer: &mut Renderer,
    options: &CaptureOptions,
    params: &FrameParams,
    grid: &TileGrid,
    captions: Option<&[Vec<String>]>,
) -> Result<image::RgbaImage, RenderError> {
    let [width, height] = options.size;
    let captions: Option<Vec<Vec<String>>> = captions.map(|c| c.iter().map(|l| wrap_caption(l, width)).collect());
    let lines = captions.as_ref().map_or(0, |c| c.iter().map(Vec::len).max().unwrap_or(0));
    let strip = if captions.is_some() { caption_strip_height(width, lines) } else { 0 };
    let (columns, rows) = (grid.columns.max(1) as u64, grid.rows() as u64);
    let (total_width, total_height) = (u64::from(width) * columns, u64::from(height + strip) * rows);
    if total_width * total_height > MAX_EXPORT_PIXELS || total_width > u32::MAX.into() || total_height > u32::MAX.into()
    {
        return Err(RenderError::ExportTooLarge { width: total_width, height: total_height, limit: MAX_EXPORT_PIXELS });
    }
    let columns = columns as u32;
    let mut image = image::RgbaImage::new(total_width as u32, total_height as u32);
    for (i, shading) in grid.tiles.iter().enumerate() {
        let tile = render_capture(renderer, options, &FrameParams { shading: *shading, ..*params })?;
        let (x0, y0) = (i as u32 % columns * width, i as u32 / columns * (height + strip));
        image::imageops::replace(&mut image, &tile, x0 as i64, y0 as i64);
        let area = [x0, y0, x0 + width, y0 + height];
        annotate::legend(&mut image, shading.view, shading.difference_range_deg, area, true);
        if let Some(lines) = captions.as_ref().and_then(|c| c.get(i)) {
            let [r, g, b] = CAPTION_BACKGROUND;
            for y in y0 + height..y0 + height + strip {
                for x in x0..x0 + width {
                    image.put_pixel(x, y, image::Rgba([r, g, b, 255]));
                }
            }
            let px = caption_px(width);
            for (line, words) in lines.iter().enumerate() {
                let baseline = (y0 + height) as f32 + px * 0.5 + px * (1.25 * line as f32 + 1.0);
                text::draw(&mut image, words, [x0, x0 + width], x0 as f32 + px * 0.5, baseline, px, CAPTION_TEXT);
            }
        }
    }
    Ok(image)
}

/// One picture as `render` and the viewer's screenshot export write it: the capture of
/// `params` or, with `split` and its two labels, of the split view with its divider and labels
/// drawn in ([`annotate::split`]); a half or picture in the Difference or Over-tilt view
/// carries its key at its outer top corner ([`annotate::legend`]).
pub fn render_picture(
    renderer: &mut Renderer,
    options: &CaptureOptions,
    params: &FrameParams,
    split: Option<(&SplitFrame, [&str; 2])>,
) -> Result<image::RgbaImage, RenderError> {
    let Some((split, labels)) = split else {
        let mut image = render_capture(renderer, options, params)?;
        let (width, height) = image.dimensions();
        let shading = &params.shading;
        annotate::legend(&mut image, shading.view, shading.difference_range_deg, [0, 0, width, height], true);
        return Ok(image);
    };
    let mut image = render_capture_split(renderer, options, params, split)?;
    let (width, height) = image.dimensions();
    let divider = split.divider_pixels(width);
    let [left, right] = [&split.left, &split.right];
    annotate::legend(&mut image, left.view, left.difference_range_deg, [0, 0, divider, height], false);
    annotate::legend(&mut image, right.view, right.difference_range_deg, [divider, 0, width, height], true);
    annotate::split(&mut image, divider, labels);
    Ok(image)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_name_tiles_by_picture_view_and_strength() {
        let current = ShadingSettings { strength: 1.5, mode: ShadingMode::BumpOnly, ..Default::default() };
        let row = TileGrid::default_row(&current);
        assert_eq!((row.columns, row.rows()), (3, 1));
        assert!(!row.tiles[0].bump_enabled && row.tiles[1].bump_enabled);
        assert_eq!(row.tiles[1].mode, ShadingMode::BumpOnly, "lit tiles keep the current mode");
        assert_eq!(row.tiles[2].view, ViewMode::Tangent);
        let grid = TileGrid::parse("flat, bumped@3 ; handedness,colour-only@-1", &current).unwrap();
        assert_eq!((grid.columns, grid.rows()), (2, 2));
        assert_eq!([grid.tiles[0].strength, grid.tiles[1].strength, grid.tiles[3].strength], [1.5, 3.0, -1.0]);
        assert_eq!(grid.tiles[2].view, ViewMode::Handedness);
        assert_eq!(grid.tiles[3].mode, ShadingMode::ColourOnly);
        assert_eq!(TileGrid::default_grid(&current).tiles.len(), 6);
    }

    #[test]
    fn bad_specs_say_what_is_wrong() {
        let current = ShadingSettings::default();
        assert!(
            TileGrid::parse("flat,bumped;tangent", &current)
                .unwrap_err()
                .to_string()
                .contains("every row needs 2 tiles")
        );
        assert!(TileGrid::parse("flat,shiny", &current).unwrap_err().to_string().contains("shading-normal"));
        assert!(TileGrid::parse("bumped@lots", &current).unwrap_err().to_string().contains("NAME@STRENGTH"));
        assert!(TileGrid::parse("", &current).is_err());
        assert_eq!(TileGrid::parse("bumped@1e30", &current).unwrap().tiles[0].strength, 4.0, "clamped");
    }
}
