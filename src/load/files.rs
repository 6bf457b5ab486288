//! The files of a scene: a mesh file (or the built-in scene) and texture files put into every
//! material's slots — what the command line's `MESH --color --normal --height --gloss`, a
//! preset's `[files]` table, the viewer's loader and its texture slots all describe
//! ([`SceneFiles`]) — and MTL height maps.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::image::{load_scene_texture, load_scene_texture_stored};
use super::load_scene;
use crate::error::LoadError;
use crate::height::Kernel;
use crate::scene::material::TEXTURE_SPAN_M;
use crate::scene::teaching::TeachingScene;
use crate::scene::{DetailBlend, DetailMap, HeightMap, NormalMap, Scene, TextureImage, TextureKind};
use crate::texture::compressed::Stored;

/// Metres the full range of a height map from a file spans (times an MTL `-bm`).
pub const HEIGHT_RANGE_M: f32 = 0.01;

/// What a scene is made from: a mesh file, or none for the built-in teaching scene, and
/// texture files that replace a slot of every material. A preset stores it as its `[files]`
/// table (these field names).
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SceneFiles {
    /// A glTF 2.0 (`.gltf`, `.glb`) or OBJ file; `None`: the built-in scene.
    pub mesh: Option<PathBuf>,
    /// Base colour (sRGB).
    pub color: Option<PathBuf>,
    /// Tangent-space normal map, OpenGL convention (+Y up the image).
    pub normal: Option<PathBuf>,
    /// Height map (white = high, 1 cm per full range); also becomes the normal
    /// map unless `normal` is given.
    pub height: Option<PathBuf>,
    /// Gloss (Blinn-Phong specular) map: linear RGB multiplying the material's `k_s`.
    pub gloss: Option<PathBuf>,
    /// Detail normal map: tangent space, OpenGL convention, tiled over every material's
    /// normal map ([`crate::scene::DetailMap`]). glTF has no detail slot: a preset beside the
    /// model names one here (its `[files] detail`).
    pub detail: Option<PathBuf>,
    /// Without a mesh: the built-in scene to make (`None`: [`TeachingScene::Bricks`]).
    pub builtin: Option<TeachingScene>,
    /// Let the mesh read files outside its folder (buffers, textures, material libraries
    /// named by an absolute path, through `..` or a symbolic link leading out); without it
    /// such a file fails the load, named ([`load_model`]). `--allow-outside-files`.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub allow_outside_files: bool,
}

/// A texture slot of [`SceneFiles`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "lowercase")]
pub enum TextureSlot {
    /// sRGB base colour.
    Color,
    /// Tangent-space normal map.
    Normal,
    /// Height map (white = high); also becomes the normal map unless one is given.
    Height,
    /// Gloss (specular) map.
    Gloss,
    /// Detail normal map, tiled over the normal map.
    Detail,
}

impl TextureSlot {
    /// The slot's name for people (panel and messages).
    pub fn label(self) -> &'static str {
        match self {
            TextureSlot::Color => "colour",
            TextureSlot::Normal => "normal map",
            TextureSlot::Height => "height map",
            TextureSlot::Gloss => "gloss",
            TextureSlot::Detail => "detail normal map",
        }
    }
}

impl SceneFiles {
    /// Whether no file is named (the built-in scene as it is; a permission alone names none).
    pub fn is_empty(&self) -> bool {
        SceneFiles { allow_outside_files: false, ..self.clone() } == SceneFiles::default()
    }

    /// The file in `slot`.
    pub fn texture(&self, slot: TextureSlot) -> Option<&Path> {
        self.slot(slot).as_deref()
    }

    /// Puts `path` into `slot`.
    pub fn set_texture(&mut self, slot: TextureSlot, path: PathBuf) {
        *self.slot_mut(slot) = Some(path);
    }

    fn slot(&self, slot: TextureSlot) -> &Option<PathBuf> {
        match slot {
            TextureSlot::Color => &self.color,
            TextureSlot::Normal => &self.normal,
            TextureSlot::Height => &self.height,
            TextureSlot::Gloss => &self.gloss,
            TextureSlot::Detail => &self.detail,
        }
    }

    fn slot_mut(&mut self, slot: TextureSlot) -> &mut Option<PathBuf> {
        match slot {
            TextureSlot::Color => &mut self.color,
            TextureSlot::Normal => &mut self.normal,
            TextureSlot::Height => &mut self.height,
            TextureSlot::Gloss => &mut self.gloss,
            TextureSlot::Detail => &mut self.detail,
        }
    }

    /// Every file named: the mesh first, then the textures in slot order.
    pub fn paths(&self) -> Vec<&Path> {
        let textures = [&self.color, &self.normal, &self.height, &self.gloss, &self.detail];
        self.mesh.iter().chain(textures.into_iter().flatten()).map(PathBuf::as_path).collect()
    }

