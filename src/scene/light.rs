//! Lights as plain data: point and directional lights with colour, intensity, on/off and
//! OpenGL attenuation, the set of at most [`MAX_LIGHTS`] a frame is lit by with its ambient
//! light, and the specular mode of the classic model. The formulas that use them are in
//! [`crate::shading::lights`].

use glam::Vec3;

/// The most lights a frame has (the size of the frame uniform's light array).
pub const MAX_LIGHTS: usize = 8;

/// Where a light's rays come from. Named `point`, `directional`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum LightKind {
    /// Rays from a position (OpenGL `GL_POSITION` with w = 1), attenuated with distance.
    #[default]
    Point,
    /// Parallel rays from a direction (OpenGL `GL_POSITION` with w = 0), never attenuated.
    Directional,
}

/// OpenGL's distance attenuation `1 / (c + l·d + q·d²)`, `d` in metres
/// ([`crate::shading::lights::attenuation`]). Each coefficient is finite and at least 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attenuation {
    pub constant: f32,
    pub linear: f32,
    pub quadratic: f32,
}

impl Attenuation {
    /// No falloff, OpenGL's default `(1, 0, 0)`.
    pub const NONE: Attenuation = Attenuation { constant: 1.0, linear: 0.0, quadratic: 0.0 };

    /// The coefficients `[c, l, q]`.
    pub fn to_array(self) -> [f32; 3] {
        [self.constant, self.linear, self.quadratic]
    }

    /// Coefficients `[c, l, q]` when each is finite and at least 0 and one is positive; else
    /// a sentence saying what is wrong.
    pub fn from_array([constant, linear, quadratic]: [f32; 3]) -> Result<Attenuation, String> {
        let values = [constant, linear, quadratic];
        if values.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(format!("attenuation {values:?}: each of C, L, Q must be a finite number, at least 0"));
        }
        if values.iter().all(|v| *v == 0.0) {
            return Err("attenuation [0, 0, 0]: one of C, L, Q must be positive".into());
        }
        Ok(Attenuation { constant, linear, quadratic })
    }
}

impl Default for Attenuation {
    fn default() -> Self {
        Attenuation::NONE
    }
}

/// One light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    /// A point light's position (metres, world space); a directional light's direction
    /// *towards* the light (world space, any non-zero length), as OpenGL's `GL_POSITION`.
    pub position: Vec3,
    /// Linear RGB.
    pub color: Vec3,
    /// Multiplies `color`: the light brings `color · intensity · attenuation`.
    pub intensity: f32,
    /// A switched-off light keeps its place and settings but brings nothing.
    pub enabled: bool,
    /// Distance falloff of a point light (directional lights ignore it).
    pub attenuation: Attenuation,
}

impl Light {
    /// A point light at `position` of `color`, intensity 1, on, without attenuation.
    pub fn point(position: Vec3, color: Vec3) -> Light {
        Light { kind: LightKind::Point, position, color, intensity: 1.0, enabled: true, attenuation: Attenuation::NONE }
    }

    /// A directional light from `towards_light` (world space, pointing at the light).
    pub fn directional(towards_light: Vec3, color: Vec3) -> Light {
        Light { kind: LightKind::Directional, ..Light::point(towards_light, color) }
    }

    /// Whether every number is finite (what commands and presets accept).
    pub fn is_finite(&self) -> bool {
        self.position.is_finite()
            && self.color.is_finite()
            && self.intensity.is_finite()
            && self.attenuation.to_array().iter().all(|v| v.is_finite())
    }
}

/// How the classic model's highlight is shaped (GLScene's `smBlinn`, `smPhong`, `smOff`).
/// A uniform. Named `blinn`, `phong`, `off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum SpecularMode {
    /// `max(N·H, 0)^shininess` with the half vector `H = normalize(L + V)`.
    #[default]
    Blinn,
    /// `max(R·V, 0)^shininess` with `L` mirrored about `N`: `R = 2(N·L)N − L`.
    Phong,
    /// No highlight: ambient and diffuse only.
    Off,
}

impl SpecularMode {
    /// The index the shader switches on (`frame.specular_mode`).
    pub fn shader_index(self) -> u32 {
        self as u32
    }

    /// A mode's name for people (labels and captions).
    pub fn label(self) -> &'static str {
        match self {
            SpecularMode::Blinn => "Blinn (N·H)",
            SpecularMode::Phong => "Phong (R·V)",
            SpecularMode::Off => "no specular",
        }
    }
}

