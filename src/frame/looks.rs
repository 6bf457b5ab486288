//! The classic mistakes and the legacy looks a frame can be drawn with: pipeline variants
//! of the lit views ([`crate::chain::mistakes`], [`crate::chain::legacy`]). Each is named once,
//! by its [`Named`] name, on the command line, in the panel, in captions and split labels.

use crate::names::Named;

/// A classic mistake to draw the scene with, for the split view against the correct picture
/// ([`crate::chain::mistakes`], `shaders/mistakes.wgsl`). A pipeline variant (the `MISTAKE`
/// constant). Named as on the command line (`--mistake`) and in presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum Mistake {
    /// The correct picture.
    #[default]
    None,
    /// The GLSL practicum's transposition typo: the TBN matrix's `[1].z = Normal.z` where
    /// `Normal.y` belongs, so the world normal's y takes `N.z · n_t.z`.
    TbnTypo,
    /// Handedness ignored: `B = N × T`, the tangent's `w` dropped.
    HandednessIgnored,
    /// The normal map sampled through an sRGB view: its texels are decoded from sRGB first.
    SrgbNormalMap,
    /// No re-normalisation after interpolation: the interpolated normal shades as it comes,
    /// and the perturbed normal is not normalised.
    NoRenormalization,
    /// Averaged tangents without Gram-Schmidt: `T` is used as interpolated, not made
    /// orthogonal to `N`.
    NoGramSchmidt,
    /// Green flipped: the normal map read with the other green convention.
    GreenFlipped,
    /// The half vector computed per vertex and interpolated instead of per pixel (Cg
    /// tutorial 8.1.4): highlights smear and shrink across large triangles.
    HalfVectorPerVertex,
    /// The light vector normalised per vertex before interpolation (the ARB-era tangent-space vertex
    /// shader): the interpolated direction bends where the light is near large triangles.
    LightPerVertex,
}

impl Mistake {
    /// What goes wrong, in one line (panel and captions).
    pub fn explanation(self) -> &'static str {
        match self {
            Mistake::None => "the correct picture",
            Mistake::TbnTypo => "TBN[1].z = N.z instead of N.y: walls lean up, floors lose their normal",
            Mistake::HandednessIgnored => "B = N × T without w: mirrored UV islands light upside down",
            Mistake::SrgbNormalMap => "sRGB-decoded texels: a flat texel tilts 39° towards −T −B",
            Mistake::NoRenormalization => "interpolated normals shorter than 1: curved surfaces darken mid-triangle",
            Mistake::NoGramSchmidt => "T not orthogonal to N: the bump leaks into the normal's own direction",
            Mistake::GreenFlipped => "the other green convention: the relief lit from the mirrored side",
            Mistake::HalfVectorPerVertex => "H interpolated from the vertices: highlights smear across triangles",
            Mistake::LightPerVertex => "unit L interpolated from the vertices: wrong direction near the light",
        }
    }

    /// The index the `MISTAKE` pipeline constant takes (shaders/mistakes.wgsl).
    pub fn shader_index(self) -> u32 {
        self as u32
    }

    /// Whether the mistake lights with the vertex stage's interpolated light direction or
    /// half vector (its pipelines read them; the others leave them out).
    pub fn reads_per_vertex_vectors(self) -> bool {
        matches!(self, Mistake::HalfVectorPerVertex | Mistake::LightPerVertex)
    }
}

/// A legacy look (the history of DOT3 and emboss) as a lit mode, a pipeline variant (the `LEGACY`
/// constant, shaders/legacy.wgsl; [`crate::chain::legacy`]). Named `off`, `dot3`, `emboss`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum LegacyLook {
    /// Today's lighting.
    #[default]
    Off,
    /// DOT3 bump mapping: diffuse `albedo · light · max(N·L, 0)` alone, no ambient, no
    /// specular; `L` normalised per vertex and interpolated (not re-normalised), or
    /// re-normalised through a normalization cube map ([`LegacySettings::cube_map_size`]).
    Dot3,
    /// The classic Pascal emboss demo's 2D light-map bump on surfaces with a height map: the slope from
    /// neighbouring height differences (in height-map steps of 1/255), the colour read from a
    /// precomputed light map at `(n.x − (light.x − x), n.y − (light.y − y))`, in texels of
    /// the height map, `x` right and `y` down the image.
    Emboss,
}

/// What the emboss look's lit disc is ([`crate::chain::legacy::emboss_brightness`]): its light
/// map's spot `1 − r/128`, at 100 of its texels a metre, is centred on the light's offset along
/// the surface's T and B (the slope shifts the lookup), so a surface is lit within 1.28 m of the
/// point under the light whatever the light's height or `N·L`, and black beyond (no ambient).
pub const EMBOSS_DISC: &str = "lit within 1.28 m of the point under the light, fading to the rim (the 2D light map's spot, not N·L); black beyond";

/// The face sizes a normalization cube map may have (Cg tutorial 8.1.3).
pub const CUBE_MAP_SIZES: [u32; 4] = [8, 16, 32, 64];

/// The legacy look and its settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct LegacySettings {
    pub look: LegacyLook,
    /// DOT3's normalization cube map face size (one of [`CUBE_MAP_SIZES`]); `None`: the
    /// interpolated light vector is used as it comes.
    pub cube_map_size: Option<u32>,
}

impl LegacySettings {
    /// The index the `LEGACY` pipeline constant takes: 0 off, 1 DOT3 per vertex, 2 DOT3
    /// through the cube map, 3 emboss.
    pub fn shader_index(self) -> u32 {
        match (self.look, self.cube_map_size) {
            (LegacyLook::Off, _) => 0,
            (LegacyLook::Dot3, None) => 1,
            (LegacyLook::Dot3, Some(_)) => 2,
            (LegacyLook::Emboss, _) => 3,
        }
    }

    /// The cube map face size in use (DOT3 with a cube map only).
    pub fn cube_map_in_use(self) -> Option<u32> {
        self.cube_map_size.filter(|_| self.look == LegacyLook::Dot3)
    }

    /// A caption: the look's [`Named`] name and what it draws, e.g. `dot3: N·L only, cube map 32²`;
    /// emboss says what its lit disc is ([`EMBOSS_DISC`]).
    pub fn caption(self) -> String {
        let name = self.look.name();
        match (self.look, self.cube_map_in_use()) {
            (LegacyLook::Off, _) => name.to_owned(),
            (LegacyLook::Dot3, Some(size)) => format!("{name}: N·L only, cube map {size}²"),
            (LegacyLook::Dot3, None) => format!("{name}: N·L only, L per vertex"),
            (LegacyLook::Emboss, _) => format!("{name}: {EMBOSS_DISC}"),
        }
    }
}
