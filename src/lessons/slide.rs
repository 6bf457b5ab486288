//! A lesson as a slide: the title, the picture(s) with their labels, the caption wrapped to the
//! slide's width and the claim with the number measured in this run, on a dark background or,
//! for lit rooms, a light one ([`SlideTheme`]).

use image::{Rgba, RgbaImage};

use super::Lesson;
use super::grid::tile_cells;
use super::inset::{Inset, inset_size};
use super::keys;
use super::measure::Measured;
use crate::render::annotate;
use crate::render::text::{self, text_width, wrap_paragraph};

/// The slide's colours: dark for a darkened room, light for a lit one (the pictures are the
/// same; the divider stays white, as the viewer draws it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum SlideTheme {
    #[default]
    Dark,
    Light,
}

/// The colours of a theme: background, text, muted text (labels, page number), the claim.
struct Palette {
    background: [u8; 3],
    text: [u8; 3],
    muted: [u8; 3],
    accent: [u8; 3],
}

impl SlideTheme {
    fn palette(self) -> Palette {
        match self {
            SlideTheme::Dark => Palette {
                background: [24, 26, 30],
                text: [232, 232, 228],
                muted: [150, 154, 160],
                accent: [255, 196, 84],
            },
            // WCAG contrast against the background, as the dark theme's: text 16.7:1 (14.2),
            // labels 6.4:1 (6.2), the claim's orange darkened to 5.1:1.
            SlideTheme::Light => {
                Palette { background: [250, 250, 247], text: [24, 26, 30], muted: [88, 92, 99], accent: [168, 84, 0] }
            }
        }
    }
}
/// The most tiles side by side in one row; more go into further rows.
const MAX_COLUMNS: usize = 4;
/// Line height as a multiple of the font size.
const LEADING: f32 = 1.3;

/// The size of `bumpview slides`'s slides unless `--size` says otherwise, pixels.
pub const DEFAULT_SLIDE_SIZE: [u32; 2] = [1920, 1080];

/// Where things go on a slide of a given size; every length in pixels, scaled with the height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlideLayout {
    pub size: [u32; 2],
    /// The colours ([`SlideTheme::Dark`] unless [`Self::with_theme`] says otherwise).
    theme: SlideTheme,
    margin: f32,
    title_px: f32,
    body_px: f32,
    label_px: f32,
    gap: f32,
}

/// The rectangle of one picture on the slide and its label.
#[derive(Debug, Clone, PartialEq)]
struct Placed {
    x: u32,
    y: u32,
    size: [u32; 2],
}

impl SlideLayout {
    pub fn new(size: [u32; 2]) -> SlideLayout {
        let h = size[1] as f32;
        SlideLayout {
            size,
            theme: SlideTheme::default(),
            margin: h * 0.04,
            title_px: h * 0.05,
            body_px: h * 0.028,
            label_px: h * 0.024,
            gap: h * 0.015,
        }
    }

    /// This layout in `theme`'s colours.
    pub fn with_theme(self, theme: SlideTheme) -> SlideLayout {
        SlideLayout { theme, ..self }
    }

    /// The width text may take: the slide less its margins.
    pub fn text_width(&self) -> f32 {
        self.size[0] as f32 - 2.0 * self.margin
    }

    /// The caption's lines, each at most [`Self::text_width`] wide.
    pub fn caption_lines(&self, lesson: &Lesson) -> Vec<String> {
        wrap_paragraph(&lesson.caption, self.body_px, self.text_width())
    }

    /// The claim's lines with the number `percent`, each at most [`Self::text_width`] wide
    /// (a long claim wraps rather than being cut).
    pub fn claim_lines(&self, lesson: &Lesson, percent: f32) -> Vec<String> {
        wrap_paragraph(&lesson.claim_with(percent), self.body_px, self.text_width())
    }

    /// The pictures' area: below the title, above the labels, caption and claim (laid out for
    /// the widest number, 100.0 %).
    fn picture_area(&self, lesson: &Lesson) -> [f32; 4] {
        let top = self.margin + self.title_px * 1.6;
        let lines = self.caption_lines(lesson).len() + self.claim_lines(lesson, 100.0).len();
        let bottom_block = self.body_px * LEADING * lines as f32 + self.body_px * 0.8 + self.margin;
        let labels = self.label_px * LEADING * 1.4;
        let bottom = self.size[1] as f32 - bottom_block - labels;
        [self.margin, top, self.text_width(), (bottom - top).max(1.0)]
    }

