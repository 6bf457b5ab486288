//! The 3D view: an offscreen texture the controller draws into ([`View::draw`], only when the
//! picture would change; smaller than the view while interactive frames are drawn at a lower
//! render scale) and egui shows as an image stretched over the view, with what goes over it — the split
//! view's divider and labels (dragged with the mouse), the Difference view's legend, the
//! lesson's caption card ([`lesson_card`]), a grid lesson's tiles in its place ([`lesson_grid`]), the probe's marker and readout ([`probe_overlay`]) — and the mouse gestures on it ([`input`]).

pub mod input;
mod legend;
mod lesson_card;
mod lesson_grid;
pub mod probe_overlay;

use bumpview::frame::{Msaa, SplitFrame, ViewMode};
use bumpview::render::RenderTarget;
use bumpview::render::srgb_copy::SrgbCopy;
use bumpview::state::{Command, RedrawTracker};
use eframe::egui_wgpu::RenderState;

use super::action::Action;
use super::controller::Controller;

/// Format of the view texture; egui samples it as gamma-encoded colour.
const VIEW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Format the renderer draws through: the same bytes, sRGB-encoded on write.
const VIEW_RENDER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// How close to the split view's divider (points) a drag must begin to move it.
const DIVIDER_GRAB_POINTS: f32 = 8.0;

/// The offscreen texture the 3D view is drawn into, registered with egui.
struct ViewTexture {
    /// The `Rgba8UnormSrgb` view the renderer draws through.
    render_view: wgpu::TextureView,
    /// egui's handle of the plain `Rgba8Unorm` view.
    id: egui::TextureId,
    /// Width and height in pixels: the view's, or fewer at a lower render scale.
    size: [u32; 2],
    /// Where the adapter cannot view one texture in both formats (WebGL2 lacks
    /// `DownlevelFlags::VIEW_FORMATS`), and in every browser: the copy and the plain `Rgba8Unorm` view egui shows,
    /// which gets the same bytes after each draw into `render_view` (a texture of its own).
    copy: Option<(std::sync::Arc<SrgbCopy>, wgpu::TextureView)>,
}

pub struct View {
    /// eframe's device and egui's renderer, which the view texture is registered with.
    render_state: RenderState,
    texture: Option<ViewTexture>,
    /// The view's size in pixels, as last laid out.
    size: Option<[u32; 2]>,
    tracker: RedrawTracker,
    /// The split view and the controller's revision the texture was last drawn with.
    drawn: Option<(Option<SplitFrame>, u64)>,
    /// The divider is being dragged (the drag began near it).
    dragging_divider: bool,
    /// Why the last draw failed.
    render_error: Option<String>,
    /// A grid lesson's tiles, and the size in pixels they were last laid out at.
    grid: lesson_grid::GridView,
    grid_tile_size: Option<[u32; 2]>,
    /// The sRGB copy, made on first use (only where the adapter needs it).
    srgb_copy: Option<std::sync::Arc<SrgbCopy>>,
}

impl View {
    pub fn new(render_state: RenderState) -> View {
        View {
            render_state,
            texture: None,
            size: None,
            tracker: RedrawTracker::default(),
            drawn: None,
            dragging_divider: false,
            render_error: None,
            grid: lesson_grid::GridView::default(),
            grid_tile_size: None,
            srgb_copy: None,
        }
    }

    /// The view's size in pixels, once laid out (the texture may have fewer).
    pub fn size(&self) -> Option<[u32; 2]> {
        self.size
    }

    /// Why the last draw failed.
    pub fn render_error(&self) -> Option<&str> {
        self.render_error.as_deref()
    }

