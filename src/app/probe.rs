//! The pixel probe in the viewer: **P + click** on the 3D view pins the surface point under
//! the pointer; the panel's Probe section shows the whole chain there ([`bumpview::probe`]),
//! recomputed whenever the picture's parameters change (the point stays pinned when the
//! camera or light moves), and a marker is drawn on the view where the point is.

use bumpview::frame::BumpKind;
use bumpview::frame::{FrameParams, SceneOptions};
use bumpview::names::Named;
use bumpview::probe::{ProbePoint, ProbeReadout, ProbeScene, project_to_pixel};
use bumpview::scene::{OrbitCamera, Scene};
use egui::Key;
use glam::{Vec2, Vec3};

use super::Action;

/// The pinned probe and what it needs to recompute.
#[derive(Default)]
pub(super) struct Probe {
    pinned: Option<Pinned>,
    /// The scene as drawn with these options, made on first use after a change.
    cache: Option<(SceneOptions, ProbeScene)>,
}

struct Pinned {
    /// The clicked pixel and the view's size then.
    pixel: [u32; 2],
    size: [u32; 2],
    /// `None` until picked (again after the scene changed); `Some(None)`: nothing there.
    point: Option<Option<ProbePoint>>,
    /// The last readout and the parameters and view size it was computed for.
    last: Option<(FrameParams, [u32; 2], ProbeReadout)>,
    mesh_name: String,
    /// In the split view: which half the readout follows, e.g. "right: tangents: mikktspace".
    half: Option<String>,
}

impl Probe {
    /// Pins the point under `pixel` of a `size` view.
    pub(super) fn pin(&mut self, pixel: [u32; 2], size: [u32; 2]) {
        self.pinned = Some(Pinned { pixel, size, point: None, last: None, mesh_name: String::new(), half: None });
    }

    pub(super) fn is_pinned(&self) -> bool {
        self.pinned.is_some()
    }

    /// Where the pinned point shows in a `size` view seen by `camera`, pixels from the top-left:
    /// its projection once read out, else the clicked pixel (scaled to `size`).
    pub(super) fn shown_at(&self, camera: &OrbitCamera, size: [u32; 2]) -> Option<Vec2> {
        let pinned = self.pinned.as_ref()?;
        match &pinned.last {
            Some((_, _, readout)) => project_to_pixel(camera, size, readout.position),
            None => Some(Vec2::new(
                (pinned.pixel[0] as f32 + 0.5) * size[0] as f32 / pinned.size[0] as f32,
                (pinned.pixel[1] as f32 + 0.5) * size[1] as f32 / pinned.size[1] as f32,
            )),
        }
    }

    pub(super) fn clear(&mut self) {
        self.pinned = None;
    }

    /// The scene was replaced: forget the prepared scene and pick the pinned pixel again.
    pub(super) fn scene_changed(&mut self) {
        self.cache = None;
        if let Some(pinned) = &mut self.pinned {
            pinned.point = None;
            pinned.last = None;
        }
    }

    /// Recomputes the readout when the options, the point, the parameters or the view's `size`
    /// changed; `half` names the split view's half they belong to.
    pub(super) fn update(
        &mut self,
        scene: &Scene,
        options: &SceneOptions,
        params: &FrameParams,
        size: [u32; 2],
        half: Option<String>,
    ) {
        let Some(pinned) = &mut self.pinned else { return };
        pinned.half = half;
        if self.cache.as_ref().is_none_or(|(made_with, _)| made_with != options) {
            // Geometry and triangle order do not depend on the options: the point stays.
            self.cache = Some((options.clone(), ProbeScene::new(scene, options)));
            pinned.last = None;
        }
        let (_, probe_scene) = self.cache.as_ref().expect("made above");
        let point = *pinned.point.get_or_insert_with(|| probe_scene.pick(&params.camera, pinned.size, pinned.pixel));
        let Some(point) = point else {
            pinned.last = None;
            return;
        };
        if pinned.last.as_ref().is_some_and(|(p, s, _)| p == params && *s == size) {
            return;
        }
        let readout = probe_scene.readout(&point, params, size);
        pinned.mesh_name = probe_scene.scene().meshes[readout.mesh].name.clone();
        pinned.last = Some((*params, size, readout));
    }

    /// Draws the marker at the pinned point in the view `rect` (`size` pixels) seen by `camera`.
    pub(super) fn paint(&self, painter: &egui::Painter, rect: egui::Rect, size: [u32; 2], params: &FrameParams) {
        let Some(pixel) = self.shown_at(&params.camera, size) else { return };
        let centre = rect.min + egui::vec2(pixel.x, pixel.y) * (rect.width() / size[0] as f32);
        for (width, colour) in [(3.0, egui::Color32::BLACK), (1.5, egui::Color32::from_rgb(255, 220, 0))] {
            let stroke = egui::Stroke::new(width, colour);
            painter.circle_stroke(centre, 6.0, stroke);
            for d in [egui::vec2(1.0, 0.0), egui::vec2(0.0, 1.0)] {
                painter.line_segment([centre + d * 9.0, centre + d * 14.0], stroke);
                painter.line_segment([centre - d * 9.0, centre - d * 14.0], stroke);
            }
        }
    }

