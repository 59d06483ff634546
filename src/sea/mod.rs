//! Sea states: the water surface, linear (Airy) wave components and their spectra,
//! and the kinematics the cable loads and vessel motions read from them.
//!
//! Conventions (stated once, used by every function here and by its WGSL twin):
//! the mean water level is `z = 0`, `z` up; a component's elevation is
//! `eta = A cos(theta)`, `theta = k (x cos b + y sin b) - w t + phi`, where `b` is the
//! direction the component travels towards, measured from +x towards +y, and `phi` its
//! phase. Angles are radians inside the library (the scenario file takes degrees).

/// One linear wave component, as the kinematics and the RAO-driven bodies use it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaveComponent {
    /// Amplitude `A`, m.
    pub amplitude: f64,
    /// Angular frequency `w`, rad/s.
    pub omega: f64,
    /// Wave number `k`, rad/m (from the finite-depth dispersion relation).
    pub k: f64,
    /// Direction of travel `b`, rad, from +x towards +y.
    pub direction: f64,
    /// Phase `phi`, rad.
    pub phase: f64,
}

impl WaveComponent {
    /// The phase angle `theta` at horizontal position `(x, y)` and time `t`.
    #[inline]
    pub fn theta(&self, x: f64, y: f64, t: f64) -> f64 {
        self.k * (x * self.direction.cos() + y * self.direction.sin()) - self.omega * t
            + self.phase
    }
}
