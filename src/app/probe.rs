//! The pixel probe's model: **P + click** on the 3D view (or `--probe X,Y`) pins the surface
//! point under a pixel; the readout of the whole shading chain there ([`bumpview::probe`]) is
//! recomputed whenever the picture's parameters change (the point stays pinned when the camera
//! or light moves). It probes the very prepared scene the renderer draws that picture from
//! ([`bumpview::render::Renderer::prepared`]), never a copy of its own. No egui here: the view
//! draws the marker and the readout window ([`super::view::probe_overlay`]).

use std::sync::Arc;

use bumpview::frame::{BumpKind, FrameParams};
use bumpview::names::Named;
use bumpview::prepare::PreparedScene;
use bumpview::probe::{ProbePoint, ProbeReadout, ProbeScene, project_to_pixel};
use bumpview::scene::OrbitCamera;
use glam::{Vec2, Vec3, Vec4};

/// The pinned probe and what it needs to recompute.
#[derive(Default)]
pub struct Probe {
    pinned: Option<Pinned>,
    /// The renderer's prepared scene the readout comes from, wrapped for probing; re-made when
    /// the renderer holds another one.
    probed: Option<ProbeScene>,
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
    pub fn pin(&mut self, pixel: [u32; 2], size: [u32; 2]) {
        self.pinned = Some(Pinned { pixel, size, point: None, last: None, mesh_name: String::new(), half: None });
    }

    pub fn clear(&mut self) {
        self.pinned = None;
    }

    pub fn is_pinned(&self) -> bool {
        self.pinned.is_some()
    }

    /// Where the pinned point shows in a `size` view seen by `camera`, pixels from the top-left:
    /// its projection once read out, else the clicked pixel (scaled to `size`).
    pub fn shown_at(&self, camera: &OrbitCamera, size: [u32; 2]) -> Option<Vec2> {
        let pinned = self.pinned.as_ref()?;
        match &pinned.last {
            Some((_, _, readout)) => project_to_pixel(camera, size, readout.position),
            None => Some(Vec2::new(
                (pinned.pixel[0] as f32 + 0.5) * size[0] as f32 / pinned.size[0] as f32,
                (pinned.pixel[1] as f32 + 0.5) * size[1] as f32 / pinned.size[1] as f32,
            )),
        }
    }

    /// The scene was replaced: pick the pinned pixel again.
    pub fn scene_changed(&mut self) {
        self.probed = None;
        if let Some(pinned) = &mut self.pinned {
            pinned.point = None;
            pinned.last = None;
        }
    }

    /// The prepared scene the readout comes from.
    #[cfg(test)]
    pub fn prepared(&self) -> Option<&Arc<PreparedScene>> {
        self.probed.as_ref().map(ProbeScene::prepared)
    }

    /// Recomputes the readout from `prepared` (the renderer's scene of the picture at the
    /// point) when it, the point, the parameters or the view's `size` changed; `half` names the
    /// split view's half the picture is.
    pub fn update(
        &mut self,
        prepared: &Arc<PreparedScene>,
        params: &FrameParams,
        size: [u32; 2],
        half: Option<String>,
    ) {
        let Some(pinned) = &mut self.pinned else { return };
        pinned.half = half;
        if self.probed.as_ref().is_none_or(|probed| !Arc::ptr_eq(probed.prepared(), prepared)) {
            // Geometry and triangle order do not depend on the scene options: the point stays,
            // unless the GPU displaces meshes, whose triangles follow the view.
            if !prepared.gpu_displaced.is_empty() {
                pinned.point = None;
            }
            self.probed = Some(ProbeScene::wrap(Arc::clone(prepared)));
            pinned.last = None;
        }
        let probed = self.probed.as_ref().expect("made above");
        let point = *pinned.point.get_or_insert_with(|| probed.pick(&params.camera, pinned.size, pinned.pixel));
        let Some(point) = point else {
            pinned.last = None;
            return;
        };
        if pinned.last.as_ref().is_some_and(|(p, s, _)| p == params && *s == size) {
            return;
        }
        let readout = probed.readout(&point, params, size);
        pinned.mesh_name = probed.scene().meshes[readout.mesh].name.clone();
        pinned.last = Some((*params, size, readout));
    }

    /// What the readout window shows: the split half, and the readout as text or why there is
    /// none; `None` while nothing is pinned.
    pub fn report(&self) -> Option<ProbeReport> {
        let pinned = self.pinned.as_ref()?;
        let text = match (&pinned.point, &pinned.last) {
            (Some(None), _) => Err("nothing at that pixel (background)"),
            (_, Some((_, _, readout))) => Ok(lines(readout, &pinned.mesh_name)),
            _ => Err("picking…"),
        };
        Some(ProbeReport { pixel: pinned.pixel, half: pinned.half.clone(), text })
    }
}

