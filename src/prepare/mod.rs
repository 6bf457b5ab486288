//! The prepare stage: everything decided about a scene before anything is drawn, on the CPU
//! and without a GPU. [`PreparedScene::new`] applies the material overrides, decides each
//! instance's [`BumpKind`] and pipeline [`Variant`], which textures each binds, which meshes
//! get tangent frames (only those drawn with a tangent stream) and by which method, makes the
//! drawn geometry (unwelded for per-face frames, non-finite data repaired) and lists what it
//! could not honour as notices. The GPU renderer uploads exactly what a prepared scene holds;
//! the CPU probe samples and shades the same prepared scene, so both draw the same surface.

mod cone;
pub mod displace;
mod file_blocks;
mod repair;
pub mod seams;
mod weld;

use std::borrow::Cow;

use glam::{Mat4, Vec4};
use rayon::prelude::*;

use crate::frame::{BumpKind, SceneOptions, bump_kind};
use crate::scene::{Material, Mesh, Scene, TextureImage, TextureKind};
use crate::tangent::{self, TangentMethod};
use crate::texture::MipFilter;

/// What a drawn instance needs from its pipeline: by its [`BumpKind`], plus whether the mesh
/// brings a tangent stream to show in the T/B views.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Variant {
    /// Positions, normals, UVs; no tangent stream, no bump texture.
    Plain,
    /// Adds the tangent stream (tangents supplied by the mesh, shown in the T/B views).
    Tangent,
    /// Adds the tangent stream and the (tangent-space) normal map.
    NormalMapped,
    /// No tangent stream; an object-space normal map.
    ObjectSpace,
    /// No tangent stream; the height map, differentiated in screen space.
    HeightBump,
}

impl Variant {
    /// Whether the variant reads a tangent stream.
    pub fn has_tangents(self) -> bool {
        matches!(self, Variant::Tangent | Variant::NormalMapped)
    }

    /// Whether the variant binds a bump texture (normal or height map).
    pub fn has_bump_texture(self) -> bool {
        matches!(self, Variant::NormalMapped | Variant::ObjectSpace | Variant::HeightBump)
    }
}

/// The textures an instance binds, as indices into the prepared scene's textures; `None`
/// where the material has no such texture (the shader then ignores the slot).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct InstanceTextures {
    pub base_color: Option<usize>,
    /// The normal map or the height map, as the variant needs; `None` for variants without one.
    pub bump: Option<usize>,
    pub metallic_roughness: Option<usize>,
    pub occlusion: Option<usize>,
    pub gloss: Option<usize>,
    /// Only for a material that emits (a non-zero factor).
    pub emissive: Option<usize>,
    /// The clear coat's strength, roughness and normal textures, only for a visible coat; the
    /// normal map only for variants with a tangent stream.
    pub clearcoat: Option<usize>,
    pub clearcoat_roughness: Option<usize>,
    pub clearcoat_normal: Option<usize>,
    /// The height map the parallax family marches: for tangent-space normal-mapped variants
    /// whose material has one.
    pub height: Option<usize>,
    /// X-Ray's `bump#` correction texture: for normal-mapped variants whose map has the X-Ray
    /// layout and a `bump#`.
    pub bump_correction: Option<usize>,
    /// The detail normal map: for tangent-space normal-mapped variants whose material has one.
    pub detail: Option<usize>,
}

impl InstanceTextures {
    fn of(material: &Material, variant: Variant, parallax: bool) -> InstanceTextures {
        let bump = match variant {
            Variant::NormalMapped | Variant::ObjectSpace => material.normal_map.as_ref().map(|m| m.texture),
            Variant::HeightBump => material.height_map.as_ref().map(|m| m.texture),
            Variant::Plain | Variant::Tangent => None,
        };
        let coat = material.visible_clearcoat();
        InstanceTextures {
            base_color: material.base_color_texture,
            bump,
            metallic_roughness: material.metallic_roughness_texture,
            occlusion: material.occlusion.as_ref().map(|o| o.texture),
            gloss: material.gloss_texture,
            emissive: material.emissive_texture.filter(|_| material.emits()),
            clearcoat: coat.and_then(|c| c.texture),
            clearcoat_roughness: coat.and_then(|c| c.roughness_texture),
            clearcoat_normal: coat
                .and_then(|c| c.normal_map.as_ref())
                .map(|m| m.texture)
                .filter(|_| variant.has_tangents()),
            height: material
                .height_map
                .as_ref()
                .map(|h| h.texture)
                .filter(|_| parallax && variant == Variant::NormalMapped),
            bump_correction: material
                .normal_map
                .as_ref()
                .and_then(|m| m.correction_in_use())
                .filter(|_| matches!(variant, Variant::NormalMapped | Variant::ObjectSpace)),
            detail: material.detail_map.map(|d| d.texture).filter(|_| variant == Variant::NormalMapped),
        }
    }

