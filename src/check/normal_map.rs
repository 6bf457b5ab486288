//! Sanity of a normal map: unit length, texels below the surface, sRGB encoding, the channel
//! layout its texels suggest, whether it is in object space, and (for tangent-space maps)
//! its likely green-channel convention ([`super::green`]).

use glam::{Vec3, Vec4};

use super::green::{GreenConvention, GreenEvidence, Undetermined, green_evidence_of};
use crate::scene::{NormalLayout, TextureImage};
use crate::shading::{NormalTexel, unpack_normal};

/// Findings about one normal map.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMapFindings {
    /// Share of texels whose decoded vector is more than 10% off unit length: `2·rgb − 1` read
    /// as RGB; for a two-channel layout (RG, AG), whose z is rebuilt, `(x, y)` more than 10%
    /// outside the unit disc.
    pub non_unit_share: f32,
    /// Share of texels with `z < 0` (blue below 128) read as RGB: pointing into the surface;
    /// none in a two-channel layout.
    pub negative_z_share: f32,
    /// The flat texel looks sRGB-encoded: most texels sit near (188, 188, 255) (0.5 encoded
    /// as sRGB in red and green, blue near full) instead of near (128, 128, 255).
    pub looks_srgb: bool,
    /// The channel layout the texels suggest ([`suggested_layout`]): RG where blue is
    /// constant, AG where red and blue are constant and alpha varies, else RGB. X-Ray's pair
    /// is told by its files, not its texels.
    pub suggested_layout: NormalLayout,
    /// The decoded normals spread over the sphere rather than around +Z ([`looks_object_space`]):
    /// an object-space map, whose green has no tangent-space convention to judge.
    pub looks_object_space: bool,
    /// The layout the vectors were decoded in for the space and green tests: the one asked
    /// for, or for RGB the one the texels suggest (a BC5 or DXT5nm map as it lands in RGB).
    pub read_layout: NormalLayout,
    /// The tiles' votes on the green convention, and the verdict or why there is none.
    pub green: GreenEvidence,
    /// The decided convention with its confidence (0.5..1, at least
    /// [`super::green::DECIDED_CONFIDENCE`]); `None` when undetermined or in object space.
    pub convention: Option<(GreenConvention, f32)>,
}

impl NormalMapFindings {
    /// The green verdict in words: `OpenGL (+Y), confidence 0.98`, `undetermined (too flat)`,
    /// `not judged (object space)`.
    pub fn green_text(&self) -> String {
        match (self.looks_object_space, self.green.verdict) {
            (true, _) => "not judged (object space)".to_owned(),
            (false, Ok((GreenConvention::OpenGl, c))) => format!("OpenGL (+Y), confidence {c:.2}"),
            (false, Ok((GreenConvention::DirectX, c))) => format!("DirectX (−Y), confidence {c:.2}"),
            (false, Err(reason)) => format!("undetermined ({})", reason.reason()),
        }
    }

    /// Why the convention is undetermined, for a tangent-space map without a verdict.
    pub fn undetermined(&self) -> Option<Undetermined> {
        self.green.verdict.err().filter(|_| !self.looks_object_space)
    }
}

/// Share of texels with `z` below [`OBJECT_SPACE_Z`] from which a map reads as object space.
pub const OBJECT_SPACE_SHARE: f32 = 0.25;
/// A tangent-space normal leans at most about 73° from +Z on all but a few texels.
pub const OBJECT_SPACE_Z: f32 = 0.3;

/// Whether unit normals spread over the sphere rather than around +Z: at least
/// [`OBJECT_SPACE_SHARE`] of them have `z < ` [`OBJECT_SPACE_Z`].
pub fn looks_object_space(normals: impl ExactSizeIterator<Item = Vec3>) -> bool {
    let count = normals.len();
    let low = normals.filter(|n| n.z < OBJECT_SPACE_Z).count();
    low as f32 >= OBJECT_SPACE_SHARE * count.max(1) as f32
}

/// The unit vector of one RGBA texel `t` read in `layout` (X-Ray without its correction).
fn decoded_normal(t: &[u8], layout: NormalLayout) -> Vec3 {
    let texel =
        NormalTexel { rgba: Vec4::new(t[0] as f32, t[1] as f32, t[2] as f32, t[3] as f32) / 255.0, correction: None };
    unpack_normal(texel, layout).try_normalize().unwrap_or(Vec3::Z)
}

