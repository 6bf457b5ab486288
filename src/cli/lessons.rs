//! `bumpview lessons` lists the course; `bumpview slides` draws it as slide PNGs, one PDF and
//! an index ([`bumpview::lessons`]).

use std::path::{Path, PathBuf};

use bumpview::atomic::{check_outputs, write_bytes_atomically};
use bumpview::lessons::deck::{DeckEntry, index_markdown, slide_file};
use bumpview::lessons::deck_html::{WEB_FOLDER, deck_html};
use bumpview::lessons::files::load_dir;
use bumpview::lessons::measure::{SceneCache, measure};
use bumpview::lessons::pdf::{PdfPage, slides_pdf};
use bumpview::lessons::slide::{SlideLayout, SlideTheme};
use bumpview::lessons::{self, Lesson};
use bumpview::read::{FileKind, read_file};
use bumpview::render::capture::write_png_atomically;
use bumpview::render::{Gpu, Renderer};

use super::Failure;
use super::args;

/// The smallest and largest slides: below 480x270 the caption's text gets too small to read;
/// above 7680x4320 (8K) a deck of 31 slides takes minutes on a software adapter.
const MIN_SIZE: [u32; 2] = [480, 270];
const MAX_SIZE: [u32; 2] = [7680, 4320];

#[derive(clap::Args)]
pub struct SlidesArgs {
    /// The folder to write into (made if missing): NN-NAME.png per slide, slides.pdf, index.md.
    #[arg(long)]
    out: PathBuf,
    /// Slide size in pixels (16:9 suits the layout), 480x270 to 7680x4320; the default is the
    /// size the viewer's lesson card measures its number at.
    #[arg(long, value_parser = args::parse_size, default_value = "1920x1080")]
    size: [u32; 2],
    /// Only these built-in lessons, in this order (names as `bumpview lessons` lists them).
    /// Without it, every built-in lesson unless --lesson or --lessons-dir names others.
    #[arg(long, value_name = "NAME,…", value_delimiter = ',')]
    lessons: Vec<String>,
    /// A lesson file of your own (repeatable), drawn after the built-in lessons chosen; its
    /// model and texture paths are relative to the file.
    #[arg(long = "lesson", value_name = "FILE")]
    lesson_files: Vec<PathBuf>,
    /// Every lesson file (*.toml) in this folder, in the order of their names.
    #[arg(long, value_name = "DIR")]
    lessons_dir: Option<PathBuf>,
    /// The slides' colours: dark (a darkened room) or light (a lit one).
    #[arg(long, value_parser = args::named::<SlideTheme>(), default_value = "dark")]
    theme: SlideTheme,
    /// Also write index.html, a page of the slides where each built-in lesson's slide opens
    /// it live in the web build, copied into DIR/web (serve DIR as it is).
    #[arg(long)]
    html: bool,
    /// The web build `--html` copies (what scripts/build-web.sh makes).
    #[arg(long, value_name = "DIR", default_value = "web/dist", requires = "html")]
    web_build: PathBuf,
    /// Replace files that exist; without it an existing output is kept and nothing is drawn.
    #[arg(long)]
    force: bool,
}

/// `bumpview lessons`: one line per lesson, its name, title and caption's first sentence.
pub fn list() -> Result<(), Failure> {
    let all = lessons::catalogue().map_err(|e| Failure::Failed(e.to_string()))?;
    let width = all.iter().map(|l| l.name.len()).max().unwrap_or(0);
    for lesson in &all {
        println!("{:<width$}  {} — {}", lesson.name, lesson.title, first_sentence(&lesson.caption));
    }
    Ok(())
}

/// The caption's first sentence (up to the first `. ` or the end).
fn first_sentence(caption: &str) -> &str {
    caption.find(". ").map_or(caption, |end| &caption[..=end])
}

