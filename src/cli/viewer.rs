//! Starting the viewer from the command line: from a preset, the files and flags given, or the
//! state the viewer had when it last closed.

use bumpview::lessons::Lesson;
use bumpview::state::preset::Preset;

use super::start::start;
use super::{Cli, Failure};
use crate::app;

/// Opens the viewer window and runs until it is closed.
pub fn run(cli: &Cli) -> Result<(), Failure> {
    // `--exit-after` runs (scripts, tests) neither restore nor save the last state.
    let last_state = app::last_state_file().filter(|_| cli.exit_after.is_none());
    let lesson = cli.lesson.as_deref().map(Lesson::load).transpose().map_err(|e| Failure::Failed(e.to_string()))?;
    let command_line = cli.preset.is_some()
        || lesson.is_some()
        || !cli.inputs.files().is_empty()
        || !cli.methods.is_empty()
        || !cli.picture.is_empty();
    let mut notice = None;
    let restored = match (&cli.preset, &last_state) {
        _ if lesson.is_some() => lesson.as_ref().map(|l| l.viewer_preset().clone()),
        (Some(path), _) => Some(Preset::load(path)?),
        (None, Some(path)) if !command_line && path.exists() => {
            Preset::load(path).map_err(|e| notice = Some(format!("last state not restored: {e}"))).ok()
        }
        _ => None,
    };
    let from_last = restored.is_some() && cli.preset.is_none() && lesson.is_none();
    let mut started = match start(restored.unwrap_or_default(), cli.inputs.files(), &cli.methods) {
        Err(e) if from_last => {
            notice = Some(format!("last state not restored: {e}"));
            start(Preset::default(), cli.inputs.files(), &cli.methods)?
        }
        started => started?,
    };
    // The picture flags, as `render` applies them.
    cli.picture.apply(&mut started.state)?;
    app::run(app::Options {
        exit_after: cli.exit_after,
        capture_window: cli.capture_window.clone(),
        probe: cli.probe,
        files: started.files,
        capture: started.capture,
        scene: started.scene,
        state: started.state,
        last_state,
        notice,
        lesson,
    })
    .map_err(Failure::Failed)
}