/// The unit vectors of `image`'s texels read in `layout` (X-Ray without its correction).
pub fn decoded_normals(image: &TextureImage, layout: NormalLayout) -> Vec<Vec3> {
    image.rgba.chunks_exact(4).map(|t| decoded_normal(t, layout)).collect()
}

/// How far texel `t` read in `layout` is from unit length, and whether it points into the
/// surface: `2·rgb − 1` for RGB and X-Ray (its channels without their correction), `(x, y)`
/// alone where z is rebuilt from them.
fn length_and_below(t: &[u8], layout: NormalLayout) -> (f32, bool) {
    let unorm = |c: usize| t[c] as f32 / 127.5 - 1.0;
    match layout {
        NormalLayout::Rg => (glam::vec2(unorm(0), unorm(1)).length(), false),
        NormalLayout::Ag => (glam::vec2(unorm(3), unorm(1)).length(), false),
        NormalLayout::Rgb | NormalLayout::Xray => (Vec3::new(unorm(0), unorm(1), unorm(2)).length(), t[2] < 128),
    }
}

/// Checks `image` as a normal map read in `layout`: the length and `z < 0` statistics in that
/// layout ([`length_and_below`]), the sRGB test on red, green, blue.
pub fn check_normal_map(image: &TextureImage, layout: NormalLayout) -> NormalMapFindings {
    let texels = (image.width as usize * image.height as usize).max(1) as f32;
    let (mut non_unit, mut negative_z, mut near_srgb_flat, mut near_linear_flat) = (0usize, 0usize, 0usize, 0usize);
    let first = image.rgba.get(..4).map_or([0; 4], |t| [t[0], t[1], t[2], t[3]]);
    let mut constant = [true; 4];
    for t in image.rgba.chunks_exact(4) {
        let (length, below) = length_and_below(t, layout);
        let two_channel = matches!(layout, NormalLayout::Rg | NormalLayout::Ag);
        non_unit += if two_channel { length > 1.1 } else { (length - 1.0).abs() > 0.1 } as usize;
        negative_z += below as usize;
        let near = |c: u8, centre: i32| (c as i32 - centre).abs() <= 12;
        near_srgb_flat += (near(t[0], 188) && near(t[1], 188) && t[2] >= 240) as usize;
        near_linear_flat += (near(t[0], 128) && near(t[1], 128) && t[2] >= 240) as usize;
        (0..4).for_each(|c| constant[c] &= t[c] == first[c]);
    }
    let suggested_layout = suggested_layout(constant, image.rgba.len() / 4);
    let read_layout = if layout == NormalLayout::Rgb { suggested_layout } else { layout };
    let looks_object_space = looks_object_space(image.rgba.chunks_exact(4).map(|t| decoded_normal(t, read_layout)));
    let normal_at = |i: usize| decoded_normal(&image.rgba[4 * i..4 * i + 4], read_layout);
    let green = green_evidence_of(normal_at, image.width, image.height);
    let convention = green.verdict.ok().filter(|_| !looks_object_space);
    NormalMapFindings {
        non_unit_share: non_unit as f32 / texels,
        negative_z_share: negative_z as f32 / texels,
        looks_srgb: !looks_object_space && near_srgb_flat > near_linear_flat.max(1) * 2,
        suggested_layout,
        looks_object_space,
        read_layout,
        green,
        convention,
    }
}

/// The layout channels that are constant over `texels` texels suggest (RGBA order): AG
/// (DXT5nm) where red and blue are constant and alpha varies, RG (two-channel) where blue is
/// constant, else RGB. A map of fewer than 4 texels tells nothing (RGB).
pub fn suggested_layout(constant: [bool; 4], texels: usize) -> NormalLayout {
    match constant {
        _ if texels < 4 => NormalLayout::Rgb,
        [true, _, true, false] => NormalLayout::Ag,
        [_, _, true, _] => NormalLayout::Rg,
        _ => NormalLayout::Rgb,
    }
}