    /// Each picture's place and each inset's: one 16:9 picture for a split (with its two
    /// insets, half its size, stacked beside it), else one per side in the rows of at most
    /// [`MAX_COLUMNS`] that make them largest (with an inset under each), centred.
    fn places(&self, lesson: &Lesson) -> (Vec<Placed>, Vec<Placed>) {
        let [x0, y0, width, height] = self.picture_area(lesson);
        if lesson.split && lesson.inset.is_some() {
            let w = ((width - self.gap) / 1.5).min((height - self.gap) * 16.0 / 9.0).floor().max(16.0);
            let main = [w as u32, (w * 9.0 / 16.0).round() as u32];
            let [iw, ih] = inset_size(lesson, main);
            let left = (x0 + (width - w - self.gap - iw as f32) / 2.0).round() as u32;
            let top = (y0 + ((height - main[1] as f32 - self.gap) / 2.0).max(0.0)).round() as u32;
            let column = left + main[0] + self.gap.round() as u32;
            let insets = [top, top + ih + self.gap.round() as u32].map(|y| Placed { x: column, y, size: [iw, ih] });
            return (vec![Placed { x: left, y: top, size: main }], insets.to_vec());
        }
        let count = if lesson.split { 1 } else { lesson.sides.len() };
        let blocks = if lesson.inset.is_some() { 2 } else { 1 };
        let label_row = self.label_px * LEADING * 1.4;
        let area = [x0, y0, width, height];
        let mut places: Vec<Placed> = tile_cells(count, area, self.gap, label_row, MAX_COLUMNS, blocks)
            .into_iter()
            .map(|[x, y, w, h]| Placed { x: x as u32, y: y as u32, size: [w as u32, h as u32] })
            .collect();
        let insets = places.split_off(count);
        (places, insets)
    }

    /// The size every side of `lesson` is drawn at on this slide.
    pub fn picture_size(&self, lesson: &Lesson) -> [u32; 2] {
        self.places(lesson).0[0].size
    }

    /// The slide of `lesson` (number `index` of `total`, from 1) with the pictures `measured`
    /// drew at [`Self::picture_size`].
    pub fn compose(&self, lesson: &Lesson, measured: &Measured, index: usize, total: usize) -> RgbaImage {
        let [width, height] = self.size;
        let colours = self.theme.palette();
        let [r, g, b] = colours.background;
        let mut slide = RgbaImage::from_pixel(width, height, Rgba([r, g, b, 255]));
        let m = self.margin;
        let title_baseline = m + self.title_px;
        draw_text(&mut slide, &lesson.title, m, title_baseline, self.title_px, colours.text);
        let page = format!("{index} / {total}");
        let page_x = width as f32 - m - text_width(&page, self.label_px);
        draw_text(&mut slide, &page, page_x, m + self.label_px, self.label_px, colours.muted);
        let (places, inset_places) = self.places(lesson);
        let pictures: Vec<&RgbaImage> = match &measured.split {
            Some(split) if lesson.split => vec![split],
            _ => measured.sides.iter().collect(),
        };
        let mut labels_bottom = 0.0f32;
        for (place, picture) in places.iter().zip(pictures) {
            image::imageops::replace(&mut slide, picture, place.x.into(), place.y.into());
            labels_bottom = labels_bottom.max((place.y + place.size[1]) as f32);
        }
        for place in &inset_places {
            labels_bottom = labels_bottom.max((place.y + place.size[1]) as f32);
        }
        let label_baseline = |place: &Placed| (place.y + place.size[1]) as f32 + self.label_px * 1.2;
        if lesson.split {
            // The split's halves: each label centred under its half.
            let place = &places[0];
            let divider = lesson.preset.split.divider.clamp(0.0, 1.0);
            // The divider line as the viewer and `render --split` draw it, across the picture.
            let column = place.x + (place.size[0] as f32 * divider).round() as u32;
            let [d0, d1] = annotate::divider_columns(column, place.size[1]);
            let rows = [place.y as i64, (place.y + place.size[1]) as i64];
            text::fill(&mut slide, [d0 as i64, rows[0], d1 as i64, rows[1]], [255, 255, 255], 1.0);
            let halves = [(0.0, divider), (divider, 1.0)];
            for (side, (from, to)) in lesson.sides.iter().zip(halves) {
                let centre = place.x as f32 + place.size[0] as f32 * (from + to) / 2.0;
                let x = centre - text_width(&side.label, self.label_px) / 2.0;
                draw_text(&mut slide, &side.label, x, label_baseline(place), self.label_px, colours.muted);
            }
        } else {
            for (place, side) in places.iter().zip(&lesson.sides) {
                let label = fit(&side.label, self.label_px, place.size[0] as f32);
                let x = place.x as f32 + (place.size[0] as f32 - text_width(&label, self.label_px)) / 2.0;
                draw_text(&mut slide, &label, x, label_baseline(place), self.label_px, colours.muted);
            }
        }
        let rects = |places: &[Placed]| places.iter().map(|p| [p.x, p.y, p.size[0], p.size[1]]).collect::<Vec<_>>();
        let areas = side_areas(lesson, &rects(&places));
        keys::draw(&mut slide, lesson, &areas, self.label_px);
        if let (Some(inset), Some(zoom)) = (&measured.inset, lesson.inset) {
            let shown = InsetSlide { inset, zoom, places: &rects(&places), insets: &rects(&inset_places) };
            self.draw_insets(&mut slide, lesson, &shown);
        }
        let mut baseline = labels_bottom + self.label_px * LEADING * 1.4 + self.body_px * 1.2;
        for line in self.caption_lines(lesson) {
            draw_text(&mut slide, &line, m, baseline, self.body_px, colours.text);
            baseline += self.body_px * LEADING;
        }
        for line in self.claim_lines(lesson, measured.changed_percent) {
            draw_text(&mut slide, &line, m, baseline + self.body_px * 0.4, self.body_px, colours.accent);
            baseline += self.body_px * LEADING;
        }
        slide
    }
}

