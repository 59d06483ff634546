//! Several seas in one run: the seas of a packed model (`crate::model::pack`), each
//! cable in one of them.
//!
//! A study's members each have their own sea (their own wave components, ramp, cache
//! tolerance). Packed into one model, every cable keeps the sea of its member: the CPU
//! path gives each block the kinematics cache of its cable's sea, and the GPU path
//! stores the seas' components back to back and gives each block the rows of its
//! sea. Each sea keeps its own refresh schedule (its own interval, from its own
//! components, tolerance and reach, on the fixed ladder of the common refresh grid:
//! `sea::schedule`), so a cable sees exactly the waves it sees in a run of its member
//! alone, whatever else is packed with it (the reach of a member's sea comes from its
//! own nodes and ends).

use super::SeaState;

/// The seas of a run and the sea of each cable.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaSet {
    /// The seas (still water where a sea has no components).
    pub seas: Vec<SeaState>,
    /// Per cable (layout order): its index into `seas`; empty when every cable is in
    /// `seas[0]`.
    pub cable_sea: Vec<u32>,
    /// Per sea: the highest height its nodes reach over the run, m, for the cache's
    /// refresh interval (`sea::schedule::refresh_plan`; set by `sim::reach`); empty
    /// when unknown (infinite: the interval for nodes at the surface).
    pub reach: Vec<f64>,
}

impl SeaSet {
    /// One sea for every cable.
    pub fn single(sea: &SeaState) -> Self {
        Self {
            seas: vec![sea.clone()],
            cable_sea: Vec::new(),
            reach: Vec::new(),
        }
    }

    /// The highest height sea `q`'s nodes reach, m (infinite when unknown).
    pub fn reach_of(&self, q: usize) -> f64 {
        self.reach.get(q).copied().unwrap_or(f64::INFINITY)
    }

    /// The refresh plan of sea `q` stepping by `dt` (`sea::schedule::refresh_plan` at
    /// its reach): what both paths refresh by.
    pub fn plan(&self, q: usize, dt: f64) -> super::schedule::RefreshPlan {
        super::schedule::refresh_plan(&self.seas[q], self.reach_of(q), dt)
    }

    /// The sea index of cable `c`.
    #[inline]
    pub fn sea_of_cable(&self, c: usize) -> usize {
        self.cable_sea.get(c).map_or(0, |&s| s as usize)
    }

    /// True when no sea has waves.
    pub fn is_still(&self) -> bool {
        self.seas.iter().all(|s| s.is_still())
    }
}
