//! Prescribed motions of constrained nodes (anchors, fairleads, towing points).
//!
//! A route gives the target position, velocity and acceleration `r_d, rd_d, rdd_d` at
//! time `t`; the constraint drives the node onto it with Baumgarte stabilisation
//! (docs/src/model/constraints.md, paper Eq. 6).

use crate::body::{attachment, Body};
use std::f64::consts::PI;
use std::sync::Arc;

/// A prescribed path `r_d(t)`.
#[derive(Clone, Debug, PartialEq)]
pub enum Route {
    /// Held at a point (an anchor, a fixed fairlead).
    Fixed {
        /// Position, m.
        position: [f64; 3],
    },
    /// Straight line at constant velocity: `r_d = start + velocity t`.
    Line {
        /// Position at `t = 0`, m.
        start: [f64; 3],
        /// Velocity, m/s.
        velocity: [f64; 3],
    },
    /// Circle (and, with `advance != 0`, a screw: the circle advancing along its axis).
    Circle {
        /// Centre of the circle at `t = 0`, m.
        center: [f64; 3],
        /// Radius, m.
        radius: f64,
        /// Time of one revolution, s.
        period: f64,
        /// Unit axis; the motion is counter-clockwise about it.
        axis: [f64; 3],
        /// Angle at `t = 0`, rad, measured from the in-plane reference direction `e1`.
        phase: f64,
        /// Advance along `axis` per revolution, m (0 for a circle).
        advance: f64,
    },
    /// Positions read from a table, linearly interpolated; held at the first and last
    /// rows outside the table's time span.
    Table {
        /// Sample times, s, strictly increasing.
        t: Vec<f64>,
        /// Positions, m.
        p: Vec<[f64; 3]>,
    },
    /// A point fixed on a body with prescribed motion: rigid-body kinematics of the
    /// body's state (`crate::body`).
    Body {
        /// The body (shared by every end attached to it).
        body: Arc<Body>,
        /// The point in body coordinates, relative to the body's reference point, m.
        at: [f64; 3],
    },
}

/// Target kinematics of a route at one time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RouteState {
    /// Position, m.
    pub r: [f64; 3],
    /// Velocity, m/s.
    pub v: [f64; 3],
    /// Acceleration, m/s^2.
    pub a: [f64; 3],
}

/// The in-plane basis `(e1, e2)` of a circle about unit `axis`: `e1` is the global x
/// direction projected onto the plane (or y when the axis is along x), `e2 = axis x e1`.
pub fn circle_basis(axis: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let n = axis;
    let seed = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let d = seed[0] * n[0] + seed[1] * n[1] + seed[2] * n[2];
    let mut e1 = [seed[0] - d * n[0], seed[1] - d * n[1], seed[2] - d * n[2]];
    let l = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
    e1 = [e1[0] / l, e1[1] / l, e1[2] / l];
    let e2 = [
        n[1] * e1[2] - n[2] * e1[1],
        n[2] * e1[0] - n[0] * e1[2],
        n[0] * e1[1] - n[1] * e1[0],
    ];
    (e1, e2)
}

/// The state on a straight route from `start` at constant `velocity` at time `t`.
#[inline(always)]
fn line_state(start: &[f64; 3], velocity: &[f64; 3], t: f64) -> RouteState {
    RouteState {
        r: [
            start[0] + velocity[0] * t,
            start[1] + velocity[1] * t,
            start[2] + velocity[2] * t,
        ],
        v: *velocity,
        a: [0.0; 3],
    }
}

impl Route {
    /// [`Route::eval`] with the straight route inlined into the caller (a call and a
    /// large stack frame fewer on a hot path; the same values).
    #[inline(always)]
    pub fn eval_inline(&self, t: f64) -> RouteState {
        match self {
            Route::Line { start, velocity } => line_state(start, velocity, t),
            _ => self.eval(t),
        }
    }

    /// Target position, velocity and acceleration at time `t`.
    pub fn eval(&self, t: f64) -> RouteState {
        match self {
            Route::Fixed { position } => RouteState {
                r: *position,
                v: [0.0; 3],
                a: [0.0; 3],
            },
            Route::Line { start, velocity } => line_state(start, velocity, t),
            Route::Circle {
                center,
                radius,
                period,
                axis,
                phase,
                advance,
            } => {
                let w = 2.0 * PI / period;
                let th = w * t + phase;
                let (c, s) = (th.cos(), th.sin());
                let (e1, e2) = circle_basis(*axis);
                let adv = advance / period; // axial speed
                let mut st = RouteState {
                    r: [0.0; 3],
                    v: [0.0; 3],
                    a: [0.0; 3],
                };
                for k in 0..3 {
                    st.r[k] = center[k] + radius * (c * e1[k] + s * e2[k]) + axis[k] * adv * t;
                    st.v[k] = radius * w * (-s * e1[k] + c * e2[k]) + axis[k] * adv;
                    st.a[k] = -radius * w * w * (c * e1[k] + s * e2[k]);
                }
                st
            }
            Route::Table { t: ts, p } => {
                let n = ts.len();
                if n == 1 || t <= ts[0] {
                    return RouteState {
                        r: p[0],
                        v: [0.0; 3],
                        a: [0.0; 3],
                    };
                }
                if t >= ts[n - 1] {
                    return RouteState {
                        r: p[n - 1],
                        v: [0.0; 3],
                        a: [0.0; 3],
                    };
                }
                let i = ts.partition_point(|&x| x <= t).max(1);
                let (t0, t1) = (ts[i - 1], ts[i]);
                let s = (t - t0) / (t1 - t0);
                let mut st = RouteState {
                    r: [0.0; 3],
                    v: [0.0; 3],
                    a: [0.0; 3],
                };
                #[allow(clippy::needless_range_loop)] // three arrays indexed together
                for k in 0..3 {
                    st.r[k] = p[i - 1][k] + s * (p[i][k] - p[i - 1][k]);
                    st.v[k] = (p[i][k] - p[i - 1][k]) / (t1 - t0);
                }
                st
            }
            Route::Body { body, at } => attachment(&body.state(t), *at),
        }
    }

    /// The same route moved by `d` (a whole pattern of cables shifted in space).
    pub fn translated(&self, d: [f64; 3]) -> Route {
        let add = |a: [f64; 3]| [a[0] + d[0], a[1] + d[1], a[2] + d[2]];
        match self {
            Route::Fixed { position } => Route::Fixed {
                position: add(*position),
            },
            Route::Line { start, velocity } => Route::Line {
                start: add(*start),
                velocity: *velocity,
            },
            Route::Circle {
                center,
                radius,
                period,
                axis,
                phase,
                advance,
            } => Route::Circle {
                center: add(*center),
                radius: *radius,
                period: *period,
                axis: *axis,
                phase: *phase,
                advance: *advance,
            },
            Route::Table { t, p } => Route::Table {
                t: t.clone(),
                p: p.iter().map(|x| add(*x)).collect(),
            },
            // The whole body moved by `d`: its point at `at` moves by `d` at all times.
            Route::Body { body, at } => {
                let mut b = Body::clone(body);
                b.pose.offset = add(b.pose.offset);
                Route::Body {
                    body: Arc::new(b),
                    at: *at,
                }
            }
        }
    }

    /// True for a route that never moves.
    pub fn is_fixed(&self) -> bool {
        matches!(self, Route::Fixed { .. })
    }
}