    fn all(&self) -> impl Iterator<Item = usize> {
        let slots = [self.base_color, self.bump, self.metallic_roughness, self.occlusion, self.gloss, self.emissive];
        let more = [self.clearcoat, self.clearcoat_roughness, self.clearcoat_normal, self.height, self.bump_correction];
        let more = more.into_iter().chain([self.detail]);
        slots.into_iter().chain(more).flatten()
    }
}

/// One placed mesh as it is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedInstance {
    /// Indices into [`PreparedScene::meshes`] and the scene's materials.
    pub mesh: usize,
    pub material: usize,
    /// Model → world.
    pub transform: Mat4,
    pub bump: BumpKind,
    pub variant: Variant,
    pub textures: InstanceTextures,
    /// How its normal map is mip-filtered as drawn ([`mip_filter_of`]): the scene option's
    /// method, or [`MipFilter::RenormalizedBox`] where that method cannot apply.
    pub mip_filter: MipFilter,
}

impl PreparedInstance {
    /// The model matrix mirrors (negative determinant): front faces, counter-clockwise in
    /// model space, are clockwise on screen.
    pub fn mirrored(&self) -> bool {
        self.transform.determinant() < 0.0
    }
}

/// A mesh's tangent frames as drawn: one per vertex of the drawn geometry, model space.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnFrames {
    pub tangents: Vec<Vec4>,
    /// The method they come from (the file's own, or a generator).
    pub method: TangentMethod,
}

/// A mesh as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedMesh {
    /// The geometry drawn: unwelded (a vertex per corner) for per-face frames; triangles with
    /// a non-finite or out-of-range position dropped; normals and UVs one per vertex, a
    /// non-finite or missing one replaced (+Z, 0). Model space.
    pub mesh: Mesh,
    /// The tangent frames, for meshes drawn with a tangent stream only.
    pub frames: Option<DrawnFrames>,
}

/// A scene as it is drawn with one set of [`SceneOptions`].
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedScene {
    /// The scene with the material overrides applied (normal maps re-made from height maps
    /// where their height settings changed).
    pub scene: Scene,
    pub options: SceneOptions,
    /// Per mesh of `scene`.
    pub meshes: Vec<PreparedMesh>,
    /// Per instance of `scene`, in its order.
    pub instances: Vec<PreparedInstance>,
    /// What the scene asked for but cannot get (the loader's warnings, a bump map on a mesh
    /// without texture coordinates, non-finite vertex data repaired), one line each, for the user.
    pub notices: Vec<String>,
    /// Tangent frames made by a generator (not read from the file) for this preparation.
    pub tangent_frames_generated: u64,
    /// Per texture of `scene`: its mip chain when made ahead ([`Self::precompute_mip_chains`]).
    pub mip_chains: Vec<Option<Vec<TextureImage>>>,
    /// The displaced meshes' size when [`SceneOptions::displacement`] is on and anything had
    /// a height map to displace (those instances then draw displaced copies of their mesh
    /// and material, appended to `scene`; see [`displace`]).
    pub displacement: Option<displace::DisplacementStats>,
    /// The meshes the GPU displaces when [`SceneOptions::displacement`] asks for it on the GPU
    /// (their instances draw copies of the base meshes with flat materials, appended to `scene`).
    pub gpu_displaced: Vec<displace::GpuDisplacedMesh>,
}

