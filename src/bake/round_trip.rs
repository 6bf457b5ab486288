//! Normal maps through a GPU texture file and back, on the CPU: encoded by the bake's encoders
//! ([`super::compressed_out::encode`]) and decoded by the loader's one entry point
//! ([`crate::texture::decode::decode_image`]), read in the layout the file's format states.
//! The `compression` split's right half and the report's compression study draw them. The
//! split's last few trips are kept ([`TRIPS_KEPT`]): a UASTC encode of a 512² map takes a second
//! or two, and the split's scene is prepared again whenever a drawing option changes.

use std::borrow::Cow;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

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
/// one line (sides not multiples of 4; Basis files in the browser build).
pub fn round_trip(rgba: &[u8], width: u32, height: u32, format: CompressedFormat) -> Result<RoundTrip, String> {
    use crate::texture::decode::{MAX_DECODE_BYTES, decode_image};
    let started = std::time::Instant::now();
    let file = encode(rgba, width, height, format)?;
    let encode_seconds = started.elapsed().as_secs_f64();
    let (image, stored) = decode_image(&file, false, MAX_DECODE_BYTES, |_| Ok(()))?;
    Ok(RoundTrip { rgba: image.into_rgba8().into_raw(), stored, file_bytes: file.len(), encode_seconds })
}

/// How many finished trips [`trip`] keeps (each a texture's size again as RGBA8).
pub const TRIPS_KEPT: usize = 4;

/// A finished trip: its texture's name, size and texels hashed, and the format.
type TripKey = (u64, CompressedFormat);

/// A kept trip: its key, the texture it made and what its format says.
type KeptTrip = (TripKey, Arc<TextureImage>, Option<Stored>);

/// The trips kept, most recent last.
static TRIPS: Mutex<Vec<KeptTrip>> = Mutex::new(Vec::new());

/// `texture` through `format`, as the loader would hold the file: the texels and what the
/// format says about them; one of the last [`TRIPS_KEPT`] trips where it was made already.
fn trip(texture: &TextureImage, format: CompressedFormat) -> Result<(Arc<TextureImage>, Option<Stored>), String> {
    let mut hasher = std::hash::DefaultHasher::new();
    (&texture.name, texture.width, texture.height, texture.kind, &texture.rgba).hash(&mut hasher);
    let key = (hasher.finish(), format);
    let kept = |trips: &mut Vec<KeptTrip>| {
        let at = trips.iter().position(|(k, _, _)| *k == key)?;
        let found = trips.remove(at);
        trips.push(found.clone());
        Some((found.1, found.2))
    };
    if let Some(found) = kept(&mut TRIPS.lock().unwrap_or_else(|e| e.into_inner())) {
        return Ok(found);
    }
    let done = round_trip(&texture.rgba, texture.width, texture.height, format)?;
    let name = format!("{} (through {})", texture.name, format.name());
    let (width, height, kind) = (texture.width, texture.height, texture.kind);
    let made = Arc::new(TextureImage::new(name, width, height, kind, done.rgba));
    let mut trips = TRIPS.lock().unwrap_or_else(|e| e.into_inner());
    trips.push((key, Arc::clone(&made), done.stored.clone()));
    if trips.len() > TRIPS_KEPT {
        trips.remove(0);
    }
    Ok((made, done.stored))
}

/// Adds `made` (the round trip of texture `source`) to `scene` as the loader adds a file's
/// texture, and draws every material whose RGB normal map is `source` with it instead, read in
/// the layout `stored` states ([`NormalMap::with_stored`]).
pub fn use_round_trip(scene: &mut Scene, source: usize, made: Arc<TextureImage>, stored: Option<&Stored>) {
    scene.textures.push(made);
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

#[cfg(all(test, not(target_arch = "wasm32")))]
mod tests {
    use super::*;

    /// The same texels through the same format come from the kept trip, not the encoder again;
    /// another texel or another format is a trip of its own.
    #[test]
    fn a_trip_made_already_is_taken_from_those_kept() {
        let rgba = (0..16 * 16).flat_map(|i| [(i * 7 % 256) as u8, (i * 3 % 256) as u8, 255, 255]).collect();
        let map = TextureImage::new("kept", 16, 16, TextureKind::NormalMap, rgba);
        let (first, stored) = trip(&map, CompressedFormat::DdsBc5).unwrap();
        let (again, stored_again) = trip(&map, CompressedFormat::DdsBc5).unwrap();
        assert!(Arc::ptr_eq(&first, &again));
        assert_eq!(stored, stored_again);
        assert!(!Arc::ptr_eq(&first, &trip(&map, CompressedFormat::DdsBc1).unwrap().0));
        let mut changed = map.clone();
        changed.rgba[0] ^= 1;
        assert!(!Arc::ptr_eq(&first, &trip(&changed, CompressedFormat::DdsBc5).unwrap().0));
    }
}