    /// Each path mapped by `f`.
    fn map(&self, f: impl Fn(&Path) -> PathBuf) -> SceneFiles {
        let map = |path: &Option<PathBuf>| path.as_deref().map(&f);
        SceneFiles {
            mesh: map(&self.mesh),
            color: map(&self.color),
            normal: map(&self.normal),
            height: map(&self.height),
            gloss: map(&self.gloss),
            detail: map(&self.detail),
            builtin: self.builtin,
            allow_outside_files: self.allow_outside_files,
        }
    }

    /// These files with relative paths joined to `folder` (a preset's paths are relative to
    /// its file's folder).
    pub fn resolved(&self, folder: &Path) -> SceneFiles {
        self.map(|path| folder.join(path))
    }

    /// These files as a preset in `folder` stores them, so that [`Self::resolved`] finds them
    /// again whatever the working directory: a file under `folder` relative to it (the folder
    /// can move with its files), any other absolute (against the current directory).
    pub fn relative_to(&self, folder: &Path) -> SceneFiles {
        let absolute = |path: &Path| std::path::absolute(path).unwrap_or_else(|_| path.to_owned());
        let folder = absolute(if folder.as_os_str().is_empty() { Path::new(".") } else { folder });
        self.map(|path| {
            let path = absolute(path);
            path.strip_prefix(&folder).map_or(path.clone(), Path::to_owned)
        })
    }

    /// These files with paths made absolute against the current directory (unchanged where
    /// that fails), so that file-change events, which name absolute paths, match them.
    pub fn absolute(&self) -> SceneFiles {
        self.map(|path| std::path::absolute(path).unwrap_or_else(|_| path.to_owned()))
    }

    /// These files over `base`, slot by slot: a file named here wins, an empty slot keeps
    /// `base`'s (the command line's files over a preset's).
    pub fn over(self, base: SceneFiles) -> SceneFiles {
        SceneFiles {
            mesh: self.mesh.or(base.mesh),
            color: self.color.or(base.color),
            normal: self.normal.or(base.normal),
            height: self.height.or(base.height),
            gloss: self.gloss.or(base.gloss),
            detail: self.detail.or(base.detail),
            builtin: self.builtin.or(base.builtin),
            allow_outside_files: self.allow_outside_files || base.allow_outside_files,
        }
    }

    /// Loads the scene: the mesh file ([`load_model`], outside files as allowed) or, without one, the built-in scene
    /// with its brick normal map made by `kernel`, then the slot textures on every material
    /// ([`replace_textures`]). Reads files, so it may take a while (the viewer runs it on a
    /// worker thread). The error names the file that failed.
    pub fn build(&self, kernel: Kernel) -> Result<Scene, LoadError> {
        let mut scene = match &self.mesh {
            Some(path) => load_model(path, self.allow_outside_files)?,
            None => self.builtin.unwrap_or_default().build(kernel),
        };
        replace_textures(&mut scene, self)?;
        Ok(scene)
    }
}

/// Loads the model at `path` ([`load_scene`]) reading the files it names outside its folder
/// only when `allow_outside_files`; otherwise the first such file fails the load with one
/// line naming it and how to allow it ([`super::uri::with_outside_files`]), and nothing
/// outside was read. How the command line and the viewer load models.
pub fn load_model(path: &Path, allow_outside_files: bool) -> Result<Scene, LoadError> {
    super::uri::with_outside_files(path, allow_outside_files, || load_scene(path))
}

/// Loads each texture file of `files` (its mesh is not read) and puts it into its slot on
/// every material of `scene`. A colour texture `NAME.*` given without a normal or height map
/// brings X-Ray's pair beside it when there is one ([`xray_pair_beside`]): `NAME_bump.*` as a
/// normal map in the [`crate::scene::NormalLayout::Xray`] layout, with `NAME_bump#.*`.
pub fn replace_textures(scene: &mut Scene, files: &SceneFiles) -> Result<(), LoadError> {
    let pair = files.color.as_deref().filter(|_| files.normal.is_none() && files.height.is_none());
    if let Some((bump, correction)) = pair.and_then(xray_pair_beside) {
        let texture = load_scene_texture(scene, &bump, TextureKind::NormalMap)?;
        scene.textures.push(texture.into());
        let bump_index = scene.textures.len() - 1;
        let correction_index = match &correction {
            Some(path) => {
                let texture = load_scene_texture(scene, path, TextureKind::Data)?;
                scene.textures.push(texture.into());
                Some(scene.textures.len() - 1)
            }
            None => None,
        };
        scene.materials.iter_mut().for_each(|m| m.normal_map = Some(NormalMap::xray(bump_index, correction_index)));
        scene.files.extend(std::iter::once(bump).chain(correction));
    }
    if let Some(path) = &files.height {
        let every: Vec<usize> = (0..scene.materials.len()).collect();
        let heights = load_scene_texture(scene, path, TextureKind::Height)?;
        add_height_map(scene, &every, heights, 1.0);
    }
    let each = |scene: &mut Scene, path: &Option<PathBuf>, kind, set: fn(&mut crate::scene::Material, usize)| {
        if let Some(path) = path {
            let (texture, stored) = load_scene_texture_stored(scene, path, kind)?;
            scene.textures.push(texture.into());
            let texture = scene.textures.len() - 1;
            scene.materials.iter_mut().for_each(|m| set(m, texture));
            return Ok::<Option<Stored>, LoadError>(stored);
        }
        Ok(None)
    };
    each(scene, &files.color, TextureKind::Color, |m, t| m.base_color_texture = Some(t))?;
    let stored =
        each(scene, &files.normal, TextureKind::NormalMap, |m, t| m.normal_map = Some(NormalMap::new(t, 1.0)))?;
    if stored.is_some() {
        for map in scene.materials.iter_mut().filter_map(|m| m.normal_map.as_mut()) {
            *map = map.clone().with_stored(stored.as_ref());
        }
    }
    each(scene, &files.gloss, TextureKind::Data, |m, t| m.gloss_texture = Some(t))?;
    each(scene, &files.detail, TextureKind::NormalMap, |m, t| {
        m.detail_map = Some(DetailMap::new(t, DetailBlend::default()))
    })?;
    Ok(())
}