/// A lesson's inset as the slide shows it: the rectangles (`[x, y, width, height]`) of the
/// pictures the window is framed on and of the magnified pictures.
struct InsetSlide<'a> {
    inset: &'a Inset,
    zoom: u32,
    places: &'a [[u32; 4]],
    insets: &'a [[u32; 4]],
}

impl SlideLayout {
    /// The magnified pictures with their labels (inside, top left), a frame around each and
    /// one around the window on each picture they come from, in the theme's accent colour.
    fn draw_insets(&self, slide: &mut RgbaImage, lesson: &Lesson, shown: &InsetSlide) {
        let accent = self.theme.palette().accent;
        let line = (self.size[1] as f32 / 270.0).round().max(1.0) as u32;
        let [wx, wy, ww, wh] = shown.inset.window;
        for &[x, y, _, _] in shown.places {
            frame(slide, [x + wx, y + wy, ww, wh], line, accent);
        }
        let px = self.label_px;
        for ((&place, picture), side) in shown.insets.iter().zip(&shown.inset.sides).zip(&lesson.sides) {
            let [x, y, w, _] = place;
            image::imageops::replace(slide, picture, x.into(), y.into());
            frame(slide, place, line, accent);
            let label = fit(&format!("{} ×{}", side.label, shown.zoom), px, w as f32 - px);
            let pad = px * 0.3;
            let (x, y) = (x as f32 + pad, y as f32 + pad);
            let backing = [x, y, x + text_width(&label, px) + 2.0 * pad, y + px * 1.3];
            text::fill(slide, backing.map(|v| v.round() as i64), [0, 0, 0], 170.0 / 255.0);
            draw_text(slide, &label, x + pad, y + px * 1.0, px, [255, 255, 255]);
        }
    }
}

/// Where each side of `lesson` shows on the slide (`[x, y, width, height]`): a split's halves
/// of its one picture, else each side's own picture of `places`.
fn side_areas(lesson: &Lesson, places: &[[u32; 4]]) -> Vec<[u32; 4]> {
    if !lesson.split {
        return places.to_vec();
    }
    let [x, y, w, h] = places[0];
    let column = (w as f32 * lesson.preset.split.divider.clamp(0.0, 1.0)).round() as u32;
    vec![[x, y, column, h], [x + column, y, w - column, h]]
}

/// A frame `line` pixels wide just outside `[x, y, width, height]`.
fn frame(slide: &mut RgbaImage, [x, y, w, h]: [u32; 4], line: u32, color: [u8; 3]) {
    let [x0, y0] = [x, y].map(|c| i64::from(c) - i64::from(line));
    let [x1, y1] = [i64::from(x + w) + i64::from(line), i64::from(y + h) + i64::from(line)];
    let (l, r, t, b) = (i64::from(x), i64::from(x + w), i64::from(y), i64::from(y + h));
    for bar in [[x0, y0, x1, t], [x0, b, x1, y1], [x0, t, l, b], [r, t, x1, b]] {
        text::fill(slide, bar, color, 1.0);
    }
}

