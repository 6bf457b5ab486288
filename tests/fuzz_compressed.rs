//! Mutation fuzzing of the DDS and KTX2 readers: bytes of the committed fixtures
//! (tests/fixtures/compressed) overwritten, header words set to hostile values, files cut short,
//! decoded as a normal map the way every image is opened ([`decode_texture`]): a texture or one
//! line naming the file, never a panic, and never more texels than the header states.
//!
//! The case count per target is `BUMPVIEW_FUZZ_CASES` (default 256); failing inputs are kept in
//! `tests/fuzz_compressed.proptest-regressions` and replayed first.

mod common;

use std::path::{Path, PathBuf};

use bumpview::load::image::decode_texture;
use bumpview::scene::TextureKind;
use proptest::prelude::*;

fn fixture(name: &str) -> (PathBuf, Vec<u8>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/compressed").join(name);
    let bytes = std::fs::read(&path).unwrap();
    (path, bytes)
}

/// The KTX2 fixtures mutated: Basis UASTC, and ETC1S (BasisLZ), whose corrupt codebooks and
/// slices once aborted the program on the transcoder's debug asserts (.cargo/config.toml).
const KTX2_FIXTURES: &[&str] = &["brick_normal_uastc.ktx2", "brick_normal_uastc_mips.ktx2", "brick_normal_etc1s.ktx2"];

/// Hostile 32-bit words for size, offset and format slots.
const WORDS: &[u32] = &[0, 1, 2, 3, 4, 5, 16, 255, 0x7fff_ffff, 0x8000_0000, u32::MAX, 16384, 16385, 65536];

/// A mutation: a word written at a 4-byte slot, a byte overwritten, or the file cut.
#[derive(Debug, Clone)]
enum Mutation {
    Word { slot: usize, value: u32 },
    Byte { at: usize, value: u8 },
    Cut { keep: usize },
}

fn mutation(header_slots: usize) -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (0..header_slots, prop::sample::select(WORDS)).prop_map(|(slot, value)| Mutation::Word { slot, value }),
        (any::<prop::sample::Index>(), any::<u8>())
            .prop_map(|(at, value)| Mutation::Byte { at: at.index(1 << 20), value }),
        any::<prop::sample::Index>().prop_map(|keep| Mutation::Cut { keep: keep.index(1 << 20) }),
    ]
}

fn mutate(bytes: &mut Vec<u8>, mutation: &Mutation) {
    match *mutation {
        Mutation::Word { slot, value } => {
            if let Some(word) = bytes.get_mut(slot * 4..slot * 4 + 4) {
                word.copy_from_slice(&value.to_le_bytes());
            }
        }
        Mutation::Byte { at, value } => {
            let len = bytes.len().max(1);
            if let Some(byte) = bytes.get_mut(at % len) {
                *byte = value;
            }
        }
        Mutation::Cut { keep } => {
            let keep = keep % bytes.len().max(1);
            bytes.truncate(keep);
        }
    }
}

