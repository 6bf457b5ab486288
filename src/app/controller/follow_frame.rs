//! What follows the picture between frames: the probe's readout where its point shows now,
//! and GPU displacement's budget on stderr.

use super::Controller;

impl Controller {
    /// Tells stderr when GPU displacement's budget starts lengthening the edges, or lengthens
    /// them differently (the panel says it on screen): never silently.
    pub fn tell_budget(&mut self) {
        let notice = self.renderer.gpu_displacement(false).and_then(|s| s.budget_notice());
        if notice != self.said_budget {
            if let Some(notice) = &notice {
                eprintln!("bumpview: {notice}");
            }
            self.said_budget = notice;
        }
    }

    /// Recomputes the probe's readout, if one is pinned, from the renderer's prepared scene of
    /// the picture where its point shows now (in the split view, that half's).
    pub fn refresh_probe(&mut self) {
        let Some(size) = self.view_size.filter(|_| self.probe.is_pinned()) else { return };
        let column = self.probe.shown_at(&self.state.camera, size).map_or(0, |p| p.x.max(0.0) as u32);
        let (params, _, half) = self.state.picture_at(column, size[0]);
        let Some(prepared) = self.renderer.drawn_prepared(half == Some(1)) else { return };
        let half = half.map(|i| format!("{}: {}", ["left", "right"][i], self.state.split.labels()[i]));
        self.probe.update(&prepared, &params, size, half);
    }
}
