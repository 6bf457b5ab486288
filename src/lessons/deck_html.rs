//! The deck as a web page (`bumpview slides --html`): every slide's PNG with its title and
//! measured claim, each built-in lesson's slide a link that opens it live in the web build
//! copied beside the page (`web/index.html#lesson=NAME`), so the deck's folder can be served as
//! it is. A lesson file of the lecturer's own has no such link: the web build opens the
//! built-in course only.

use super::Lesson;
use super::deck::DeckEntry;

/// Where the web build is copied, relative to the page.
pub const WEB_FOLDER: &str = "web";

/// The page (HTML5, no scripts of its own) for the slides of `entries`; `built_in` tells
/// whether a lesson is one the web build knows.
pub fn deck_html(entries: &[DeckEntry], built_in: impl Fn(&Lesson) -> bool) -> String {
    let mut page = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>bumpview lessons</title>\n<style>\n\
         body { background: #181a1e; color: #e8e8e8; font-family: sans-serif; margin: 2em auto; max-width: 1000px; }\n\
         figure { margin: 0 0 2.5em; } img { width: 100%; display: block; }\n\
         figcaption { margin-top: 0.5em; } a { color: #8cc8ff; } .claim { color: #ffc66d; }\n\
         </style>\n</head>\n<body>\n<h1>bumpview lessons</h1>\n\
         <p>Each slide opens its lesson live in the viewer (the web build beside this page). \
         All slides: <a href=\"slides.pdf\">slides.pdf</a>.</p>\n",
    );
    for (i, entry) in entries.iter().enumerate() {
        let lesson = &entry.lesson;
        let title = escape(&lesson.title);
        let image = format!("<img src=\"{}\" alt=\"{title}\">", escape(&entry.file));
        let (picture, live) = if built_in(lesson) {
            let href = format!("{WEB_FOLDER}/index.html#lesson={}", escape(&lesson.name));
            (format!("<a href=\"{href}\">{image}</a>"), format!(" · <a href=\"{href}\">open it live</a>"))
        } else {
            (image, " · a lesson file of your own: the web build opens the built-in lessons only".to_owned())
        };
        let claim = escape(&lesson.claim_with(entry.changed_percent));
        page.push_str(&format!(
            "<figure id=\"{name}\">\n{picture}\n<figcaption>{number}. <strong>{title}</strong>{live}<br>\
             <span class=\"claim\">{claim}</span></figcaption>\n</figure>\n",
            name = escape(&lesson.name),
            number = i + 1,
        ));
    }
    page.push_str("</body>\n</html>\n");
    page
}

/// `text` with HTML's special characters escaped, for text and attribute values.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;").replace('\'', "&#39;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lessons::catalogue;

    #[test]
    fn built_in_slides_link_their_lesson_live_and_an_own_lesson_says_why_not() {
        let all = catalogue().unwrap();
        let mut own = all[0].clone();
        own.name = "my-wall".into();
        own.title = "Mine: <wall> & \"bricks\"".into();
        let entries = [
            DeckEntry { file: "01-cg-wall.png".into(), lesson: all[0].clone(), changed_percent: 12.5 },
            DeckEntry { file: "02-my-wall.png".into(), lesson: own, changed_percent: 3.0 },
        ];
        let page = deck_html(&entries, |lesson| all.contains(lesson));
        let link = format!("href=\"web/index.html#lesson={}\"", all[0].name);
        assert_eq!(page.matches(&link).count(), 2, "the picture and the words link it: {page}");
        assert!(page.contains(&all[0].claim_with(12.5).replace('\'', "&#39;")));
        assert!(!page.contains("#lesson=my-wall") && page.contains("the web build opens the built-in lessons only"));
        assert!(page.contains("Mine: &lt;wall&gt; &amp; &quot;bricks&quot;") && !page.contains("<wall>"));
    }
}
