//! The derivative the slopes of a height field are taken to be, as the Fourier symbols the
//! integration divides by ([`super::integrate`]) and the packed spectrum solves with
//! ([`super::spectrum`]).

use rustfft::num_complex::Complex32;

use super::{Kernel, Tap};

/// Which derivative the slopes are taken to be.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Derivative {
    /// The exact derivative `iω` (Frankot & Chellappa's): right for slopes sampled from a
    /// continuous surface.
    Spectral,
    /// The finite-difference kernel that made the slopes (see the module docs).
    Kernel(Kernel),
}

/// One axis's frequency: the angle `θ` (radians per texel) and `e^{iθo}` for the offsets
/// `o = −2..=2` the kernels reach.
pub(super) struct Phase {
    theta: f32,
    powers: [Complex32; 5],
}

impl Phase {
    pub(super) fn new(theta: f32) -> Phase {
        Phase { theta, powers: [-2.0f32, -1.0, 0.0, 1.0, 2.0].map(|o| Complex32::from_polar(1.0, theta * o)) }
    }

    /// `e^{iθ·offset}`, `offset` in −2..=2.
    fn power(&self, offset: i64) -> Complex32 {
        self.powers[(offset + 2) as usize]
    }
}

impl Derivative {
    /// Fourier symbols `(D̂x, D̂y_up)` at angular frequencies `(θx, θy)` radians per texel,
    /// `θy` along rows (down the image), for a field sampled as `Σ Ĥ e^{i(θx·x + θy·row)}`.
    pub(super) fn symbols(self, x: &Phase, y: &Phase) -> (Complex32, Complex32) {
        match self {
            // Rows run down, y_up runs up: ∂/∂y_up = −∂/∂row.
            Derivative::Spectral => (Complex32::new(0.0, x.theta), Complex32::new(0.0, -y.theta)),
            Derivative::Kernel(kernel) => {
                let (mut dx, mut dy) = (Complex32::ZERO, Complex32::ZERO);
                for &Tap { along, across, weight } in kernel.taps() {
                    // ∂/∂x reads (x + along, row + across); ∂/∂y_up reads (x + across, row − along).
                    dx += x.power(along) * y.power(across) * weight;
                    dy += x.power(across) * y.power(-along) * weight;
                }
                (dx, dy)
            }
        }
    }
}

/// Modes whose `|D̂x|² + |D̂y|²` is below this are taken as unseen by the derivative (a height
/// mode of unit amplitude whose slope is under 1e-3 per texel) and set to 0: dividing by such
/// a symbol only amplifies f32 rounding (up to 2e-4 of the relief near the smoothing kernels'
/// zeros at the Nyquist corner, measured on a 27×15 field with 1e-10).
pub(super) const BLIND: f32 = 1e-6;

/// Frequency index `k` of an `n`-point transform as a signed frequency in `−n/2..n/2`.
pub(super) fn signed_frequency(k: usize, n: usize) -> i64 {
    if k <= n / 2 { k as i64 } else { k as i64 - n as i64 }
}
