//! The control panel: one section per topic, each control labelled with its key.
//! Widgets edit copies of the state and report changes as [`Action`]s.

use bumpview::WorkCounters;
use bumpview::check::{CheckReport, GreenConvention};
use bumpview::frame::BumpSource;
use bumpview::frame::STRENGTH_RANGE;
use bumpview::frame::{ShadingMode, ViewMode};
use bumpview::height::{Border, Kernel};
use bumpview::names::Named;
use bumpview::render::glyphs::MAX_GLYPHS_PER_MESH;
use bumpview::scene::{GreenAxis, Material, MaterialOverrides, ShadingModel};
use bumpview::shading::OVER_TILT_LIMIT_DEG;
use bumpview::state::{Command, SplitDifference, ViewerState};
use bumpview::tangent::{MethodMeasurement, TangentMethod};

use super::{Action, MAX_SUPERSAMPLE, PresetForm, ScreenshotForm};

/// Range of the light position sliders, metres.
const LIGHT_RANGE: std::ops::RangeInclusive<f32> = -5.0..=5.0;

/// What the stats lines report.
pub(super) struct Stats<'a> {
    /// Per mesh: the chosen tangent method's time and error against the reference.
    pub measurements: &'a [(String, MethodMeasurement)],
    pub adapter: &'a str,
    pub view_size: Option<[u32; 2]>,
    pub counters: WorkCounters,
    pub render_error: Option<&'a str>,
    /// The scene's materials, as loaded (before overrides).
    pub materials: &'a [Material],
    /// What `bumpview check` finds in the scene.
    pub check: &'a CheckReport,
    /// The check's warnings, one line each.
    pub check_warnings: &'a [String],
    /// What the renderer could not do as asked (downscaled textures, dropped bump maps…).
    pub notices: &'a [String],
    /// The pinned pixel probe.
    pub probe: &'a super::probe::Probe,
}

/// The panel's text fields and their outcomes, kept between frames.
pub(super) struct Forms<'a> {
    pub screenshot: &'a mut ScreenshotForm,
    pub preset: &'a mut PresetForm,
}

/// Shows the whole panel, with the files section ([`super::files_panel`]) drawn by `files`
/// under the heading, and returns what the user changed.
pub(super) fn show(
    ui: &mut egui::Ui,
    state: &ViewerState,
    forms: Forms,
    stats: &Stats,
    files: impl FnOnce(&mut egui::Ui, &mut Vec<Action>),
) -> Vec<Action> {
    let mut actions = Vec::new();
    egui::ScrollArea::vertical().show(ui, |ui| {
        ui.heading("bumpview");
        files(ui, &mut actions);
        bump_section(ui, state, &mut actions);
        light_section(ui, state, &mut actions);
        view_section(ui, state, &mut actions);
        split_section(ui, state, &mut actions);
        stats.probe.section(ui, &mut actions);
        methods_section(ui, state, stats.measurements, &mut actions);
        conventions_section(ui, state, stats.materials, &mut actions);
        check_section(ui, stats, &mut actions);
        camera_section(ui, &mut actions);
        screenshot_section(ui, forms.screenshot, &mut actions);
        preset_section(ui, forms.preset, &mut actions);
        ui.separator();
        stats_section(ui, stats);
    });
    actions
}

fn bump_section(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Bump mapping");
    let mut bump = state.shading.bump_enabled;
    if ui.checkbox(&mut bump, "Bump on (B)").changed() {
        actions.push(Command::SetBump(bump).into());
    }
    let mut strength = state.shading.strength;
    let slider = egui::Slider::new(&mut strength, STRENGTH_RANGE).text("strength ([ / ])").step_by(0.01);
    if ui.add(slider).on_hover_text("0 is flat, negative inverts the relief; [ and ] step by 0.1").changed() {
        actions.push(Command::SetStrength(strength).into());
    }
}

