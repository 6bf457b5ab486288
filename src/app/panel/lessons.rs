//! The Lessons section: the course in order, the previous and next lesson (Page Up / Page
//! Down do the same) and the caption card's switch.

use crate::app::action::Action;
use crate::app::controller::LessonsForm;

pub fn show(ui: &mut egui::Ui, lessons: &LessonsForm, actions: &mut Vec<Action>) {
    if let Some(error) = &lessons.error {
        ui.colored_label(ui.visuals().error_fg_color, error);
        return;
    }
    let shown = lessons.lesson().map_or("choose a lesson…", |l| l.title.as_str());
    egui::ComboBox::from_id_salt("lesson").width(ui.available_width()).selected_text(shown).show_ui(ui, |ui| {
        for (i, lesson) in lessons.catalogue.iter().enumerate() {
            let label = format!("{:>2}. {}", i + 1, lesson.title);
            if ui.selectable_label(lessons.current == Some(i), label).clicked() {
                actions.push(Action::OpenLesson(i));
            }
        }
    });
    ui.horizontal(|ui| {
        let first = lessons.current.is_none_or(|i| i == 0);
        if ui.add_enabled(!first, egui::Button::new("Previous")).on_hover_text("Page Up").clicked() {
            actions.push(Action::StepLesson(-1));
        }
        let last = lessons.current.is_some_and(|i| i + 1 >= lessons.catalogue.len());
        if ui.add_enabled(!last, egui::Button::new("Next")).on_hover_text("Page Down").clicked() {
            actions.push(Action::StepLesson(1));
        }
        let mut card = lessons.card;
        if ui.add_enabled(lessons.current.is_some(), egui::Checkbox::new(&mut card, "caption card")).changed() {
            actions.push(Action::ShowLessonCard(card));
        }
    });
    ui.horizontal(|ui| {
        if ui.button("Present").on_hover_text("hide this panel (H) and go full-screen (F11)").clicked() {
            actions.extend([Action::TogglePanel, Action::ToggleFullscreen]);
        }
        ui.weak("H hides the panel, F11 full-screen");
    });
}
