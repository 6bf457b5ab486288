//! The numerical methods (tangent frames, bump source, normal-map mips, kernels) with their measurements, the
//! texture conventions and shading model per material, and what `bumpview check` finds.

use bumpview::frame::ViewMode;
use bumpview::frame::{BumpSource, SceneOptions};
use bumpview::height::{Border, Kernel};
use bumpview::names::Named;
use bumpview::scene::camera::{MAX_DISTANCE, MIN_DISTANCE};
use bumpview::scene::{GreenAxis, Material, MaterialOverrides, NormalLayout, ShadingModel};
use bumpview::state::{Command, ViewerState};
use bumpview::tangent::{MethodMeasurement, TangentMethod};
use bumpview::texture::MipFilter;

use crate::app::action::Action;
use crate::app::controller::Controller;

/// The tangent method, bump source and brick-map kernel, and the chosen method measured on
/// each mesh.
pub(super) fn methods(
    ui: &mut egui::Ui,
    state: &ViewerState,
    measurements: &[(String, MethodMeasurement)],
    actions: &mut Vec<Action>,
) {
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
    mip_filter(ui, state, actions);
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

/// The normal maps' mip filter (every material) and the camera's distance beside it, to
/// minify the surface and watch the highlight sparkle or hold.
fn mip_filter(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let mut filter = state.scene_options.mip_filter;
    egui::ComboBox::from_label("normal-map mips").selected_text(filter.name()).show_ui(ui, |ui| {
        for &choice in MipFilter::all() {
            ui.selectable_value(&mut filter, choice, choice.name());
        }
    });
    if filter != state.scene_options.mip_filter {
        actions.push(Command::SetMipFilter(filter).into());
    }
    let camera = state.camera;
    let mut distance = camera.distance;
    let slider = egui::Slider::new(&mut distance, MIN_DISTANCE..=MAX_DISTANCE).logarithmic(true);
    if ui.add(slider.text("camera distance (m)")).changed() {
        actions.push(Command::PointCamera { yaw: camera.yaw, pitch: camera.pitch, distance }.into());
    }
}

/// Normal-map and height-map conventions for every material or one of them, what each
/// material is drawn with, and the shading model.
pub(super) fn conventions(ui: &mut egui::Ui, state: &ViewerState, materials: &[Material], actions: &mut Vec<Action>) {
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
    let layout_name = |l: Option<NormalLayout>| l.map_or(unset, NormalLayout::label);
    egui::ComboBox::from_label("normal map layout").selected_text(layout_name(new.layout)).show_ui(ui, |ui| {
        for choice in std::iter::once(None).chain(NormalLayout::all().iter().copied().map(Some)) {
            ui.selectable_value(&mut new.layout, choice, layout_name(choice));
        }
    });
    for (flag, base, label) in [
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
    // The all-materials method is the methods section's "normal-map mips".
    if target.is_some() {
        let mip_name = |m: Option<MipFilter>| m.map_or("as all materials", MipFilter::name);
        egui::ComboBox::from_label("normal-map mips").selected_text(mip_name(new.mip_filter)).show_ui(ui, |ui| {
            for choice in std::iter::once(None).chain(MipFilter::all().iter().copied().map(Some)) {
                ui.selectable_value(&mut new.mip_filter, choice, mip_name(choice));
            }
        });
    }
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
    conventions_in_use(ui, options, materials);
    shading_model(ui, state, actions);
    super::detail::detail(ui, state, materials.iter().any(|m| m.detail_map.is_some()), actions);
}

/// What each material is drawn with (after overrides), `*` marking its own settings.
fn conventions_in_use(ui: &mut egui::Ui, options: &SceneOptions, materials: &[Material]) {
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
}

/// The shading model for every material: the material's own (auto) or one for all.
fn shading_model(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
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

/// The findings of `bumpview check` for the scene, how its textures went to the GPU, the
/// renderer's notices, and a button for the view that highlights degenerate and mirrored
/// triangles.
pub(super) fn check(ui: &mut egui::Ui, controller: &Controller, actions: &mut Vec<Action>) {
    let (meshes, maps, warnings) = match controller.facts() {
        Some(facts) => (&facts.check.meshes[..], &facts.check.normal_maps[..], &facts.check_warnings[..]),
        None => (&[][..], &[][..], &[][..]),
    };
    for mesh in meshes {
        ui.small(format!(
            "{}: {} triangles, {} degenerate-UV, {} mirrored, {} UV-seam positions",
            mesh.name, mesh.triangles, mesh.degenerate_uv, mesh.mirrored, mesh.seam_positions
        ));
    }
    for map in maps {
        ui.small(format!("{}: green {}", map.material, map.findings.green_text()));
    }
    for upload in controller.renderer().texture_uploads(false) {
        let name = std::path::Path::new(&upload.name).file_name().and_then(|n| n.to_str()).unwrap_or(&upload.name);
        ui.small(format!("{name}: {} on the GPU, {:.1} KiB", upload.form, upload.bytes as f64 / 1024.0));
    }
    let warn = ui.visuals().warn_fg_color;
    for line in warnings.iter().chain(&controller.renderer().notices()) {
        ui.colored_label(warn, egui::RichText::new(line).small());
    }
    if ui.button("Highlight degenerate / mirrored UVs").clicked() {
        actions.push(Command::SetView(ViewMode::UvCheck).into());
    }
}
