//! Every lesson shows its point: the sides of its comparison, drawn as `bumpview render` draws
//! them (at 320x180 to keep the test short), differ in at least 5 % of the pixels by at least
//! 4/255, or in at least the share the lesson file holds with its reason.

use std::path::Path;

use bumpview::lessons::measure::{SceneCache, changed_percent, measure};
use bumpview::lessons::{Lesson, MIN_CHANGED_PERCENT, catalogue, names};
use bumpview::render::{Gpu, Renderer};

/// The test's picture size: 16:9 like a slide, small enough for a debug build on two cores.
const SIZE: [u32; 2] = [320, 180];

fn folder() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/lessons")
}

/// The catalogue; with `LESSONS_FROM_DISK` set, the files in assets/lessons as they are now
/// (to try a lesson without rebuilding the library), in the catalogue's order, new ones last.
fn lessons() -> Vec<Lesson> {
    if std::env::var_os("LESSONS_FROM_DISK").is_none() {
        return catalogue().unwrap_or_else(|e| panic!("{e}"));
    }
    let mut files: Vec<String> = std::fs::read_dir(folder())
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().to_str()?.strip_suffix(".toml").map(str::to_owned))
        .collect();
    let order = names();
    files.sort_by_key(|n| (order.iter().position(|o| o == n).unwrap_or(usize::MAX), n.clone()));
    let only = std::env::var("LESSONS_ONLY").unwrap_or_default();
    files
        .into_iter()
        .filter(|n| only.is_empty() || only.split(',').any(|o| o == n))
        .map(|name| {
            let text = std::fs::read_to_string(folder().join(format!("{name}.toml"))).unwrap();
            Lesson::parse(Box::leak(name.into_boxed_str()), &text).unwrap_or_else(|e| panic!("{e}"))
        })
        .collect()
}

#[test]
fn every_lesson_shows_its_point() {
    let lessons = lessons();
    let gpu = Gpu::headless().expect("an adapter (lavapipe in CI)");
    let mut renderer = Renderer::from_gpu(&gpu);
    let mut scenes = SceneCache::default();
    let mut failed = vec![];
    for lesson in &lessons {
        let started = std::time::Instant::now();
        let measured = measure(&mut renderer, &mut scenes, lesson, SIZE, false).unwrap_or_else(|e| panic!("{e}"));
        let changed = measured.changed_percent;
        println!(
            "{:<28} {changed:6.2} % changed (holds {:.1} %), {} sides, {:.1} s",
            lesson.name,
            lesson.min_changed,
            lesson.sides.len(),
            started.elapsed().as_secs_f32()
        );
        if measured.sides.len() > 2 {
            let pairs: Vec<String> =
                measured.sides.windows(2).map(|p| format!("{:.2}", changed_percent(&p[0], &p[1]))).collect();
            println!("    neighbours: {}", pairs.join(", "));
        }
        if std::env::var_os("LESSON_PNGS").is_some() {
            for (i, side) in measured.sides.iter().enumerate() {
                side.save(format!("/tmp/lesson-{}-{i}.png", lesson.name)).unwrap();
            }
        }
        if changed < lesson.min_changed {
            failed.push(format!("{}: {changed:.2} % < {:.1} %", lesson.name, lesson.min_changed));
        }
    }
    assert!(failed.is_empty(), "lessons whose point does not show:\n{}", failed.join("\n"));
}

/// At least 25 lessons, every file in assets/lessons among them, and a lesson that shows fewer
/// than 5 % says why.
#[test]
fn the_course_is_complete_and_every_exception_explains_itself() {
    let lessons = catalogue().unwrap_or_else(|e| panic!("{e}"));
    assert!(lessons.len() >= 25, "{} lessons", lessons.len());
    for file in std::fs::read_dir(folder()).unwrap() {
        let name = file.unwrap().file_name().to_string_lossy().into_owned();
        let name = name.strip_suffix(".toml").unwrap_or_else(|| panic!("{name}: not a lesson file"));
        assert!(names().contains(&name), "{name}.toml is not in the catalogue's list");
    }
    for lesson in &lessons {
        assert_eq!(lesson.min_changed < MIN_CHANGED_PERCENT, lesson.why_fewer.is_some(), "{}", lesson.name);
    }
}

/// `bumpview slides` writes a PNG per lesson, a PDF whose every page poppler's `pdftoppm`
/// renders, whose embedded images (`pdfimages`) are the slides exactly and whose titles and
/// captions `pdftotext` reads, an index, and keeps existing files without `--force`.
#[test]
fn slides_make_pngs_a_pdf_that_renders_and_an_index() {
    let dir = std::env::temp_dir().join(format!("bumpview-slides-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let slides = |force: bool| {
        let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_bumpview"));
        command.args(["slides", "--out"]).arg(&dir).args(["--size", "480x270", "--lessons", "emboss,cg-wall"]);
        if force {
            command.arg("--force");
        }
        command.output().unwrap()
    };
    let output = slides(false);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    for file in ["01-emboss.png", "02-cg-wall.png"] {
        assert_eq!(image::image_dimensions(dir.join(file)).unwrap(), (480, 270), "{file}");
    }
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    assert!(index.contains("(01-emboss.png)") && index.contains("(02-cg-wall.png)"), "{index}");
    // Every page renders: 960 pt at 36 dpi is 480 pixels, the slide's size.
    let poppler = |tool: &str, args: &[&str], prefix: &str| {
        let output = std::process::Command::new(tool)
            .args(args)
            .arg(dir.join("slides.pdf"))
            .arg(dir.join(prefix))
            .output()
            .unwrap_or_else(|e| panic!("{tool} (apt-get install poppler-utils): {e}"));
        assert!(output.status.success(), "{tool}: {}", String::from_utf8_lossy(&output.stderr));
    };
    poppler("pdftoppm", &["-png", "-r", "36"], "page");
    // The images the pages embed are the slides, pixel for pixel (poppler's rendering resamples).
    poppler("pdfimages", &["-png"], "embedded");
    for (page, embedded, slide) in
        [("page-1.png", "embedded-000.png", "01-emboss.png"), ("page-2.png", "embedded-001.png", "02-cg-wall.png")]
    {
        let slide = image::open(dir.join(slide)).unwrap().to_rgb8();
        assert_eq!(image::image_dimensions(dir.join(page)).unwrap(), slide.dimensions(), "{page}");
        let embedded = image::open(dir.join(embedded)).unwrap().to_rgb8();
        assert!(embedded == slide, "{page}: the embedded image is the slide, pixel for pixel");
    }
    // The titles and captions are text a reader finds and copies (poppler's pdftotext).
    poppler("pdftotext", &[], "slides.txt");
    let text = std::fs::read_to_string(dir.join("slides.txt")).unwrap();
    let all = bumpview::lessons::catalogue().unwrap();
    let cg_wall = all.iter().find(|l| l.name == "cg-wall").unwrap();
    assert!(text.contains(&cg_wall.title), "{text}");
    let first_words: String = cg_wall.caption.split_whitespace().take(6).collect::<Vec<_>>().join(" ");
    assert!(text.split_whitespace().collect::<Vec<_>>().join(" ").contains(&first_words), "{text}");
    let again = slides(false);
    assert_eq!(again.status.code(), Some(2), "an existing output is kept without --force");
    assert!(slides(true).status.success());
    let _ = std::fs::remove_dir_all(&dir);
}
