//! Interactive frames: while the user drags (camera, light, divider, sliders) or the light
//! orbits, frames are drawn with one sample per pixel and, while such a frame is still over
//! its budget, at a lower render scale; once input stops, one full-quality frame (4× MSAA,
//! every pixel). Decided here, without a window or a GPU: the viewer says whether input or an
//! animation is active and reports what each interactive frame cost.

use std::num::NonZeroU32;

use crate::error::RenderError;
use crate::frame::{FrameQuality, Msaa};
use crate::render::Renderer;
use crate::render::timing::{TimedPicture, time_frames};

/// An interactive frame may cost this many times the adapter's floor (one sample per pixel,
/// at the view's size; [`crate::render::Renderer::draw_floor`]).
pub const BUDGET_FLOOR_RATIO: f64 = 2.0;
/// ...but never less than this many milliseconds: frames that fast are never drawn smaller
/// (on a GPU the floor is a fraction of a millisecond).
pub const MIN_BUDGET_MS: f64 = 4.0;
/// The smallest render scale an interactive frame is drawn at.
pub const MIN_RENDER_SCALE: f32 = 0.25;
/// Render scales are multiples of this, so the view's texture changes size in steps.
pub const RENDER_SCALE_STEP: f32 = 1.0 / 16.0;
/// A frame under this share of its budget lets the render scale grow again (with the budget
/// itself as the upper bound this leaves a band where the scale stays, so timing noise does
/// not make it flicker).
pub const GROW_BELOW_SHARE: f64 = 0.7;
/// A new render scale aims at this share of the budget, inside the band, so frames a little
/// slower than the one measured still fit.
pub const AIM_SHARE: f64 = 0.85;

/// Chooses each frame's quality and adapts the interactive render scale to the budget.
#[derive(Debug, Clone, PartialEq)]
pub struct InteractiveQuality {
    /// The panel setting: off, every frame is full quality.
    pub enabled: bool,
    /// The render scale of interactive frames, in `MIN_RENDER_SCALE..=1`.
    render_scale: f32,
}

impl Default for InteractiveQuality {
    /// On, starting at every pixel.
    fn default() -> Self {
        InteractiveQuality { enabled: true, render_scale: 1.0 }
    }
}

impl InteractiveQuality {
    /// The quality of the next frame: while `active` (input is being dragged or an animation
    /// runs) and the setting is on, one sample per pixel at the learnt render scale; else
    /// [`FrameQuality::FULL`].
    pub fn quality(&self, active: bool) -> FrameQuality {
        if self.enabled && active { self.interactive() } else { FrameQuality::FULL }
    }

    /// One sample per pixel at the learnt render scale.
    fn interactive(&self) -> FrameQuality {
        FrameQuality { msaa: Msaa::Off, render_scale: self.render_scale }
    }

    /// The render scale interactive frames are drawn at now.
    pub fn render_scale(&self) -> f32 {
        self.render_scale
    }

    /// The budget of an interactive frame in milliseconds, given the adapter's floor at the
    /// view's size with one sample per pixel (milliseconds).
    pub fn budget_ms(floor_ms: f64) -> f64 {
        (BUDGET_FLOOR_RATIO * floor_ms).max(MIN_BUDGET_MS)
    }

    /// Learns from an interactive frame drawn at the current render scale: it took
    /// `frame_ms` (drawing until the adapter finished) where the floor takes `floor_ms`.
    /// Over budget or under [`GROW_BELOW_SHARE`] of it, the scale changes by the square root
    /// of the frame's time against [`AIM_SHARE`] of the budget (a frame's cost grows with its
    /// pixels, the square of the scale), rounded down to a [`RENDER_SCALE_STEP`], within
    /// `MIN_RENDER_SCALE..=1`. Non-finite or non-positive times are ignored.
    pub fn record(&mut self, frame_ms: f64, floor_ms: f64) {
        if !(frame_ms.is_finite() && frame_ms > 0.0 && floor_ms.is_finite() && floor_ms >= 0.0) {
            return;
        }
        let budget = Self::budget_ms(floor_ms);
        if frame_ms <= budget && frame_ms >= GROW_BELOW_SHARE * budget {
            return;
        }
        let wanted = self.render_scale as f64 * (AIM_SHARE * budget / frame_ms).sqrt();
        let stepped = (wanted as f32 / RENDER_SCALE_STEP).floor() * RENDER_SCALE_STEP;
        self.render_scale = stepped.clamp(MIN_RENDER_SCALE, 1.0);
    }