/// Why the channels suggest `layout` (see [`suggested_layout`]).
pub fn layout_evidence(layout: NormalLayout) -> &'static str {
    match layout {
        NormalLayout::Rgb => "red, green and blue vary",
        NormalLayout::Rg => "blue is constant",
        NormalLayout::Ag => "red and blue are constant, alpha varies",
        NormalLayout::Xray => "X-Ray's bump pair",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::height::{Border, Kernel};
    use crate::scene::bricks::brick_height_field;

    fn flip_green(image: &TextureImage) -> TextureImage {
        let mut flipped = image.clone();
        flipped.rgba.chunks_exact_mut(4).for_each(|t| t[1] = 255 - t[1]);
        flipped
    }

    #[test]
    fn the_brick_map_reads_as_opengl_and_its_flip_as_directx() {
        let map = brick_height_field(1.0).to_normal_map(Kernel::CentralDifference, Border::Wrap, "bricks");
        let findings = check_normal_map(&map, NormalLayout::Rgb);
        let (convention, confidence) = findings.convention.unwrap();
        assert_eq!(convention, GreenConvention::OpenGl);
        assert!(confidence > 0.5, "{confidence}");
        assert!(!findings.looks_srgb && findings.negative_z_share == 0.0);
        assert_eq!(findings.suggested_layout, NormalLayout::Rgb);
        let (flipped, confidence) = check_normal_map(&flip_green(&map), NormalLayout::Rgb).convention.unwrap();
        assert_eq!(flipped, GreenConvention::DirectX);
        assert!(confidence > 0.5, "{confidence}");
    }

    #[test]
    fn a_flat_map_has_no_convention_and_srgb_encoding_is_spotted() {
        let flat = |rgb: [u8; 3]| {
            TextureImage::new(
                "flat",
                8,
                8,
                crate::scene::TextureKind::NormalMap,
                [rgb[0], rgb[1], rgb[2], 255].repeat(64),
            )
        };
        let linear = check_normal_map(&flat([128, 128, 255]), NormalLayout::Rgb);
        assert!(linear.convention.is_none() && !linear.looks_srgb);
        assert_eq!(linear.suggested_layout, NormalLayout::Rg);
        assert!(check_normal_map(&flat([188, 188, 255]), NormalLayout::Rgb).looks_srgb);
        assert_eq!(check_normal_map(&flat([128, 128, 0]), NormalLayout::Rgb).negative_z_share, 1.0);
        // Two channels (a BC5 map, blue 0): z is rebuilt, nothing points into the surface, and
        // only (x, y) outside the unit disc is off unit length.
        let two_channel = check_normal_map(&flat([128, 128, 0]), NormalLayout::Rg);
        assert_eq!((two_channel.negative_z_share, two_channel.non_unit_share), (0.0, 0.0));
        assert_eq!(check_normal_map(&flat([255, 255, 0]), NormalLayout::Rg).non_unit_share, 1.0);
    }

    /// DXT5nm keeps red and blue constant and x in alpha; BC5 keeps blue constant.
    #[test]
    fn constant_channels_suggest_the_layout() {
        let map = brick_height_field(1.0).to_normal_map(Kernel::CentralDifference, Border::Wrap, "bricks");
        let mut ag = map.clone();
        ag.rgba.chunks_exact_mut(4).for_each(|t| t.copy_from_slice(&[255, t[1], 0, t[0]]));
        let mut rg = map.clone();
        rg.rgba.chunks_exact_mut(4).for_each(|t| t[2] = 0);
        let layouts = [&map, &ag, &rg].map(|m| check_normal_map(m, NormalLayout::Rgb).suggested_layout);
        assert_eq!(layouts, [NormalLayout::Rgb, NormalLayout::Ag, NormalLayout::Rg]);
    }

    /// The normals of a sphere laid out by longitude and latitude spread over all directions:
    /// object space, not judged for green, and not taken for sRGB.
    #[test]
    fn a_sphere_map_reads_as_object_space() {
        let (width, height) = (64u32, 32u32);
        let mut rgba = Vec::new();
        for row in 0..height {
            for x in 0..width {
                let longitude = std::f32::consts::TAU * (x as f32 + 0.5) / width as f32;
                let latitude = std::f32::consts::PI * ((row as f32 + 0.5) / height as f32 - 0.5);
                let n = Vec3::new(latitude.cos() * longitude.cos(), latitude.cos() * longitude.sin(), -latitude.sin());
                rgba.extend(n.to_array().map(|c| (127.5 * (c + 1.0)).round() as u8));
                rgba.push(255);
            }
        }
        let kind = crate::scene::TextureKind::NormalMap;
        let sphere = TextureImage::new("sphere", width, height, kind, rgba);
        let findings = check_normal_map(&sphere, NormalLayout::Rgb);
        assert!(findings.looks_object_space && !findings.looks_srgb);
        assert_eq!(findings.convention, None);
        assert_eq!(findings.green_text(), "not judged (object space)");
        let bricks = brick_height_field(1.0).to_normal_map(Kernel::CentralDifference, Border::Wrap, "bricks");
        assert!(!check_normal_map(&bricks, NormalLayout::Rgb).looks_object_space);
    }
}