    /// The panel's Probe section.
    pub(super) fn section(&self, ui: &mut egui::Ui, actions: &mut Vec<Action>) {
        ui.separator();
        ui.strong("Probe");
        let Some(pinned) = &self.pinned else {
            ui.weak("P + click on the view pins a pixel: the whole shading chain there");
            return;
        };
        ui.horizontal(|ui| {
            ui.label(format!("pixel ({}, {})", pinned.pixel[0], pinned.pixel[1]));
            if ui.button("Clear probe").clicked() {
                actions.push(Action::ClearProbe);
            }
        });
        if let Some(half) = &pinned.half {
            ui.label(format!("split half {half}"));
        }
        match (&pinned.point, &pinned.last) {
            (Some(None), _) => {
                ui.weak("nothing at that pixel (background)");
            }
            (_, Some((_, _, readout))) => {
                ui.label(egui::RichText::new(lines(readout, &pinned.mesh_name)).monospace().size(11.0));
            }
            _ => {}
        }
    }
}

/// Whether P is held and the primary button was clicked on the view: the clicked pixel of a
/// `size` view shown in `rect`.
pub(super) fn clicked(ctx: &egui::Context, rect: egui::Rect, size: [u32; 2]) -> Option<Action> {
    if ctx.text_edit_focused() {
        return None;
    }
    let position =
        ctx.input(|i| (i.key_down(Key::P) && i.pointer.primary_clicked()).then(|| i.pointer.interact_pos()).flatten())?;
    if !rect.contains(position) {
        return None;
    }
    let scale = size[0] as f32 / rect.width();
    let local = (position - rect.min) * scale;
    let pixel = [(local.x.max(0.0) as u32).min(size[0] - 1), (local.y.max(0.0) as u32).min(size[1] - 1)];
    Some(Action::PinProbe { pixel, size })
}

fn v3(v: Vec3) -> String {
    format!("({:6.3}, {:6.3}, {:6.3})", v.x, v.y, v.z)
}

fn opt3(v: Option<Vec3>) -> String {
    v.map_or_else(|| "—".to_owned(), v3)
}

/// The readout as text, 3 decimals, one quantity a line.
fn lines(r: &ProbeReadout, mesh_name: &str) -> String {
    let face = if r.point.front_facing { "front" } else { "back" };
    let bump = match r.bump {
        BumpKind::None => "no bump map",
        BumpKind::TangentSpace => "tangent-space normal map",
        BumpKind::ObjectSpace => "object-space normal map",
        BumpKind::HeightInShader => "height map in the shader (screen-space derivatives)",
    };
    let texel = match (r.texel_xy, r.texel_raw) {
        (Some([x, y]), Some([red, green, blue, alpha])) => format!("({x}, {y}) = {red} {green} {blue} {alpha}"),
        _ => "—".to_owned(),
    };
    let srgb = (r.color_linear.map(bumpview::math::linear_to_srgb) * 255.0).round();
    let mut text = vec![
        format!("mesh     {mesh_name} ({face} face)"),
        format!("bump     {bump}{}", if r.bump_enabled { "" } else { ", off (B)" }),
        format!("P [m]    {}  {:.3} m away", v3(r.position), r.distance),
        format!("UV       ({:6.3}, {:6.3})", r.uv.x, r.uv.y),
        format!("texel    {texel} (0–255, mip 0)"),
        format!("filtered {}", opt3(r.texel)),
        format!("decoded  {}", opt3(r.decoded)),
        format!("s={:<6.3} {}", r.strength, opt3(r.after_strength)),
        format!("T        {}", opt3(r.tangent)),
        format!("B        {}", opt3(r.bitangent)),
        format!("N        {}", v3(r.normal)),
        format!("w        {}", r.w.map_or_else(|| "—".to_owned(), |w| format!("{w:+.0}"))),
        format!("frames   {}", r.tangent_method.map_or("none", |m| m.name())),
        format!("N'       {}  (world)", v3(r.shading_normal)),
        format!("L        {}", v3(r.light_dir)),
        format!("H        {}", v3(r.half)),
        format!("N'·L     {:6.3}   N'·H {:6.3}", r.n_dot_l, r.n_dot_h),
        format!("fade     {:6.3}  (N·L self-shadow)", r.self_shadow),
        format!("albedo   {}  linear", v3(r.albedo)),
        format!("colour   {}  linear", v3(r.color_linear)),
        format!("sRGB     {:.0} {:.0} {:.0}  (0–255)", srgb.x, srgb.y, srgb.z),
    ];
    if let Some(shown) = r.shown_bytes() {
        text.push(format!("shown    {:.0} {:.0} {:.0}  (this view)", shown.x, shown.y, shown.z));
    }
    text.join("\n")
}
