//! Bending of lumped-mass cables: the clamped cable ends a scenario gives, and the
//! hinges where a cable of bending stiffness `EI > 0` resists bending
//! (docs/src/model/bending.md; the forces are `crate::physics::bending_hinge`'s).

use super::Layout;

/// Sentinel for "no element" on one side of a [`Hinge`] (a clamped end).
pub const NO_ELEM: u32 = u32::MAX;

/// A cable end whose direction is held: the cable leaves the end along `tangent`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clamp {
    /// Index of the cable (into `ModelDef::cables`, the same in `Layout::cables`).
    pub cable: usize,
    /// True for the cable's end b (its last node), false for end a.
    pub end_b: bool,
    /// The held unit tangent of the cable at this end, pointing from end a towards
    /// end b (at end b: the direction in which the cable arrives).
    pub tangent: [f64; 3],
}

/// Two cables joined end to end at a shared node that bend as one: the hinge there
/// joins the last element of `prev` (whose end b is the node) and the first element of
/// `next` (whose end a is the node), as a hinge inside a cable does. A ring of several
/// cables (a net cage's collar or sinker tube, `super::cage`) is closed by them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Joint {
    /// The cable that ends at the node (index into `ModelDef::cables`).
    pub prev: usize,
    /// The cable that starts there.
    pub next: usize,
}

/// A hinge: the node between packed element `prev` (which ends there) and packed
/// element `next` (which starts there) of one cable, or a clamped end, where one of
/// them is [`NO_ELEM`] and `dir` stands for its tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hinge {
    /// The element before the hinge ([`NO_ELEM`] at a clamped end a).
    pub prev: u32,
    /// The element after it ([`NO_ELEM`] at a clamped end b).
    pub next: u32,
    /// Stiffness `EI / lbar`, N m (`lbar`: half of each unstretched element beside it).
    pub k: f64,
    /// The held tangent at a clamped end (unused at an interior node).
    pub dir: [f64; 3],
}

impl Hinge {
    /// The packed element by which hinges are ordered: `prev`, or `next` at end a.
    pub fn anchor(&self) -> u32 {
        if self.prev != NO_ELEM {
            self.prev
        } else {
            self.next
        }
    }
}

impl Layout {
    /// Whether any element of the layout has bending stiffness.
    pub fn has_bending(&self) -> bool {
        self.elem_line
            .iter()
            .any(|&l| self.line_types[l as usize].ei > 0.0)
    }

    /// Every hinge of the layout, ordered by [`Hinge::anchor`]: the interior nodes of
    /// each cable whose elements on both sides have `EI > 0` (`EI` their mean there),
    /// its clamped ends (`Layout::clamps`) where its end element has `EI > 0`, and the
    /// joints between cables (`Layout::joints`) whose two elements there have `EI > 0`
    /// and share the node (end b of the one, end a of the other).
    /// Pinned and free ends are no hinge: the moment there is zero.
    pub fn hinges(&self) -> Vec<Hinge> {
        let ei = |e: u32| self.line_types[self.elem_line[e as usize] as usize].ei;
        let l0 = |e: u32| self.elem_l0[e as usize];
        let mut out = Vec::new();
        for (ci, c) in self.cables.iter().enumerate() {
            let els = &c.elements;
            let clamp = |end_b: bool| {
                self.clamps
                    .iter()
                    .find(|k| k.cable == ci && k.end_b == end_b)
            };
            if let (Some(k), Some(&e)) = (clamp(false), els.first()) {
                if ei(e) > 0.0 {
                    out.push(Hinge {
                        prev: NO_ELEM,
                        next: e,
                        k: ei(e) / (0.5 * l0(e)),
                        dir: k.tangent,
                    });
                }
            }
            for w in els.windows(2) {
                let (p, n) = (w[0], w[1]);
                let e = 0.5 * (ei(p) + ei(n));
                if ei(p) > 0.0 && ei(n) > 0.0 {
                    out.push(Hinge {
                        prev: p,
                        next: n,
                        k: e / (0.5 * (l0(p) + l0(n))),
                        dir: [0.0; 3],
                    });
                }
            }
            if let (Some(k), Some(&e)) = (clamp(true), els.last()) {
                if ei(e) > 0.0 {
                    out.push(Hinge {
                        prev: e,
                        next: NO_ELEM,
                        k: ei(e) / (0.5 * l0(e)),
                        dir: k.tangent,
                    });
                }
            }
        }
        for j in &self.joints {
            let (Some(pc), Some(nc)) = (self.cables.get(j.prev), self.cables.get(j.next)) else {
                continue;
            };
            let (Some(&p), Some(&n)) = (pc.elements.last(), nc.elements.first()) else {
                continue;
            };
            if pc.nodes.last() != nc.nodes.first() || ei(p) <= 0.0 || ei(n) <= 0.0 {
                continue;
            }
            out.push(Hinge {
                prev: p,
                next: n,
                k: 0.5 * (ei(p) + ei(n)) / (0.5 * (l0(p) + l0(n))),
                dir: [0.0; 3],
            });
        }
        out.sort_by_key(|h| h.anchor());
        out
    }
}

/// The hinges of one block (packed elements `e0..e1`) out of all of them, ordered
/// by anchor.
pub fn block_hinges(all: &[Hinge], e0: usize, e1: usize) -> &[Hinge] {
    let a = all.partition_point(|h| (h.anchor() as usize) < e0);
    let b = all.partition_point(|h| (h.anchor() as usize) < e1);
    &all[a..b]
}