impl PreparedScene {
    /// Prepares `scene` for drawing with `options`.
    pub fn new(scene: &Scene, options: &SceneOptions) -> PreparedScene {
        let mut notices: Vec<String> = scene.warnings.iter().map(ToString::to_string).collect();
        let scene = crate::bake::round_trip::normal_maps_through(scene, options.normal_maps_through, &mut notices);
        let scene = options.materials.applied_with(&options.per_material, &scene);
        let (scene, displacement, gpu_displaced) = displace::displaced(scene, &options.displacement, &mut notices);
        let instances: Vec<PreparedInstance> = scene
            .instances
            .iter()
            .map(|instance| {
                let material = &scene.materials[instance.material];
                let bump = bump_kind(&scene, instance.mesh, instance.material, options.bump_source);
                let variant = variant_of(bump, &scene.meshes[instance.mesh], material);
                let textures = InstanceTextures::of(material, variant, options.parallax);
                PreparedInstance {
                    mesh: instance.mesh,
                    material: instance.material,
                    transform: instance.transform,
                    bump,
                    variant,
                    textures,
                    mip_filter: mip_filter_of(
                        options.mip_filter_of(instance.material),
                        variant,
                        textures.bump.map(|t| &*scene.textures[t]),
                    ),
                }
            })
            .collect();
        notices.extend(lean_refusals(&scene, &instances, options));
        notices.extend(missing_uv_notices(&scene));
        let mut tangent_frames_generated = 0;
        let meshes = scene
            .meshes
            .iter()
            .enumerate()
            .map(|(index, mesh)| {
                let with_tangents = instances.iter().any(|i| i.mesh == index && i.variant.has_tangents());
                if !with_tangents {
                    return PreparedMesh { mesh: repair::repaired(mesh, &mut notices), frames: None };
                }
                // Per-face frames need a vertex per corner.
                let per_face = options.tangent_method == Some(TangentMethod::PerFace);
                let drawn = if per_face { mesh.unwelded() } else { mesh.clone() };
                let (mut tangents, method) = tangent::resolve(&drawn, options.tangent_method);
                // The classic mistake: the same frames before their Gram-Schmidt.
                if options.tangents_without_gram_schmidt
                    && let Some(raw) = tangent::without_gram_schmidt(&drawn, method)
                {
                    tangents = raw;
                }
                if method.is_generated() {
                    tangent_frames_generated += tangents.len() as u64;
                }
                let tangents = repair::full_stream(&tangents, drawn.positions.len());
                let frames = Some(DrawnFrames { tangents, method });
                PreparedMesh { mesh: repair::repaired(&drawn, &mut notices), frames }
            })
            .collect();
        let mip_chains = vec![None; scene.textures.len()];
        PreparedScene {
            scene,
            options: options.clone(),
            meshes,
            instances,
            notices,
            tangent_frames_generated,
            mip_chains,
            displacement,
            gpu_displaced,
        }
    }

    /// Whether any instance binds texture `index` of [`Self::scene`], or the GPU displaces by it.
    pub fn uses_texture(&self, index: usize) -> bool {
        self.instances.iter().any(|i| i.textures.all().any(|t| t == index))
            || self.gpu_displaced.iter().any(|g| g.height_texture == index)
    }