fn light_section(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Light");
    let mut position = state.light.position;
    let mut moved = false;
    for (axis, value) in [("X", &mut position.x), ("Y", &mut position.y), ("Z", &mut position.z)] {
        moved |= ui.add(egui::Slider::new(value, LIGHT_RANGE).text(axis).suffix(" m")).changed();
    }
    if moved {
        actions.push(Command::SetLightPosition(position).into());
    }
    ui.weak("Ctrl-drag in the view moves the light");
    let mut orbit = state.light_orbit;
    if ui.checkbox(&mut orbit, "Orbit light (L)").changed() {
        actions.push(Command::SetLightOrbit(orbit).into());
    }
    let mut marker = state.shading.show_light_marker;
    if ui.checkbox(&mut marker, "Show light marker").changed() {
        actions.push(Command::SetLightMarker(marker).into());
    }
}

fn view_section(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("View (V cycles)");
    let mut view = state.shading.view;
    for &mode in ViewMode::all() {
        if ui.radio_value(&mut view, mode, view_radio_label(mode)).changed() {
            actions.push(Command::SetView(view).into());
        }
    }
    ui.weak(view_hint(state.shading.view));
    if state.shading.view == ViewMode::Difference {
        let mut range = state.shading.difference_range_deg;
        let slider = egui::Slider::new(&mut range, 0.01..=90.0).logarithmic(true).text("scale").suffix("°");
        if ui.add(slider).changed() {
            actions.push(Command::SetDifferenceRange(range).into());
        }
    }
    modes_and_overlay(ui, state, actions);
}

/// The classic demo modes (keys 1/2/3), the wireframe overlay (W) and the T/B/N glyphs (G).
fn modes_and_overlay(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    ui.label("Lit picture");
    let mut mode = state.shading.mode;
    ui.horizontal(|ui| {
        for (choice, label, hint) in [
            (ShadingMode::BumpTimesColour, "bump × colour (1)", "lighting with the bumped normal times the colour"),
            (ShadingMode::BumpOnly, "bump only (2)", "lighting with a white albedo: the relief alone"),
            (ShadingMode::ColourOnly, "colour only (3)", "the colour texture as stored: no bump, no lighting"),
        ] {
            ui.radio_value(&mut mode, choice, label).on_hover_text(hint);
        }
    });
    if mode != state.shading.mode {
        actions.push(Command::SetShadingMode(mode).into());
    }
    let mut wireframe = state.shading.wireframe;
    let checkbox = ui.checkbox(&mut wireframe, "Wireframe overlay (W)").on_hover_text(
        "triangle edges drawn again as lines; needs line polygon mode on the GPU, else the Check section says so",
    );
    if checkbox.changed() {
        actions.push(Command::SetWireframe(wireframe).into());
    }
    let mut glyphs = state.shading.tbn_glyphs;
    let checkbox = ui.checkbox(&mut glyphs, "T/B/N glyphs (G)").on_hover_text(format!(
        "short lines at vertices: tangent red, bitangent green, normal blue (the frames the shading uses); \
         meshes with tangent frames only, at most {MAX_GLYPHS_PER_MESH} glyphs per mesh, spread evenly"
    ));
    if checkbox.changed() {
        actions.push(Command::SetGlyphs(glyphs).into());
    }
}

fn methods_section(
    ui: &mut egui::Ui,
    state: &ViewerState,
    measurements: &[(String, MethodMeasurement)],
    actions: &mut Vec<Action>,
) {
    ui.separator();
    ui.strong("Methods");
    let tangent_name = |m: Option<TangentMethod>| m.map_or("auto (file, else mikktspace)", TangentMethod::name);
    let mut tangent_method = state.scene_options.tangent_method;
    egui::ComboBox::from_label("tangent frames").selected_text(tangent_name(tangent_method)).show_ui(ui, |ui| {
        for choice in std::iter::once(None).chain(TangentMethod::all().iter().copied().map(Some)) {
            ui.selectable_value(&mut tangent_method, choice, tangent_name(choice));
        }
    });
    if tangent_method != state.scene_options.tangent_method {
        actions.push(Command::SetTangentMethod(tangent_method).into());
    }
    let mut bump_source = state.scene_options.bump_source;
    egui::ComboBox::from_label("bump source").selected_text(bump_source.name()).show_ui(ui, |ui| {
        for &choice in BumpSource::all() {
            ui.selectable_value(&mut bump_source, choice, choice.name());
        }
    });
    if bump_source != state.scene_options.bump_source {
        actions.push(Command::SetBumpSource(bump_source).into());
    }
    let mut kernel = state.kernel;
    egui::ComboBox::from_label("height-to-normal kernel").selected_text(kernel.name()).show_ui(ui, |ui| {
        for &choice in Kernel::all() {
            ui.selectable_value(&mut kernel, choice, choice.name());
        }
    });
    if kernel != state.kernel {
        actions.push(Command::SetKernel(kernel).into());
    }
    ui.weak("time of one run; angle to the reference frame (T / B, mean and max)");
    egui::Grid::new("measurements").striped(true).show(ui, |ui| {
        for (mesh, m) in measurements {
            ui.small(mesh).on_hover_text(format!("{} against {}", m.method.name(), m.reference.name()));
            ui.small(format!("{:.2} ms", m.seconds * 1e3));
            ui.small(format!("{:.3}° / {:.3}°", m.tangent.mean, m.bitangent.mean));
            ui.small(format!("max {:.2}°", m.tangent.max.max(m.bitangent.max)));
            ui.end_row();
        }
    });
}

