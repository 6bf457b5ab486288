//! Structure-aware fuzzing, one target per loader: glTF JSON, GLB containers, OBJ, MTL,
//! images (PNG, TGA, BMP headers and bodies), presets and lesson TOML. Each target writes
//! files built from hostile values put into the slots of a valid document (counts, offsets,
//! indices, types, URIs, node links, extras) and loads them the way the command line does
//! ([`load_model`], outside files refused): every load answers with a scene or one line
//! naming a file, never a panic. Sizes stay small (at most 4096 elements or 64² texels), so
//! all targets together run within a minute at the default case count.
//!
//! The case count per target is `BUMPVIEW_FUZZ_CASES` (default 256); failing inputs are kept
//! in `tests/fuzz_loaders.proptest-regressions` and replayed first. Long runs:
//! `scripts/fuzz-campaign.sh`.

mod common;

use std::path::{Path, PathBuf};

use bumpview::load::image::decode_texture;
use bumpview::load::load_model;
use bumpview::scene::TextureKind;
use proptest::prelude::*;

/// A folder for one target's files, made once per process.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-fuzz-loaders-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The load's outcome is a scene or an error on one line that names a file.
fn one_line(result: Result<bumpview::scene::Scene, bumpview::error::LoadError>) -> Result<(), TestCaseError> {
    if let Err(e) = result {
        let message = e.to_string();
        prop_assert!(!message.contains('\n'), "{message}");
        prop_assert!(!e.path.as_os_str().is_empty(), "{message}");
    }
    Ok(())
}

/// Hostile JSON values for a count, index or offset slot (small enough to stay quick).
const NUMBERS: &[&str] =
    &["0", "1", "2", "3", "-1", "4096", "1.5", "1e3", "null", "\"3\"", "[]", "{}", "true", "2147483648", "36"];

/// Hostile values for a name or URI slot.
const STRINGS: &[&str] = &[
    "\"x.bin\"",
    "\"../outside.bin\"",
    "\"/etc/hostname\"",
    "\"file:///etc/hostname\"",
    "\"http://example.invalid/x\"",
    "\"data:application/octet-stream;base64,AAAA\"",
    "\"data:;base64,!!\"",
    "\"a\\u202eb.bin\"",
    "\"\\u001b[31m\"",
    "\"\"",
    "7",
    "null",
];

/// Hostile values for `extras` and other free slots.
const EXTRAS: &[&str] = &["[]", "[1, 2]", "3", "\"text\"", "{}", "{\"a\": [null]}", "null"];

/// A glTF document whose slots hold the picked values: one triangle with indices, a sparse
/// accessor, a material with a texture, nodes that may link in a loop.
fn gltf_document(n: &[&str], s: &[&str], extras: &str, glb: bool) -> String {
    let buffer = if glb {
        format!(r#"{{"byteLength": {}}}"#, n[0])
    } else {
        format!(r#"{{"uri": {}, "byteLength": {}}}"#, s[0], n[0])
    };
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "extras": {extras},
        "buffers": [{buffer}, {{"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA", "byteLength": 42}}],
        "bufferViews": [{{"buffer": {}, "byteOffset": {}, "byteLength": {}}}, {{"buffer": 1, "byteOffset": 36, "byteLength": 6}}],
        "accessors": [
          {{"bufferView": 0, "componentType": 5126, "count": {}, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
          {{"bufferView": {}, "componentType": {}, "count": {}, "type": "SCALAR"}},
          {{"componentType": 5126, "count": {}, "type": "VEC3", "sparse": {{"count": {}, "indices": {{"bufferView": 1, "componentType": 5123}}, "values": {{"bufferView": 0}}}}}}],
        "images": [{{"uri": {}}}], "textures": [{{"source": {}}}],
        "materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": {}}}}}, "extras": {extras}}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": {}}}, "indices": {}, "material": {}, "mode": {}}}], "extras": {extras}}}],
        "nodes": [{{"mesh": 0, "children": [{}]}}, {{"children": [{}]}}], "scenes": [{{"nodes": [{}]}}], "scene": {}}}"#,
        n[1],
        n[2],
        n[3],
        n[4],
        n[5],
        n[6],
        n[7],
        n[8],
        n[9],
        s[1],
        n[10],
        n[11],
        n[12],
        n[13],
        n[14],
        n[15],
        n[16],
        n[17],
        n[18],
        n[19]
    )
}