/// The decode of `bytes` as `path` is a texture within its header's size or one line naming it.
fn decodes_or_refuses(path: &Path, bytes: &[u8]) -> Result<(), TestCaseError> {
    match decode_texture(bytes, path, TextureKind::NormalMap) {
        Ok(texture) => {
            prop_assert_eq!(texture.rgba.len() as u64, texture.width as u64 * texture.height as u64 * 4);
            prop_assert!(texture.width <= 16384 && texture.height <= 16384);
        }
        Err(e) => {
            let message = e.to_string();
            prop_assert!(!message.contains('\n'), "{}", message);
            prop_assert!(message.contains(&*path.to_string_lossy()), "{}", message);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(common::fuzz_config())]

    /// DDS: the magic, the 124-byte header and the 20-byte DX10 header are 37 words.
    #[test]
    fn mutated_dds_files_decode_or_refuse_in_one_line(
        name in prop::sample::select(&["brick_normal_bc5.dds", "brick_normal_bc7.dds", "brick_normal_bc5_mips.dds"][..]),
        mutations in prop::collection::vec(mutation(37), 1..4),
    ) {
        let (path, mut bytes) = fixture(name);
        mutations.iter().for_each(|m| mutate(&mut bytes, m));
        decodes_or_refuses(&path, &bytes)?;
    }

    /// KTX2 (UASTC with Zstandard, ETC1S with BasisLZ): the 80-byte header, the level index and
    /// the data format descriptor are 37 words; the global data and levels follow.
    #[test]
    fn mutated_ktx2_files_decode_or_refuse_in_one_line(
        name in prop::sample::select(KTX2_FIXTURES),
        mutations in prop::collection::vec(mutation(37), 1..4),
    ) {
        let (path, mut bytes) = fixture(name);
        mutations.iter().for_each(|m| mutate(&mut bytes, m));
        decodes_or_refuses(&path, &bytes)?;
    }
}

/// The meshopt grid with its compressed buffer's bytes and its extension objects' numbers
/// mutated, loaded as the command line does: a scene or one line naming a file.
fn load_mutated_grid(bin: &[u8], json: &str, case: usize) -> Result<(), TestCaseError> {
    let dir = std::env::temp_dir().join(format!("bumpview-fuzz-meshopt-{}-{case}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("grid_meshopt.bin"), bin).unwrap();
    std::fs::write(dir.join("grid_meshopt.gltf"), json).unwrap();
    let (_, png) = fixture("brick_normal.png");
    std::fs::write(dir.join("brick_normal.png"), png).unwrap();
    let loaded = bumpview::load::load_model(&dir.join("grid_meshopt.gltf"), false);
    let _ = std::fs::remove_dir_all(&dir);
    if let Err(e) = loaded {
        let message = e.to_string();
        prop_assert!(!message.contains('\n'), "{}", message);
        prop_assert!(!e.path.as_os_str().is_empty(), "{}", message);
    }
    Ok(())
}

/// Hostile values for the extension's numbers and names.
const VALUES: &[&str] = &[
    "0",
    "1",
    "3",
    "4",
    "7",
    "8",
    "256",
    "-1",
    "4294967296",
    "\"NONE\"",
    "\"OCTAHEDRAL\"",
    "\"QUATERNION\"",
    "\"EXPONENTIAL\"",
    "\"TRIANGLES\"",
    "\"INDICES\"",
    "null",
];

proptest! {
    #![proptest_config(common::fuzz_config())]

    /// `EXT_meshopt_compression`: byte mutations of the compressed buffer, and one of the
    /// extension's fields (`byteOffset`, `byteLength`, `byteStride`, `count`, `mode`, `filter`,
    /// the fallback's `byteLength`) set to a hostile value.
    #[test]
    fn mutated_meshopt_models_load_or_refuse_in_one_line(
        mutations in prop::collection::vec(mutation(8), 0..4),
        field in 0usize..40,
        value in prop::sample::select(VALUES),
    ) {
        let (_, mut bin) = fixture("grid_meshopt.bin");
        mutations.iter().for_each(|m| mutate(&mut bin, m));
        let (_, json) = fixture("grid_meshopt.gltf");
        let json = String::from_utf8(json).unwrap();
        let keys = ["\"byteOffset\":", "\"byteLength\":", "\"byteStride\":", "\"count\":", "\"mode\":", "\"filter\":"];
        let mut slots: Vec<(usize, &str)> =
            keys.iter().flat_map(|k| json.match_indices(k).collect::<Vec<_>>()).collect();
        slots.sort();
        let (at, key) = slots[field % slots.len()];
        let start = at + key.len();
        let end = start + json[start..].find([',', '}']).unwrap();
        let json = format!("{}{value}{}", &json[..start], &json[end..]);
        load_mutated_grid(&bin, &json, field)?;
    }
}

/// Headers claiming the largest sides over files of a few hundred bytes are refused before any
/// texel is allocated, naming the file.
#[test]
fn huge_headers_over_small_files_are_refused_in_one_line() {
    let (dds, mut bytes) = fixture("brick_normal_bc5.dds");
    bytes.truncate(200);
    bytes[12..16].copy_from_slice(&16384u32.to_le_bytes()); // height
    bytes[16..20].copy_from_slice(&16384u32.to_le_bytes()); // width
    let error = decode_texture(&bytes, &dds, TextureKind::NormalMap).unwrap_err().to_string();
    assert!(error.contains("truncated") || error.contains("over"), "{error}");
    let (ktx2, mut bytes) = fixture("brick_normal_uastc.ktx2");
    bytes[20..24].copy_from_slice(&16384u32.to_le_bytes());
    bytes[24..28].copy_from_slice(&16384u32.to_le_bytes());
    let error = decode_texture(&bytes, &ktx2, TextureKind::NormalMap).unwrap_err().to_string();
    assert!(error.contains("brick_normal_uastc.ktx2"), "{error}");
    println!("{error}");
}