/// Normal-map and height-map conventions for every material or one of them, what each
/// material is drawn with, and the shading model.
fn conventions_section(ui: &mut egui::Ui, state: &ViewerState, materials: &[Material], actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Texture conventions and shading");
    let options = &state.scene_options;
    let target_id = egui::Id::unique("conventions target");
    let mut target = ui.data(|d| d.get_temp::<Option<usize>>(target_id)).flatten().filter(|&i| i < materials.len());
    let target_name = |t: Option<usize>| t.map_or_else(|| "all materials".to_owned(), |i| material_label(materials, i));
    egui::ComboBox::from_label("apply to").selected_text(target_name(target)).show_ui(ui, |ui| {
        for choice in std::iter::once(None).chain((0..materials.len()).map(Some)) {
            ui.selectable_value(&mut target, choice, target_name(choice));
        }
    });
    ui.data_mut(|d| d.insert_temp(target_id, target));
    // A material's own setting where set, else the viewer-wide one is shown (and inherited).
    let inherited = if target.is_some() { options.materials } else { MaterialOverrides::default() };
    let old = options.overrides(target);
    let mut new = old;
    let unset = if target.is_some() { "as all materials" } else { "as loaded" };
    let green_name = |g: Option<GreenAxis>| match g {
        None => unset,
        Some(GreenAxis::OpenGl) => "OpenGL (+Y)",
        Some(GreenAxis::DirectX) => "DirectX (−Y, green flipped)",
    };
    egui::ComboBox::from_label("normal map green").selected_text(green_name(new.green)).show_ui(ui, |ui| {
        for choice in [None, Some(GreenAxis::OpenGl), Some(GreenAxis::DirectX)] {
            ui.selectable_value(&mut new.green, choice, green_name(choice));
        }
    });
    for (flag, base, label) in [
        (&mut new.two_channel, inherited.two_channel, "two-channel (reconstruct z)"),
        (&mut new.object_space, inherited.object_space, "object-space normal map (no tangents)"),
        (&mut new.depth_map, inherited.depth_map, "height map is a depth map (white = deep)"),
    ] {
        let mut on = flag.or(base).unwrap_or(false);
        if ui.checkbox(&mut on, label).changed() {
            *flag = Some(on);
        }
    }
    let kernel_name = |k: Option<Kernel>| k.map_or(unset, Kernel::name);
    egui::ComboBox::from_label("height map kernel").selected_text(kernel_name(new.kernel)).show_ui(ui, |ui| {
        for choice in std::iter::once(None).chain(Kernel::all().iter().copied().map(Some)) {
            ui.selectable_value(&mut new.kernel, choice, kernel_name(choice));
        }
    });
    let border_name = |b: Option<Border>| b.map_or(unset, border_label);
    egui::ComboBox::from_label("height map border").selected_text(border_name(new.border)).show_ui(ui, |ui| {
        for choice in [None, Some(Border::Wrap), Some(Border::Clamp)] {
            ui.selectable_value(&mut new.border, choice, border_name(choice));
        }
    });
    let mut range_mm = new.height_range_m.or(inherited.height_range_m).map_or(10.0, |m| m * 1e3);
    let drag = egui::DragValue::new(&mut range_mm).range(0.0..=1000.0).speed(0.1).suffix(" mm");
    let changed = ui
        .horizontal(|ui| {
            let changed = ui.add(drag).changed();
            ui.label("height map range (metres per full range, shown in mm)");
            changed
        })
        .inner;
    if changed {
        new.height_range_m = Some(range_mm * 1e-3);
    }
    let reset = if target.is_some() { "Use the settings for all materials" } else { "Use the files' settings" };
    if ui.add_enabled(!old.is_empty(), egui::Button::new(reset)).clicked() {
        new = MaterialOverrides::default();
    }
    if new != old {
        actions.push(Command::SetMaterialOverrides { material: target, overrides: new }.into());
    }
    ui.weak("in use (after overrides); * marks a material with its own settings");
    egui::Grid::new("conventions in use").striped(true).num_columns(2).show(ui, |ui| {
        for (index, material) in materials.iter().enumerate() {
            let own = if options.per_material.contains_key(&index) { " *" } else { "" };
            ui.small(format!("{}{own}", material_label(materials, index)));
            let (drawn, remade) = options.overrides_in_use(index).in_use(material);
            ui.small(convention_in_use(&drawn, remade));
            ui.end_row();
        }
    });
    let shading_name = |m: Option<ShadingModel>| match m {
        None => "auto (glTF: metallic-roughness, else Blinn-Phong)",
        Some(ShadingModel::BlinnPhong) => "Blinn-Phong",
        Some(ShadingModel::MetallicRoughness) => "metallic-roughness (GGX + sky)",
    };
    let mut shading = state.shading.shading_override;
    egui::ComboBox::from_label("shading").selected_text(shading_name(shading)).show_ui(ui, |ui| {
        for choice in [None, Some(ShadingModel::BlinnPhong), Some(ShadingModel::MetallicRoughness)] {
            ui.selectable_value(&mut shading, choice, shading_name(choice));
        }
    });
    if shading != state.shading.shading_override {
        actions.push(Command::SetShadingOverride(shading).into());
    }
}

