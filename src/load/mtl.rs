//! MTL material libraries for OBJ: `Kd`, `Ks`, `Ns`, `map_Kd`, `map_Bump`/`bump` (with
//! `-bm`), `norm`, `map_Ks`/`map_Ns`. Texture paths are relative to the library.
//!
//! `map_Bump` is a height map by the MTL spec, but many exporters put a tangent-space normal
//! map there; the image decides ([`looks_like_normal_map`]). A height map becomes a normal
//! map (and the height map slot) as `--height` does ([`super::files`]).

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use glam::{Vec3, Vec4};

use super::files::add_height_map;
use super::image::load_scene_texture;
use crate::error::{LoadError, LoadWarning};
use crate::scene::{HeightMap, Material, NormalMap, Scene, TextureImage, TextureKind};

/// Blinn-Phong exponents `Ns` is clamped to.
const SHININESS: std::ops::RangeInclusive<f32> = 1.0..=1024.0;

/// A material with the MTL defaults (`Kd 0.8`, no specular), also used for faces without
/// `usemtl` or naming an unknown material.
fn default_material(name: &str) -> Material {
    Material {
        name: name.to_owned(),
        base_color_factor: Vec4::new(0.8, 0.8, 0.8, 1.0),
        specular: Vec3::ZERO,
        shininess: 32.0,
        ..Material::default()
    }
}

/// What the libraries of one OBJ loaded already, so that a library or an image named again
/// is read and decoded once: 2,000 `mtllib` lines naming one file, or 2,000 `map_Kd` lines
/// naming one image, cost one read.
#[derive(Default)]
struct Loaded {
    /// Libraries read.
    libraries: HashSet<PathBuf>,
    /// (image, kind) → index in `scene.textures`; `None`: unreadable (warned about once).
    textures: HashMap<(PathBuf, TextureKind), Option<usize>>,
    /// (bump image, `-bm` bits, `norm`?) → the normal map and height map slots it gave a
    /// material; `None`: unreadable.
    bumps: HashMap<(PathBuf, u32, bool), Option<(NormalMap, Option<HeightMap>)>>,
}

/// Reads every library (each file once), adding its materials and textures to `scene`;
/// returns material name → index in `scene.materials`.
pub fn load_libraries(
    libraries: &[String],
    base: &Path,
    obj: &Path,
    scene: &mut Scene,
) -> Result<HashMap<String, usize>, LoadError> {
    let mut names = HashMap::new();
    let mut loaded = Loaded::default();
    for library in libraries {
        let path = base.join(library.replace('\\', "/"));
        if !loaded.libraries.insert(path.clone()) {
            continue;
        }
        super::uri::admit_file(&path, obj, "material library")?;
        let text = crate::read::read_file(&path, crate::read::FileKind::MaterialLibrary).map_err(|e| {
            let obj_name = obj.file_name().unwrap_or_default().to_string_lossy();
            LoadError::new(&path, format!("could not read the material library that {obj_name} names: {e}"))
        })?;
        parse(&String::from_utf8_lossy(&text), &path, scene, &mut names, &mut loaded)?;
        scene.files.push(path);
    }
    Ok(names)
}

/// The material index for a `usemtl` name; unknown or missing names share a default material
/// (the library's `default`, else one made on first need and named in `materials`).
pub fn material_index(name: Option<&str>, materials: &mut HashMap<String, usize>, scene: &mut Scene) -> usize {
    if let Some(&index) = name.and_then(|n| materials.get(n)).or_else(|| materials.get("default")) {
        return index;
    }
    scene.materials.push(default_material("default"));
    materials.insert("default".to_owned(), scene.materials.len() - 1);
    scene.materials.len() - 1
}

/// The texture `path` read as `kind` in `scene`, loaded once ([`load_referenced`]); `None`
/// when it cannot be read.
fn texture(scene: &mut Scene, loaded: &mut Loaded, path: &Path, kind: TextureKind) -> Option<usize> {
    let key = (path.to_owned(), kind);
    if let Some(&index) = loaded.textures.get(&key) {
        return index;
    }
    let index = load_referenced(scene, path, kind).map(|image| add(scene, image));
    loaded.textures.insert(key, index);
    index
}

