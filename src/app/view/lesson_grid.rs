//! A grid lesson's tiles in the 3D view's place: laid out as the slide lays them
//! ([`tile_cells`]), each picture as it arrived from the worker
//! ([`crate::app::controller::LessonGrid`]) with its label over its top-left corner.

use bumpview::lessons::Lesson;
use bumpview::lessons::grid::tile_cells;

use crate::app::controller::Tiles;

/// Points between tiles.
const GAP: f32 = 8.0;
/// At most this many tiles in a row, as on the slide.
const MAX_COLUMNS: usize = 4;

/// The tiles' textures, kept until new pictures arrive.
#[derive(Default)]
pub struct GridView {
    textures: Vec<egui::TextureHandle>,
    /// The serial of the tiles the textures hold.
    serial: Option<u64>,
}

impl GridView {
    /// Shows `lesson`'s tiles (number `current` of the catalogue) in `area`, from `tiles` when
    /// they are that lesson's; returns the size in pixels each tile should be drawn at.
    pub fn show(
        &mut self,
        ui: &egui::Ui,
        area: egui::Rect,
        lesson: &Lesson,
        current: usize,
        tiles: Option<&Tiles>,
    ) -> [u32; 2] {
        let cells = tile_cells(
            lesson.sides.len(),
            [area.left(), area.top(), area.width(), area.height()],
            GAP,
            GAP,
            MAX_COLUMNS,
            1,
        );
        let painter = ui.painter();
        let tiles = tiles.filter(|t| t.key.lesson == current);
        let pictures = match tiles.map(|t| (t.serial, &t.pictures)) {
            Some((serial, Ok(pictures))) => {
                self.take_in(ui.ctx(), serial, pictures);
                Some(&self.textures)
            }
            Some((_, Err(why))) => {
                let text = format!("the tiles could not be drawn: {why}");
                painter.text(
                    area.center(),
                    egui::Align2::CENTER_CENTER,
                    text,
                    egui::FontId::proportional(16.0),
                    ui.visuals().error_fg_color,
                );
                None
            }
            None => None,
        };
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        let font = egui::FontId::proportional(15.0);
        for (i, (cell, side)) in cells.iter().zip(&lesson.sides).enumerate() {
            let rect = egui::Rect::from_min_size(egui::pos2(cell[0], cell[1]), egui::vec2(cell[2], cell[3]));
            match pictures.and_then(|textures| textures.get(i)) {
                Some(texture) => {
                    painter.image(texture.id(), rect, uv, egui::Color32::WHITE);
                }
                None => {
                    painter.rect_filled(rect, 0.0, egui::Color32::from_gray(24));
                    let text = "drawing…";
                    painter.text(rect.center(), egui::Align2::CENTER_CENTER, text, font.clone(), egui::Color32::GRAY);
                }
            }
            let galley = painter.layout_no_wrap(side.label.clone(), font.clone(), egui::Color32::WHITE);
            let text_rect = egui::Align2::LEFT_TOP.anchor_size(rect.min + egui::vec2(8.0, 8.0), galley.size());
            painter.rect_filled(text_rect.expand(4.0), 4.0, egui::Color32::from_black_alpha(170));
            painter.galley(text_rect.min, galley, egui::Color32::WHITE);
        }
        let pixels_per_point = ui.ctx().pixels_per_point();
        let tile = cells.first().map_or([1.0, 1.0], |c| [c[2], c[3]]);
        tile.map(|points| ((points * pixels_per_point).round() as u32).max(1))
    }

    /// Makes the pictures of tiles `serial` into textures, unless they are already.
    fn take_in(&mut self, ctx: &egui::Context, serial: u64, pictures: &[image::RgbaImage]) {
        if self.serial == Some(serial) {
            return;
        }
        self.serial = Some(serial);
        self.textures.truncate(pictures.len());
        for (i, picture) in pictures.iter().enumerate() {
            let size = [picture.width() as usize, picture.height() as usize];
            let image = egui::ColorImage::from_rgba_unmultiplied(size, picture.as_raw());
            match self.textures.get_mut(i) {
                Some(texture) => texture.set(image, egui::TextureOptions::LINEAR),
                None => self.textures.push(ctx.load_texture(
                    format!("lesson tile {i}"),
                    image,
                    egui::TextureOptions::LINEAR,
                )),
            }
        }
    }
}