/// "index: name" of material `index`.
fn material_label(materials: &[Material], index: usize) -> String {
    format!("{index}: {}", materials[index].name)
}

fn border_label(border: Border) -> &'static str {
    match border {
        Border::Wrap => "wrap (tiles)",
        Border::Clamp => "clamp (edge repeats)",
    }
}

/// One material's normal-map convention and height-map settings as drawn.
fn convention_in_use(material: &Material, remade: bool) -> String {
    let normal = match &material.normal_map {
        Some(map) if remade => format!("normals made from height: {}", map.convention.describe()),
        Some(map) => map.convention.describe(),
        None => "no normal map".to_owned(),
    };
    let Some(height) = &material.height_map else { return normal };
    let kind = if height.depth { "depth" } else { "height" };
    let border = border_label(height.border);
    let kernel = height.kernel.name();
    format!("{normal}\n{kind} map: {kernel} kernel, {border}, {:.2} mm range", height.range_m * 1e3)
}

/// One line on what the colours of a view mean.
fn view_hint(mode: ViewMode) -> &'static str {
    match mode {
        ViewMode::Lit => "Blinn-Phong lighting with the (bumped) shading normal",
        ViewMode::UvCheck => "red: triangles whose UVs have no area (no tangent frame); blue: mirrored UVs (w = −1)",
        ViewMode::Difference => {
            "larger of the angles between T and between B of the chosen frames and the reference \
             (analytic on built-in surfaces, else MikkTSpace); grey: no frames"
        }
        ViewMode::Handedness => "green: w = +1, magenta: w = −1 (mirrored UV island), grey: no tangents",
        ViewMode::OverTilt => over_tilt_hint(),
        _ => "colour = 0.5·v + 0.5 of the world-space vector v (red +X, green +Y, blue +Z)",
    }
}

/// The Over-tilt view's hint, with its threshold.
fn over_tilt_hint() -> &'static str {
    const _: () = assert!(OVER_TILT_LIMIT_DEG == 75.0, "update the hint below");
    "lit, red where the bumped normal tilts more than 75° from the surface normal (or below it): \
     the strength is too high there"
}