/// The normal map (and height map) slots of a bump statement (`norm` when `norm`), loaded
/// once per file and multiplier: a tangent-space normal map as it is, a height map as
/// `--height` makes it ([`add_height_map`]).
fn bump(
    scene: &mut Scene,
    loaded: &mut Loaded,
    reference: &TextureRef,
    norm: bool,
) -> Option<(NormalMap, Option<HeightMap>)> {
    let key = (reference.path.clone(), reference.bump_multiplier.to_bits(), norm);
    if let Some(slots) = loaded.bumps.get(&key) {
        return slots.clone();
    }
    let slots = match load_referenced(scene, &reference.path, TextureKind::NormalMap) {
        Some(image) if norm || looks_like_normal_map(&image) => {
            let texture = add(scene, image);
            Some((NormalMap::new(texture, reference.bump_multiplier), None))
        }
        Some(image) => {
            drop(image);
            load_referenced(scene, &reference.path, TextureKind::Height).map(|heights| {
                let slot = add_height_map(scene, &[], heights, reference.bump_multiplier);
                (NormalMap::new(slot.texture - 1, 1.0), Some(slot))
            })
        }
        None => None,
    };
    loaded.bumps.insert(key, slots.clone());
    slots
}

/// [`load_scene_texture`], and `path` remembered in [`Scene::files`] (readable or not, so that
/// hot reload picks it up once it is fixed); `None` with a [`LoadWarning`] when it cannot be
/// read.
fn load_referenced(scene: &mut Scene, path: &Path, kind: TextureKind) -> Option<TextureImage> {
    if !scene.files.iter().any(|f| f == path) {
        scene.files.push(path.to_owned());
    }
    match load_scene_texture(scene, path, kind) {
        Ok(image) => Some(image),
        Err(e) => {
            let warning = LoadWarning::UnreadableTexture { file: e.path, problem: e.problem };
            if !scene.warnings.contains(&warning) {
                scene.warnings.push(warning);
            }
            None
        }
    }
}

