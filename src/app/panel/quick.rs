//! The top of the panel, always in sight: bump on/off and strength, the view, the split view
//! and the light.

use bumpview::bake::compressed_format::CompressedFormat;
use bumpview::frame::{
    BumpSource, DEFAULT_PIXELS_PER_EDGE, DetailBlend, LightingSpace, MAX_DISPLACEMENT_LEVEL, Mistake, Parallax,
    STRENGTH_RANGE, ShadingMode, ViewMode,
};
use bumpview::names::Named;
use bumpview::scene::GreenAxis;
use bumpview::shading::OVER_TILT_LIMIT_DEG;
use bumpview::state::{Command, SplitDifference, ViewerState};
use bumpview::tangent::TangentMethod;
use bumpview::texture::MipFilter;

use crate::app::action::Action;

/// Range of the light position sliders, metres.
const LIGHT_RANGE: std::ops::RangeInclusive<f32> = -5.0..=5.0;

pub(super) fn show(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    bump(ui, state, actions);
    view(ui, state, actions);
    split(ui, state, actions);
    light(ui, state, actions);
}

fn bump(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let mut bump = state.shading.bump_enabled;
    if ui.checkbox(&mut bump, "Bump on (B)").changed() {
        actions.push(Command::SetBump(bump).into());
    }
    let mut strength = state.shading.strength;
    let slider = egui::Slider::new(&mut strength, STRENGTH_RANGE).text("strength ([ ])").step_by(0.01);
    if ui.add(slider).on_hover_text("0 is flat, negative inverts the relief; [ and ] step by 0.1").changed() {
        actions.push(Command::SetStrength(strength).into());
    }
}

fn view(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let mut view = state.shading.view;
    egui::ComboBox::from_label("view (V)").selected_text(view.label()).show_ui(ui, |ui| {
        for &mode in ViewMode::all() {
            ui.selectable_value(&mut view, mode, view_choice_label(mode)).on_hover_text(view_hint(mode));
        }
    });
    if view != state.shading.view {
        actions.push(Command::SetView(view).into());
    }
    ui.add(egui::Label::new(egui::RichText::new(view_hint(state.shading.view)).weak().small()).wrap());
    if state.shading.view == ViewMode::Difference {
        let mut range = state.shading.difference_range_deg;
        let slider = egui::Slider::new(&mut range, 0.01..=90.0).logarithmic(true).text("scale").suffix("°");
        if ui.add(slider).changed() {
            actions.push(Command::SetDifferenceRange(range).into());
        }
    }
}

/// The split view: on/off, what differs, and the two values of that difference.
fn split(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let split = state.split;
    let mut enabled = split.enabled;
    ui.horizontal(|ui| {
        let toggle = ui.checkbox(&mut enabled, "Split (S)").on_hover_text("drag the divider in the view to move it");
        if toggle.changed() {
            actions.push(Command::SetSplit(enabled).into());
        }
        if !enabled {
            return;
        }
        let combo = egui::ComboBox::from_id_salt("split differs in").selected_text(split.difference.name());
        combo.show_ui(ui, |ui| {
            for &d in SplitDifference::all() {
                if ui.selectable_label(split.difference == d, d.name()).clicked() && d != split.difference {
                    actions.push(Command::SetSplitDifference(d).into());
                }
            }
        });
        ui.label("differs");
    });
    if !enabled {
        return;
    }
    if split.difference.changes_gpu_data() {
        ui.weak("the right half is drawn from a second upload of the scene");
    }
    let command = match split.difference {
        SplitDifference::Bump => {
            ui.weak("left bump off, right bump on");
            None
        }
        SplitDifference::View => pair_combos(ui, "view", split.views, ViewMode::label).map(Command::SetSplitViews),
        SplitDifference::Strength => {
            let mut strengths = split.strengths;
            for (side, strength) in ["left", "right"].into_iter().zip(strengths.iter_mut()) {
                ui.add(egui::Slider::new(strength, STRENGTH_RANGE).text(format!("{side} strength")).step_by(0.01));
            }
            (strengths != split.strengths).then_some(Command::SetSplitStrengths(strengths))
        }
        SplitDifference::Mode => pair_combos(ui, "mode", split.modes, ShadingMode::label).map(Command::SetSplitModes),
        SplitDifference::Tangents => {
            pair_combos(ui, "tangents", split.tangent_methods, TangentMethod::name).map(Command::SetSplitTangentMethods)
        }
        SplitDifference::Convention => {
            pair_combos(ui, "green", split.conventions, GreenAxis::label).map(Command::SetSplitConventions)
        }
        SplitDifference::BumpSource => {
            pair_combos(ui, "bump source", split.bump_sources, BumpSource::label).map(Command::SetSplitBumpSources)
        }
        SplitDifference::LightingSpace => pair_combos(ui, "lighting space", split.lighting_spaces, LightingSpace::name)
            .map(Command::SetSplitLightingSpaces),
        SplitDifference::MipFilter => {
            pair_combos(ui, "mip filter", split.mip_filters, MipFilter::name).map(Command::SetSplitMipFilters)
        }
        SplitDifference::DetailBlend => {
            pair_combos(ui, "detail blend", split.detail_blends, DetailBlend::name).map(Command::SetSplitDetailBlends)
        }
        SplitDifference::Compression => {
            let mut format = split.compression;
            egui::ComboBox::from_label("right: normal map through").selected_text(format.name()).show_ui(ui, |ui| {
                for &choice in CompressedFormat::all() {
                    ui.selectable_value(&mut format, choice, choice.name());
                }
            });
            ui.weak("left: as loaded; right: encoded and decoded on the CPU");
            (format != split.compression).then_some(Command::SetSplitCompression(format))
        }
        SplitDifference::Parallax => {
            pair_combos(ui, "parallax", split.parallax, Parallax::name).map(Command::SetSplitParallax)
        }
        SplitDifference::Displacement => {
            let [mut technique, _] = split.parallax;
            egui::ComboBox::from_label("left parallax").selected_text(technique.name()).show_ui(ui, |ui| {
                for &choice in Parallax::all() {
                    ui.selectable_value(&mut technique, choice, choice.name());
                }
            });
            let mut on_gpu = split.displacement_gpu.is_some();
            let mut changed = ui.checkbox(&mut on_gpu, "right: on the GPU").changed();
            let mut level = split.displacement_level;
            if !on_gpu {
                let slider =
                    egui::Slider::new(&mut level, 1..=MAX_DISPLACEMENT_LEVEL).text("right: displacement level");
                changed |= ui.add(slider).changed();
            }
            let gpu = on_gpu.then(|| split.displacement_gpu.unwrap_or(DEFAULT_PIXELS_PER_EDGE));
            (changed || technique != split.parallax[0]).then_some(Command::SetSplitDisplacement(technique, level, gpu))
        }
        SplitDifference::Mistake => {
            let chosen = pair_combos(ui, "mistake", split.mistakes, Mistake::name).map(Command::SetSplitMistakes);
            for (side, mistake) in ["left", "right"].into_iter().zip(split.mistakes) {
                ui.weak(format!("{side}: {}", mistake.explanation()));
            }
            chosen
        }
    };
    actions.extend(command.map(Action::from));
}

