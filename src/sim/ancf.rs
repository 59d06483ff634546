//! The ANCF backend: a scenario run with the ANCF reference model (`formulation =
//! "ancf"` in `[simulation]`, or `cablesim run --formulation ancf`). Every cable of the
//! scenario becomes an [`AncfCable`] (ALE-ANCF with its winch), stepped on the CPU in
//! f64, one thread per cable, and read out in the same [`CableState`]s as a lumped-mass
//! run (so the same sinks write the same files), so that the two models of one scenario
//! can be compared line by line.
//!
//! # What maps to what
//! - Mesh: elements of `[ancf] element_length` (default: the cable's own lumped-mass
//!   element length), `ceil(length / element_length)` equal elements; with a winch the
//!   same length is the standard length `l_s` of the remeshing rules.
//! - Ends: a fixed or route end is a prescribed position (its slope free: pinned); a
//!   free end carries its point mass. Inner nodes (shared `[[points]]`, networks) are
//!   not supported: the ANCF reference is a model of single cables.
//! - Line type, environment, current: the cable's; `ei` of the line type is the
//!   bending stiffness (0 when not given).
//! - Initial shape: `straight` as the lumped-mass model's; `catenary` the analytic
//!   elastic catenary (on a fine polyline: the lumped-mass nodes' kink at the
//!   touchdown would give cubic elements large spurious strains), then brought to the
//!   ANCF's own static equilibrium, so a line whose ends hold still stays still. Where
//!   that Newton solve stalls (Gauss points slipping in and out of seabed contact) the
//!   run starts from the catenary with a warning.
//! - Step: `dt = "auto"` takes [`crate::stability::AUTO_SAFETY`] of each cable's stable step (with a winch,
//!   of its worst mesh), rounded down to divide the output interval; a given `dt` is
//!   used for every cable, with a warning when it is above a cable's stable step.
//! - Outputs: positions are the ANCF nodes' (fewer than the lumped mass's: the last
//!   node is the cable's end in both); the tension of an element is the mean of its two
//!   node tensions ([`AncfCable::node_tensions`]); end forces are the force on each held
//!   end (zero at a free end); winches and the summary as for the lumped-mass model.
//! - Time: each cable steps at its own `dt`; output times are whole output intervals,
//!   then the duration (a partial last interval), each cable at the step nearest it.

use super::plan::fit_step;
use crate::ancf::{AncfCable, AncfConfig, AncfEnd, StaticOptions};
use crate::error::Error;
use crate::model::{Layout, ModelDef};
use crate::options::{AncfSettings, Scheme};
use crate::output::{CableState, EndForces, WinchSummary};
use crate::physics::catenary::catenary_positions;
use crate::scenario::{DtSpec, InitialShape, Scenario};
use crate::stability::AUTO_SAFETY;
use rayon::prelude::*;

/// One cable of the run.
struct Runner {
    cable: AncfCable,
    /// Steps per output interval.
    per_output: u64,
    /// Whether its node positions are written (`output_positions`).
    positions: bool,
}

fn unsupported(sc: &Scenario, ci: usize, what: String) -> Error {
    Error::Model(format!(
        "{}: cable '{}': the ANCF model {what}; run it with the lumped-mass model (formulation = \"glmf\")",
        sc.path.display(),
        sc.model.cables[ci].name
    ))
}

/// How many cable node lists each described node of `def` appears in.
pub fn node_uses(def: &ModelDef) -> Vec<u32> {
    let mut uses = vec![0u32; def.nodes.len()];
    for c in &def.cables {
        for &n in &c.nodes {
            uses[n] += 1;
        }
    }
    uses
}