fn parse(
    text: &str,
    path: &Path,
    scene: &mut Scene,
    names: &mut HashMap<String, usize>,
    loaded: &mut Loaded,
) -> Result<(), LoadError> {
    let base = path.parent().unwrap_or(Path::new("."));
    for (number, line) in text.lines().enumerate() {
        let at = |problem: String| LoadError::new(path, format!("line {}: {problem}", number + 1));
        let line = line.split('#').next().unwrap_or("").trim();
        let (keyword, rest) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
        let rest = rest.trim();
        if keyword == "newmtl" {
            scene.materials.push(default_material(rest));
            names.insert(rest.to_owned(), scene.materials.len() - 1);
            continue;
        }
        let Some(material_index) = scene.materials.len().checked_sub(1).filter(|_| !names.is_empty()) else {
            continue;
        };
        let numbers = || -> Result<Vec<f32>, LoadError> {
            rest.split_whitespace().map(|w| w.parse().map_err(|_| at(format!("{w:?} is not a number")))).collect()
        };
        let colour = || -> Result<Vec3, LoadError> {
            match numbers()?[..] {
                [r, g, b, ..] => Ok(Vec3::new(r, g, b)),
                [grey] => Ok(Vec3::splat(grey)),
                _ => Err(at(format!("{keyword} needs a colour"))),
            }
        };
        let map = || {
            let reference = TextureRef::parse(rest, base).ok_or_else(|| at(format!("{keyword} names no file")))?;
            super::uri::admit_file(&reference.path, path, "texture").map(|_| reference)
        };
        let lower = keyword.to_ascii_lowercase();
        match lower.as_str() {
            "kd" => {
                let kd = colour()?;
                scene.materials[material_index].base_color_factor = kd.extend(1.0);
            }
            "ks" => scene.materials[material_index].specular = colour()?,
            "ke" => scene.materials[material_index].emissive_factor = colour()?,
            "ns" => {
                let ns = numbers()?.first().copied().ok_or_else(|| at("Ns needs a number".into()))?;
                scene.materials[material_index].shininess = ns.clamp(*SHININESS.start(), *SHININESS.end());
            }
            "map_kd" => {
                if let Some(texture) = texture(scene, loaded, &map()?.path, TextureKind::Color) {
                    scene.materials[material_index].base_color_texture = Some(texture);
                }
            }
            "map_ke" => {
                if let Some(texture) = texture(scene, loaded, &map()?.path, TextureKind::Color) {
                    let material = &mut scene.materials[material_index];
                    material.emissive_texture = Some(texture);
                    // The texture scales Ke; without a Ke (or with a black one) it shows as is.
                    if material.emissive_factor == Vec3::ZERO {
                        material.emissive_factor = Vec3::ONE;
                    }
                }
            }
            "map_ks" | "map_ns" => {
                if let Some(texture) = texture(scene, loaded, &map()?.path, TextureKind::Data) {
                    scene.materials[material_index].gloss_texture = Some(texture);
                }
            }
            "norm" | "map_bump" | "bump" => {
                if let Some((normal_map, height_map)) = bump(scene, loaded, &map()?, lower == "norm") {
                    let material = &mut scene.materials[material_index];
                    material.normal_map = Some(normal_map);
                    if height_map.is_some() {
                        material.height_map = height_map;
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

fn add(scene: &mut Scene, texture: TextureImage) -> usize {
    scene.textures.push(texture.into());
    scene.textures.len() - 1
}

/// A texture statement's file and the options this loader uses.
struct TextureRef {
    path: PathBuf,
    /// `-bm`: bump multiplier (normal map scale, or height range factor), 1 by default.
    bump_multiplier: f32,
}

impl TextureRef {
    /// Skips options (`-name` and their numbers, or `-clamp on`-style words) and takes the
    /// rest of the line as the file name, which may contain spaces.
    fn parse(rest: &str, base: &Path) -> Option<TextureRef> {
        let words: Vec<&str> = rest.split_whitespace().collect();
        let mut bump_multiplier = 1.0;
        let mut i = 0;
        while i < words.len() && words[i].starts_with('-') && words[i].len() > 1 {
            let option = words[i];
            i += 1;
            let numbers = words[i..].iter().take_while(|w| w.parse::<f32>().is_ok()).count();
            match option {
                "-bm" if numbers > 0 => {
                    bump_multiplier = words[i].parse().unwrap_or(1.0);
                    i += 1;
                }
                // Options whose value is a word (`on`, a channel, a type name).
                "-clamp" | "-blendu" | "-blendv" | "-imfchan" | "-type" | "-cc" => i += 1,
                // `-o`, `-s`, `-t` take up to three numbers, `-mm` two, others one.
                _ => i += numbers.min(3),
            }
        }
        let file = words[i.min(words.len())..].join(" ");
        (!file.is_empty()).then(|| TextureRef { path: base.join(file.replace('\\', "/")), bump_multiplier })
    }
}

/// Whether a picture read as RGB is a tangent-space normal map rather than a grey height map:
/// its mean colour is bluish (`b > 0.6`) with red and green near the middle (±0.15), as
/// `0.5·n + 0.5` with `n` mostly along +Z is.
fn looks_like_normal_map(image: &TextureImage) -> bool {
    let texels = (image.rgba.len() / 4).max(1) as f32;
    let mean =
        image.rgba.chunks_exact(4).fold(Vec3::ZERO, |sum, t| sum + Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32))
            / (255.0 * texels);
    mean.z > 0.6 && (mean.x - 0.5).abs() < 0.15 && (mean.y - 0.5).abs() < 0.15
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texture_options_are_skipped_and_bump_multiplier_kept() {
        let base = Path::new("/m");
        let r = TextureRef::parse("-bm 0.5 -o 0.1 0.2 -clamp on my bump.png", base).unwrap();
        assert_eq!((r.path.as_path(), r.bump_multiplier), (Path::new("/m/my bump.png"), 0.5));
        assert_eq!(TextureRef::parse("tex.png", base).unwrap().bump_multiplier, 1.0);
        assert!(TextureRef::parse("-bm 2", base).is_none());
    }
}
