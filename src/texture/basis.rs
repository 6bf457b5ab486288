//! UASTC blocks (`KHR_texture_basisu`) → RGBA8 through Binomial's Basis Universal transcoder
//! (the `basis-universal` crate, C++ built by `cc`). It does not build for the browser: there
//! the file is refused in one line that says so.
//!
//! The transcoder writes BC7 blocks (UASTC's designed near-lossless target), which
//! [`super::blocks`] decodes: the crate's wrapper sizes an RGBA32 output as if it were blocks
//! (a quarter of the row), so asking it for RGBA32 directly writes past its buffer.

#[cfg(not(target_arch = "wasm32"))]
use super::blocks::{Block, decode_level};

/// Transcodes `width`×`height` texels of UASTC blocks (16 bytes each, rows of blocks) to RGBA8
/// (`Ok(None)`: no memory for the texels).
#[cfg(not(target_arch = "wasm32"))]
pub fn transcode_uastc(blocks: &[u8], width: u32, height: u32) -> Result<Option<Vec<u8>>, String> {
    use basis_universal::{DecodeFlags, LowLevelUastcTranscoder, SliceParametersUastc, TranscoderBlockFormat};
    let parameters = SliceParametersUastc {
        num_blocks_x: width.div_ceil(4),
        num_blocks_y: height.div_ceil(4),
        has_alpha: true,
        original_width: width,
        original_height: height,
    };
    let bc7 = LowLevelUastcTranscoder::new()
        .transcode_slice(blocks, parameters, DecodeFlags::empty(), TranscoderBlockFormat::BC7)
        .map_err(|e| format!("the UASTC blocks do not transcode: {e:?}"))?;
    Ok(decode_level(Block::Bc7, &bc7, width, height))
}

/// The browser build has no Basis transcoder.
#[cfg(target_arch = "wasm32")]
pub fn transcode_uastc(_blocks: &[u8], _width: u32, _height: u32) -> Result<Option<Vec<u8>>, String> {
    Err("UASTC (Basis Universal) textures cannot be transcoded in the browser build".to_owned())
}
