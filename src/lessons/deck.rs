//! A deck of slides: the file names of its slides and its index page.

use super::Lesson;

/// One slide written: its file, its lesson and the share of changed pixels measured for it.
pub struct DeckEntry {
    pub file: String,
    pub lesson: Lesson,
    pub changed_percent: f32,
}

/// The PNG of slide `number` (from 1): `NN-NAME.png`, so the files sort in the course's order.
pub fn slide_file(number: usize, lesson: &Lesson) -> String {
    format!("{number:02}-{}.png", lesson.name)
}

/// The deck's index (Markdown): the PDF, then one row per slide with its title, the lesson's
/// name and the number measured in this run.
pub fn index_markdown(entries: &[DeckEntry], size: [u32; 2]) -> String {
    let mut text = format!(
        "# bumpview lessons\n\n{} slides of {}x{} pixels; all of them in [slides.pdf](slides.pdf). \
         Each number is the share of the picture's pixels in which the two sides of the comparison \
         differ by at least 4/255, measured when the slides were drawn.\n\n\
         | # | slide | lesson | measured |\n|---|---|---|---|\n",
        entries.len(),
        size[0],
        size[1]
    );
    for (i, entry) in entries.iter().enumerate() {
        let title = entry.lesson.title.replace('|', "\\|");
        text.push_str(&format!(
            "| {} | [{title}]({}) | `{}` | {} |\n",
            i + 1,
            entry.file,
            entry.lesson.name,
            entry.lesson.claim_with(entry.changed_percent).replace('|', "\\|")
        ));
    }
    text
}