/// A scene of one material and no mesh around an image file, for `bumpview check`: X-Ray's
/// pair when `path` is a colour texture with `NAME_bump.*` beside it ([`xray_pair_beside`]),
/// else the image as an RGB normal map.
pub fn texture_scene(path: &Path) -> Result<Scene, LoadError> {
    let mut scene = super::empty_scene();
    let name = path.file_name().map_or_else(|| "texture".to_owned(), |n| n.to_string_lossy().into_owned());
    scene.materials.push(crate::scene::Material { name, ..Default::default() });
    let files = match xray_pair_beside(path) {
        Some(_) => SceneFiles { color: Some(path.to_owned()), ..Default::default() },
        None => SceneFiles { normal: Some(path.to_owned()), ..Default::default() },
    };
    replace_textures(&mut scene, &files)?;
    Ok(scene)
}

/// Whether `path` names an image this build decodes, by its extension.
pub fn is_image_path(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    ext.is_some_and(|e| IMAGE_EXTENSIONS.contains(&e.as_str()))
}

/// Image extensions this build decodes ([`super::image::load_texture`]).
const IMAGE_EXTENSIONS: [&str; 8] = ["png", "jpg", "jpeg", "tga", "bmp", "webp", "dds", "ktx2"];

/// X-Ray's (S.T.A.L.K.E.R.) normal-map pair beside a colour texture `NAME.*`: the files
/// `NAME_bump.*` and, where it exists, `NAME_bump#.*` in the same folder (any extension this
/// build decodes, the first in name order); `None` without `NAME_bump.*`.
pub fn xray_pair_beside(color: &Path) -> Option<(PathBuf, Option<PathBuf>)> {
    let stem = color.file_stem()?.to_str()?;
    let folder =
        color.parent().map_or_else(|| Path::new("."), |p| if p.as_os_str().is_empty() { Path::new(".") } else { p });
    let mut names: Vec<PathBuf> = std::fs::read_dir(folder).ok()?.filter_map(|e| e.ok().map(|e| e.path())).collect();
    names.sort();
    let find = |wanted: String| {
        names
            .iter()
            .find(|path| {
                path.file_stem().and_then(|s| s.to_str()) == Some(wanted.as_str())
                    && is_image_path(path)
                    && path.is_file()
            })
            .map(|path| color.with_file_name(path.file_name().expect("listed files have names")))
    };
    let bump = find(format!("{stem}_bump"))?;
    Some((bump, find(format!("{stem}_bump#"))))
}

/// Puts a [`TextureKind::Height`] texture into the height map slot of `materials`, spanning
/// `multiplier ·` [`HEIGHT_RANGE_M`] metres, and the normal map made from it with the slot's
/// settings ([`HeightMap::new`]: central differences, wrapping) into its normal map slot;
/// returns the height map slot (the normal map is the texture before its own).
pub fn add_height_map(scene: &mut Scene, materials: &[usize], heights: TextureImage, multiplier: f32) -> HeightMap {
    let range_m = HEIGHT_RANGE_M * if multiplier.is_finite() { multiplier } else { 1.0 };
    let slot = HeightMap::new(scene.textures.len() + 1, range_m);
    let normal_map = slot.to_normal_map(&heights, TEXTURE_SPAN_M);
    scene.textures.extend([normal_map, heights].map(Into::into));
    for &m in materials {
        scene.materials[m].normal_map = Some(NormalMap::new(slot.texture - 1, 1.0));
        scene.materials[m].height_map = Some(slot.clone());
    }
    slot
}
