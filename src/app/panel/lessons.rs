//! The Lessons section: the course in order, the previous and next lesson (Page Up / Page
//! Down do the same), the caption card's switch and "Save as lesson".

use crate::app::action::Action;
use crate::app::controller::LessonsForm;

pub fn show(ui: &mut egui::Ui, lessons: &mut LessonsForm, actions: &mut Vec<Action>) {
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
    save_as_lesson(ui, lessons, actions);
}

/// "Save as lesson": the split view as it is now, with a title, a caption and a claim, written
/// as a lesson file (bumpview slides --lesson FILE draws it) and opened as a lesson.
fn save_as_lesson(ui: &mut egui::Ui, lessons: &mut LessonsForm, actions: &mut Vec<Action>) {
    egui::CollapsingHeader::new("Save as lesson…").id_salt("save as lesson").show(ui, |ui| {
        let (words, path) = (&mut lessons.draft, &mut lessons.draft_path);
        ui.weak("the split view as it is now: its two halves are the lesson's sides");
        ui.add(egui::TextEdit::singleline(&mut words.title).hint_text("title"));
        ui.add(
            egui::TextEdit::multiline(&mut words.caption)
                .hint_text("caption: what to look at, and its source")
                .desired_rows(2),
        );
        ui.add(egui::TextEdit::singleline(&mut words.claim).hint_text("claim, with {changed} for the measured share"))
            .on_hover_text(
                "{changed} becomes the share of the picture where the sides differ, measured as the slides measure it",
            );
        ui.add(egui::TextEdit::singleline(path).hint_text("lecture/my-lesson.toml"));
        let named = !path.trim().is_empty();
        if ui.add_enabled(named, egui::Button::new("Save as lesson")).clicked() {
            actions.push(Action::SaveLesson { path: path.trim().into(), words: words.clone() });
        }
        match &lessons.draft_message {
            Some(Ok(done)) => ui.label(done),
            Some(Err(why)) => ui.colored_label(ui.visuals().error_fg_color, why),
            None => ui.weak("paths in it are relative to the lesson file"),
        };
    });
}
