//! The parallax family's settings and the displaced reference's level: how texture
//! coordinates are shifted by a height map, and how finely displacement subdivides.

use crate::names::Named;

/// How texture coordinates are shifted by the material's height map before the normal map and
/// the colour are read (the parallax family). The reference plane is the mesh surface, the
/// top of the relief: a texel of height `h` (0..1, white = high; `1 − sample` for a depth map)
/// lies `(1 − h) · depth` metres below it. A uniform. Named `off`, `offset`, `offset-limited`,
/// `steep`, `occlusion`, `relief`, `relaxed-cone`.
///
/// This enum is the family's registry: the report, panel, split view and command line iterate
/// it ([`Parallax::shifting`]) and ask the capabilities below instead of naming a technique.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum Parallax {
    /// No shift: plain normal mapping.
    #[default]
    Off,
    /// Kaneko et al. 2001, "Detailed shape representation with parallax mapping": one height
    /// sample at the pixel's UV, shifted along the view ray to that depth (`÷ N·V`).
    Offset,
    /// Welsh 2004, "Parallax mapping with offset limiting": as [`Parallax::Offset`] without
    /// the `÷ N·V`, so the shift never exceeds the depth at grazing views.
    OffsetLimited,
    /// McGuire & McGuire 2005, "Steep parallax mapping": a linear search along the view ray
    /// through equally spaced depth layers; the first layer below the relief.
    Steep,
    /// Tatarchuk 2006, "Dynamic parallax occlusion mapping with approximate soft shadows": the
    /// linear search, then the ray's intersection with the straight line between the heights
    /// of the last two layers.
    Occlusion,
    /// Policarpo, Oliveira & Comba 2005, "Real-time relief mapping on arbitrary polygonal
    /// surfaces": the linear search, then binary-search steps between the last two layers.
    Relief,
    /// Policarpo & Oliveira 2007, "Relaxed cone stepping for relief mapping" (GPU Gems 3
    /// ch. 18), on cone maps after Dummer 2006: steps as far as the relaxed cone read at the
    /// ray's texel allows (the layers are the most steps), then the binary search of relief
    /// mapping. Reads the cone map the prepare stage packs into the height texture
    /// ([`crate::height::cone`]).
    RelaxedCone,
}

impl Parallax {
    /// The index the `PARALLAX` pipeline constant takes (shaders/parallax.wgsl).
    pub fn shader_index(self) -> u32 {
        self as u32
    }

    /// Whether the technique shifts the UV at all (every one but off).
    pub fn shifts(self) -> bool {
        self != Parallax::Off
    }

    /// Every technique that shifts the UV, in declaration order: what the studies, charts
    /// and CPU-against-GPU tests iterate.
    pub fn shifting() -> impl Iterator<Item = Parallax> {
        Parallax::all().iter().copied().filter(|t| t.shifts())
    }

    /// Whether the technique searches along the ray, taking `ParallaxSettings::layers` steps
    /// (steep, occlusion, relief, relaxed cones): it has a layer count and casts the soft
    /// self-shadows.
    pub fn marches(self) -> bool {
        matches!(self, Parallax::Steep | Parallax::Occlusion | Parallax::Relief | Parallax::RelaxedCone)
    }

    /// Whether the technique reads the relaxed cone map beside the heights (relaxed cones): the
    /// scene is prepared with it only then ([`crate::frame::SceneOptions::cone_maps`]).
    pub fn reads_cones(self) -> bool {
        self == Parallax::RelaxedCone
    }

    /// Whether the technique ends with `ParallaxSettings::steps` binary-search steps (relief,
    /// relaxed cones).
    pub fn refines(self) -> bool {
        matches!(self, Parallax::Relief | Parallax::RelaxedCone)
    }

    /// The technique the studies measure the others against at equal layers: the search with
    /// the fewest extra samples per layer (steep).
    pub fn plainest_search() -> Parallax {
        Parallax::Steep
    }