    /// Shows the 3D view filling `ui` with its overlays and returns what the mouse did to it.
    pub fn show(&mut self, ui: &mut egui::Ui, controller: &Controller) -> Vec<Action> {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, egui::Sense::drag());
        let Some(size) = pixel_size(rect.size() * ui.ctx().pixels_per_point(), controller) else {
            return Vec::new();
        };
        self.size = Some(size);
        // The texture's size is decided when it is drawn ([`Self::draw`]); the id stays.
        if let Some(lesson) = controller.lessons.grid_lesson() {
            return self.show_grid(ui, &response, rect, size, controller, lesson);
        }
        self.grid_tile_size = None;
        let id = match &self.texture {
            Some(texture) => texture.id,
            None => self.ensure_texture(size),
        };
        if controller.renderer().prepared(false).is_none() {
            // Before the first scene job is done (the scene given at start) there is nothing
            // to draw yet; the panel names the job's stage.
            let text = "preparing the scene…";
            let color = ui.visuals().weak_text_color();
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                text,
                egui::FontId::proportional(18.0),
                color,
            );
            return Vec::new();
        }
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        ui.painter().image(id, rect, uv, egui::Color32::WHITE);
        let state = &controller.state;
        if state.shading.view == ViewMode::Difference {
            legend::difference(ui.painter(), rect, state.shading.difference_range_deg);
        }
        let mut actions: Vec<Action> = match controller.busy().filter(|_| controller.lessons.card) {
            // The lesson's scene is still on its way: the picture is the previous one's.
            Some(busy) => {
                lesson_card::show_preparing(ui.painter(), &controller.lessons, rect, &busy);
                Vec::new()
            }
            None => lesson_card::show(ui, &controller.lessons, rect).0.into_iter().collect(),
        };
        if state.split.enabled {
            if let Some(divider) = self.split_divider(ui, &response, rect, controller) {
                actions.push(divider);
                return actions;
            }
        } else {
            self.dragging_divider = false;
        }
        actions.extend(probe_overlay::show(ui, controller.probe(), rect, size, &state.camera));
        actions.extend(input::viewport(&response, ui.ctx(), size));
        actions.extend(input::probe_click(ui.ctx(), rect, size));
        actions
    }

    /// Shows grid `lesson`'s tiles filling `rect` (the view, `size` pixels) above its card, and
    /// returns what the mouse did: the camera and light gestures, which the tiles follow.
    fn show_grid(
        &mut self,
        ui: &mut egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        size: [u32; 2],
        controller: &Controller,
        lesson: &bumpview::lessons::Lesson,
    ) -> Vec<Action> {
        let (card, card_height) = lesson_card::show(ui, &controller.lessons, rect);
        let area = egui::Rect::from_min_max(rect.min, egui::pos2(rect.max.x, rect.max.y - card_height));
        let current = controller.lessons.current.unwrap_or_default();
        let tiles = controller.lessons.grid.shown();
        self.grid_tile_size = Some(self.grid.show(ui, area, lesson, current, tiles));
        card.into_iter().chain(input::viewport(response, ui.ctx(), size)).collect()
    }

    /// Draws the split view's divider and labels over the view at `rect`; a drag that began
    /// within [`DIVIDER_GRAB_POINTS`] of the divider moves it (the returned action, instead of
    /// orbiting), elsewhere the view's gestures work as usual (`None`).
    fn split_divider(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        rect: egui::Rect,
        controller: &Controller,
    ) -> Option<Action> {
        let split = controller.state.split;
        let x = rect.left() + rect.width() * split.divider;
        let painter = ui.painter();
        painter.vline(x, rect.y_range(), egui::Stroke::new(2.0, egui::Color32::WHITE));
        let [left, right] = split.labels();
        let font = egui::FontId::proportional(15.0);
        let label_y = rect.top() + 8.0;
        for (text, anchor, pos) in [
            (left, egui::Align2::RIGHT_TOP, egui::pos2(x - 10.0, label_y)),
            (right, egui::Align2::LEFT_TOP, egui::pos2(x + 10.0, label_y)),
        ] {
            let galley = painter.layout_no_wrap(text, font.clone(), egui::Color32::WHITE);
            let text_rect = anchor.anchor_size(pos, galley.size());
            painter.rect_filled(text_rect.expand(4.0), 4.0, egui::Color32::from_black_alpha(170));
            painter.galley(text_rect.min, galley, egui::Color32::WHITE);
        }
        let near = |p: egui::Pos2| (p.x - x).abs() <= DIVIDER_GRAB_POINTS && rect.y_range().contains(p.y);
        if response.hover_pos().is_some_and(near) || self.dragging_divider {
            ui.ctx().set_cursor_icon(egui::CursorIcon::ResizeHorizontal);
        }
        if response.drag_started() {
            self.dragging_divider = ui.ctx().input(|i| i.pointer.press_origin()).is_some_and(near);
        }
        if !response.dragged() {
            self.dragging_divider = false;
            return None;
        }
        if !self.dragging_divider {
            return None;
        }
        let pointer = response.interact_pointer_pos()?;
        let fraction = ((pointer.x - rect.left()) / rect.width()).clamp(0.0, 1.0);
        Some(Command::SetSplitDivider(fraction).into())
    }

    /// Makes the view texture `size` pixels, recreating it only when the size changed.
    fn ensure_texture(&mut self, size: [u32; 2]) -> egui::TextureId {
        if let Some(texture) = self.texture.as_ref().filter(|t| t.size == size) {
            return texture.id;
        }
        let device = &self.render_state.device;
        // In the browser always through the copy: WebGL2 lacks view formats, and Chromium's WebGPU
        // on SwiftShader wrote the picture through the sRGB view without encoding it (too dark).
        let flags = self.render_state.adapter.get_downlevel_capabilities().flags;
        let views_both = !cfg!(target_arch = "wasm32") && flags.contains(wgpu::DownlevelFlags::VIEW_FORMATS);
        let create = |format, usage, view_formats: &[wgpu::TextureFormat]| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some("3d view"),
                size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats,
            })
        };
        let shown_views: &[wgpu::TextureFormat] = if views_both { &[VIEW_RENDER_FORMAT] } else { &[] };
        let both = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
        let texture = create(VIEW_FORMAT, both, shown_views);
        let egui_view = texture.create_view(&Default::default());
        let (render_view, copy) = if views_both {
            let srgb = wgpu::TextureViewDescriptor { format: Some(VIEW_RENDER_FORMAT), ..Default::default() };
            (texture.create_view(&srgb), None)
        } else {
            let drawn = create(VIEW_RENDER_FORMAT, both, &[]);
            let copy = std::sync::Arc::clone(self.srgb_copy.get_or_insert_with(|| SrgbCopy::new(device).into()));
            (drawn.create_view(&Default::default()), Some((copy, egui_view.clone())))
        };
        let mut egui_renderer = self.render_state.renderer.write();
        let id = match &self.texture {
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
        self.texture = Some(ViewTexture { render_view, id, size, copy });
        id
    }

    /// Draws the controller's picture into the view texture at the quality it chooses
    /// ([`Controller::frame_quality`]: interactive while `active`), only when the picture, its
    /// size or quality, the split view or the scene's GPU data changed (nothing before the
    /// first scene is uploaded). Returns whether it drew an interactive frame: then a
    /// full-quality one is owed once input stops.
    pub fn draw(&mut self, controller: &mut Controller, active: bool) -> bool {
        if controller.lessons.grid_lesson().is_some() {
            // The grid's tiles are drawn by the lesson's worker, not into the view texture.
            if let Some(size) = self.grid_tile_size {
                controller.ask_grid_tiles(size);
            }
            self.tracker.invalidate();
            return false;
        }
        let Some(size) = self.size.filter(|_| controller.renderer().prepared(false).is_some()) else { return false };
        let quality = controller.frame_quality(active);
        let render_size = quality.render_size(size);
        self.ensure_texture(render_size);
        let Some(texture) = &self.texture else { return false };
        let drawn = (controller.state.split_frame(), controller.revision());
        if self.drawn != Some(drawn) {
            self.drawn = Some(drawn);
            self.tracker.invalidate();
        }
        if !self.tracker.needs_redraw(&controller.state.frame_params(), render_size, quality.msaa) {
            return false;
        }
        let target = RenderTarget { view: &texture.render_view, format: VIEW_RENDER_FORMAT, size: render_size };
        self.render_error = controller.draw(&target, quality.msaa).err().map(|e| e.to_string());
        if let Some((copy, shown)) = &texture.copy {
            let (device, queue) = (&self.render_state.device, &self.render_state.queue);
            let mut encoder = device.create_command_encoder(&Default::default());
            copy.record(device, &mut encoder, &texture.render_view, shown);
            queue.submit([encoder.finish()]);
        }
        quality.msaa == Msaa::Off
    }
}

/// Whole pixels for a view of `pixels`, within the adapter's limit; `None` when empty.
fn pixel_size(pixels: egui::Vec2, controller: &Controller) -> Option<[u32; 2]> {
    let limit = controller.renderer().max_target_size();
    let side = |v: f32| (v.round() as u32).min(limit);
    let size = [side(pixels.x), side(pixels.y)];
    (size[0] > 0 && size[1] > 0).then_some(size)
}