/// `text`, cut with an ellipsis when it is wider than `width` at `px` (labels are one line).
fn fit(text: &str, px: f32, width: f32) -> String {
    if text_width(text, px) <= width {
        return text.to_owned();
    }
    let mut cut: String = text.to_owned();
    while !cut.is_empty() && text_width(&format!("{cut}…"), px) > width {
        cut.pop();
    }
    format!("{cut}…")
}

/// Draws `text` anywhere on the slide ([`text::draw`] across the whole width).
fn draw_text(slide: &mut image::RgbaImage, line: &str, x: f32, baseline: f32, px: f32, color: [u8; 3]) {
    let columns = [0, slide.width()];
    text::draw(slide, line, columns, x, baseline, px, color);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lessons::catalogue;

    /// Every caption and claim fits the slide whole at the sizes slides are made at, 16:9 and
    /// 4:3: each line within the width, the last claim line above the slide's bottom edge; and
    /// the pictures and insets fit between the title and the caption.
    #[test]
    fn captions_claims_and_pictures_fit_every_slide() {
        for size in [[1920, 1080], [960, 540], [1280, 720], [1440, 1080], [1024, 768]] {
            let layout = SlideLayout::new(size);
            for lesson in catalogue().unwrap() {
                let lines = layout.caption_lines(&lesson);
                assert!(lines.iter().all(|l| text_width(l, layout.body_px) <= layout.text_width()), "{}", lesson.name);
                assert_eq!(lines.join(" "), lesson.caption.split_whitespace().collect::<Vec<_>>().join(" "));
                let claim = layout.claim_lines(&lesson, 100.0);
                assert!(claim.iter().all(|l| text_width(l, layout.body_px) <= layout.text_width()), "{}", lesson.name);
                let whole = lesson.claim_with(100.0).split_whitespace().collect::<Vec<_>>().join(" ");
                assert_eq!(claim.join(" "), whole, "{}: the claim whole, not cut", lesson.name);
                let (pictures, insets) = layout.places(&lesson);
                assert_eq!(insets.len(), if lesson.inset.is_some() { lesson.sides.len() } else { 0 });
                for place in pictures.iter().chain(&insets) {
                    assert!(place.x + place.size[0] <= size[0] && place.y + place.size[1] < size[1], "{}", lesson.name);
                    assert!(place.size[1] as f32 > size[1] as f32 * 0.2, "{}: {:?}", lesson.name, place.size);
                }
                // The last claim line's baseline as `compose` sets it, with room for descenders.
                let pictures_bottom = pictures.iter().chain(&insets).map(|p| p.y + p.size[1]).max().unwrap() as f32;
                let text_lines = (lines.len() + claim.len() - 1) as f32;
                let last = pictures_bottom
                    + layout.label_px * LEADING * 1.4
                    + layout.body_px * 1.2
                    + layout.body_px * LEADING * text_lines
                    + layout.body_px * 0.4;
                assert!(last + layout.body_px * 0.3 <= size[1] as f32, "{} at {size:?}: {last}", lesson.name);
            }
        }
    }

    /// The light theme draws the same slide on a light background with dark text; the
    /// pictures are the same pixels.
    #[test]
    fn the_light_theme_inverts_the_page_not_the_pictures() {
        let lesson = catalogue().unwrap().into_iter().find(|l| l.name == "cg-wall").unwrap();
        let dark = SlideLayout::new([960, 540]);
        let size = dark.picture_size(&lesson);
        let picture = RgbaImage::from_pixel(size[0], size[1], Rgba([90, 140, 200, 255]));
        let measured = Measured {
            sides: vec![picture.clone(); lesson.sides.len()],
            split: None,
            changed_percent: 12.0,
            inset: None,
        };
        let slides =
            [SlideTheme::Dark, SlideTheme::Light].map(|theme| dark.with_theme(theme).compose(&lesson, &measured, 1, 1));
        let place = &dark.places(&lesson).0[0];
        for (slide, theme) in slides.iter().zip([SlideTheme::Dark, SlideTheme::Light]) {
            let colours = theme.palette();
            assert_eq!(slide.get_pixel(1, 1).0[..3], colours.background, "{theme:?}");
            assert_eq!(slide.get_pixel(place.x + 4, place.y + 4), picture.get_pixel(0, 0), "{theme:?}");
            let title_row = (dark.margin + dark.title_px * 0.7) as u32;
            let inked = (0..slide.width()).filter(|&x| slide.get_pixel(x, title_row).0[..3] == colours.text).count();
            assert!(inked > 0, "{theme:?}: the title drawn in the theme's text colour");
        }
    }
}
