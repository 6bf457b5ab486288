//! Normal maps through a GPU texture file and back, on the CPU: encoded by the bake's encoders
//! ([`super::compressed_out::encode`]) and decoded by the loader's one entry point
//! ([`crate::texture::decode::decode_image`]), read in the layout the file's format states.
//! The `compression` split's right half and the report's compression study draw them.

use std::borrow::Cow;
use std::sync::Arc;

use super::compressed_format::CompressedFormat;
use crate::names::Named;
use crate::scene::{NormalLayout, NormalMap, Scene, TextureImage, TextureKind};
use crate::texture::compressed::Stored;

#[cfg(not(target_arch = "wasm32"))]
use super::compressed_out::encode;

/// The web build has no encoders.
#[cfg(target_arch = "wasm32")]
fn encode(_: &[u8], _: u32, _: u32, _: CompressedFormat) -> Result<Vec<u8>, String> {
    Err("the web build has no texture encoders".to_owned())
}

/// An image after the trip.
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
pub fn round_trip(rgba: &[u8], width: u32, height: u32, format: CompressedFormat) -> Result<RoundTrip, String> {
    use crate::texture::decode::{MAX_DECODE_BYTES, decode_image};
    let started = std::time::Instant::now();
    let file = encode(rgba, width, height, format)?;
    let encode_seconds = started.elapsed().as_secs_f64();
    let (image, stored) = decode_image(&file, false, MAX_DECODE_BYTES, |_| Ok(()))?;
    Ok(RoundTrip { rgba: image.into_rgba8().into_raw(), stored, file_bytes: file.len(), encode_seconds })
}

/// `texture` through `format`, as the loader would hold the file: the texels and what the
/// format says about them.
fn trip(texture: &TextureImage, format: CompressedFormat) -> Result<(TextureImage, Option<Stored>), String> {
    let done = round_trip(&texture.rgba, texture.width, texture.height, format)?;
    let name = format!("{} (through {})", texture.name, format.name());
    let (width, height, kind) = (texture.width, texture.height, texture.kind);
    Ok((TextureImage { name, width, height, kind, rgba: done.rgba }, done.stored))
}

/// Adds `made` (the round trip of texture `source`) to `scene` as the loader adds a file's
/// texture, and draws every material whose RGB normal map is `source` with it instead, read in
/// the layout `stored` states ([`NormalMap::with_stored`]).
pub fn use_round_trip(scene: &mut Scene, source: usize, made: TextureImage, stored: Option<&Stored>) {
    scene.textures.push(Arc::new(made));
    let texture = scene.textures.len() - 1;
    for material in &mut scene.materials {
        if let Some(map) = material.normal_map.as_mut().filter(|m| m.texture == source && is_rgb(m)) {
            *map = NormalMap { texture, ..map.clone() }.with_stored(stored);
        }
    }
}

fn is_rgb(map: &NormalMap) -> bool {
    map.convention.layout == NormalLayout::Rgb
}

/// `scene` with every RGB normal map replaced by its round trip through `format`
/// ([`use_round_trip`]); `None`: `scene` as it is. A map that cannot make the trip stays as
/// it is, and `notices` says why.
pub fn normal_maps_through<'a>(
    scene: &'a Scene,
    format: Option<CompressedFormat>,
    notices: &mut Vec<String>,
) -> Cow<'a, Scene> {
    let Some(format) = format else { return Cow::Borrowed(scene) };
    let mut sources: Vec<usize> =
        scene.materials.iter().filter_map(|m| m.normal_map.as_ref()).filter(|m| is_rgb(m)).map(|m| m.texture).collect();
    sources.sort_unstable();
    sources.dedup();
    let mut out = scene.clone();
    for source in sources.into_iter().filter(|&t| scene.textures[t].kind == TextureKind::NormalMap) {
        match trip(&scene.textures[source], format) {
            Ok((made, stored)) => use_round_trip(&mut out, source, made, stored.as_ref()),
            Err(e) => {
                notices.push(format!("{}: not drawn through {}: {e}", scene.textures[source].name, format.name()))
            }
        }
    }
    Cow::Owned(out)
}
