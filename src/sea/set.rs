//! Several seas in one run: the seas of a packed model (`crate::model::pack`), each
//! cable in one of them.
//!
//! A study's members each have their own sea (their own wave components, ramp, cache
//! tolerance). Packed into one model, every cable keeps the sea of its member: the CPU
//! path gives each block the kinematics cache of its cable's sea, and the GPU path
//! stores the seas' components back to back and gives each block the rows of its
//! sea. Each sea keeps its own refresh schedule (its own interval, from its own
//! components and tolerance), so a cable sees exactly the waves it sees in a run of
//! its member alone, whatever else is packed with it.

use super::SeaState;

/// The seas of a run and the sea of each cable.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaSet {
    /// The seas (still water where a sea has no components).
    pub seas: Vec<SeaState>,
    /// Per cable (layout order): its index into `seas`; empty when every cable is in
    /// `seas[0]`.
    pub cable_sea: Vec<u32>,
}

impl SeaSet {
    /// One sea for every cable.
    pub fn single(sea: &SeaState) -> Self {
        Self {
            seas: vec![sea.clone()],
            cable_sea: Vec::new(),
        }
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