    /// Draws interactive frames of `picture` (its quality is replaced; the setting is not
    /// consulted) as the viewer would while the user drags, timing [`SETTLE_FRAMES`] at a
    /// time against the floor, until the render scale stays put twice in a row or after
    /// [`SETTLE_ROUNDS`] rounds; returns the quality arrived at. For `bumpview render
    /// --frames` and the benchmark: what a drag costs on this adapter.
    pub fn settle(&mut self, renderer: &mut Renderer, picture: &TimedPicture) -> Result<FrameQuality, RenderError> {
        let frames = NonZeroU32::new(SETTLE_FRAMES).expect("not zero");
        let mut unchanged = 0;
        for _ in 0..SETTLE_ROUNDS {
            let before = self.render_scale;
            let timing = time_frames(renderer, &TimedPicture { quality: self.interactive(), ..*picture }, frames)?;
            self.record(timing.frame_ms, timing.floor_ms);
            unchanged = if self.render_scale == before { unchanged + 1 } else { 0 };
            if unchanged == 2 {
                break;
            }
        }
        Ok(self.interactive())
    }
}

/// At most this many rounds of [`InteractiveQuality::settle`].
pub const SETTLE_ROUNDS: usize = 12;
/// Frames (and floors) timed per round of [`InteractiveQuality::settle`]; their medians count.
pub const SETTLE_FRAMES: u32 = 5;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interactive_only_while_active_and_enabled() {
        let mut quality = InteractiveQuality::default();
        assert_eq!(quality.quality(true), FrameQuality { msaa: Msaa::Off, render_scale: 1.0 });
        assert_eq!(quality.quality(false), FrameQuality::FULL, "input stopped: full quality");
        quality.enabled = false;
        assert_eq!(quality.quality(true), FrameQuality::FULL, "the setting off: always full quality");
    }

    /// A frame that costs four times its budget is drawn at a little under half the scale
    /// next (aiming at 85 % of the budget: sqrt(8.5 / 40) = 0.46, down to 7/16); one within
    /// the band keeps the scale; a cheap one grows it, never past 1.
    #[test]
    fn the_scale_follows_the_budget() {
        let mut quality = InteractiveQuality::default();
        let floor = 5.0; // budget 10 ms
        quality.record(40.0, floor);
        assert_eq!(quality.render_scale(), 7.0 / 16.0);
        quality.record(9.0, floor);
        assert_eq!(quality.render_scale(), 7.0 / 16.0, "within the band");
        quality.record(2.5, floor);
        assert_eq!(quality.render_scale(), 12.0 / 16.0, "0.4375 · sqrt(8.5 / 2.5) = 0.81");
        quality.record(1.0, floor);
        assert_eq!(quality.render_scale(), 1.0, "never past every pixel");
        quality.record(1000.0, floor);
        assert_eq!(quality.render_scale(), MIN_RENDER_SCALE, "never below the least scale");
        assert_eq!(quality.quality(true).render_scale, MIN_RENDER_SCALE);
    }

    #[test]
    fn scales_are_whole_steps() {
        let mut quality = InteractiveQuality::default();
        quality.record(13.0, 5.0);
        let steps = quality.render_scale() / RENDER_SCALE_STEP;
        assert_eq!(steps, steps.floor());
        assert!(quality.render_scale() < 1.0);
    }

    /// On a fast adapter the floor is tiny; frames under [`MIN_BUDGET_MS`] keep every pixel.
    #[test]
    fn fast_frames_keep_every_pixel() {
        let mut quality = InteractiveQuality::default();
        quality.record(3.0, 0.05);
        assert_eq!(quality.render_scale(), 1.0);
        assert_eq!(InteractiveQuality::budget_ms(0.05), MIN_BUDGET_MS);
        assert_eq!(InteractiveQuality::budget_ms(3.3), 6.6);
    }

    #[test]
    fn bad_times_are_ignored() {
        let mut quality = InteractiveQuality::default();
        for (frame, floor) in [(f64::NAN, 3.0), (0.0, 3.0), (-5.0, 3.0), (40.0, f64::INFINITY), (40.0, -1.0)] {
            quality.record(frame, floor);
        }
        assert_eq!(quality, InteractiveQuality::default());
    }
}