/// `bumpview slides`: each lesson drawn and measured at its slide's picture size, composed,
/// written as a PNG, then the PDF and the index; every output checked before any work.
pub fn slides(args: &SlidesArgs) -> Result<(), Failure> {
    let [w, h] = args.size;
    if w < MIN_SIZE[0] || h < MIN_SIZE[1] || w > MAX_SIZE[0] || h > MAX_SIZE[1] {
        let range = format!("{}x{} to {}x{}", MIN_SIZE[0], MIN_SIZE[1], MAX_SIZE[0], MAX_SIZE[1]);
        return Err(Failure::BadArguments(format!("--size {w}x{h}: slides are {range} pixels")));
    }
    let chosen = chosen(args)?;
    let web_files = if args.html { web_build_files(&args.web_build)? } else { vec![] };
    let mut outputs = outputs(&args.out, &chosen);
    if args.html {
        outputs.push(args.out.join("index.html"));
        outputs.extend(web_files.iter().map(|(name, _)| args.out.join(WEB_FOLDER).join(name)));
    }
    let paths: Vec<&Path> = outputs.iter().map(PathBuf::as_path).collect();
    let inputs = lesson_inputs(&chosen, &args.lesson_files);
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    check_outputs(&inputs, &paths, args.force).map_err(|e| Failure::BadArguments(e.to_string()))?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| Failure::Failed(format!("could not make {}: {e}", args.out.display())))?;
    let started = std::time::Instant::now();
    // A renderer keeps every pipeline it built, and lavapipe the code it compiled for each
    // until the pipeline goes: a fresh renderer every few lessons bounds the deck's memory.
    const RENDERER_LESSONS: usize = 6;
    let gpu = Gpu::headless()?;
    let mut renderer = Renderer::from_gpu(&gpu);
    let mut scenes = SceneCache::default();
    let layout = SlideLayout::new(args.size).with_theme(args.theme);
    let (mut entries, mut pages) = (vec![], vec![]);
    for (i, lesson) in chosen.iter().enumerate() {
        if i % RENDERER_LESSONS == 0 && i > 0 {
            renderer = Renderer::from_gpu(&gpu);
            scenes.renderer_replaced();
        }
        let size = layout.picture_size(lesson);
        let measured =
            measure(&mut renderer, &mut scenes, lesson, size, true).map_err(|e| Failure::Failed(e.to_string()))?;
        let slide = layout.compose(lesson, &measured, i + 1, chosen.len());
        let file = slide_file(i + 1, lesson);
        write_png_atomically(&slide, &args.out.join(&file))?;
        println!("{file}: {}", lesson.claim_with(measured.changed_percent));
        pages.push(PdfPage::new(&slide, &lesson.title, &lesson.caption));
        entries.push(DeckEntry { file, lesson: lesson.clone(), changed_percent: measured.changed_percent });
        scenes.keep_only(&chosen[i + 1..]);
    }
    let write = |name: &str, bytes: &[u8]| {
        let path = args.out.join(name);
        write_bytes_atomically(&path, bytes)
            .map_err(|e| Failure::Failed(format!("could not write {}: {e}", path.display())))
    };
    write("slides.pdf", &slides_pdf(&pages))?;
    write("index.md", index_markdown(&entries, args.size).as_bytes())?;
    if args.html {
        let built_in = lessons::catalogue().map_err(|e| Failure::Failed(e.to_string()))?;
        write("index.html", deck_html(&entries, |lesson| built_in.contains(lesson)).as_bytes())?;
        copy_web_build(&web_files, &args.out.join(WEB_FOLDER))?;
    }
    println!(
        "wrote {} slides, slides.pdf, index.md{} to {} in {:.1} s ({})",
        entries.len(),
        if args.html { ", index.html and the web build" } else { "" },
        args.out.display(),
        started.elapsed().as_secs_f32(),
        gpu.adapter_name()
    );
    Ok(())
}

/// The files of the web build in `folder` (name and path; its top level, where
/// scripts/build-web.sh puts the page, its script and its wasm), which must hold the page.
fn web_build_files(folder: &Path) -> Result<Vec<(String, PathBuf)>, Failure> {
    let missing = || {
        Failure::BadArguments(format!(
            "--html copies the web build, and {} holds none (index.html): make it with scripts/build-web.sh, \
             or name it with --web-build DIR",
            folder.display()
        ))
    };
    let entries = std::fs::read_dir(folder).map_err(|_| missing())?;
    let mut files: Vec<(String, PathBuf)> = entries
        .filter_map(Result::ok)
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .map(|e| (e.file_name().to_string_lossy().into_owned(), e.path()))
        .collect();
    files.sort();
    if !files.iter().any(|(name, _)| name == "index.html") {
        return Err(missing());
    }
    Ok(files)
}

/// Copies the web build's `files` into `folder` (made if missing), each written atomically.
fn copy_web_build(files: &[(String, PathBuf)], folder: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(folder)
        .map_err(|e| Failure::Failed(format!("could not make {}: {e}", folder.display())))?;
    for (name, path) in files {
        let bytes = read_file(path, FileKind::WebBuild)
            .map_err(|e| Failure::Failed(format!("could not read {}: {e}", path.display())))?;
        let to = folder.join(name);
        write_bytes_atomically(&to, &bytes)
            .map_err(|e| Failure::Failed(format!("could not write {}: {e}", to.display())))?;
    }
    Ok(())
}

/// The lessons to draw: the built-in ones named (all of them when neither names nor files are
/// given), then the lesson files given one by one, then those of the folder.
fn chosen(args: &SlidesArgs) -> Result<Vec<Lesson>, Failure> {
    let own_files = !args.lesson_files.is_empty() || args.lessons_dir.is_some();
    let mut chosen = if own_files && args.lessons.is_empty() {
        vec![]
    } else {
        lessons::select(&args.lessons).map_err(|e| Failure::BadArguments(e.to_string()))?
    };
    for path in &args.lesson_files {
        chosen.push(Lesson::load(path).map_err(|e| Failure::Failed(e.to_string()))?);
    }
    if let Some(folder) = &args.lessons_dir {
        chosen.extend(load_dir(folder).map_err(|e| Failure::Failed(e.to_string()))?);
    }
    Ok(chosen)
}

/// Every file the chosen lessons read (lesson files and the models and textures they name),
/// which no output may replace.
fn lesson_inputs(chosen: &[Lesson], lesson_files: &[PathBuf]) -> Vec<PathBuf> {
    let named = chosen.iter().flat_map(|l| l.sides.iter()).flat_map(|side| side.preset.files.paths());
    lesson_files.iter().cloned().chain(named.map(Path::to_path_buf)).collect()
}

/// Every file `slides` writes into `out` for `chosen`.
fn outputs(out: &Path, chosen: &[Lesson]) -> Vec<PathBuf> {
    let slides = chosen.iter().enumerate().map(|(i, l)| out.join(slide_file(i + 1, l)));
    slides.chain(["slides.pdf", "index.md"].map(|name| out.join(name))).collect()
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    /// `slides` without `--size` draws the slides the viewer's card measures its number on.
    #[test]
    fn the_default_slide_size_is_the_one_the_card_measures_at() {
        #[derive(Parser)]
        struct Slides {
            #[command(flatten)]
            args: super::SlidesArgs,
        }
        let parsed = Slides::parse_from(["slides", "--out", "deck"]);
        assert_eq!(parsed.args.size, bumpview::lessons::slide::DEFAULT_SLIDE_SIZE);
    }
}