/// 20 numeric slots and 2 string slots of [`gltf_document`], each a valid value or a hostile one.
fn gltf_slots() -> impl Strategy<Value = (Vec<&'static str>, Vec<&'static str>, &'static str)> {
    let valid =
        ["36", "1", "0", "36", "3", "1", "5123", "3", "3", "1", "0", "0", "0", "1", "0", "4", "1", "0", "0", "0"];
    let numbers = valid.map(|v| prop_oneof![3 => Just(v), 1 => prop::sample::select(NUMBERS)].boxed()).to_vec();
    let strings = ["\"data:application/octet-stream;base64,AAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAACAPwAA\"", "\"t.png\""]
        .map(|v| prop_oneof![2 => Just(v), 1 => prop::sample::select(STRINGS)].boxed())
        .to_vec();
    (numbers, strings, prop::sample::select(EXTRAS))
}

/// A GLB container around `json` and `bin`, with its length fields as given or as picked.
fn glb(json: &str, bin: &[u8], lengths: Option<(u32, u32, u32)>) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().div_ceil(4) * 4, 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let (total, json_length, bin_length) = lengths.unwrap_or((total as u32, json.len() as u32, bin.len() as u32));
    let mut bytes = b"glTF".to_vec();
    for word in [2, total, json_length, 0x4E4F_534A] {
        bytes.extend(u32::to_le_bytes(word));
    }
    bytes.extend(&json);
    bytes.extend(u32::to_le_bytes(bin_length));
    bytes.extend(u32::to_le_bytes(0x004E_4942));
    bytes.extend(&bin);
    bytes
}

/// OBJ statements with hostile values: indices 0, negative, past the end; NaN and huge
/// coordinates; many names; libraries inside, outside, missing.
fn obj_line() -> impl Strategy<Value = String> {
    let index = prop_oneof![
        Just("1".to_owned()),
        Just("0".to_owned()),
        Just("-1".to_owned()),
        Just("99".to_owned()),
        Just("-99".to_owned()),
        Just("1.5".to_owned()),
        Just("x".to_owned()),
        (1i64..8).prop_map(|i| i.to_string())
    ];
    let number =
        prop_oneof![Just("0"), Just("1"), Just("-1"), Just("nan"), Just("inf"), Just("1e39"), Just("0.5"), Just("x")];
    let corner =
        (index.clone(), prop::option::of(index.clone()), prop::option::of(index)).prop_map(|(v, t, n)| match (t, n) {
            (None, None) => v,
            (t, n) => format!("{v}/{}/{}", t.unwrap_or_default(), n.unwrap_or_default()),
        });
    prop_oneof![
        3 => prop::collection::vec(number.clone(), 0..5).prop_map(|v| format!("v {}", v.join(" "))),
        1 => prop::collection::vec(number.clone(), 0..4).prop_map(|v| format!("vt {}", v.join(" "))),
        1 => prop::collection::vec(number, 0..4).prop_map(|v| format!("vn {}", v.join(" "))),
        3 => prop::collection::vec(corner, 0..6).prop_map(|c| format!("f {}", c.join(" "))),
        1 => prop::sample::select(&["usemtl a", "usemtl b", "usemtl", "usemtl \u{202e}x", "o x", "g a b", "s 1", "s off"][..])
            .prop_map(str::to_owned),
        1 => prop::sample::select(&["mtllib m.mtl", "mtllib missing.mtl", "mtllib ../outside.mtl", "mtllib /etc/hostname", "mtllib", "mtllib m.mtl m.mtl"][..])
            .prop_map(str::to_owned),
    ]
}

/// MTL statements with hostile values: texture options with missing numbers, files inside,
/// outside, missing, not images; colours and exponents out of range.
fn mtl_line() -> impl Strategy<Value = String> {
    let file = prop::sample::select(
        &["t.png", "missing.png", "../outside.png", "/etc/hostname", "m.obj", "", "-bm", "t.png t.png"][..],
    );
    let option =
        prop::sample::select(&["", "-bm 2 ", "-bm ", "-o 1 2 3 ", "-s ", "-clamp on ", "-imfchan ", "-mm 0 "][..]);
    let keyword = prop::sample::select(&["map_Kd", "map_Ke", "map_Ks", "map_Ns", "norm", "map_Bump", "bump"][..]);
    let number = prop::sample::select(&["0", "1", "-1", "nan", "1e39", "x", ""][..]);
    prop_oneof![
        1 => prop::sample::select(&["newmtl a", "newmtl b", "newmtl", "newmtl a"][..]).prop_map(str::to_owned),
        2 => (keyword, option, file).prop_map(|(k, o, f)| format!("{k} {o}{f}")),
        1 => (prop::sample::select(&["Kd", "Ks", "Ke", "Ns"][..]), prop::collection::vec(number, 0..4))
            .prop_map(|(k, v)| format!("{k} {}", v.join(" "))),
    ]
}

