//! Sanity of a tangent-space normal map, and its likely green-channel convention.
//!
//! A normal map is the gradient of some height field: with decoded `n`, the slopes are
//! `p = ∂h/∂x = −n.x/n.z` and `q = ∂h/∂y_up = −n.y/n.z`, and a gradient field has zero curl,
//! `∂p/∂y_up − ∂q/∂x = 0`. Read with the wrong green convention `q` changes sign, and the
//! "curl" becomes `∂p/∂y_up + ∂q/∂x`, which is not zero where the relief bends. Comparing the
//! two energies tells the convention (Kovesi's integrability test, in short).

use crate::scene::{NormalLayout, TextureImage};

/// Which way green points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GreenConvention {
    /// +Y (green) up the image: OpenGL, glTF, Blender.
    OpenGl,
    /// +Y down the image: DirectX, Unreal.
    DirectX,
}

/// Findings about one normal map.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMapFindings {
    /// Share of texels whose decoded vector `2·rgb − 1` is more than 10% off unit length.
    pub non_unit_share: f32,
    /// Share of texels with `z < 0` (blue below 128): pointing into the surface.
    pub negative_z_share: f32,
    /// The flat texel looks sRGB-encoded: most texels sit near (188, 188) in red and green
    /// (0.5 encoded as sRGB) instead of near 128.
    pub looks_srgb: bool,
    /// The channel layout the texels suggest ([`suggested_layout`]): RG where blue is
    /// constant, AG where red and blue are constant and alpha varies, else RGB. X-Ray's pair
    /// is told by its files, not its texels.
    pub suggested_layout: NormalLayout,
    /// The convention whose slope field is closer to curl-free, with a confidence in 0..1
    /// (`1 − smaller energy / larger energy`); `None` for a map too flat to tell.
    pub convention: Option<(GreenConvention, f32)>,
}

/// Slopes (p, q) of texel (x, y) under the OpenGL reading, or `None` where z ≤ 0.
fn slopes(image: &TextureImage, x: i64, y: i64) -> Option<(f32, f32)> {
    let t = image.texel(x, y);
    let [nx, ny, nz] = [0, 1, 2].map(|c| t[c] as f32 / 127.5 - 1.0);
    (nz > 0.05).then(|| (-nx / nz, -ny / nz))
}

/// Checks `image` as a tangent-space normal map.
pub fn check_normal_map(image: &TextureImage) -> NormalMapFindings {
    let texels = (image.width as usize * image.height as usize).max(1) as f32;
    let (mut non_unit, mut negative_z, mut near_srgb_flat, mut near_linear_flat) = (0usize, 0usize, 0usize, 0usize);
    let first = image.rgba.get(..4).map_or([0; 4], |t| [t[0], t[1], t[2], t[3]]);
    let mut constant = [true; 4];
    for t in image.rgba.chunks_exact(4) {
        let [x, y, z] = [0, 1, 2].map(|c| t[c] as f32 / 127.5 - 1.0);
        if ((x * x + y * y + z * z).sqrt() - 1.0).abs() > 0.1 {
            non_unit += 1;
        }
        if t[2] < 128 {
            negative_z += 1;
        }
        let near = |c: u8, centre: i32| (c as i32 - centre).abs() <= 12;
        near_srgb_flat += (near(t[0], 188) && near(t[1], 188)) as usize;
        near_linear_flat += (near(t[0], 128) && near(t[1], 128)) as usize;
        (0..4).for_each(|c| constant[c] &= t[c] == first[c]);
    }
    NormalMapFindings {
        non_unit_share: non_unit as f32 / texels,
        negative_z_share: negative_z as f32 / texels,
        looks_srgb: near_srgb_flat > near_linear_flat.max(1) * 2,
        suggested_layout: suggested_layout(constant, image.rgba.len() / 4),
        convention: green_convention(image),
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

/// Integrability energies of both readings, summed over the image (central differences,
/// wrapped); the smaller one wins.
fn green_convention(image: &TextureImage) -> Option<(GreenConvention, f32)> {
    let (mut opengl, mut directx) = (0.0f64, 0.0f64);
    for y in 0..image.height as i64 {
        for x in 0..image.width as i64 {
            let (Some((p_up, _)), Some((p_down, _)), Some((_, q_right)), Some((_, q_left))) =
                (slopes(image, x, y - 1), slopes(image, x, y + 1), slopes(image, x + 1, y), slopes(image, x - 1, y))
            else {
                continue;
            };
            // y_up runs towards smaller rows.
            let dp_dy_up = (p_up - p_down) as f64 * 0.5;
            let dq_dx = (q_right - q_left) as f64 * 0.5;
            opengl += (dp_dy_up - dq_dx).powi(2);
            directx += (dp_dy_up + dq_dx).powi(2);
        }
    }
    let (smaller, larger) = (opengl.min(directx), opengl.max(directx));
    if larger < 1e-6 * image.width as f64 * image.height as f64 {
        return None;
    }
    let convention = if opengl <= directx { GreenConvention::OpenGl } else { GreenConvention::DirectX };
    Some((convention, (1.0 - smaller / larger) as f32))
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
        let findings = check_normal_map(&map);
        let (convention, confidence) = findings.convention.unwrap();
        assert_eq!(convention, GreenConvention::OpenGl);
        assert!(confidence > 0.5, "{confidence}");
        assert!(!findings.looks_srgb && findings.negative_z_share == 0.0);
        assert_eq!(findings.suggested_layout, NormalLayout::Rgb);
        let (flipped, confidence) = check_normal_map(&flip_green(&map)).convention.unwrap();
        assert_eq!(flipped, GreenConvention::DirectX);
        assert!(confidence > 0.5, "{confidence}");
    }

    #[test]
    fn a_flat_map_has_no_convention_and_srgb_encoding_is_spotted() {
        let flat = |rgb: [u8; 3]| TextureImage {
            name: "flat".into(),
            width: 8,
            height: 8,
            kind: crate::scene::TextureKind::NormalMap,
            rgba: [rgb[0], rgb[1], rgb[2], 255].repeat(64),
        };
        let linear = check_normal_map(&flat([128, 128, 255]));
        assert!(linear.convention.is_none() && !linear.looks_srgb);
        assert_eq!(linear.suggested_layout, NormalLayout::Rg);
        assert!(check_normal_map(&flat([188, 188, 255])).looks_srgb);
        assert_eq!(check_normal_map(&flat([128, 128, 0])).negative_z_share, 1.0);
    }

    /// DXT5nm keeps red and blue constant and x in alpha; BC5 keeps blue constant.
    #[test]
    fn constant_channels_suggest_the_layout() {
        let map = brick_height_field(1.0).to_normal_map(Kernel::CentralDifference, Border::Wrap, "bricks");
        let mut ag = map.clone();
        ag.rgba.chunks_exact_mut(4).for_each(|t| t.copy_from_slice(&[255, t[1], 0, t[0]]));
        let mut rg = map.clone();
        rg.rgba.chunks_exact_mut(4).for_each(|t| t[2] = 0);
        let layouts = [&map, &ag, &rg].map(|m| check_normal_map(m).suggested_layout);
        assert_eq!(layouts, [NormalLayout::Rgb, NormalLayout::Ag, NormalLayout::Rg]);
    }
}
