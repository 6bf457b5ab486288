//! A material's detail normal map: a second tangent-space normal map, tiled over the base map,
//! and the way the two are blended ([`DetailBlend`], re-exported as `crate::frame::DetailBlend`).
//! Here, in the data layer, because a material holds its method; the formulas are
//! `crate::shading::detail_blend`'s, their WGSL twins `shaders/detail.wgsl`; docs/detail-normals.md
//! lists them with their sources and measured errors.

/// How a detail normal map is blended with the base normal map, both tangent space. Named (as
/// on the command line, in presets and lesson files) `linear`, `partial-derivative`,
/// `whiteout`, `udn`, `rnm`, `surface-gradient`. Each is one function of
/// `crate::shading::detail_blend` and one branch of `shaders/detail.wgsl` under the
/// `DETAIL_BLEND` pipeline constant ([`DetailBlend::shader_index`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum DetailBlend {
    /// The two vectors averaged and re-normalised, `normalize(b + d)` (Godot's detail mix at
    /// half weight).
    Linear,
    /// Partial-derivative addition: the slopes `x/z`, `y/z` of the two add,
    /// `normalize(bx·dz + dx·bz, by·dz + dy·bz, bz·dz)`: the normal of the summed heights.
    PartialDerivative,
    /// Whiteout (Barré-Brisebois & Hill 2012, after Christopher Oat's post):
    /// `normalize(bx + dx, by + dy, bz·dz)`.
    Whiteout,
    /// UDN (Unreal Developer Network): `normalize(bx + dx, by + dy, bz)`, cheap, flattens the
    /// detail where the base tilts.
    Udn,
    /// Reoriented normal mapping (Barré-Brisebois & Hill 2012): the detail's frame rotated by
    /// the shortest arc from +Z onto the base normal.
    #[default]
    Rnm,
    /// Mikkelsen's surface gradients (JCGT 2020): each normal turned into a surface gradient
    /// against the unperturbed normal, the gradients added, the sum resolved.
    SurfaceGradient,
}

impl DetailBlend {
    /// The index the `DETAIL_BLEND` pipeline constant takes (shaders/detail.wgsl).
    pub fn shader_index(self) -> u32 {
        self as u32
    }
}

/// A material's detail normal map: tangent space, OpenGL convention (+Y up), RGB, sampled with
/// the detail sampler at the base UV times `tiling`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetailMap {
    /// Index into [`super::Scene::textures`].
    pub texture: usize,
    /// How many times the detail map repeats per unit of the base UV (UV × tiling).
    pub tiling: f32,
    /// Its strength, as a normal map's scale: `normalize(x·s, y·s, z)`; 0 is flat.
    pub strength: f32,
    /// How it is blended with the base normal.
    pub blend: DetailBlend,
}

/// Tiling of a detail map given without one.
pub const DEFAULT_DETAIL_TILING: f32 = 8.0;

impl DetailMap {
    /// `texture` at the default tiling, strength 1, blended by `blend`.
    pub fn new(texture: usize, blend: DetailBlend) -> DetailMap {
        DetailMap { texture, tiling: DEFAULT_DETAIL_TILING, strength: 1.0, blend }
    }

    /// The UV the detail map is read at for the base UV `uv`.
    pub fn uv(&self, uv: glam::Vec2) -> glam::Vec2 {
        uv * self.tiling
    }
}

/// A detail normal map of `size`² texels (RGB, OpenGL convention) holding the sine pair
/// `h = (s/k)·(sin(k·x) + sin(k·y))` with `periods` periods across, `x`, `y` in texels
/// (`y` up the image): slopes `s·cos(k·x)`, `s·cos(k·y)`, at most `slope`.
pub fn sine_pair_normal_map(size: u32, periods: u32, slope: f32) -> super::TextureImage {
    let k = std::f32::consts::TAU * periods as f32 / size as f32;
    let mut rgba = Vec::with_capacity((size * size * 4) as usize);
    for row in 0..size {
        let y = (size - 1 - row) as f32 + 0.5;
        for column in 0..size {
            let x = column as f32 + 0.5;
            let n = glam::Vec3::new(-slope * (k * x).cos(), -slope * (k * y).cos(), 1.0).normalize();
            let rgb = (n * 0.5 + 0.5) * 255.0;
            rgba.extend([rgb.x.round() as u8, rgb.y.round() as u8, rgb.z.round() as u8, 255]);
        }
    }
    let name = format!("sine-pair detail ({periods} periods, slope {slope})");
    super::TextureImage::new(name, size, size, super::TextureKind::NormalMap, rgba)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    /// The shader's `DETAIL_` constants are these indices (names: tests/names.rs).
    #[test]
    fn shader_indices_follow_the_declaration_order() {
        let indices: Vec<u32> = DetailBlend::all().iter().map(|m| m.shader_index()).collect();
        assert_eq!(indices, [0, 1, 2, 3, 4, 5]);
    }
}
