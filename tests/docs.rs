//! The README and the `docs/` pages hold: every relative link and image points at a file that
//! exists (and a `#section` at one of its headings), and every command in a code block runs.
//!
//! Commands are the lines of fenced code blocks that start with `bumpview ` (or `$ bumpview `,
//! or `cargo run --release -- `), continued over `\` line ends; a line holding `[`, `…` or `|`
//! is a synopsis and is not run. Each runs in a fresh folder holding the files the pages name
//! (`model.glb`, `model.gltf`, `other.obj`, `height.png`, made here or copied from
//! `tests/fixtures`), as written,
//! except that pictures are drawn small (`--size 96x54` where no size is given; slides
//! `--size 480x270`, two lessons where none are named), the viewer
//! closes after a few frames under Xvfb (`--exit-after 3`) and the report runs `--quick`. A
//! `$ ` command followed by output lines must print lines of the same shape on stdout (numbers
//! may differ). `cargo bench --bench NAME` and `cargo test --test NAME` name existing targets.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every page under docs/, with their text.
fn pages() -> Vec<(PathBuf, String)> {
    let mut paths = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    paths.extend(docs);
    paths.into_iter().map(|p| (p.clone(), std::fs::read_to_string(&p).unwrap())).collect()
}

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces as hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn headings(text: &str) -> Vec<String> {
    let mut in_code = false;
    let mut found = vec![];
    for line in text.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
        } else if !in_code && line.starts_with('#') {
            found.push(anchor(line.trim_start_matches('#')));
        }
    }
    found
}

/// The targets of every `[text](target)` and `![alt](target)` outside code blocks.
fn links(text: &str) -> Vec<String> {
    let mut in_code = false;
    let mut found = vec![];
    for line in text.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        let mut rest = line;
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let end = after.find(')').unwrap_or(after.len());
            found.push(after[..end].to_owned());
            rest = &after[end..];
        }
    }
    found
}

