//! Bodies with prescribed motion (vessels, buoys, towing ships) that cable ends attach
//! to.
//!
//! A body has a reference point, a mean pose ([`MeanPose`]: the reference point at
//! rest, a mean offset and a mean heading) and a motion about it, from a 6-DOF time
//! series ([`motion`]) or from RAOs in the sea state's wave components ([`rao`]). Its
//! state at a time ([`kinematics::BodyState`]) gives every attached point's position,
//! velocity and acceleration by rigid-body kinematics ([`kinematics::attachment`]),
//! which drive the end constraint exactly as a route's target does: an attachment is
//! a [`crate::model::Route::Body`]. [`output`] writes the force and moment the cables
//! exert on each body (`bodies.csv`).
//!
//! On the GPU path the host evaluates each body's state once per step (per body, not
//! per node; the bodies in parallel) into rows uploaded with each submission, and the
//! shaders apply the attachment kinematics per end node (`gpu::solver::body_rows`,
//! WGSL `body_point`). An RAO motion is the same function of time on both paths: the
//! exact sum at knots, Hermite interpolation between them ([`rao`]).

pub mod free;
pub mod kinematics;
pub mod motion;
pub mod output;
pub mod rao;

pub use kinematics::{attachment, BodyState, Dofs, MeanPose};
pub use motion::MotionTable;
pub use rao::{RaoMotion, RaoTable};

use std::collections::HashMap;
use std::sync::Mutex;

/// How many states [`Body::state`] keeps: enough that every cable of a run, each
/// stepped through an output interval (or a chunk of steps) on its own, finds the
/// states the first cable computed, for intervals of up to some two thousand steps;
/// cleared when full. About 400 kB per body at most (a packed study has a body per
/// member).
const STATE_CACHE_LEN: usize = 2048;

/// How a body moves about its mean pose.
#[derive(Clone, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)] // one per body, evaluated in place each step
pub enum Motion {
    /// At rest in its mean pose.
    Still,
    /// A 6-DOF time series.
    Table(MotionTable),
    /// RAOs driven by wave components.
    Rao(RaoMotion),
    /// Its own dynamics, free or pinned ([`free`]): as a function of time, the
    /// initial pose (and a pinned body's prescribed translation); the solver steps the
    /// state.
    Dynamic(Box<Dynamic>),
}

/// A body with its own dynamics: its properties and initial state, and a pinned
/// body's prescribed translation.
#[derive(Clone, Debug, PartialEq)]
pub struct Dynamic {
    /// Properties and initial state.
    pub body: free::FreeBody,
    /// A pinned body's translation (the `x, y, z` columns of its motion file; `None`:
    /// held at its pose).
    pub pin: Option<MotionTable>,
    /// Whether the statics (`initial = "catenary"` lines) move the body to its static
    /// equilibrium with its lines (`initial = "equilibrium"`, the default), or hold it
    /// at its pose (`initial = "pose"`: the run is the release from there).
    pub equilibrium: bool,
}

/// A body with prescribed motion.
#[derive(Debug)]
pub struct Body {
    /// Name (what ends refer to, and the `body` column of `bodies.csv`).
    pub name: String,
    /// Mean pose.
    pub pose: MeanPose,
    /// Motion about the mean pose.
    pub motion: Motion,
    /// The states evaluated, keyed by the time's bits: every end on the body asks for
    /// the same times (the CPU path steps each cable through an output interval in
    /// turn, so the times come round once per cable), and an RAO motion costs a
    /// Hermite interpolation of 18 values (and, once per knot, a sine and cosine per
    /// wave component) plus the rigid-body state. A pure function of `t`, so a hit
    /// returns exactly what evaluating again would.
    cache: Mutex<HashMap<u64, BodyState>>,
}

impl Clone for Body {
    fn clone(&self) -> Self {
        Self::new(self.name.clone(), self.pose, self.motion.clone())
    }
}

impl PartialEq for Body {
    fn eq(&self, o: &Self) -> bool {
        self.name == o.name && self.pose == o.pose && self.motion == o.motion
    }
}

impl Body {
    /// A body named `name` in mean pose `pose`, moving by `motion`.
    pub fn new(name: String, pose: MeanPose, motion: Motion) -> Self {
        Self {
            name,
            pose,
            motion,
            cache: Mutex::new(HashMap::new()),
        }
    }

    /// The motion about the mean pose at time `t`, s.
    pub fn dofs(&self, t: f64) -> Dofs {
        match &self.motion {
            Motion::Still => Dofs::default(),
            Motion::Table(m) => m.eval(t),
            Motion::Rao(m) => m.eval(t),
            Motion::Dynamic(d) => {
                let mut q = match &d.pin {
                    Some(m) => m.eval(t),
                    None => Dofs::default(),
                };
                q.q[3..].copy_from_slice(&d.body.spec.angles);
                q.qd[3..].fill(0.0);
                q.qdd[3..].fill(0.0);
                q
            }
        }
    }

    /// The free or pinned body's dynamics, or `None` for a prescribed motion.
    pub fn dynamic(&self) -> Option<&Dynamic> {
        match &self.motion {
            Motion::Dynamic(d) => Some(d),
            _ => None,
        }
    }

    /// The prescribed motion of a pinned body's reference point at `t`.
    pub fn pin(&self, t: f64) -> free::Pin {
        let s = self.evaluate(t);
        free::Pin {
            x: s.x.to_f64(),
            v: s.v.to_f64(),
            a: s.a.to_f64(),
        }
    }

    /// The body's state at time `t`, s, evaluated (not cached: for callers that ask for
    /// each time once, as the GPU path's per-step rows do).
    pub fn evaluate(&self, t: f64) -> BodyState {
        kinematics::body_state(&self.pose, &self.dofs(t))
    }

    /// The body's state at time `t`, s (kept for the other ends that ask for it).
    pub fn state(&self, t: f64) -> BodyState {
        let lock = || self.cache.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(s) = lock().get(&t.to_bits()) {
            return *s;
        }
        // Evaluated outside the lock: cables on other threads go on meanwhile.
        let s = self.evaluate(t);
        let mut cache = lock();
        if cache.len() >= STATE_CACHE_LEN {
            cache.clear();
        }
        cache.insert(t.to_bits(), s);
        s
    }
}