/// The lights of a frame (one to [`MAX_LIGHTS`], in order) and its ambient light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lights {
    slots: [Light; MAX_LIGHTS],
    count: usize,
    /// Linear RGB of the ambient light (the classic model multiplies it by the albedo).
    pub ambient_color: Vec3,
    /// Multiplies `ambient_color`.
    pub ambient_strength: f32,
}

/// Why a light could not be added or removed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LightsError {
    #[error("at most {MAX_LIGHTS} lights")]
    Full,
    #[error("the last light cannot be removed (switch it off instead)")]
    LastLight,
}

impl Lights {
    /// `light` alone with an ambient light of `ambient` at strength 1.
    pub fn one(light: Light, ambient: Vec3) -> Lights {
        let mut slots = [light; MAX_LIGHTS];
        slots[1..].iter_mut().for_each(|s| s.enabled = false);
        Lights { slots, count: 1, ambient_color: ambient, ambient_strength: 1.0 }
    }

    /// The ambient light: colour times strength, linear RGB.
    pub fn ambient(&self) -> Vec3 {
        self.ambient_color * self.ambient_strength
    }

    pub fn len(&self) -> usize {
        self.count
    }

    /// Always false: a frame has at least one light.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The first light that is on: the shader's `frame.lights[0]` (the light of the legacy
    /// looks and of the per-vertex mistakes); `None` when every light is off.
    pub fn first_on(&self) -> Option<&Light> {
        self.as_slice().iter().find(|light| light.enabled)
    }

    pub fn as_slice(&self) -> &[Light] {
        &self.slots[..self.count]
    }

    pub fn as_mut_slice(&mut self) -> &mut [Light] {
        &mut self.slots[..self.count]
    }

    /// Appends `light`; its index.
    pub fn push(&mut self, light: Light) -> Result<usize, LightsError> {
        if self.count == MAX_LIGHTS {
            return Err(LightsError::Full);
        }
        self.slots[self.count] = light;
        self.count += 1;
        Ok(self.count - 1)
    }

    /// Removes light `index` (the later ones move down); an index past the end is ignored.
    pub fn remove(&mut self, index: usize) -> Result<(), LightsError> {
        if self.count == 1 {
            return Err(LightsError::LastLight);
        }
        if index < self.count {
            self.slots.copy_within(index + 1..self.count, index);
            self.count -= 1;
        }
        Ok(())
    }

    /// The lights given (one to [`MAX_LIGHTS`]) with the ambient light of `self`.
    pub fn with_lights(&self, lights: &[Light]) -> Result<Lights, LightsError> {
        let (first, rest) = lights.split_first().ok_or(LightsError::LastLight)?;
        let mut out = *self;
        out.slots[0] = *first;
        out.count = 1;
        for light in rest {
            out.push(*light)?;
        }
        Ok(out)
    }
}

impl std::ops::Index<usize> for Lights {
    type Output = Light;
    fn index(&self, index: usize) -> &Light {
        &self.as_slice()[index]
    }
}

impl std::ops::IndexMut<usize> for Lights {
    fn index_mut(&mut self, index: usize) -> &mut Light {
        &mut self.as_mut_slice()[index]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lights_grow_to_the_limit_and_keep_one() {
        let mut lights = Lights::one(Light::point(Vec3::ZERO, Vec3::ONE), Vec3::splat(0.1));
        for i in 1..MAX_LIGHTS {
            assert_eq!(lights.push(Light::point(Vec3::splat(i as f32), Vec3::ONE)), Ok(i));
        }
        assert_eq!(lights.push(Light::point(Vec3::ZERO, Vec3::ONE)), Err(LightsError::Full));
        lights.remove(0).unwrap();
        assert_eq!(lights.len(), MAX_LIGHTS - 1);
        assert_eq!(lights[0].position, Vec3::ONE);
        while lights.len() > 1 {
            lights.remove(lights.len() - 1).unwrap();
        }
        assert_eq!(lights.remove(0), Err(LightsError::LastLight));
    }

    #[test]
    fn attenuation_rejects_negative_non_finite_and_all_zero() {
        assert!(Attenuation::from_array([1.0, 0.5, 0.25]).is_ok());
        assert!(Attenuation::from_array([0.0, 0.0, 1.0]).is_ok());
        for bad in [[0.0; 3], [-1.0, 0.0, 0.0], [1.0, f32::NAN, 0.0], [1.0, 0.0, f32::INFINITY]] {
            assert!(Attenuation::from_array(bad).is_err(), "{bad:?}");
        }
    }
}
