//! Sea states: the water surface, linear (Airy) wave components and their spectra,
//! and the kinematics the cable loads and vessel motions read from them.
//!
//! Conventions (stated once, used by every function here and by its WGSL twin):
//! the mean water level is `z = 0`, `z` up; a component's elevation is
//! `eta = A cos(theta)`, `theta = k (x cos b + y sin b) - w t + phi`, where `b` is the
//! direction the component travels towards, measured from +x towards +y, and `phi` its
//! phase. Angles are radians inside the library (the scenario file takes degrees).
//!
//! # What a stepper calls
//!
//! A validated scenario carries a [`SeaState`] (`Scenario::sea`; still water when it
//! has no components, [`SeaState::is_still`]). A stepper that applies waves:
//!
//! 1. builds one [`cache::WaveCache`] for the run: `WaveCache::new(&sea, n_nodes)`
//!    (refresh interval from [`cache::refresh_interval`] and `sea.cache_tolerance`),
//!    or, as the solvers do, `WaveCache::with_clock(&sea, n_nodes,
//!    RefreshClock::on_grid(&plan))` with the [`schedule::refresh_plan`] of the sea
//!    for the height its nodes reach and the step (the common refresh grid), or,
//!    as the CPU solver does, `WaveCache::with_bands(&sea, n_nodes, &bands)` with the
//!    [`bands::band_plan`] (a refresh interval per depth band of nodes);
//! 2. before each force evaluation at time `t` (every stage of a multi-stage scheme;
//!    times must not go backwards except to restart), calls
//!    `cache.refresh_if_due(t, &positions, &velocities)` with the nodes' positions and
//!    velocities as flat `[x0, y0, z0, x1, ...]` arrays, m and m/s. This evaluates the
//!    full sum only when `t` passes the cache's `t1`;
//! 3. reads node `i`'s elevation, water velocity and acceleration at `t` with
//!    `cache.node(i, t)` (a [`kinematics::Kinematics`]), or all nodes at once with
//!    `cache.interpolate(t, &mut out)` ([`cache::CACHE_STRIDE`] values per node:
//!    `eta, u, a`). `eta` is the surface elevation above the node's `(x, y)`, which
//!    the wetted fraction needs; `u` and `a` are the wave part only (add the current).
//!    Above the surface the values are the surface values: scale by the wetted
//!    fraction.
//!
//! Exact evaluation at a point, without the cache, is
//! `kinematics::WaveField::new(&sea).kinematics(p, t)`.
//!
//! On the GPU the twins are in `shaders/shared/waves.wgsl`: the struct `WaveComp` is
//! [`kinematics::PackedComponent`] (thirteen scalars, `WaveField::comps`, sorted by `k`
//! for the decay cut of [`cut`], phases referred
//! to `WaveField::t_ref`: rebase on the host and pass `t - t_ref`), the per-node
//! refresh is `wave_kinematics_rates_tau` (values and rates along each node's path), the
//! interpolation `wave_cache_hermite`, as on the CPU; see the shader file's header for
//! the buffers. Infinite depth goes to the GPU as
//! [`GPU_DEEP`] m.

pub mod bands;
pub mod cache;
pub mod columns;
pub mod cut;
pub mod dispersion;
pub mod irregular;
pub mod kinematics;
pub mod measured;
pub mod poly;
pub mod schedule;
pub mod set;
pub mod spectrum;

pub use set::SeaSet;

/// The depth, m, that stands for infinite depth on the GPU (finite in f32; the
/// decay `e^{-2 k h}` is 0 there for any wave).
pub const GPU_DEEP: f64 = 1e30;

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
        self.k * (x * self.direction.cos() + y * self.direction.sin()) - self.omega * t + self.phase
    }
}

/// How the linear profile is evaluated near the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Stretching {
    /// Wheeler stretching: the column `[-h, eta]` mapped onto `[-h, 0]`.
    #[default]
    Wheeler,
    /// The profile as it is below the mean level, held at its `z = 0` value above.
    Constant,
}

/// A validated sea state: every wave component of every train, and how they are
/// evaluated.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaState {
    /// All components (regular and irregular trains together).
    pub components: Vec<WaveComponent>,
    /// Water depth `h`, m (`f64::INFINITY`: deep water).
    pub depth: f64,
    /// Profile above the mean level.
    pub stretching: Stretching,
    /// Start-up ramp duration `T_r`, s (0: waves at full height from the start).
    pub ramp_duration: f64,
    /// Relative tolerance of the kinematics cache's interpolation (see
    /// [`cache::refresh_interval`]).
    pub cache_tolerance: f64,
}

impl SeaState {
    /// Still water of depth `depth`, m.
    pub fn still(depth: f64) -> Self {
        Self {
            components: Vec::new(),
            depth,
            stretching: Stretching::Wheeler,
            ramp_duration: 0.0,
            cache_tolerance: 1e-3,
        }
    }

    /// True when there are no waves.
    pub fn is_still(&self) -> bool {
        self.components.is_empty()
    }
}

impl Default for SeaState {
    fn default() -> Self {
        Self::still(f64::INFINITY)
    }
}
