//! Stage 4 of the pipeline: the step plan of a lumped-mass run (the time step from the
//! stability bound and the output interval, steps per output, total steps), and the
//! winch schedules followed over it before anything runs.

use crate::ale::{WinchEnd, WinchTracker};
use crate::error::Error;
use crate::model::{Layout, ModelDef};
use crate::options::SolverOptions;
use crate::scenario::{DtSpec, Scenario};
use crate::stability::{stable_step, StepBound, AUTO_SAFETY};

/// The step plan of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct StepPlan {
    /// Time step, s.
    pub dt: f64,
    /// Steps per output interval.
    pub steps_per_output: u64,
    /// Total steps.
    pub total_steps: u64,
    /// The stability bound.
    pub bound: StepBound,
    /// A warning to show (user step above the bound).
    pub warning: Option<String>,
}

/// Chooses the step: `auto` takes [`AUTO_SAFETY`] of the stable step, rounded down so
/// that a whole number of steps fits each output interval; a given step must divide the
/// output interval and gets a warning when it is above the stable step.
///
/// With winches, the stable step is that of the worst mesh the run can reach (each
/// variable element at its shortest, `0.5 l_s`; a cable hauled in to a single element
/// when the schedule goes that far), and the schedules are followed over the planned
/// step times without dynamics: a drum overrun or a haul-in past the last node is
/// reported here, naming the cable and the time, before anything runs.
pub fn plan_steps(
    sc: &Scenario,
    lay: &Layout,
    opts: &SolverOptions,
    duration: f64,
    dt: DtSpec,
) -> Result<StepPlan, Error> {
    let plan = plan_unbounded(sc, lay, opts, duration, dt)?;
    super::budget::check_output(sc, duration)?;
    Ok(plan)
}

fn plan_unbounded(
    sc: &Scenario,
    lay: &Layout,
    opts: &SolverOptions,
    duration: f64,
    dt: DtSpec,
) -> Result<StepPlan, Error> {
    let mut bound = stable_step(lay, opts.scheme, opts.baumgarte);
    if sc.winches.is_empty() {
        return plan_with(sc, lay, opts, duration, dt, bound);
    }
    let worst = |bound: &mut StepBound, collapse: &[usize]| -> Result<(), Error> {
        let (wl, _) = Layout::build(&winch_worst_case(&sc.model, sc, collapse))?;
        let b = stable_step(&wl, opts.scheme, opts.baumgarte);
        if b.dt < bound.dt {
            *bound = StepBound {
                dt: b.dt,
                term: format!("{} (winch mesh at its shortest variable element)", b.term),
                fix: b.fix,
            };
        }
        Ok(())
    };
    worst(&mut bound, &[])?;
    let mut plan = plan_with(sc, lay, opts, duration, dt, bound.clone())?;
    let collapse = scan_winches(sc, &plan)?;
    if !collapse.is_empty() {
        worst(&mut bound, &collapse)?;
        plan = plan_with(sc, lay, opts, duration, dt, bound)?;
        scan_winches(sc, &plan)?;
    }
    Ok(plan)
}

/// The model with every winch cable's variable element at `0.5 l_s`, and the cables
/// listed in `collapse` hauled in to that single element.
fn winch_worst_case(def: &ModelDef, sc: &Scenario, collapse: &[usize]) -> ModelDef {
    let mut d = def.clone();
    for (wi, w) in sc.winches.iter().enumerate() {
        let c = &mut d.cables[w.cable];
        let short = crate::ale::DELETE_RATIO * w.element_length;
        if collapse.contains(&wi) {
            // Interior nodes are left loose (no mass, no elements): the step ignores them.
            let (a, b) = (c.nodes[0], c.nodes[c.nodes.len() - 1]);
            c.nodes = vec![a, b];
            c.l0 = vec![short];
        } else {
            let k = match w.end {
                WinchEnd::Start => 0,
                WinchEnd::End => c.l0.len() - 1,
            };
            c.l0[k] = short;
        }
    }
    d
}