/// A left and a right combo box choosing among every value of `T`; the new pair when one changed.
fn pair_combos<T: Named>(ui: &mut egui::Ui, what: &str, pair: [T; 2], label: fn(T) -> &'static str) -> Option<[T; 2]> {
    let mut chosen = pair;
    ui.horizontal(|ui| {
        for (side, value) in ["left", "right"].into_iter().zip(chosen.iter_mut()) {
            let combo = egui::ComboBox::from_id_salt(format!("split {side} {what}")).selected_text(label(*value));
            combo.width(100.0).show_ui(ui, |ui| {
                for &option in T::all() {
                    ui.selectable_value(value, option, label(option));
                }
            });
        }
        ui.label(what);
    });
    (chosen != pair).then_some(chosen)
}

/// The selected light's position (a directional light's direction towards it), orbit and
/// markers; the other settings are in the "Lights and specular" section.
fn light(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let selected = state.selected_light();
    let mut position = state.lights[selected].position;
    let mut moved = false;
    if state.lights.len() > 1 {
        ui.weak(format!("light {} of {}", selected + 1, state.lights.len()));
    }
    for (axis, value) in [("light X", &mut position.x), ("light Y", &mut position.y), ("light Z", &mut position.z)] {
        moved |= ui.add(egui::Slider::new(value, LIGHT_RANGE).text(axis).suffix(" m")).changed();
    }
    if moved {
        actions.push(Command::SetLightPosition(position).into());
    }
    ui.horizontal(|ui| {
        let mut orbit = state.light_orbit;
        if ui.checkbox(&mut orbit, "Orbit (L)").changed() {
            actions.push(Command::SetLightOrbit(orbit).into());
        }
        let mut marker = state.shading.show_light_marker;
        if ui.checkbox(&mut marker, "markers").changed() {
            actions.push(Command::SetLightMarker(marker).into());
        }
        ui.weak("Ctrl-drag moves it");
    });
}

/// A view's entry in the view list: its label and, for the analysis views, what it shows.
fn view_choice_label(mode: ViewMode) -> String {
    let what = match mode {
        ViewMode::Difference => " (frame vs reference)",
        ViewMode::UvCheck => " (degenerate / mirrored)",
        ViewMode::Handedness => " (tangent w)",
        ViewMode::OverTilt => " (normal near or below the surface)",
        _ => "",
    };
    format!("{}{what}", mode.label())
}

/// One line on what the colours of a view mean.
fn view_hint(mode: ViewMode) -> &'static str {
    match mode {
        ViewMode::Lit => "lighting with the (bumped) shading normal",
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
    "lit in grey, red where the bumped normal tilts more than 75° from the surface normal (or below it): \
     the strength is too high there"
}
