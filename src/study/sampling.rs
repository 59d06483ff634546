//! Feeding a member's channels at each output time.
//!
//! A runner holds, at an output time, each cable's element tensions and end forces and
//! each body's load; [`Sampler`] picks every study channel's value out of that snapshot
//! and pushes it into the member's statistics. Owners are looked up by name once, when
//! the sampler is built, so sampling is a few indexed reads per channel.

use super::channel_stats::ChannelStats;
use super::channels::{BodyComponent, Channel, ModelChannels, Quantity};

/// One cable at an output time.
#[derive(Clone, Copy, Debug)]
pub struct CableSnapshot<'a> {
    /// Axial force of each element, start to end, N.
    pub tensions: &'a [f64],
    /// Force the cable exerts on its start support, N.
    pub start_force: [f64; 3],
    /// Force the cable exerts on its end support, N.
    pub end_force: [f64; 3],
}

/// One body at an output time.
#[derive(Clone, Copy, Debug, Default)]
pub struct BodySnapshot {
    /// Total force of the cables on the body, N.
    pub force: [f64; 3],
    /// Their moment about the body's reference point, N m.
    pub moment: [f64; 3],
    /// Its reference point, m (`None`: the body is not in the snapshot).
    pub position: Option<[f64; 3]>,
}

/// Where each channel's value comes from: its owner's index in the snapshot.
#[derive(Clone, Debug)]
pub struct Sampler {
    sources: Vec<(usize, Quantity)>,
    /// Each body's `reference` position (the origin of its offset), in model order.
    references: Vec<[f64; 3]>,
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

impl Sampler {
    /// A sampler for `channels` (resolved against `model`): snapshots then list cables
    /// and bodies in `model`'s order.
    pub fn new(channels: &[Channel], model: &ModelChannels) -> Sampler {
        let sources = channels
            .iter()
            .map(|c| {
                let owner = if c.quantity.of_cable() {
                    model.cables.iter().position(|m| m.name == c.owner)
                } else {
                    model.bodies.iter().position(|b| *b == c.owner)
                };
                let owner = owner.unwrap_or_else(|| {
                    panic!("channel {} was not resolved against this model", c.name())
                });
                (owner, c.quantity)
            })
            .collect();
        Sampler {
            sources,
            references: model.body_references.clone(),
        }
    }

    /// The value of channel `i` in a snapshot; `None` for an element a winch has
    /// hauled in (the cable has fewer elements now than at the start).
    pub fn value(
        &self,
        i: usize,
        cables: &[CableSnapshot],
        bodies: &[BodySnapshot],
    ) -> Option<f64> {
        let (owner, q) = self.sources[i];
        Some(match q {
            Quantity::TensionMax => cables[owner].tensions.iter().copied().reduce(f64::max)?,
            Quantity::StartForce => norm(cables[owner].start_force),
            Quantity::EndForce => norm(cables[owner].end_force),
            Quantity::Tension(k) => *cables[owner].tensions.get(k)?,
            Quantity::Offset => {
                let x = bodies[owner].position?;
                let r = self.references.get(owner).copied().unwrap_or_default();
                (x[0] - r[0]).hypot(x[1] - r[1])
            }
            Quantity::Body(c) => {
                let b = &bodies[owner];
                match c {
                    BodyComponent::Fx => b.force[0],
                    BodyComponent::Fy => b.force[1],
                    BodyComponent::Fz => b.force[2],
                    BodyComponent::Mx => b.moment[0],
                    BodyComponent::My => b.moment[1],
                    BodyComponent::Mz => b.moment[2],
                }
            }
        })
    }

    /// Pushes every channel's value at simulated time `t` (s) into `stats` (one per
    /// channel, in channel order).
    pub fn record(
        &self,
        stats: &mut [ChannelStats],
        t: f64,
        cables: &[CableSnapshot],
        bodies: &[BodySnapshot],
    ) {
        debug_assert_eq!(stats.len(), self.sources.len());
        for (i, s) in stats.iter_mut().enumerate() {
            if let Some(x) = self.value(i, cables, bodies) {
                s.push(t, x);
            }
        }
    }
}