    /// The mip chain of texture `index` as it is sampled (level 0 first, box-filtered down to
    /// one texel; see [`TextureImage::mip_chain`]; a normal map's by its instances' method,
    /// [`TextureImage::mip_chain_filtered`]; a file's own levels decoded where
    /// [`Self::file_blocks`] draws them): the one made ahead, else made now; the notice
    /// when the system refused its memory (draw [`Self::neutral_chain`] then).
    pub fn mip_chain(&self, index: usize) -> Result<Cow<'_, [TextureImage]>, String> {
        match &self.mip_chains[index] {
            Some(chain) => Ok(Cow::Borrowed(chain)),
            None => self.made_mip_chain(index).map(Cow::Owned),
        }
    }

    /// The mip filter of texture `index` where an instance reads it as its normal map (the
    /// first such instance's; one texture drawn with two methods takes the first).
    pub fn normal_map_filter(&self, index: usize) -> Option<MipFilter> {
        let reads = |i: &&PreparedInstance| {
            i.textures.bump == Some(index) && matches!(i.variant, Variant::NormalMapped | Variant::ObjectSpace)
        };
        self.instances.iter().find(reads).map(|i| i.mip_filter)
    }

    /// LEAN's texture of texture `index` ([`TextureImage::lean_texture`], level 0 first) where
    /// an instance draws it as its normal map with [`MipFilter::Lean`]; `None` elsewhere: no
    /// other method makes or uploads it.
    pub fn lean_texture(&self, index: usize) -> Option<Vec<crate::texture::LeanTexels>> {
        let lean = |i: &PreparedInstance| i.textures.bump == Some(index) && i.mip_filter.reads_moments();
        self.instances.iter().any(lean).then(|| self.scene.textures[index].lean_texture())
    }

    /// Texture `index`'s mip chain, made now; the system refusing its memory is a notice.
    fn made_mip_chain(&self, index: usize) -> Result<Vec<TextureImage>, String> {
        let texture = &self.scene.textures[index];
        let no_memory = |problem: &dyn std::fmt::Display| {
            let (name, w, h) = (&texture.name, texture.width, texture.height);
            format!("texture {name:?} ({w}x{h}): no memory for its mip chain ({problem}): drawn without it")
        };
        if let Some(chain) = self.file_mip_chain(index) {
            return chain.ok_or_else(|| no_memory(&"its file's levels decoded"));
        }
        let chain = match (self.normal_map_filter(index), self.marched_height_map(index)) {
            (Some(filter), _) => texture.mip_chain_filtered(filter),
            (None, Some(slot)) if self.options.cone_maps => cone::with_cone_map(texture, slot).mip_chain(),
            (None, _) => texture.mip_chain(),
        };
        chain.map_err(|problem| no_memory(&problem))
    }

    /// The chain texture `index` is drawn with when its own could not be made: a neutral 1×1.
    pub fn neutral_chain(&self, index: usize) -> Vec<TextureImage> {
        let texture = &self.scene.textures[index];
        vec![TextureImage::neutral(&texture.name, texture.kind)]
    }

    /// The height map slot of the first instance that binds texture `index` for the parallax
    /// family to march ([`InstanceTextures::height`]): its texture carries the cone map.
    fn marched_height_map(&self, index: usize) -> Option<&crate::scene::HeightMap> {
        let marches = |i: &&PreparedInstance| i.textures.height == Some(index);
        let instance = self.instances.iter().find(marches)?;
        self.scene.materials[instance.material].height_map.as_ref()
    }

    /// Makes the mip chains of every texture an instance binds now (textures in parallel), so
    /// that uploading the scene, on the UI thread, only copies them to the GPU. A chain the
    /// system had no memory for is [`Self::neutral_chain`], with a notice.
    pub fn precompute_mip_chains(&mut self) {
        let used: Vec<usize> = (0..self.scene.textures.len()).filter(|&index| self.uses_texture(index)).collect();
        let made: Vec<(usize, Result<Vec<TextureImage>, String>)> =
            used.par_iter().map(|&index| (index, self.made_mip_chain(index))).collect();
        self.mip_chains = vec![None; self.scene.textures.len()];
        for (index, chain) in made {
            let chain = chain.unwrap_or_else(|notice| {
                self.notices.push(notice);
                self.neutral_chain(index)
            });
            self.mip_chains[index] = Some(chain);
        }
    }

    /// Number of triangles drawn.
    pub fn triangle_count(&self) -> usize {
        self.instances.iter().map(|i| self.meshes[i.mesh].mesh.indices.len() / 3).sum()
    }
}

/// The most texels a normal map drawn with LEAN may have (4096²): its moments take 8 bytes a
/// texel with their mips (170 MiB here, 682 MiB at 8192²), held once on the CPU and once by
/// the GPU; a larger map is drawn with Toksvig's widening instead, with a notice.
pub const MAX_LEAN_TEXELS: u64 = 1 << 24;

