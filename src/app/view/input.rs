//! Keyboard shortcuts and mouse gestures on the 3D view (P + click pins the probe), turned
//! into [`Action`]s.

use bumpview::frame::ShadingMode;
use bumpview::state::Command;
use egui::{Event, Key, PointerButton};
use glam::Vec2;

use crate::app::action::Action;

/// Camera rotation per pixel dragged, radians.
const ORBIT_RADIANS_PER_PIXEL: f32 = 0.01;
/// Zoom per point scrolled: the distance is multiplied by `exp(-scroll · ZOOM_PER_POINT)`.
const ZOOM_PER_POINT: f32 = 0.002;
/// Strength change per `[` or `]` press.
const STRENGTH_STEP: f32 = 0.1;

/// The shortcuts pressed this frame: B bump, `[`/`]` strength, 1/2/3 bump × colour, bump
/// only, colour only, W wireframe, G T/B/N glyphs, S split view, L light orbit, V view, R camera reset, F12 screenshot,
/// Page Down / Page Up the next / previous lesson, H the panel, F11 full-screen. None while a
/// text field has keyboard focus.
pub fn keyboard(ctx: &egui::Context) -> Vec<Action> {
    if ctx.text_edit_focused() {
        return Vec::new();
    }
    let keys: Vec<(Key, bool)> = ctx.input(|i| {
        i.events
            .iter()
            .filter_map(|event| match event {
                Event::Key { key, pressed: true, repeat, modifiers, .. }
                    if !(modifiers.ctrl || modifiers.alt || modifiers.command) =>
                {
                    Some((*key, *repeat))
                }
                _ => None,
            })
            .collect()
    });
    keys.into_iter().filter_map(|(key, repeat)| key_action(key, repeat)).collect()
}

/// The action of one key press. Toggles ignore auto-repeat; the strength keys repeat.
fn key_action(key: Key, repeat: bool) -> Option<Action> {
    let command = match key {
        Key::OpenBracket => Command::StepStrength(-STRENGTH_STEP),
        Key::CloseBracket => Command::StepStrength(STRENGTH_STEP),
        _ if repeat => return None,
        Key::B => Command::ToggleBump,
        Key::L => Command::ToggleLightOrbit,
        Key::V => Command::CycleView,
        Key::R => Command::ResetCamera,
        Key::Num1 => Command::SetShadingMode(ShadingMode::BumpTimesColour),
        Key::Num2 => Command::SetShadingMode(ShadingMode::BumpOnly),
        Key::Num3 => Command::SetShadingMode(ShadingMode::ColourOnly),
        Key::W => Command::ToggleWireframe,
        Key::G => Command::ToggleGlyphs,
        Key::S => Command::ToggleSplit,
        Key::F12 => return Some(Action::Screenshot),
        Key::F11 => return Some(Action::ToggleFullscreen),
        Key::H => return Some(Action::TogglePanel),
        Key::PageDown => return Some(Action::StepLesson(1)),
        Key::PageUp => return Some(Action::StepLesson(-1)),
        _ => return None,
    };
    Some(command.into())
}

/// Mouse gestures on the 3D view, whose texture is `size` pixels: left-drag orbits the
/// camera, Ctrl-drag moves the light, Shift-drag or middle-drag pans, the wheel zooms.
pub(super) fn viewport(response: &egui::Response, ctx: &egui::Context, size: [u32; 2]) -> Vec<Action> {
    let mut actions = Vec::new();
    let delta = response.drag_delta() * ctx.pixels_per_point();
    if delta != egui::Vec2::ZERO {
        actions.extend(drag_action(response, ctx.input(|i| i.modifiers), Vec2::new(delta.x, delta.y), size[1] as f32));
    }
    let scroll = ctx.input(|i| i.smooth_scroll_delta.y);
    if response.contains_pointer() && scroll != 0.0 {
        actions.push(Command::Zoom((-scroll * ZOOM_PER_POINT).exp()).into());
    }
    actions
}

/// The command for a drag of `pixels` in a view `viewport_height` pixels tall.
fn drag_action(
    response: &egui::Response,
    modifiers: egui::Modifiers,
    pixels: Vec2,
    viewport_height: f32,
) -> Option<Action> {
    let primary = response.dragged_by(PointerButton::Primary);
    let command = if response.dragged_by(PointerButton::Middle) || (primary && modifiers.shift) {
        Command::PanCamera { pixels, viewport_height }
    } else if primary && (modifiers.ctrl || modifiers.command) {
        Command::DragLight { pixels, viewport_height }
    } else if primary {
        // The scene follows the pointer: drag right turns it right, drag down tips it forward.
        Command::OrbitCamera { d_yaw: -pixels.x * ORBIT_RADIANS_PER_PIXEL, d_pitch: pixels.y * ORBIT_RADIANS_PER_PIXEL }
    } else {
        return None;
    };
    Some(command.into())
}

/// Whether P is held and the primary button was clicked on the view: the clicked pixel of a
/// `size` view shown in `rect`, as the action that pins the probe there.
pub(super) fn probe_click(ctx: &egui::Context, rect: egui::Rect, size: [u32; 2]) -> Option<Action> {
    if ctx.text_edit_focused() {
        return None;
    }
    let position =
        ctx.input(|i| (i.key_down(Key::P) && i.pointer.primary_clicked()).then(|| i.pointer.interact_pos()).flatten())?;
    if !rect.contains(position) {
        return None;
    }
    let scale = size[0] as f32 / rect.width();
    let local = (position - rect.min) * scale;
    let pixel = [(local.x.max(0.0) as u32).min(size[0] - 1), (local.y.max(0.0) as u32).min(size[1] - 1)];
    Some(Action::PinProbe { pixel, size })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What presenter remotes send: Page Down the next lesson, Page Up the previous one; a held
    /// key does not skip through the course.
    #[test]
    fn page_keys_step_through_the_lessons() {
        assert_eq!(key_action(Key::PageDown, false), Some(Action::StepLesson(1)));
        assert_eq!(key_action(Key::PageUp, false), Some(Action::StepLesson(-1)));
        assert_eq!(key_action(Key::PageDown, true), None);
    }

    /// Presenting: F11 full-screen, H hides the panel; a held key toggles once.
    #[test]
    fn presenting_keys_toggle_full_screen_and_the_panel() {
        assert_eq!(key_action(Key::F11, false), Some(Action::ToggleFullscreen));
        assert_eq!(key_action(Key::H, false), Some(Action::TogglePanel));
        assert_eq!(key_action(Key::F11, true), None);
    }
}
