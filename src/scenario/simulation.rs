//! The `[simulation]` and `[ancf]` tables: the time step, scheme, formulation and
//! the solver settings, validated.

use super::raw::{RawAncf, RawDt, RawSimulation};
use super::{err, non_negative, positive, DtSpec, SimulationConfig};
use crate::error::Error;
use crate::options::{AncfSettings, Baumgarte};
use std::path::Path;

/// The `[simulation]` table, validated.
pub(super) fn simulation(p: &Path, s: &RawSimulation) -> Result<SimulationConfig, Error> {
    let duration = positive(p, "simulation.duration", s.duration)?;
    let output_interval = positive(p, "simulation.output_interval", s.output_interval)?;
    let dt = match &s.dt {
        None => DtSpec::Auto,
        Some(RawDt::Word(w)) if w == "auto" => DtSpec::Auto,
        Some(RawDt::Word(w)) => {
            return Err(err(
                p,
                "simulation.dt",
                format!("must be \"auto\" or a step in seconds, got \"{w}\""),
            ))
        }
        Some(RawDt::Number(x)) => DtSpec::Fixed(positive(p, "simulation.dt", *x)?),
    };
    // The enums are parsed by serde (raw.rs): an unknown value is an error naming
    // the field and the values allowed.
    let backend = s.backend.unwrap_or_default();
    let scheme = s.scheme.unwrap_or_default();
    let choice = s.formulation.unwrap_or_default();
    let (cable_model, formulation) = (choice.model(), choice.formulation());
    let mut baumgarte = Baumgarte::default();
    if let Some(a) = s.baumgarte_alpha {
        baumgarte.alpha = non_negative(p, "simulation.baumgarte_alpha", a)?;
    }
    if let Some(b) = s.baumgarte_beta {
        baumgarte.beta = non_negative(p, "simulation.baumgarte_beta", b)?;
    }
    let max_speed = match s.max_speed {
        Some(v) => positive(p, "simulation.max_speed", v)?,
        None => 1.0e4,
    };
    Ok(SimulationConfig {
        duration,
        dt,
        output_interval,
        backend,
        precision: s.precision,
        scheme,
        formulation,
        model: cable_model,
        baumgarte,
        max_speed,
    })
}

/// The `[ancf]` table, validated.
pub(super) fn ancf_settings(p: &Path, a: &RawAncf) -> Result<AncfSettings, Error> {
    let mut s = AncfSettings::default();
    if let Some(l) = a.element_length {
        s.element_length = Some(positive(p, "ancf.element_length", l)?);
    }
    if let Some(n) = a.gauss_points {
        if !(1..=16).contains(&n) {
            return Err(err(
                p,
                "ancf.gauss_points",
                format!("must be between 1 and 16, got {n}"),
            ));
        }
        s.gauss_points = n as usize;
    }
    if let Some(m) = a.added_mass {
        s.added_mass = m;
    }
    Ok(s)
}