    /// The technique whose layers-for-half-a-texel the parallax page leads with (occlusion,
    /// Tatarchuk's, the usual one in engines).
    pub fn headline() -> Parallax {
        Parallax::Occlusion
    }

    /// The technique references are drawn with: relief mapping (at many layers and steps it
    /// converges on the exact hit).
    pub fn reference() -> Parallax {
        Parallax::Relief
    }
}

/// The most layers a search takes, and the most binary-search steps of relief mapping: the
/// bounds of the shader's loops.
pub const MAX_PARALLAX_LAYERS: u32 = 256;
pub const MAX_PARALLAX_STEPS: u32 = 16;

/// The parallax technique and its settings (uniforms).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParallaxSettings {
    pub technique: Parallax,
    /// Layers of the linear search: `max` seen face-on, `min` at grazing views, linear in
    /// `N·V` between (Tatarchuk 2006); each clamped to 1..=[`MAX_PARALLAX_LAYERS`]. Equal
    /// values give a fixed count.
    pub layers_min: u32,
    pub layers_max: u32,
    /// Binary-search steps of relief mapping, 0..=[`MAX_PARALLAX_STEPS`].
    pub steps: u32,
    /// The relief's depth, metres: `None` takes each material's height range
    /// ([`crate::scene::HeightMap::range_m`]). 0 is plain normal mapping.
    pub depth_m: Option<f32>,
    /// Soft self-shadowing of the searches (Tatarchuk 2006): how dark the relief's own
    /// shadows are, 0 (off) to [`MAX_PARALLAX_SHADOW_STRENGTH`]; a uniform.
    pub shadow_strength: f32,
}

/// The strongest parallax self-shadowing (4 darkens fully where a blocker rises a 32nd of the
/// depth above the light ray next to the point).
pub const MAX_PARALLAX_SHADOW_STRENGTH: f32 = 4.0;

impl Default for ParallaxSettings {
    fn default() -> Self {
        ParallaxSettings {
            technique: Parallax::Off,
            layers_min: 8,
            layers_max: 32,
            steps: 5,
            depth_m: None,
            shadow_strength: 0.0,
        }
    }
}

impl ParallaxSettings {
    /// The layer count at `n_dot_v` (`N·V`, 0 grazing .. 1 face-on): Tatarchuk's
    /// `⌊max + (min − max) · N·V + ½⌋`, within [`Self::layer_range`].
    pub fn layers(&self, n_dot_v: f32) -> u32 {
        let (low, high) = self.layer_range();
        let t = if n_dot_v.is_finite() { n_dot_v.clamp(0.0, 1.0) } else { 0.0 };
        (high as f32 + (low as f32 - high as f32) * t + 0.5).floor() as u32
    }

    /// `(min, max)` clamped to 1..=[`MAX_PARALLAX_LAYERS`], `min ≤ max`.
    pub fn layer_range(&self) -> (u32, u32) {
        let clamp = |n: u32| n.clamp(1, MAX_PARALLAX_LAYERS);
        let (a, b) = (clamp(self.layers_min), clamp(self.layers_max));
        (a.min(b), a.max(b))
    }

    /// A caption: `parallax: ` and the technique's [`Named`] name; for searches, its layers
    /// (and relief's steps, and the shadows when on); a depth set instead of the materials'
    /// height ranges, in centimetres.
    pub fn caption(&self) -> String {
        let (low, high) = self.layer_range();
        let layers = if low == high { format!("{high} layers") } else { format!("{low}–{high} layers") };
        let shadows = if self.shadows_on() { ", shadows" } else { "" };
        let depth = match self.depth_m {
            Some(depth) => format!(", depth {:.2} cm", depth * 100.0),
            None => String::new(),
        };
        let (name, technique) = (self.technique.name(), self.technique);
        if technique.refines() {
            format!("parallax: {name}, {layers} + {} steps{shadows}{depth}", self.steps)
        } else if technique.marches() {
            format!("parallax: {name}, {layers}{shadows}{depth}")
        } else {
            format!("parallax: {name}{depth}")
        }
    }