/// A small PNG (1 to 64 texels a side) of any colour type and depth the encoder writes,
/// possibly cut short or with a flipped byte.
fn png_file() -> impl Strategy<Value = Vec<u8>> {
    let kinds = [
        (png::ColorType::Grayscale, 1),
        (png::ColorType::Rgb, 3),
        (png::ColorType::Rgba, 4),
        (png::ColorType::GrayscaleAlpha, 2),
    ];
    (
        1u32..64,
        1u32..64,
        prop::sample::select(kinds.to_vec()),
        any::<bool>(),
        any::<prop::sample::Index>(),
        any::<u8>(),
        any::<bool>(),
    )
        .prop_map(|(w, h, (color, channels), sixteen, at, value, cut)| {
            let depth = if sixteen { png::BitDepth::Sixteen } else { png::BitDepth::Eight };
            let bytes_per = channels * if sixteen { 2 } else { 1 };
            let mut out = vec![];
            {
                let mut encoder = png::Encoder::new(&mut out, w, h);
                encoder.set_color(color);
                encoder.set_depth(depth);
                let mut writer = encoder.write_header().unwrap();
                let data: Vec<u8> = (0..(w * h) as usize * bytes_per).map(|i| (i * 37) as u8).collect();
                writer.write_image_data(&data).unwrap();
            }
            let i = at.index(out.len());
            if cut {
                out.truncate(i)
            } else {
                out[i] = value
            }
            out
        })
}

/// A TGA or BMP header claiming a small size (or a nonsense one) over a short body.
fn tga_or_bmp() -> impl Strategy<Value = (Vec<u8>, &'static str)> {
    (any::<bool>(), 0u16..80, 0u16..80, prop::sample::select(&[0u8, 8, 16, 24, 32, 7][..]), 0usize..20000, any::<u8>())
        .prop_map(|(tga, w, h, bits, body, type_byte)| {
            if tga {
                let mut b =
                    vec![0u8, 0, [2, 3, 10, 11, type_byte][(type_byte % 5) as usize], 0, 0, 0, 0, 0, 0, 0, 0, 0];
                b.extend(w.to_le_bytes());
                b.extend(h.to_le_bytes());
                b.extend([bits, 0]);
                b.extend((0..body).map(|i| i as u8));
                (b, "x.tga")
            } else {
                let mut b = b"BM".to_vec();
                b.extend(u32::to_le_bytes(54 + body as u32));
                b.extend([0, 0, 0, 0]);
                b.extend(u32::to_le_bytes(54));
                b.extend(u32::to_le_bytes(40));
                b.extend(i32::to_le_bytes(i32::from(w)));
                b.extend(i32::to_le_bytes(-i32::from(h)));
                b.extend(u16::to_le_bytes(1));
                b.extend(u16::to_le_bytes(u16::from(bits)));
                b.extend([0u8; 24]);
                b.extend((0..body).map(|i| i as u8));
                (b, "x.bmp")
            }
        })
}

/// Preset and lesson keys with hostile values: wrong types, NaN, huge, unknown names.
fn toml_line() -> impl Strategy<Value = String> {
    let key = prop::sample::select(
        &[
            "[files]\nmesh",
            "[files]\nallow_outside_files",
            "[files]\nnormal",
            "[camera]\nyaw_deg",
            "[camera]\ntarget",
            "[shading]\nview",
            "[shading]\nstrength",
            "[shading]\ndifference_range_deg",
            "[split]\nenabled",
            "[split]\ndifference",
            "[capture]\nsize",
            "[capture]\nsupersample",
            "[scene]\nkernel",
            "[light]\nposition",
            "[shading.parallax]\nlayers",
            "[unknown]\nx",
            "version",
        ][..],
    );
    let value = prop::sample::select(
        &[
            "1",
            "-1",
            "nan",
            "inf",
            "1e39",
            "true",
            "\"lit\"",
            "\"bogus\"",
            "\"\u{202e}x\"",
            "[1, 2]",
            "[0, nan, 0]",
            "[1280, 720]",
            "[0, 0]",
            "[4294967295, 1]",
            "{}",
            "\"/dev/zero\"",
            "\"../x.png\"",
            "\"\"",
        ][..],
    );
    (key, value).prop_map(|(k, v)| format!("{k} = {v}"))
}