fn camera_section(ui: &mut egui::Ui, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Camera");
    ui.weak("Left-drag orbits, wheel zooms, Shift- or middle-drag pans");
    if ui.button("Reset camera (R)").clicked() {
        actions.push(Command::ResetCamera.into());
    }
}

fn screenshot_section(ui: &mut egui::Ui, form: &mut ScreenshotForm, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Screenshot (3D view only)");
    ui.horizontal(|ui| {
        ui.label("Size");
        ui.add(egui::TextEdit::singleline(&mut form.size_text).hint_text("view size").desired_width(110.0))
            .on_hover_text("WxH in pixels, e.g. 3840x2160, up to the adapter's limit; empty uses the view's size");
    });
    ui.checkbox(&mut form.transparent, "Transparent background")
        .on_hover_text("alpha 0 where there is no geometry; the PNG keeps alpha");
    ui.add(egui::Slider::new(&mut form.supersample, 1..=MAX_SUPERSAMPLE).text("supersampling ×"))
        .on_hover_text("render at k times the size and average k×k pixels in linear light");
    if ui.button("Save PNG (F12)").clicked() {
        actions.push(Action::Screenshot);
    }
    ui.add(
        egui::TextEdit::singleline(&mut form.tiles_text).hint_text("flat,bumped,tangent").desired_width(f32::INFINITY),
    )
    .on_hover_text(
        "tiles: rows separated by ';', tiles by ',', each NAME or NAME@STRENGTH; NAME is flat, bumped, \
         bump-only, colour-only or a view (tangent, shading-normal, handedness, ...); empty: flat,bumped,tangent",
    );
    ui.horizontal(|ui| {
        if ui.button("Export tiles").on_hover_text("the tiles above as one PNG, each of the size above").clicked() {
            actions.push(Action::ExportTiles);
        }
        ui.checkbox(&mut form.captions, "captions")
            .on_hover_text("a strip under each tile: view and mode, strength, normal-map convention, tangents");
    });
    outcome(ui, &form.message);
}

/// The split view: on/off, what differs, and the two values of that difference.
fn split_section(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    ui.separator();
    let split = state.split;
    let mut enabled = split.enabled;
    if ui.checkbox(&mut enabled, "Split view (S)").on_hover_text("drag the divider in the view to move it").changed() {
        actions.push(Command::SetSplit(enabled).into());
    }
    if !enabled {
        return;
    }
    egui::ComboBox::from_label("differs in").selected_text(split.difference.name()).show_ui(ui, |ui| {
        for &d in SplitDifference::all() {
            if ui.selectable_label(split.difference == d, d.name()).clicked() && d != split.difference {
                actions.push(Command::SetSplitDifference(d).into());
            }
        }
    });
    if split.difference.changes_gpu_data() {
        ui.weak("the right half is drawn from a second upload of the scene");
    }
    let command = match split.difference {
        SplitDifference::Bump => {
            ui.weak("left bump off, right bump on");
            None
        }
        SplitDifference::View => {
            pair_combos(ui, "view", split.views, ViewMode::all(), ViewMode::label).map(Command::SetSplitViews)
        }
        SplitDifference::Strength => {
            let mut strengths = split.strengths;
            for (side, strength) in ["left", "right"].into_iter().zip(strengths.iter_mut()) {
                ui.add(egui::Slider::new(strength, STRENGTH_RANGE).text(format!("{side} strength")).step_by(0.01));
            }
            (strengths != split.strengths).then_some(Command::SetSplitStrengths(strengths))
        }
        SplitDifference::Mode => {
            pair_combos(ui, "mode", split.modes, ShadingMode::all(), ShadingMode::label).map(Command::SetSplitModes)
        }
        SplitDifference::Tangents => {
            pair_combos(ui, "tangents", split.tangent_methods, TangentMethod::all(), TangentMethod::name)
                .map(Command::SetSplitTangentMethods)
        }
        SplitDifference::Convention => pair_combos(ui, "green", split.conventions, GreenAxis::all(), GreenAxis::label)
            .map(Command::SetSplitConventions),
        SplitDifference::BumpSource => {
            pair_combos(ui, "bump source", split.bump_sources, BumpSource::all(), BumpSource::label)
                .map(Command::SetSplitBumpSources)
        }
    };
    actions.extend(command.map(Action::from));
}