/// The mip filter an instance of `variant` whose bump texture is `bump` is drawn with:
/// `chosen` where it applies, else [`MipFilter::RenormalizedBox`] (today's mips, no widening).
/// Only normal maps (tangent- or object-space) are filtered; the methods that read the
/// averaged normal's length or LEAN's moments need an RGB map ([`TextureKind::NormalMap`]:
/// packed layouts average channel by channel); LEAN's slopes are tangent-space ones, so it
/// applies to tangent-space normal maps only, of at most [`MAX_LEAN_TEXELS`] (Toksvig's
/// widening past that).
pub fn mip_filter_of(chosen: MipFilter, variant: Variant, bump: Option<&TextureImage>) -> MipFilter {
    let normal_map = matches!(variant, Variant::NormalMapped | Variant::ObjectSpace);
    let rgb = bump.is_some_and(|t| t.kind == TextureKind::NormalMap);
    match chosen {
        _ if !normal_map || bump.is_none() => MipFilter::RenormalizedBox,
        MipFilter::Lean if !rgb || variant != Variant::NormalMapped => MipFilter::RenormalizedBox,
        MipFilter::Lean if bump.is_some_and(too_large_for_lean) => MipFilter::Toksvig,
        MipFilter::Toksvig | MipFilter::Vmf if !rgb => MipFilter::RenormalizedBox,
        _ => chosen,
    }
}

/// Whether `map` has more than [`MAX_LEAN_TEXELS`] texels.
fn too_large_for_lean(map: &TextureImage) -> bool {
    u64::from(map.width) * u64::from(map.height) > MAX_LEAN_TEXELS
}

/// The notice for each normal map drawn with Toksvig's widening where LEAN was chosen because
/// it is larger than LEAN may be ([`MAX_LEAN_TEXELS`]), once per map.
fn lean_refusals(scene: &Scene, instances: &[PreparedInstance], options: &SceneOptions) -> Vec<String> {
    let mut refused: Vec<usize> = instances
        .iter()
        .filter(|i| options.mip_filter_of(i.material).reads_moments() && !i.mip_filter.reads_moments())
        .filter_map(|i| i.textures.bump.filter(|&t| too_large_for_lean(&scene.textures[t])))
        .collect();
    refused.sort_unstable();
    refused.dedup();
    refused
        .into_iter()
        .map(|t| {
            let map = &scene.textures[t];
            format!(
                "normal map {:?} ({}x{}): LEAN's moments would take {} MiB (LEAN is drawn up to 4096x4096 texels): drawn with toksvig instead",
                map.name,
                map.width,
                map.height,
                (u64::from(map.width) * u64::from(map.height) * 8 * 4 / 3) >> 20
            )
        })
        .collect()
}

/// The variant an instance is drawn with: by its [`BumpKind`]; without a bump, with the
/// tangent stream when the mesh supplies tangents (for the T/B views) or its material's clear
/// coat has a normal map (drawn through its own frame), else plain.
fn variant_of(bump: BumpKind, mesh: &Mesh, material: &Material) -> Variant {
    let vertices = mesh.positions.len();
    let supplied = mesh.tangents.as_ref().is_some_and(|t| t.len() == vertices);
    let coat_normal =
        material.visible_clearcoat().is_some_and(|c| c.normal_map.is_some()) && mesh.uvs.len() == vertices;
    match bump {
        BumpKind::HeightInShader => Variant::HeightBump,
        BumpKind::TangentSpace => Variant::NormalMapped,
        BumpKind::ObjectSpace => Variant::ObjectSpace,
        BumpKind::None if supplied || coat_normal => Variant::Tangent,
        BumpKind::None => Variant::Plain,
    }
}

/// A notice per mesh whose material has a normal or height map but which has no texture
/// coordinates: it is drawn without bump.
fn missing_uv_notices(scene: &Scene) -> Vec<String> {
    let mut notices = vec![];
    for instance in &scene.instances {
        let (mesh, material) = (&scene.meshes[instance.mesh], &scene.materials[instance.material]);
        let bumped = material.normal_map.is_some() || material.height_map.is_some();
        let notice = format!("mesh {:?} has no texture coordinates: drawn without its bump map", mesh.name);
        if bumped && mesh.uvs.len() != mesh.positions.len() && !notices.contains(&notice) {
            notices.push(notice);
        }
    }
    notices
}

#[cfg(test)]
mod tests;