proptest! {
    #![proptest_config(common::fuzz_config())]

    /// glTF JSON with hostile values in its slots: loads or fails on one line.
    #[test]
    fn gltf_json_loads_or_fails_on_one_line((numbers, strings, extras) in gltf_slots()) {
        let dir = scratch("gltf");
        image::GrayImage::from_pixel(4, 4, image::Luma([128])).save(dir.join("t.png")).unwrap();
        let path = dir.join("m.gltf");
        std::fs::write(&path, gltf_document(&numbers, &strings, extras, false)).unwrap();
        one_line(load_model(&path, false))?;
    }

    /// GLB containers: hostile JSON slots, a binary chunk of any small length, length fields
    /// as written or picked.
    #[test]
    fn glb_loads_or_fails_on_one_line(
        (numbers, strings, extras) in gltf_slots(),
        bin in prop::collection::vec(any::<u8>(), 0..64),
        lengths in prop::option::of((0u32..400, 0u32..400, 0u32..100)),
    ) {
        let dir = scratch("glb");
        let path = dir.join("m.glb");
        std::fs::write(&path, glb(&gltf_document(&numbers, &strings, extras, true), &bin, lengths)).unwrap();
        one_line(load_model(&path, false))?;
    }

    /// OBJ statements: loads or fails on one line.
    #[test]
    fn obj_loads_or_fails_on_one_line(lines in prop::collection::vec(obj_line(), 0..40)) {
        let dir = scratch("obj");
        std::fs::write(dir.join("m.mtl"), "newmtl a\nKd 1 0 0\n").unwrap();
        let path = dir.join("m.obj");
        std::fs::write(&path, lines.join("\n")).unwrap();
        one_line(load_model(&path, false))?;
    }

    /// MTL statements under a valid triangle: loads or fails on one line.
    #[test]
    fn mtl_loads_or_fails_on_one_line(lines in prop::collection::vec(mtl_line(), 0..24)) {
        let dir = scratch("mtl");
        image::RgbImage::from_pixel(4, 4, image::Rgb([128, 128, 255])).save(dir.join("t.png")).unwrap();
        std::fs::write(dir.join("m.mtl"), lines.join("\n")).unwrap();
        let path = dir.join("m.obj");
        std::fs::write(&path, "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n").unwrap();
        one_line(load_model(&path, false))?;
    }

    /// PNG, TGA and BMP files of small claimed sizes, cut or flipped: decodes or fails on one line.
    #[test]
    fn images_decode_or_fail_on_one_line(png in png_file(), (other, name) in tga_or_bmp()) {
        for (bytes, name) in [(png, "x.png"), (other, name)] {
            for kind in [TextureKind::Color, TextureKind::NormalMap, TextureKind::Height] {
                if let Err(e) = decode_texture(&bytes, Path::new(name), kind) {
                    prop_assert!(!e.to_string().contains('\n'), "{e}");
                }
            }
        }
    }

    /// Preset and lesson TOML with hostile values: parses or fails on one line, and a preset
    /// that parses builds its scene or fails on one line.
    #[test]
    fn presets_and_lessons_parse_or_fail_on_one_line(lines in prop::collection::vec(toml_line(), 0..6)) {
        let text = lines.join("\n");
        match bumpview::state::preset::Preset::from_toml(&text) {
            Ok(preset) => {
                let scene = bumpview::scene::teaching::TeachingScene::default().build(Default::default());
                if let Err(e) = preset.to_state(&scene) {
                    prop_assert!(!e.to_string().contains('\n'), "{e}");
                }
            }
            Err(e) => prop_assert!(!e.to_string().contains('\n'), "{e}"),
        }
        let lesson = format!("title = \"t\"\ncaption = \"c\"\nclaim = \"{{changed}}\"\n{}", text.replace("\n[", "\n[preset."));
        // Lessons are built-in files: any answer but a panic will do (the command line prints
        // an error escaped onto one line).
        let _ = bumpview::lessons::Lesson::parse("fuzz", &lesson);
    }
}