#[test]
fn every_link_points_at_a_file_and_section_that_exist() {
    let mut broken = vec![];
    let mut checked = 0;
    for (page, text) in pages() {
        for link in links(&text) {
            if link.starts_with("http://") || link.starts_with("https://") {
                continue;
            }
            checked += 1;
            let (file, section) = link.split_once('#').unwrap_or((&link, ""));
            let target = if file.is_empty() { page.clone() } else { page.parent().unwrap().join(file) };
            if !target.exists() {
                broken.push(format!("{}: {link}: no such file", page.display()));
            } else if !section.is_empty() {
                let headings = headings(&std::fs::read_to_string(&target).unwrap());
                if !headings.iter().any(|h| h == section) {
                    broken.push(format!("{}: {link}: no heading #{section} (has {headings:?})", page.display()));
                }
            }
        }
    }
    assert!(checked > 20, "only {checked} links found");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_link_check_can_fail() {
    assert_eq!(
        links("see [a](docs/x.md#b-c) and ![p](assets/p.png)\n```\n[not](a link)\n```"),
        ["docs/x.md#b-c", "assets/p.png"]
    );
    assert_eq!(anchor(" Lighting spaces"), "lighting-spaces");
    assert_eq!(anchor("Error against run time: `bumpview report`"), "error-against-run-time-bumpview-report");
}

/// A command from a page: its words, the page it is on and the output lines shown after it.
#[derive(Debug)]
struct Documented {
    page: String,
    line: String,
    output: Vec<String>,
}

fn commands(page: &str, text: &str) -> Vec<Documented> {
    let mut found: Vec<Documented> = vec![];
    let mut in_code = false;
    let mut pending = String::new();
    let mut after_prompt = false;
    for raw in text.lines() {
        if raw.starts_with("```") {
            in_code = !in_code;
            after_prompt = false;
            continue;
        }
        if !in_code {
            continue;
        }
        let line = raw.split(" #").next().unwrap().trim_end();
        if !pending.is_empty() {
            pending.push(' ');
            pending.push_str(line.trim_start().trim_end_matches('\\').trim_end());
            if !line.ends_with('\\') {
                found.push(Documented { page: page.to_owned(), line: std::mem::take(&mut pending), output: vec![] });
            }
            continue;
        }
        let prompt = line.starts_with("$ ");
        let command = line.trim_start_matches("$ ").trim_start();
        let runnable = command.starts_with("bumpview ") || command == "bumpview" || command.starts_with("cargo ");
        if runnable && !(command.contains('[') || command.contains('…') || command.contains('|')) {
            after_prompt = prompt;
            if command.ends_with('\\') {
                pending = command.trim_end_matches('\\').trim_end().to_owned();
            } else {
                found.push(Documented { page: page.to_owned(), line: command.to_owned(), output: vec![] });
            }
        } else if after_prompt && !line.trim().is_empty() && !runnable {
            found.last_mut().unwrap().output.push(line.to_owned());
        }
    }
    found
}

/// `line` with every number (digits, dots) made `#`: the shape a printed line must keep.
fn shape(line: &str) -> String {
    let mut out = String::new();
    let mut in_number = false;
    for c in line.chars() {
        if c.is_ascii_digit() || (in_number && c == '.') {
            if !in_number {
                out.push('#');
            }
            in_number = true;
        } else {
            in_number = false;
            out.push(c);
        }
    }
    out
}

/// The files the pages' commands name, made or copied into `dir`.
fn lay_out_inputs(dir: &Path) {
    let fixtures = root().join("tests/fixtures/gltf");
    std::fs::copy(fixtures.join("BoxTextured/glTF-Binary/BoxTextured.glb"), dir.join("model.glb")).unwrap();
    // model.gltf: NormalTangentTest with its buffer and textures beside it.
    for entry in std::fs::read_dir(fixtures.join("NormalTangentTest/glTF")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().replace("NormalTangentTest.gltf", "model.gltf");
        std::fs::copy(&path, dir.join(name)).unwrap();
    }
    std::fs::write(
        dir.join("other.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n",
    )
    .unwrap();
    // lecture/: a lesson file of one's own beside its model, as docs/lessons.md writes it.
    let lecture = dir.join("lecture");
    std::fs::create_dir_all(lecture.join("model")).unwrap();
    for entry in std::fs::read_dir(fixtures.join("NormalTangentTest/glTF")).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, lecture.join("model").join(path.file_name().unwrap())).unwrap();
    }
    std::fs::write(
        lecture.join("my-model.toml"),
        "title = \"t\"\ncaption = \"c\"\nclaim = \"{changed}\"\nlabels = [\"off\", \"on\"]\n\
         [preset.files]\nmesh = \"model/NormalTangentTest.gltf\"\n[preset.split]\nenabled = true\n",
    )
    .unwrap();
    let height = image::GrayImage::from_fn(64, 64, |x, y| image::Luma([((x * 7 + y * 3) % 64 * 4) as u8]));
    height.save(dir.join("height.png")).unwrap();
}

