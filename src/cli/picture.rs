//! The flags that set up the picture (what to show, bump, strength, camera, lights, parallax,
//! displacement, legacy looks, mistakes, split view), shared by the viewer and `render` so both
//! start in the same [`ViewerState`] from the same flags. They stand for the viewer's
//! [`Command`]s, applied by [`ViewerState::apply`] as the panel's are, with the same clamps.

use bumpview::frame::{
    DEFAULT_PIXELS_PER_EDGE, GPU_PIXELS_PER_EDGE, LegacyLook, LegacySettings, MAX_PARALLAX_SHADOW_STRENGTH,
    MAX_PARALLAX_STEPS, Mistake, Parallax, ViewMode,
};
use bumpview::state::{Command, SplitDifference, ViewerState};

use super::Failure;
use super::args;
use super::lights::LightArgs;

/// The picture flags (the viewer's and `render`'s).
#[derive(clap::Args, Clone)]
pub struct PictureArgs {
    /// What to show [default: lit].
    #[arg(long, value_parser = args::named::<ViewMode>())]
    view: Option<ViewMode>,
    /// Bump mapping on or off [default: on].
    #[arg(long, value_parser = args::parse_on_off, action = clap::ArgAction::Set)]
    bump: Option<bool>,
    /// Bump strength (0 is flat, negative inverts the relief), clamped to −2…4 as the
    /// viewer's slider [default: 1].
    #[arg(long, value_parser = args::parse_finite, allow_hyphen_values = true)]
    strength: Option<f32>,
    /// Camera YAW,PITCH,DISTANCE: degrees about +Y (0 looks along −Z), degrees above the
    /// target (clamped to ±89), metres from it (positive; clamped to 0.05…500).
    #[arg(long, value_parser = args::parse_triple, allow_hyphen_values = true)]
    camera: Option<[f32; 3]>,
    /// Parallax technique on normal-mapped surfaces with a height map, one of the possible
    /// values below (docs/parallax.md cites each one's paper) [default: off].
    #[arg(long, value_parser = args::named::<Parallax>())]
    parallax: Option<Parallax>,
    /// The searches' layers MIN,MAX (1 to 256 each; MIN face-on, MAX at grazing views, as Tatarchuk varies them)
    /// [default: 8,32].
    #[arg(long, value_name = "MIN,MAX", value_parser = args::parse_layers)]
    parallax_layers: Option<[u32; 2]>,
    /// Relief mapping's binary-search steps, 0 to 16 [default: 5].
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_PARALLAX_STEPS)))]
    parallax_steps: Option<u32>,
    /// The relief's depth in metres, 0 or more [default: each material's height range].
    #[arg(long, value_name = "METRES", value_parser = args::parse_finite)]
    parallax_depth: Option<f32>,
    /// Soft self-shadows of the searches (steep, occlusion, relief; Tatarchuk 2006) at
    /// STRENGTH, 0 (off) to 4 [default without the flag: off; with it and no value: 1].
    #[arg(long, value_name = "STRENGTH", num_args = 0..=1, default_missing_value = "1", value_parser = args::parse_finite)]
    parallax_shadows: Option<f32>,
    /// Displacement, the ground truth: meshes whose material has a height map tessellated at
    /// LEVEL on the CPU (4^LEVEL triangles per triangle, 0 to 10; 0 is off), or `gpu`: on the
    /// GPU for each view, edges cut to --pixels-per-edge; moved along their normals by the
    /// parallax depth, shaded with the displaced surface's normals. Its vertex count and memory
    /// go to stderr [default: 0].
    #[arg(long, value_name = "LEVEL|gpu", value_parser = args::parse_displacement)]
    displacement: Option<args::DisplacementArg>,
    /// With --displacement gpu: the target edge length on screen, pixels (0.5 to 64)
    /// [default: 3].
    #[arg(long, value_name = "PX", value_parser = args::parse_positive)]
    pixels_per_edge: Option<f32>,
    /// A legacy look in the lit views: dot3 (diffuse N·L alone, L normalised per vertex and
    /// interpolated) or emboss (the 2D light-map bump on surfaces with a height map)
    /// [default: off].
    #[arg(long, value_parser = args::named::<LegacyLook>())]
    legacy: Option<LegacyLook>,
    /// With --legacy dot3: re-normalise L through a normalization cube map of this face size
    /// (8, 16, 32 or 64).
    #[arg(long, value_name = "N", requires = "legacy", value_parser = clap::builder::PossibleValuesParser::new(["8", "16", "32", "64"]))]
    cube_map_size: Option<String>,
    /// Draw with one classic mistake: tbn-typo (the GLSL practicum's TBN[1].z = N.z where
    /// N.y belongs), handedness-ignored (B = N × T, w dropped), srgb-normal-map (the map sampled
    /// through an sRGB view), no-renormalization (interpolated normals used as they come),
    /// no-gram-schmidt (T not made orthogonal to N), green-flipped (the other green
    /// convention), half-vector-per-vertex (H interpolated, Cg 8.1.4), light-per-vertex (L
    /// normalised per vertex before interpolation, as the ARB-era shaders did) [default: none].
    #[arg(long, value_parser = args::named::<Mistake>())]
    mistake: Option<Mistake>,
    /// Hide the light marker.
    #[arg(long)]
    no_light_marker: bool,
    /// Draw T/B/N glyphs (red, green, blue lines) at vertices of meshes with tangent frames.
    #[arg(long)]
    glyphs: bool,
    /// Split view, left │ right, as one image: bump (off │ on), view (lit │ shading-normal),
    /// strength (1 │ 3), mode (colour-only │ bump-colour), tangents (per-face │ mikktspace),
    /// convention (opengl │ directx), bump-source (normal-map │ height-in-shader), parallax
    /// (steep │ occlusion), lighting-space (world │ tangent), mistake (none │ tbn-typo),
    /// mip-filter (renormalized-box │ toksvig), detail-blend (udn │ rnm) or displacement (a parallax technique │
    /// displacement at a level, `--split-sides occlusion,6`)
    /// [default: the preset's].
    #[arg(long, value_name = "KIND", value_parser = args::named::<SplitDifference>())]
    split: Option<SplitDifference>,
    /// With --split: the two sides instead of the defaults above, e.g. `averaged-uniform,mikktspace`
    /// for tangents or `0.5,2` for strength.
    #[arg(long, value_name = "LEFT,RIGHT", requires = "split")]
    split_sides: Option<String>,
    /// With --split: the divider as a fraction of the width, 0 to 1 [default: 0.5].
    #[arg(long, value_name = "FRACTION", value_parser = args::parse_finite, requires = "split")]
    split_at: Option<f32>,
    #[command(flatten)]
    lights: LightArgs,
}