/// The ANCF configuration of cable `ci` (see the module doc); `uses` is
/// [`node_uses`]`(&sc.model)`.
pub fn cable_config(
    sc: &Scenario,
    settings: &AncfSettings,
    ci: usize,
    uses: &[u32],
) -> Result<AncfConfig, Error> {
    let def: &ModelDef = &sc.model;
    let c = &def.cables[ci];
    if sc.failures.iter().any(|f| f.cable == c.name) {
        return Err(unsupported(sc, ci, "does not run line failures".into()));
    }
    if def.clamps.iter().any(|k| k.cable == ci) {
        return Err(unsupported(
            sc,
            ci,
            "does not run clamped ends (`clamp`): its ends are pinned".into(),
        ));
    }
    for (k, &n) in c.nodes.iter().enumerate() {
        let inner = k > 0 && k + 1 < c.nodes.len();
        let nd = &def.nodes[n];
        if uses[n] > 1 {
            let label = nd.label.clone().unwrap_or_else(|| format!("node {n}"));
            return Err(unsupported(
                sc,
                ci,
                format!("runs single cables, and this one shares '{label}' with another cable"),
            ));
        }
        if let Some(crate::model::Route::Body { body, .. }) = &nd.route {
            if body.dynamic().is_some() {
                return Err(unsupported(
                    sc,
                    ci,
                    format!("does not run free or pinned bodies (body '{}')", body.name),
                ));
            }
        }
        if inner && (nd.route.is_some() || nd.point.mass > 0.0 || nd.point.volume > 0.0) {
            return Err(unsupported(
                sc,
                ci,
                format!("takes point masses and routes at the ends only (inner node {k})"),
            ));
        }
    }
    if def.line_types[c.line_type].viscoelastic.is_some() {
        return Err(unsupported(
            sc,
            ci,
            "has no viscoelastic (static-dynamic) axial model, and this cable's line type \
             has `ea_dynamic`"
                .to_string(),
        ));
    }
    if def.line_types[c.line_type].cat != 0.0 {
        return Err(unsupported(
            sc,
            ci,
            "has no tangential added mass, and this cable's line type sets `cat`".to_string(),
        ));
    }
    let length: f64 = c.l0.iter().sum();
    let l_std = settings
        .element_length
        .unwrap_or(length / c.l0.len() as f64);
    let elements = ((length / l_std) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
    let end = |n: usize| {
        let nd = &def.nodes[n];
        let e = match &nd.route {
            Some(r) => AncfEnd::driven(r.clone()),
            None => AncfEnd::free(nd.position),
        };
        e.with_point(nd.point)
    };
    let mut cfg = AncfConfig::new(
        def.line_types[c.line_type].clone(),
        length,
        elements,
        end(c.nodes[0]),
        end(*c.nodes.last().expect("a cable has nodes")),
        def.env,
    );
    cfg.name = c.name.clone();
    cfg.current = def.currents[c.current].clone();
    cfg.gauss_points = settings.gauss_points;
    cfg.added_mass = settings.added_mass;
    cfg.max_speed = sc.sim.max_speed;
    cfg.winch = sc.winches.iter().find(|w| w.cable == ci).map(|w| {
        let mut w = w.clone();
        w.element_length = l_std;
        w
    });
    Ok(cfg)
}

/// Checks that every cable of `sc` can run with the ANCF model (at `scheme`); returns
/// per cable its name, element count and stable step (s) with what sets it.
pub fn check(
    sc: &Scenario,
    settings: &AncfSettings,
    scheme: Scheme,
) -> Result<Vec<(String, usize, f64, String)>, Error> {
    super::budget::check_ancf_size(sc, settings.element_length)?;
    let uses = node_uses(&sc.model);
    (0..sc.model.cables.len())
        .map(|ci| {
            let mut cfg = cable_config(sc, settings, ci, &uses)?;
            cfg.scheme = scheme;
            let c = AncfCable::new(cfg)?;
            let (dt, term) = c.stable_dt();
            super::budget::check_node_steps(
                sc,
                c.n_elements() + 1,
                sc.sim.duration,
                AUTO_SAFETY * dt,
                &format!("cable '{}': {term}", c.name()),
            )?;
            Ok((c.name().to_string(), c.n_elements(), dt, term.to_string()))
        })
        .collect()
}

/// Position at arc length `s` along the polyline `pts` whose segments have unstretched
/// lengths `l0` (linear between nodes, and extended straight beyond the ends, so that
/// the central differences giving the end slopes see the end segments).
fn along(pts: &[[f64; 3]], l0: &[f64], s: f64) -> [f64; 3] {
    let mut x = s;
    for (k, &l) in l0.iter().enumerate() {
        if x <= l || k + 1 == l0.len() {
            let u = x / l;
            let (a, b) = (pts[k], pts[k + 1]);
            return [0, 1, 2].map(|i| a[i] + u * (b[i] - a[i]));
        }
        x -= l;
    }
    unreachable!("a cable has elements")
}

/// The ANCF backend: every cable of a scenario, each at its own step.
pub struct AncfFleet {
    runners: Vec<Runner>,
    /// Whole output intervals in the duration.
    outputs: u64,
    /// Per cable: its steps over the whole duration (`round(duration / dt)`).
    totals: Vec<u64>,
    /// Output interval, s.
    interval: f64,
    /// Duration, s.
    duration: f64,
    /// The time the cables were last advanced to together, s.
    time: f64,
}

impl AncfFleet {
    /// Sets up every cable of `sc` (static solves included, one cable per thread) from
    /// the lumped-mass initial state `lay`, `pos`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        sc: &Scenario,
        settings: &AncfSettings,
        scheme: Scheme,
        duration: f64,
        dt_spec: DtSpec,
        lay: &Layout,
        pos: &[[f64; 3]],
    ) -> Result<Self, Error> {
        super::budget::check_ancf_size(sc, settings.element_length)?;
        let uses = node_uses(&sc.model);
        // Per-cable lines at info level only for a few cables.
        let level = if sc.model.cables.len() <= 20 {
            log::Level::Info
        } else {
            log::Level::Debug
        };
        // Cables are set up (static solves included) one per thread.
        let build = |ci: usize| -> Result<Runner, Error> {
            let mut cfg = cable_config(sc, settings, ci, &uses)?;
            cfg.scheme = scheme;
            let info = &lay.cables[ci];
            let pts: Vec<[f64; 3]> = info.nodes.iter().map(|&n| pos[n as usize]).collect();
            let l0: Vec<f64> = info
                .elements
                .iter()
                .map(|&e| lay.elem_l0[e as usize])
                .collect();
            let mut cable = AncfCable::new(cfg)?;
            let (stable, term) = cable.stable_dt();
            let term = term.to_string();
            let (dt, per_output) = fit_step(sc, dt_spec, stable)?;
            super::budget::check_node_steps(
                sc,
                cable.n_elements() + 1,
                duration,
                dt,
                &format!("cable '{}': {term}", cable.name()),
            )?;
            if matches!(dt_spec, DtSpec::Fixed(_)) && dt > stable {
                log::warn!(
                "cable '{}': dt = {dt} s is above the ANCF stable step {stable:.4e} s ({term}); expect a blow-up",
                cable.name()
            );
            }
            cable.set_dt(dt);
            if sc.initial[ci] == InitialShape::Catenary {
                // The analytic elastic catenary on a fine polyline: the lumped-mass nodes'
                // kinks (touchdown) would give the cubic elements large spurious strains.
                let lt = &sc.model.line_types[sc.model.cables[ci].line_type];
                let env = &sc.model.env;
                let w = lt.wet_weight_per_length(env.gravity, env.water_density);
                let length: f64 = l0.iter().sum();
                let n_fine = 64 * cable.n_elements();
                let fine = catenary_positions(
                    pts[0],
                    pts[pts.len() - 1],
                    length,
                    n_fine,
                    lt.ea,
                    w,
                    -env.depth,
                );
                let fl = vec![length / n_fine as f64; n_fine];
                cable.set_shape(|s| along(&fine, &fl, s));
            } else {
                cable.set_shape(|s| along(&pts, &l0, s));
            }
            if sc.initial[ci] == InitialShape::Catenary {
                let mut trial = cable.clone();
                match trial.solve_static(&StaticOptions::default()) {
                Ok(rep) => {
                    log::log!(
                        level,
                        "cable '{}': ANCF static equilibrium in {} Newton iterations, residual {:.3e} N",
                        info.name,
                        rep.iterations,
                        rep.max_residual
                    );
                    cable = trial;
                }
                // Newton can stall where Gauss points slip in and out of seabed
                // contact; the analytic catenary is then a close start.
                Err(e) => log::warn!(
                    "cable '{}': {e}; starting from the analytic catenary instead (expect a short transient)",
                    info.name
                ),
            }
            }
            log::log!(
                level,
                "cable '{}': ANCF, {} elements, dt = {dt:.4e} s (stable {stable:.4e} s: {term})",
                info.name,
                cable.n_elements()
            );
            Ok(Runner {
                cable,
                per_output,
                positions: sc.model.cables[ci].output_positions,
            })
        };
        let runners: Vec<Runner> = (0..sc.model.cables.len())
            .into_par_iter()
            .map(build)
            .collect::<Result<_, _>>()?;
        log::info!(
            "ANCF: {} cables, {} nodes",
            runners.len(),
            runners.iter().map(|r| r.cable.n_nodes()).sum::<usize>()
        );
        let interval = sc.sim.output_interval;
        let totals = runners
            .iter()
            .map(|r| (duration / r.cable.dt()).round().max(1.0) as u64)
            .collect();
        Ok(Self {
            runners,
            outputs: (duration / interval + 1e-9).floor() as u64,
            totals,
            interval,
            duration,
            time: 0.0,
        })
    }

    /// Output times after `t = 0`: whole output intervals, then the duration when it is
    /// not one (a partial last interval).
    pub fn n_outputs(&self) -> u64 {
        let tail = self
            .runners
            .iter()
            .zip(&self.totals)
            .any(|(r, &n)| n > self.outputs * r.per_output);
        self.outputs + u64::from(tail)
    }

    /// The time of output `k` (1-based), s.
    pub fn output_time(&self, k: u64) -> f64 {
        if k > self.outputs {
            self.duration
        } else {
            k as f64 * self.interval
        }
    }

    /// Advances every cable (one thread each) to output `k` (1-based).
    pub fn advance_to_output(&mut self, k: u64) -> Result<(), Error> {
        let targets: Vec<u64> = self
            .runners
            .iter()
            .zip(&self.totals)
            .map(|(r, &n)| {
                if k > self.outputs {
                    n
                } else {
                    k * r.per_output
                }
            })
            .collect();
        self.advance_cables(&targets)?;
        self.time = self.output_time(k);
        Ok(())
    }

    /// Advances every cable to the step nearest time `t` (s; each cable has its own
    /// step).
    pub fn advance_to(&mut self, t: f64) -> Result<(), Error> {
        let targets: Vec<u64> = self
            .runners
            .iter()
            .map(|r| (t / r.cable.dt()).round().max(0.0) as u64)
            .collect();
        self.advance_cables(&targets)?;
        self.time = t;
        Ok(())
    }

    /// Advances each cable to its step count in `targets` (never back).
    fn advance_cables(&mut self, targets: &[u64]) -> Result<(), Error> {
        // Cables are independent: one thread each.
        self.runners
            .par_iter_mut()
            .zip(targets)
            .try_for_each(|(r, &n)| r.cable.advance(n.saturating_sub(r.cable.steps())))
    }

    /// The time the cables were last advanced to together, s.
    pub fn time(&self) -> f64 {
        self.time
    }
    /// The most steps any cable has taken.
    pub fn steps(&self) -> u64 {
        self.runners
            .iter()
            .map(|r| r.cable.steps())
            .max()
            .unwrap_or(0)
    }
    /// The smallest step of any cable, s.
    pub fn dt(&self) -> f64 {
        self.runners
            .iter()
            .map(|r| r.cable.dt())
            .fold(f64::INFINITY, f64::min)
    }
    /// The smallest stable step of any cable, s, and what sets it.
    pub fn stable_dt(&self) -> (f64, String) {
        self.runners.iter().map(|r| r.cable.stable_dt()).fold(
            (f64::INFINITY, String::new()),
            |a, (d, t)| {
                if d < a.0 {
                    (d, t.to_string())
                } else {
                    a
                }
            },
        )
    }
    /// Node-steps taken.
    pub fn node_steps(&self) -> f64 {
        self.runners
            .iter()
            .map(|r| r.cable.steps() as f64 * r.cable.n_nodes() as f64)
            .sum()
    }
    /// Nodes of every cable.
    pub fn n_nodes(&self) -> usize {
        self.runners.iter().map(|r| r.cable.n_nodes()).sum()
    }
    /// Elements of every cable.
    pub fn n_elements(&self) -> usize {
        self.runners.iter().map(|r| r.cable.n_elements()).sum()
    }

    /// Every cable's state now.
    pub fn cables(&mut self) -> Result<Vec<CableState>, Error> {
        self.runners
            .iter_mut()
            .map(|r| {
                let c = &mut r.cable;
                let ef = c.end_forces()?;
                let tn = c.node_tensions()?;
                Ok(CableState {
                    name: c.name().to_string(),
                    output_positions: r.positions,
                    positions: c.node_positions(),
                    velocities: c.node_velocities(),
                    tensions: tn.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect(),
                    end_forces: EndForces {
                        start: ef[0].unwrap_or([0.0; 3]),
                        end: ef[1].unwrap_or([0.0; 3]),
                    },
                    winch: winch(c),
                })
            })
            .collect()
    }
}

fn winch(c: &AncfCable) -> Option<WinchSummary> {
    c.variable_length().map(|variable_l0| {
        let (inserted, deleted) = c.remeshes();
        WinchSummary {
            deployed_length: c.length(),
            variable_l0,
            elements: c.n_elements(),
            nodes_inserted: inserted,
            nodes_deleted: deleted,
            physical_coordinates: c.physical_coordinates().unwrap_or_default(),
        }
    })
}