/// The probe's readout for people.
pub struct ProbeReport {
    /// The pixel clicked.
    pub pixel: [u32; 2],
    /// In the split view: the half the readout follows.
    pub half: Option<String>,
    /// One quantity a line ([`lines`]), or why there is no readout.
    pub text: Result<String, &'static str>,
}

fn v3(v: Vec3) -> String {
    format!("({:6.3}, {:6.3}, {:6.3})", v.x, v.y, v.z)
}

fn v4(v: Vec4) -> String {
    format!("({:6.3}, {:6.3}, {:6.3}, {:6.3})", v.x, v.y, v.z, v.w)
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
    let srgb = (r.chain.color_linear.map(bumpview::math::linear_to_srgb) * 255.0).round();
    let mut text = vec![
        format!("mesh     {mesh_name} ({face} face)"),
        format!("bump     {bump}{}", if r.bump_enabled { "" } else { ", off (B)" }),
        format!("P [m]    {}  {:.3} m away", v3(r.position), r.distance),
        format!("UV       ({:6.3}, {:6.3})", r.uv.x, r.uv.y),
    ];
    if let Some(m) = r.march {
        text.extend([
            format!("V_ts     {}  (tangent space)", opt3(m.view_tangent)),
            format!("layers   {} of {}, depth {:.3}", m.layer_hit, m.layers, m.depth),
            format!("shift    ({:7.4}, {:7.4}) → UV ({:6.3}, {:6.3})", m.shift.x, m.shift.y, m.uv.x, m.uv.y),
            format!("height   {:6.3}  at the hit (0–1)", m.height),
        ]);
    }
    text.extend([
        format!("texel    {texel} (0–255, mip 0, at the read UV)"),
        format!("filtered {}", r.texel.map_or_else(|| "—".to_owned(), |t| v4(t.rgba))),
        format!("bump#    {}  (X-Ray correction)", opt3(r.texel.and_then(|t| t.correction))),
        format!("decoded  {}", opt3(r.chain.decoded)),
        format!("s={:<6.3} {}", r.chain.strength, opt3(r.chain.after_strength)),
        format!("detail   {}", opt3(r.chain.detail.map(|d| d.detail))),
        format!(
            "blended  {}  ({})",
            opt3(r.chain.detail.map(|d| d.blended)),
            r.chain.detail.map_or("no detail map", |d| d.method.name())
        ),
        format!("T        {}", opt3(r.chain.tangent)),
        format!("B        {}", opt3(r.chain.bitangent)),
        format!("N        {}", v3(r.chain.normal)),
        format!("w        {}", r.chain.w.map_or_else(|| "—".to_owned(), |w| format!("{w:+.0}"))),
        format!("frames   {}", r.tangent_method.map_or("none", |m| m.name())),
        format!("N'       {}  (world)", v3(r.chain.shading_normal)),
    ]);
    let mip = &r.chain.mip;
    let lod = mip.lod.map_or_else(|| "—".to_owned(), |lod| format!("{lod:.2}"));
    let widened = match mip.roughness {
        Some(roughness) => format!("roughness {roughness:.3}"),
        None => format!("exponent {:.1} (k_s × {:.3})", mip.shininess, mip.energy),
    };
    text.extend([
        format!("mips     {}, level {lod} (footprint)", mip.filter.name()),
        format!("  |Na| {:.3}  α² + {:.4}  {widened}", mip.length, mip.variance),
    ]);
    for (i, light) in r.chain.lights.iter().enumerate() {
        let Some(light) = light else { continue };
        text.extend([
            format!("light {}  L {}  H {}", i + 1, v3(light.direction), v3(light.half)),
            format!("  N'·L {:6.3}  N'·H {:6.3}  R·V {:6.3}", light.n_dot_l, light.n_dot_h, light.r_dot_v),
            format!("  fade {:6.3}  att {:6.3}  in {}", light.self_shadow, light.attenuation, v3(light.radiance)),
        ]);
    }
    text.extend([
        format!("lit in   {}", r.chain.lighting_space.name()),
        format!("albedo   {}  linear", v3(r.chain.albedo)),
        format!("colour   {}  linear", v3(r.chain.color_linear)),
        format!("sRGB     {:.0} {:.0} {:.0}  (0–255)", srgb.x, srgb.y, srgb.z),
    ]);
    if let Some(shown) = r.shown_bytes() {
        text.push(format!("shown    {:.0} {:.0} {:.0}  (this view)", shown.x, shown.y, shown.z));
    }
    text.join("\n")
}