impl PictureArgs {
    /// Whether no picture flag was given (the viewer then may restore its last state).
    #[cfg(any(feature = "ui", test))]
    pub fn is_empty(&self) -> bool {
        let Self {
            view,
            bump,
            strength,
            camera,
            parallax,
            parallax_layers,
            parallax_steps,
            parallax_depth,
            parallax_shadows,
            displacement,
            pixels_per_edge,
            legacy,
            cube_map_size,
            mistake,
            no_light_marker,
            glyphs,
            split,
            split_sides,
            split_at,
            lights,
        } = self;
        view.is_none()
            && bump.is_none()
            && strength.is_none()
            && camera.is_none()
            && parallax.is_none()
            && parallax_layers.is_none()
            && parallax_steps.is_none()
            && parallax_depth.is_none()
            && parallax_shadows.is_none()
            && displacement.is_none()
            && pixels_per_edge.is_none()
            && legacy.is_none()
            && cube_map_size.is_none()
            && mistake.is_none()
            && !no_light_marker
            && !glyphs
            && split.is_none()
            && split_sides.is_none()
            && split_at.is_none()
            && lights.is_empty()
    }

    /// Applies the flags to `state` (the preset's or the defaults, with the files loaded).
    pub fn apply(&self, state: &mut ViewerState) -> Result<(), Failure> {
        for command in self.commands(state)? {
            state.apply(command);
        }
        Ok(())
    }

    /// The picture flags as the viewer's commands, in the order they apply. Values no command
    /// takes (a camera distance that is not positive, a divider outside the view) are bad
    /// arguments; the others are clamped by the commands.
    pub fn commands(&self, state: &ViewerState) -> Result<Vec<Command>, Failure> {
        let mut commands = self.lights.commands(state.lights.as_slice())?;
        commands.extend(self.view.map(Command::SetView));
        commands.extend(self.bump.map(Command::SetBump));
        commands.extend(self.strength.map(Command::SetStrength));
        commands.extend(self.parallax.map(Command::SetParallax));
        commands.extend(self.mistake.map(Command::SetMistake));
        if let Some(look) = self.legacy {
            let cube_map_size = self.cube_map_size.as_deref().and_then(|n| n.parse().ok());
            commands.push(Command::SetLegacy(LegacySettings { look, cube_map_size }));
        }
        commands.extend(self.parallax_layers.map(Command::SetParallaxLayers));
        commands.extend(self.parallax_steps.map(Command::SetParallaxSteps));
        if let Some(depth) = self.parallax_depth {
            if depth < 0.0 {
                return Err(Failure::BadArguments(format!("--parallax-depth {depth}: expected metres, 0 or more")));
            }
            commands.push(Command::SetParallaxDepth(Some(depth)));
        }
        if let Some(strength) = self.parallax_shadows {
            if !(0.0..=MAX_PARALLAX_SHADOW_STRENGTH).contains(&strength) {
                let message =
                    format!("--parallax-shadows {strength}: expected a strength, 0 to {MAX_PARALLAX_SHADOW_STRENGTH}");
                return Err(Failure::BadArguments(message));
            }
            commands.push(Command::SetParallaxShadows(strength));
        }
        match (self.displacement, self.pixels_per_edge) {
            (Some(args::DisplacementArg::Gpu), pixels) => {
                let pixels = pixels.unwrap_or(DEFAULT_PIXELS_PER_EDGE);
                if !GPU_PIXELS_PER_EDGE.contains(&pixels) {
                    let (low, high) = (GPU_PIXELS_PER_EDGE.start(), GPU_PIXELS_PER_EDGE.end());
                    return Err(Failure::BadArguments(format!("--pixels-per-edge {pixels}: expected {low} to {high}")));
                }
                commands.push(Command::SetGpuDisplacement(Some(pixels)));
            }
            (_, Some(_)) => {
                return Err(Failure::BadArguments("--pixels-per-edge needs --displacement gpu".into()));
            }
            (Some(args::DisplacementArg::Level(level)), None) => commands.push(Command::SetDisplacement(level)),
            (None, None) => {}
        }
        if self.no_light_marker {
            commands.push(Command::SetLightMarker(false));
        }
        if self.glyphs {
            commands.push(Command::SetGlyphs(true));
        }
        if let Some([yaw, pitch, distance]) = self.camera {
            if distance <= 0.0 {
                return Err(Failure::BadArguments(format!("--camera: distance {distance} must be positive")));
            }
            commands.push(Command::PointCamera { yaw: yaw.to_radians(), pitch: pitch.to_radians(), distance });
        }
        if let Some(difference) = self.split {
            commands.extend([Command::SetSplit(true), Command::SetSplitDifference(difference)]);
            if let Some(sides) = &self.split_sides {
                let sides = args::parse_split_sides(difference, sides);
                commands.push(sides.map_err(|e| Failure::BadArguments(format!("--split-sides {e}")))?);
            }
        }
        if let Some(at) = self.split_at {
            if !(0.0..=1.0).contains(&at) {
                let message = format!("--split-at {at}: expected a fraction of the width, 0 to 1");
                return Err(Failure::BadArguments(message));
            }
            commands.push(Command::SetSplitDivider(at));
        }
        Ok(commands)
    }
}