    /// Whether the searches cast soft self-shadows (a strength above 0).
    pub fn shadows_on(&self) -> bool {
        self.shadow_strength > 0.0 && self.shadow_strength.is_finite()
    }
}

/// The most tessellation levels of [`Displacement`]: each triangle becomes at most
/// `4^MAX_DISPLACEMENT_LEVEL` triangles (the prepare stage lowers the level further when a
/// scene would exceed [`MAX_DISPLACED_TRIANGLES`]).
pub const MAX_DISPLACEMENT_LEVEL: u32 = 10;
/// The most triangles a displaced scene draws (about 48 bytes per vertex, 12 per triangle).
pub const MAX_DISPLACED_TRIANGLES: usize = 8 << 20;

/// The edge length in pixels the GPU tessellation aims at by default ([`Displacement::gpu`]):
/// within the parallax study's 0.01 RMSE of the CPU reference on the wall and the torus at
/// 1280 × 720 (tests/gpu_displacement.rs; 3.5 px is not, on the wall).
pub const DEFAULT_PIXELS_PER_EDGE: f32 = 3.0;
/// The target edge lengths the GPU tessellation takes, pixels.
pub const GPU_PIXELS_PER_EDGE: std::ops::RangeInclusive<f32> = 0.5..=64.0;
/// The most segments a base edge is cut into on the GPU (level 9 of the CPU tessellation).
pub const MAX_GPU_EDGE_SEGMENTS: u32 = 512;
/// The most triangles the GPU tessellation makes in a frame: above it the target edge grows
/// (a notice says so). With [`MAX_GPU_DISPLACED_VERTICES`] its buffers hold at most 16 MiB.
pub const MAX_GPU_DISPLACED_TRIANGLES: u32 = 1 << 19;
/// The most vertices the GPU tessellation makes in a frame (32 bytes each).
pub const MAX_GPU_DISPLACED_VERTICES: u32 = 5 << 16;

/// Displacement mapping, the parallax family's ground truth: every instance whose material
/// has a height map (and whose mesh has texture coordinates) is tessellated, and each vertex
/// moved along its normal by `(h − 1) · depth` — the same convention as [`Parallax`]: the mesh
/// surface is the top of the relief, a texel of height `h` lies `(1 − h) · depth` metres below
/// it. It is shaded with the displaced surface's normals instead of the normal map. Either on
/// the CPU once (each triangle's edges cut into `2^level` segments), or on the GPU every time
/// the view changes (each edge cut to about [`Self::gpu`] pixels). A scene option: it makes
/// geometry.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Displacement {
    /// CPU tessellation level, 0 (off) to [`MAX_DISPLACEMENT_LEVEL`]: `4^level` triangles per
    /// triangle. Ignored while [`Self::gpu`] is set.
    pub level: u32,
    /// The relief's depth, metres: `None` takes each material's height range. The viewer
    /// sets it from [`ParallaxSettings::depth_m`] so both mean the same relief.
    pub depth_m: Option<f32>,
    /// Tessellated on the GPU instead, each edge cut into segments about this many pixels long
    /// on screen (above 0; [`DEFAULT_PIXELS_PER_EDGE`]).
    pub gpu: Option<f32>,
}

impl Displacement {
    /// Displacement on the GPU at `pixels_per_edge`, the depth from the materials.
    pub fn on_gpu(pixels_per_edge: f32) -> Displacement {
        Displacement { gpu: Some(pixels_per_edge), ..Default::default() }
    }

    /// Whether meshes are displaced.
    pub fn is_on(&self) -> bool {
        self.level > 0 || self.gpu.is_some()
    }

    /// A caption: `displacement, level L`, `displacement on the GPU, 3 px edges` or `no
    /// displacement`.
    pub fn caption(&self) -> String {
        match self.gpu {
            Some(pixels) => format!("displacement on the GPU, {pixels} px edges"),
            None if self.is_on() => format!("displacement, level {}", self.level),
            None => "no displacement".to_owned(),
        }
    }
}
