//! `render`'s lighting flags: the lights (point and directional, repeatable), their
//! attenuation, the ambient light, the specular mode and shininess, and the lighting space,
//! as the viewer's [`LightCommand`]s.

use bumpview::frame::LightingSpace;
use bumpview::scene::{Attenuation, Light, MAX_LIGHTS, SpecularMode};
use bumpview::state::{Command, LightCommand};
use glam::Vec3;

use super::Failure;
use super::args;

/// `POSITION[:R,G,B[:INTENSITY]]` as given to `--light` or `--directional-light`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSpec {
    pub position: Vec3,
    pub color: Option<Vec3>,
    pub intensity: Option<f32>,
}

/// `"X,Y,Z[:R,G,B[:INTENSITY]]"` → a light's position (or direction), colour (each at least 0)
/// and intensity (at least 0).
pub fn parse_light(text: &str) -> Result<LightSpec, String> {
    let mut parts = text.split(':');
    let position = args::parse_vec3(parts.next().unwrap_or_default())?;
    let color = parts.next().map(args::parse_vec3).transpose()?;
    if let Some(c) = color.filter(|c| c.min_element() < 0.0) {
        return Err(format!("{text:?}: colour {c} must be linear RGB, each at least 0"));
    }
    let intensity = match parts.next() {
        None => None,
        Some(i) => Some(
            i.trim()
                .parse::<f32>()
                .ok()
                .filter(|i| i.is_finite() && *i >= 0.0)
                .ok_or_else(|| format!("{text:?}: intensity {i:?} must be a finite number, at least 0"))?,
        ),
    };
    if parts.next().is_some() {
        return Err(format!("{text:?}: expected X,Y,Z[:R,G,B[:INTENSITY]]"));
    }
    Ok(LightSpec { position, color, intensity })
}

/// `"R,G,B[:STRENGTH]"` → the ambient colour and strength (each at least 0).
pub fn parse_ambient(text: &str) -> Result<(Vec3, Option<f32>), String> {
    let (color, strength) = match text.split_once(':') {
        Some((c, s)) => (c, Some(s.trim().parse::<f32>().map_err(|_| format!("{text:?}: STRENGTH is a number"))?)),
        None => (text, None),
    };
    let color = args::parse_vec3(color)?;
    if color.min_element() < 0.0 || strength.is_some_and(|s| !(s.is_finite() && s >= 0.0)) {
        return Err(format!("{text:?}: colour and strength must be at least 0"));
    }
    Ok((color, strength))
}

/// The lighting flags of `render`.
#[derive(clap::Args, Clone)]
pub struct LightArgs {
    /// A point light at X,Y,Z metres (world space, +Y up), optionally with a linear colour
    /// R,G,B and an intensity [default colour 1,1,1, intensity 1]. Repeatable: with
    /// --directional-light, up to 8 lights replace the scene's (point lights first).
    #[arg(long, value_name = "X,Y,Z[:R,G,B[:INTENSITY]]", value_parser = parse_light, allow_hyphen_values = true)]
    light: Vec<LightSpec>,
    /// A directional light from direction DX,DY,DZ (pointing towards the light, as OpenGL's
    /// GL_POSITION with w = 0), colour and intensity as for --light. Repeatable.
    #[arg(long, value_name = "DX,DY,DZ[:R,G,B[:INTENSITY]]", value_parser = parse_light, allow_hyphen_values = true)]
    directional_light: Vec<LightSpec>,
    /// OpenGL attenuation 1 / (C + L·d + Q·d²) of every point light, d in metres; each at
    /// least 0, not all 0 [default: 1,0,0, no falloff].
    #[arg(long, value_name = "C,L,Q", value_parser = args::parse_triple)]
    attenuation: Option<[f32; 3]>,
    /// The ambient light: linear colour R,G,B and a strength multiplying it (classic model;
    /// metallic-roughness takes its ambient light from the sky) [default: the scene's, 1].
    #[arg(long, value_name = "R,G,B[:STRENGTH]", value_parser = parse_ambient)]
    ambient: Option<(Vec3, Option<f32>)>,
    /// The classic model's highlight: blinn (N·H), phong (R·V) or off [default: blinn].
    #[arg(long, value_parser = args::named::<SpecularMode>())]
    specular: Option<SpecularMode>,
    /// The classic model's shininess exponent for every material, at least 1 [default: each
    /// material's own].
    #[arg(long, value_parser = args::parse_finite)]
    shininess: Option<f32>,
    /// Where tangent-space normal-mapped surfaces are lit: world (per pixel), tangent (light
    /// and view vectors by each triangle's inverse TBN, as the ARB-era shaders do) or view (the
    /// world vectors rotated by the camera, as the GLSL practicum does) [default: world].
    #[arg(long, value_parser = args::named::<LightingSpace>())]
    lighting_space: Option<LightingSpace>,
}

