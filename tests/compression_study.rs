//! The report's compression study against exact bounds: uncompressed RG8 on the noise map
//! stays within the 8-bit quantisation bound derived below, BC5 beats BC1 on the brick map,
//! and a constant map comes back within each format's endpoint precision.

use bumpview::bake::compressed_format::CompressedFormat;
use bumpview::bake::round_trip::round_trip;
use bumpview::names::Named;
use bumpview::report::compression_study::{
    CompressionPlan, NOISE_SEED, angle_errors, maps, measure_map, noise_normal_map,
};
use bumpview::scene::{NormalLayout, TextureImage, TextureKind, stored_layout};

/// The largest angle (degrees) between a noise-map texel read as RGB and read as RG with z
/// rebuilt. Each stored component is within `q = 1/255` of the true unit normal `n`'s
/// (`round((c + 1)/2 · 255)` steps by `2/255`). RGB: the stored vector is `n + e`, `|e| ≤ √3·q`,
/// so it lies within `asin(√3·q)` of `n`. RG: `(x, y)` lies within `√2·q` of `n`'s; on the
/// upper hemisphere an arc whose projection moves `d` in the xy plane turns by at most `d / z`
/// with `z` its lowest height, and the noise map tilts at most `atan(√2)` (`|n_xy| ≤ √(2/3)`), so
/// `z ≥ √(1 − (√(2/3) + √2·q)²)`. The sum of the two, plus 10⁻⁴° for f32 arithmetic.
fn rg8_bound_deg() -> f64 {
    let q = 1.0 / 255.0;
    let z_low = (1.0 - ((2.0f64 / 3.0).sqrt() + 2f64.sqrt() * q).powi(2)).sqrt();
    ((3f64.sqrt() * q).asin() + 2f64.sqrt() * q / z_low).to_degrees() + 1e-4
}

#[test]
fn uncompressed_rg8_stays_within_the_quantisation_bound() {
    let noise = noise_normal_map(128, NOISE_SEED);
    let rows = measure_map("noise", &noise, None, [0, 0]).unwrap();
    let rg8 = rows.iter().find(|r| r.format == CompressedFormat::DdsRg8).unwrap();
    let measured = rg8.outcome.as_ref().unwrap();
    let [mean, _, max] = measured.angle_deg;
    println!("RG8 on the noise map: mean {mean:.4}°, max {max:.4}°, bound {:.4}°", rg8_bound_deg());
    assert!(max <= rg8_bound_deg(), "max {max}° over the bound {}°", rg8_bound_deg());
    assert!(mean > 0.0, "z is rebuilt, so RG8 cannot equal the RGB source everywhere");
    assert_eq!((measured.gpu_bits, measured.lit_rmse), (16, None));
    // 16 bits a texel and a 148-byte DX10 header.
    assert_eq!(measured.file_bits, (128.0 * 128.0 * 16.0 + 148.0 * 8.0) / (128.0 * 128.0));
}

#[test]
fn bc5_keeps_the_brick_map_closer_than_bc1() {
    let (maps, _) = maps(&CompressionPlan { assets: None, ..CompressionPlan::full(None) });
    let (_, brick) = &maps[0];
    let error = |format| {
        let done = round_trip(&brick.rgba, brick.width, brick.height, format).unwrap();
        let layout = done.stored.as_ref().and_then(stored_layout).unwrap_or(NormalLayout::Rgb);
        angle_errors(brick, &done.rgba, layout)
    };
    let (bc1, bc5) = (error(CompressedFormat::DdsBc1), error(CompressedFormat::DdsBc5));
    println!("bricks {}x{}: BC1 {bc1:?}, BC5 {bc5:?}", brick.width, brick.height);
    assert!(bc5[0] < bc1[0] && bc5[1] < bc1[1], "BC5 {bc5:?} against BC1 {bc1:?}");
}

/// The largest channel difference a constant colour may come back with: none where the
/// format keeps 8-bit endpoints of each channel (BC3's alpha and green, BC5, BC7, RG8, UASTC's
/// endpoints) beyond one step of rounding; BC1 half a 5-bit step (255/31/2 ≈ 4.1) of its
/// 5:6:5 endpoints; ETC1S half a 5-bit step of its base colour plus its intensity modifier.
fn constant_bound(format: CompressedFormat) -> u8 {
    match format {
        CompressedFormat::DdsBc1 => 4,
        CompressedFormat::Ktx2Etc1s => 8,
        _ => 1,
    }
}

#[test]
fn a_constant_map_comes_back_within_each_formats_endpoint_precision() {
    let texel = [171u8, 93, 230, 255];
    let map = TextureImage::new("constant", 16, 16, TextureKind::NormalMap, texel.repeat(256));
    for &format in <CompressedFormat as strum::VariantArray>::VARIANTS {
        let done = round_trip(&map.rgba, 16, 16, format).unwrap();
        let layout = done.stored.as_ref().and_then(stored_layout).unwrap_or(NormalLayout::Rgb);
        // The channels the layout reads: x and y in red and green (alpha for DXT5nm's x), z in blue for RGB.
        let read: &[usize] = match layout {
            NormalLayout::Rg => &[0, 1],
            NormalLayout::Ag => &[3, 1],
            _ => &[0, 1, 2],
        };
        let sources: &[usize] = if layout == NormalLayout::Rgb { &[0, 1, 2] } else { &[0, 1] };
        let worst = done
            .rgba
            .chunks_exact(4)
            .flat_map(|t| read.iter().zip(sources).map(move |(&c, &s)| t[c].abs_diff(texel[s])))
            .max()
            .unwrap();
        println!("{}: constant texel off by at most {worst}", format.name());
        assert!(worst <= constant_bound(format), "{}: off by {worst}", format.name());
        assert!(done.rgba.chunks_exact(4).all(|t| t == &done.rgba[..4]), "{}: not constant", format.name());
    }
}
