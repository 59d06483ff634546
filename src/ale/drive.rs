//! The winch advance loop, written once for both backends: step on the current mesh up
//! to the first step after which some winch cable must be remeshed (or passes a limit
//! of its winch), remesh between steps, go on.
//!
//! The backends differ only in how they step on a fixed mesh and how they remesh (the
//! CPU path edits its layout and state in memory; the GPU path reads the state back,
//! remeshes on the host with the same [`AleState::remesh_in_place`], and uploads the
//! new layout): the [`MeshStepper`] they implement. The remesh is only attempted when
//! [`AleState::needs_action`] says a winch acts at the current time; when it does not,
//! `remesh_in_place` would change nothing (its edit skips every winch that does not
//! act), so asking first only saves the GPU path a state read-back.

use super::AleState;
use crate::Error;

/// A solver whose cables may carry winches, as [`advance_with_winches`] drives it.
pub(crate) trait MeshStepper {
    /// The winch state, `None` without winches.
    fn ale(&self) -> Option<&AleState>;
    /// Steps taken so far; the time is `steps * dt`.
    fn steps(&self) -> u64;
    /// The step, s.
    fn dt(&self) -> f64;
    /// Advances `nsteps` steps on the current mesh.
    fn advance_fixed(&mut self, nsteps: u64) -> Result<(), Error>;
    /// Remeshes every winch cable at the current time and installs the new layout and
    /// state; an error (a limit of a winch passed) ends the run.
    fn remesh(&mut self) -> Result<(), Error>;
}

/// Advances `nsteps` steps of `s.dt()`, cut where a winch cable must be remeshed.
pub(crate) fn advance_with_winches<S: MeshStepper>(s: &mut S, nsteps: u64) -> Result<(), Error> {
    if s.ale().is_none() {
        return s.advance_fixed(nsteps);
    }
    let dt = s.dt();
    let mut left = nsteps;
    while left > 0 {
        let ale = s.ale().expect("winches");
        let k = ale.steps_on_this_mesh(s.steps(), left, dt);
        s.advance_fixed(k)?;
        left -= k;
        let t = s.steps() as f64 * dt;
        if s.ale().expect("winches").needs_action(t) {
            s.remesh()?;
        }
    }
    Ok(())
}