impl LightArgs {
    /// Whether no lighting flag was given.
    #[cfg(any(feature = "ui", test))]
    pub fn is_empty(&self) -> bool {
        let Self { light, directional_light, attenuation, ambient, specular, shininess, lighting_space } = self;
        light.is_empty()
            && directional_light.is_empty()
            && attenuation.is_none()
            && ambient.is_none()
            && specular.is_none()
            && shininess.is_none()
            && lighting_space.is_none()
    }

    /// The flags as commands on `lights` (the lights the picture starts with: the scene's or
    /// the preset's), in the order they apply.
    pub fn commands(&self, start: &[Light]) -> Result<Vec<Command>, Failure> {
        let mut commands = Vec::new();
        let given = self.light.len() + self.directional_light.len();
        if given > MAX_LIGHTS {
            return Err(Failure::BadArguments(format!("{given} lights: at most {MAX_LIGHTS}")));
        }
        let attenuation = self.attenuation.map(Attenuation::from_array).transpose();
        let attenuation = attenuation.map_err(|e| Failure::BadArguments(format!("--attenuation: {e}")))?;
        let point = self.light.iter().map(|spec| (spec, false));
        let directional = self.directional_light.iter().map(|spec| (spec, true));
        let mut lights: Vec<Light> = point
            .chain(directional)
            .map(|(spec, directional)| {
                let color = spec.color.unwrap_or(Vec3::ONE);
                let light = if directional {
                    if spec.position == Vec3::ZERO {
                        return Err(Failure::BadArguments("--directional-light 0,0,0: no direction".into()));
                    }
                    Light::directional(spec.position, color)
                } else {
                    Light::point(spec.position, color)
                };
                Ok(Light { intensity: spec.intensity.unwrap_or(1.0), ..light })
            })
            .collect::<Result<_, _>>()?;
        if lights.is_empty() && attenuation.is_some() {
            lights = start.to_vec();
        }
        for light in &mut lights {
            light.attenuation = attenuation.unwrap_or(light.attenuation);
        }
        if !lights.is_empty() {
            for (index, light) in lights.iter().enumerate() {
                commands.push(Command::Lighting(LightCommand::Set { index, light: *light }));
            }
            commands.push(Command::Lighting(LightCommand::Truncate(lights.len())));
        }
        if let Some((color, strength)) = self.ambient {
            commands.push(Command::Lighting(LightCommand::SetAmbient { color, strength: strength.unwrap_or(1.0) }));
        }
        commands.extend(self.specular.map(|m| Command::Lighting(LightCommand::SetSpecular(m))));
        if let Some(shininess) = self.shininess {
            if shininess < 1.0 {
                return Err(Failure::BadArguments(format!("--shininess {shininess}: expected at least 1")));
            }
            commands.push(Command::Lighting(LightCommand::SetShininess(Some(shininess))));
        }
        commands.extend(self.lighting_space.map(|s| Command::Lighting(LightCommand::SetLightingSpace(s))));
        Ok(commands)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_specs_parse_with_optional_colour_and_intensity() {
        let plain = parse_light("-1,2,3").unwrap();
        assert_eq!((plain.position, plain.color, plain.intensity), (Vec3::new(-1.0, 2.0, 3.0), None, None));
        let full = parse_light("0,1,0:1,0.5,0:2.5").unwrap();
        assert_eq!((full.color, full.intensity), (Some(Vec3::new(1.0, 0.5, 0.0)), Some(2.5)));
        for bad in ["1,2", "1,2,3:1,1", "1,2,3:1,1,1:x", "1,2,3:-1,0,0", "1,2,3:1,1,1:-2", "1,2,3:1,1,1:1:1"] {
            assert!(parse_light(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_ambient("0.1,0.2,0.3:0.5").unwrap(), (Vec3::new(0.1, 0.2, 0.3), Some(0.5)));
        assert!(parse_ambient("0.1,0.2,0.3:-1").is_err());
    }
}
