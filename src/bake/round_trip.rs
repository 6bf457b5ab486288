//! Normal maps through a GPU texture file and back, on the CPU: encoded by the bake's encoders
//! ([`super::compressed_out::encode`]) and decoded by the loader's one entry point
//! ([`crate::texture::decode::decode_image`]), read in the layout the file's format states.
//! The `compression` split's right half and the report's compression study draw them.

use std::borrow::Cow;
use std::sync::Arc;

use super::compressed_format::CompressedFormat;
use crate::names::Named;
use crate::scene::{NormalLayout, Scene, TextureImage, TextureKind};
#[cfg(not(target_arch = "wasm32"))]
use crate::texture::compressed::Stored;

/// An image after the trip.
#[cfg(not(target_arch = "wasm32"))]
#[derive(Debug, Clone, PartialEq)]
pub struct RoundTrip {
    /// The decoded texels, RGBA8, rows top to bottom.
    pub rgba: Vec<u8>,
    /// What the file's format says about its channels.
    pub stored: Option<Stored>,
    /// Bytes of the file written (header included).
    pub file_bytes: usize,
    /// Wall-clock seconds the encoder took.
    pub encode_seconds: f64,
}

/// `rgba` (`width`×`height`, RGBA8) encoded as `format`'s file and decoded again; the error is
/// one line (sides not multiples of 4; ETC1S files without the `etc1s` feature).
#[cfg(not(target_arch = "wasm32"))]
pub fn round_trip(rgba: &[u8], width: u32, height: u32, format: CompressedFormat) -> Result<RoundTrip, String> {
    use crate::texture::decode::{MAX_DECODE_BYTES, decode_image};
    let started = std::time::Instant::now();
    let file = super::compressed_out::encode(rgba, width, height, format)?;
    let encode_seconds = started.elapsed().as_secs_f64();
    let (image, stored) = decode_image(&file, false, MAX_DECODE_BYTES, |_| Ok(()))?;
    Ok(RoundTrip { rgba: image.into_rgba8().into_raw(), stored, file_bytes: file.len(), encode_seconds })
}

/// The web build has no encoders.
#[cfg(target_arch = "wasm32")]
fn trip(
    _: &TextureImage,
    _: CompressedFormat,
) -> Result<(TextureImage, Option<crate::texture::compressed::Stored>), String> {
    Err("the web build has no texture encoders".to_owned())
}

/// `texture` through `format`, as the loader would hold the file: the texels and what the
/// format says about them.
#[cfg(not(target_arch = "wasm32"))]
fn trip(texture: &TextureImage, format: CompressedFormat) -> Result<(TextureImage, Option<Stored>), String> {
    let done = round_trip(&texture.rgba, texture.width, texture.height, format)?;
    let name = format!("{} (through {})", texture.name, format.name());
    let (width, height, kind) = (texture.width, texture.height, texture.kind);
    Ok((TextureImage { name, width, height, kind, rgba: done.rgba }, done.stored))
}

/// `scene` with every RGB normal map replaced by its round trip through `format` (a texture
/// added, as the loader adds a file's), read in the layout the format states
/// ([`crate::scene::NormalMap::with_stored`]); `None`: `scene` as it is. A map that cannot
/// make the trip stays as it is, and `notices` says why.
pub fn normal_maps_through<'a>(
    scene: &'a Scene,
    format: Option<CompressedFormat>,
    notices: &mut Vec<String>,
) -> Cow<'a, Scene> {
    let Some(format) = format else { return Cow::Borrowed(scene) };
    let mut out = scene.clone();
    let mut done: Vec<(usize, usize, _)> = vec![];
    for index in 0..out.materials.len() {
        let Some(map) = out.materials[index].normal_map.clone() else { continue };
        let source = &scene.textures[map.texture];
        if map.convention.layout != NormalLayout::Rgb || source.kind != TextureKind::NormalMap {
            continue;
        }
        let made = match done.iter().find(|d| d.0 == map.texture) {
            Some(&(_, texture, ref stored)) => (texture, Clone::clone(stored)),
            None => match trip(source, format) {
                Ok((texture, stored)) => {
                    out.textures.push(Arc::new(texture));
                    done.push((map.texture, out.textures.len() - 1, stored.clone()));
                    (out.textures.len() - 1, stored)
                }
                Err(e) => {
                    notices.push(format!("{}: not drawn through {}: {e}", source.name, format.name()));
                    continue;
                }
            },
        };
        let moved = crate::scene::NormalMap { texture: made.0, ..map };
        out.materials[index].normal_map = Some(moved.with_stored(made.1.as_ref()));
    }
    Cow::Owned(out)
}