/// A left and a right combo box choosing among `all`; the new pair when one changed.
fn pair_combos<T: Copy + PartialEq>(
    ui: &mut egui::Ui,
    what: &str,
    pair: [T; 2],
    all: &[T],
    label: fn(T) -> &'static str,
) -> Option<[T; 2]> {
    let mut chosen = pair;
    for (side, value) in ["left", "right"].into_iter().zip(chosen.iter_mut()) {
        egui::ComboBox::from_label(format!("{side} {what}")).selected_text(label(*value)).show_ui(ui, |ui| {
            for &option in all {
                ui.selectable_value(value, option, label(option));
            }
        });
    }
    (chosen != pair).then_some(chosen)
}

/// Save and load the whole state (files, camera, light, settings, screenshot options).
fn preset_section(ui: &mut egui::Ui, form: &mut PresetForm, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Preset (whole state as TOML)");
    ui.add(egui::TextEdit::singleline(&mut form.path_text).hint_text("file, e.g. slide.toml"))
        .on_hover_text("the preset file; bumpview render --preset FILE draws the same picture");
    let path = std::path::PathBuf::from(form.path_text.trim());
    let named = !form.path_text.trim().is_empty();
    ui.horizontal(|ui| {
        if ui.add_enabled(named, egui::Button::new("Save preset")).clicked() {
            actions.push(Action::SavePreset(path.clone()));
        }
        if ui.add_enabled(named, egui::Button::new("Load preset")).clicked() {
            actions.push(Action::LoadPreset(path));
        }
    });
    outcome(ui, &form.message);
}

/// A form's last outcome: plain on success, in the error colour on failure.
fn outcome(ui: &mut egui::Ui, message: &Option<Result<String, String>>) {
    match message {
        Some(Ok(message)) => {
            ui.label(message);
        }
        Some(Err(message)) => {
            ui.colored_label(ui.visuals().error_fg_color, message);
        }
        None => {}
    }
}

/// The findings of `bumpview check` for the scene, the renderer's notices, and a button for
/// the view that highlights degenerate and mirrored triangles.
fn check_section(ui: &mut egui::Ui, stats: &Stats, actions: &mut Vec<Action>) {
    ui.separator();
    ui.strong("Check");
    for mesh in &stats.check.meshes {
        ui.small(format!(
            "{}: {} triangles, {} degenerate-UV, {} mirrored, {} UV-seam positions",
            mesh.name, mesh.triangles, mesh.degenerate_uv, mesh.mirrored, mesh.seam_positions
        ));
    }
    for map in &stats.check.normal_maps {
        let convention = match map.findings.convention {
            Some((GreenConvention::OpenGl, c)) => format!("green looks OpenGL ({c:.2})"),
            Some((GreenConvention::DirectX, c)) => format!("green looks DirectX ({c:.2})"),
            None => "green undetermined (flat)".to_owned(),
        };
        ui.small(format!("{}: {convention}", map.material));
    }
    let warn = ui.visuals().warn_fg_color;
    for line in stats.check_warnings.iter().chain(stats.notices) {
        ui.colored_label(warn, egui::RichText::new(line).small());
    }
    if ui.button("Highlight degenerate / mirrored UVs").clicked() {
        actions.push(Command::SetView(ViewMode::UvCheck).into());
    }
}

fn stats_section(ui: &mut egui::Ui, stats: &Stats) {
    let size = stats.view_size.map_or_else(|| "no view".to_owned(), |[w, h]| format!("{w}x{h}"));
    ui.small(format!(
        "{} · view {size} · {} frames drawn · {} pipelines built",
        stats.adapter, stats.counters.frames_drawn, stats.counters.pipelines_built
    ));
    if let Some(error) = stats.render_error {
        ui.colored_label(ui.visuals().error_fg_color, error);
    }
}

/// The panel's radio-button text for a view: its label and, for the analysis views, what it shows.
fn view_radio_label(mode: ViewMode) -> String {
    let what = match mode {
        ViewMode::Difference => " (frame vs reference)",
        ViewMode::UvCheck => " (degenerate / mirrored)",
        ViewMode::Handedness => " (tangent w)",
        ViewMode::OverTilt => " (normal near or below the surface)",
        _ => "",
    };
    format!("{}{what}", mode.label())
}