#[cfg(test)]
mod tests {
    use bumpview::frame::{LightingSpace, ViewMode};
    use bumpview::scene::SpecularMode;
    use bumpview::state::preset::Preset;
    use clap::Parser;

    use super::super::start::start;
    use super::super::{Cli, Command as Subcommand};
    use super::*;

    /// Picture flags of every kind: view, bump, strength, camera, lights, specular, lighting
    /// space, parallax, mistake, legacy look, glyphs, split view.
    const FLAGS: [&str; 30] = [
        "--view",
        "tangent",
        "--strength",
        "2.5",
        "--camera",
        "30,10,3",
        "--light",
        "1,2,3:1,0.5,0.5:2",
        "--specular",
        "phong",
        "--lighting-space",
        "tangent",
        "--parallax",
        "relief",
        "--parallax-layers",
        "4,16",
        "--parallax-shadows",
        "2",
        "--mistake",
        "tbn-typo",
        "--legacy",
        "dot3",
        "--cube-map-size",
        "16",
        "--glyphs",
        "--no-light-marker",
        "--split",
        "strength",
        "--split-sides",
        "0.5,2",
    ];

    /// The state `start` makes (the built-in scene, no preset) with `picture` applied.
    fn state(picture: &PictureArgs, methods: &super::super::methods::MethodArgs) -> ViewerState {
        let mut started = start(Preset::default(), Default::default(), methods).unwrap_or_else(|e| panic!("{e}"));
        picture.apply(&mut started.state).unwrap_or_else(|_| panic!("the flags apply"));
        started.state
    }

    /// `bumpview FLAGS` (the viewer) starts in the state `bumpview render --out x.png FLAGS`
    /// draws, and the flags did change it.
    #[test]
    fn the_viewer_and_render_take_the_picture_flags_into_the_same_state() {
        let viewer = Cli::try_parse_from(std::iter::once("bumpview").chain(FLAGS)).unwrap_or_else(|e| panic!("{e}"));
        let render_args = ["bumpview", "render", "--out", "x.png"].into_iter().chain(FLAGS);
        let render = Cli::try_parse_from(render_args).unwrap_or_else(|e| panic!("{e}"));
        let Some(Subcommand::Render(render)) = render.command else { panic!("render parses as render") };
        assert!(!viewer.picture.is_empty());
        let viewer_state = state(&viewer.picture, &viewer.methods);
        let render_state = state(&render.picture, &render.methods);
        assert_eq!(viewer_state, render_state);
        let shading = &viewer_state.shading;
        assert_eq!((shading.view, shading.strength), (ViewMode::Tangent, 2.5));
        assert_eq!((shading.specular, shading.lighting_space), (SpecularMode::Phong, LightingSpace::Tangent));
        assert_eq!((shading.parallax.technique, shading.parallax.shadow_strength), (Parallax::Relief, 2.0));
        assert_eq!((shading.mistake, shading.legacy.cube_map_size), (Mistake::TbnTypo, Some(16)));
        assert!(shading.tbn_glyphs && !shading.show_light_marker && viewer_state.split.enabled);
        assert_eq!(viewer_state.camera.distance, 3.0);
        assert_eq!(viewer_state.lights.as_slice().len(), 1);
        let plain = Cli::try_parse_from(["bumpview"]).unwrap();
        assert!(plain.picture.is_empty());
        assert_ne!(state(&plain.picture, &plain.methods), viewer_state);
    }
}