fn has_xvfb_run() -> bool {
    Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .stdout(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Runs one documented `bumpview` command in `dir` as the module's doc says; the failure, if any.
fn run(documented: &Documented, dir: &Path) -> Result<(), String> {
    let words: Vec<String> = documented.line.split_whitespace().map(str::to_owned).collect();
    let mut args: Vec<String> = match words.first().map(String::as_str) {
        Some("bumpview") => words[1..].to_vec(),
        Some("cargo") if words.starts_with(&["cargo".into(), "run".into(), "--release".into(), "--".into()]) => {
            words[4..].to_vec()
        }
        _ => unreachable!(),
    };
    let sub = args.first().cloned().unwrap_or_default();
    let viewer = !["render", "report", "bake", "check", "help", "lessons", "slides"].contains(&sub.as_str());
    let has = |args: &[String], flag: &str| args.iter().any(|a| a == flag || a.starts_with(&format!("{flag}=")));
    if sub == "render" && !has(&args, "--size") {
        args.extend(["--size".into(), "96x54".into()]);
    }
    if sub == "slides" && !has(&args, "--size") {
        args.extend(["--size".into(), "480x270".into()]);
    }
    if sub == "slides" && !has(&args, "--lessons") {
        args.extend(["--lessons".into(), "cg-wall,strength".into()]);
    }
    if sub == "report" && !has(&args, "--quick") {
        args.push("--quick".into());
    }
    let mut command = if viewer {
        if !has_xvfb_run() {
            return Err("xvfb-run is missing (apt-get install xvfb xauth)".to_owned());
        }
        args.extend(["--exit-after".into(), "3".into()]);
        let mut c = Command::new("xvfb-run");
        c.args(["-a", "-s", "-screen 0 1280x800x24", env!("CARGO_BIN_EXE_bumpview")]);
        c
    } else {
        Command::new(env!("CARGO_BIN_EXE_bumpview"))
    };
    let output =
        command.args(&args).current_dir(dir).env("XDG_CONFIG_HOME", dir).output().map_err(|e| e.to_string())?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    // `check` exits 1 for warnings: the page says so.
    let allowed = if sub == "check" { &[0, 1][..] } else { &[0][..] };
    if !output.status.code().is_some_and(|code| allowed.contains(&code)) {
        return Err(format!("exit {:?}\nstdout: {stdout}\nstderr: {stderr}", output.status.code()));
    }
    for expected in &documented.output {
        if !stdout.lines().any(|line| shape(line) == shape(expected)) && !expected.starts_with("bumpview: ") {
            return Err(format!("no line shaped as {expected:?} on stdout:\n{stdout}"));
        }
    }
    Ok(())
}

#[test]
fn every_documented_command_runs() {
    let mut failed = vec![];
    let mut ran = 0;
    for (page, text) in pages() {
        let name = page.strip_prefix(root()).unwrap().display().to_string();
        for documented in commands(&name, &text) {
            let words: Vec<&str> = documented.line.split_whitespace().collect();
            let bench_or_test = words.iter().position(|w| *w == "--bench" || *w == "--test");
            if words[0] == "cargo" && words.get(1) != Some(&"run")
                || words.starts_with(&["cargo", "run", "--release"]) && words.len() == 3
            {
                // `cargo test`, `cargo bench --bench NAME`, `cargo run --release` (the viewer,
                // as the viewer test runs it): the targets they name exist.
                if let Some(at) = bench_or_test {
                    let target = words[at + 1];
                    let folder = if words[at] == "--bench" { "benches" } else { "tests" };
                    if !root().join(folder).join(format!("{target}.rs")).exists() {
                        failed.push(format!("{}: {}: no {folder}/{target}.rs", documented.page, documented.line));
                    }
                }
                continue;
            }
            let dir = std::env::temp_dir().join(format!("bumpview-docs-{}-{ran}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            lay_out_inputs(&dir);
            if let Err(why) = run(&documented, &dir) {
                failed.push(format!("{}: {}: {why}", documented.page, documented.line));
            }
            std::fs::remove_dir_all(&dir).unwrap();
            ran += 1;
        }
    }
    assert!(ran >= 8, "only {ran} commands found in the pages");
    assert!(failed.is_empty(), "documented commands that fail:\n{}", failed.join("\n\n"));
}

#[test]
fn commands_are_read_as_the_pages_write_them() {
    let text = "```sh\nbumpview render --out a.png \\\n    --light=-1,2,3   # three\nbumpview [render] --out X\n```\n```\n$ bumpview render --frames 2\nframe 1.5 ms, floor 1.0 ms, ratio 1.50\n```\n";
    let found = commands("p", text);
    assert_eq!(found.len(), 2, "{found:?}");
    assert_eq!(found[0].line, "bumpview render --out a.png --light=-1,2,3");
    assert_eq!(found[1].output, ["frame 1.5 ms, floor 1.0 ms, ratio 1.50"]);
    assert_eq!(shape("frame 57.71 ms, ratio 1.11"), shape("frame 3.2 ms, ratio 10.5"));
    assert_ne!(shape("frame 57.71 ms"), shape("frame 57.71 s"));
}