/// Follows every winch's schedule over the plan's step times; returns the winches
/// whose cable gets down to a single element (from more), or the first limit passed.
fn scan_winches(sc: &Scenario, plan: &StepPlan) -> Result<Vec<usize>, Error> {
    let mut collapse = Vec::new();
    for (wi, w) in sc.winches.iter().enumerate() {
        let c = &sc.model.cables[w.cable];
        let mut tr = WinchTracker::new(w, &c.l0, w.schedule.eval(0.0).dl);
        let n0 = tr.n_elements();
        let fewest =
            tr.scan(&w.schedule, plan.dt, 0, plan.total_steps)
                .map_err(|(time, lim)| Error::Winch {
                    cable: c.name.clone(),
                    time,
                    message: lim.to_string(),
                })?;
        if fewest == 1 && n0 > 1 {
            collapse.push(wi);
        }
    }
    Ok(collapse)
}

/// The step of `spec` for a model whose stable step is `stable` (s), and the steps per
/// output interval: `auto` takes [`AUTO_SAFETY`] of `stable`, rounded down so that a
/// whole number of steps fits the output interval; a given step must divide it (an
/// error naming the field otherwise).
pub fn fit_step(sc: &Scenario, spec: DtSpec, stable: f64) -> Result<(f64, u64), Error> {
    let oi = sc.sim.output_interval;
    match spec {
        DtSpec::Auto => {
            let n = (oi / (AUTO_SAFETY * stable)).ceil().max(1.0);
            Ok((oi / n, n as u64))
        }
        DtSpec::Fixed(d) => {
            let n = (oi / d).round().max(1.0);
            if ((n * d) - oi).abs() > 1e-9 * oi {
                return Err(crate::scenario::err(
                    &sc.path,
                    "simulation.output_interval",
                    format!("{oi} s is not a whole number of steps of dt = {d} s"),
                ));
            }
            Ok((d, n as u64))
        }
    }
}

/// The plan at `bound`; refused beyond the node-step budget (before the winch scan,
/// which follows every planned step).
fn plan_with(
    sc: &Scenario,
    lay: &Layout,
    opts: &SolverOptions,
    duration: f64,
    dt_spec: DtSpec,
    bound: StepBound,
) -> Result<StepPlan, Error> {
    // A stable step that is not a number comes from an overflowing term: no step,
    // given or not, can be trusted then.
    if (matches!(dt_spec, DtSpec::Auto) && !(bound.dt > 0.0 && bound.dt.is_finite()))
        || bound.dt.is_nan()
    {
        return Err(crate::scenario::err(
            &sc.path,
            "simulation.dt",
            format!(
                "the stable step is {:e} s (set by {}): no step can run this model; check the values behind that term",
                bound.dt, bound.term
            ),
        ));
    }
    let (dt, spo) = fit_step(sc, dt_spec, bound.dt)?;
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(crate::scenario::err(
            &sc.path,
            "simulation.dt",
            format!("the step {dt:e} s is not a positive number"),
        ));
    }
    super::budget::check_lumped_node_steps(sc, lay, opts, duration, dt, dt_spec, &bound)?;
    let warning = (matches!(dt_spec, DtSpec::Fixed(_)) && dt > bound.dt).then(|| {
        format!(
            "dt = {dt} s is above the stable step {:.4e} s of the {} scheme, set by {}; expect a blow-up or wrong results",
            bound.dt,
            opts.scheme.name(),
            bound.term
        )
    });
    let total = (duration / dt).round().max(1.0) as u64;
    Ok(StepPlan {
        dt,
        steps_per_output: spo,
        total_steps: total,
        bound,
        warning,
    })
}

/// The time of step `steps` as written out: an exact multiple of the output interval at
/// output steps (`steps * dt` can be off by an ulp), else `steps * dt`.
pub(crate) fn output_time(plan: &StepPlan, oi: f64, steps: u64) -> f64 {
    if steps.is_multiple_of(plan.steps_per_output) {
        (steps / plan.steps_per_output) as f64 * oi
    } else {
        steps as f64 * plan.dt
    }
}
