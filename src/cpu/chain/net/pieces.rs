//! How the network path's element pass walks a block's elements: in pieces of at most
//! [`TILE`] elements, each either a run of elements whose ends are consecutive nodes
//! (read in place, as on the chain path: no gather) or a stretch of other elements
//! (their ends read by index, one element at a time: `gathered.rs`).
//!
//! A net's twines come in such runs: the knots of a row are numbered in order, so the
//! row's twines have ends `i, i + 1`, and the twines between two rows `i, i + columns`
//! (`model::add_net`); only a cylinder's closing twine per row and the inner nodes of
//! twines of several elements break them. A run also keeps each end in one slot of
//! its nodes (the place in their incidence lists), so that it writes what it adds to
//! them with vector stores: a net's first twine of a row, whose node a has no twine
//! before it, starts a new run. A run is cut where its node a enters a new tile of
//! [`NT`] nodes, as the step's plan would cut it (it gives each tile's elements to the
//! tile's group): a net's long run of twines between rows, cut every [`TILE`] elements
//! from its start, was cut again by the plan into twice as many pieces, each with its
//! set-up (about 340 instructions).

use super::NT;
use std::ops::Range;

/// Elements per piece: the piece's scratch stays in the core's own cache (a net cage's
/// block is far bigger).
pub const TILE: usize = 256;

/// The shortest run read in place; the elements of shorter runs are gathered.
pub const MIN_RUN: usize = 16;

/// A stretch of the element pass.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Block-local elements.
    pub elems: Range<usize>,
    /// `Some((a0, b0))`: element `elems.start + k` has ends `a0 + k` and `b0 + k`, in
    /// the same slots of them as element `elems.start`; `None`: its ends are gathered.
    pub ends: Option<(usize, usize)>,
}

impl Piece {
    /// The part of this piece within elements `er`, if any.
    pub fn clip(&self, er: &Range<usize>) -> Option<Piece> {
        let (s, e) = (self.elems.start.max(er.start), self.elems.end.min(er.end));
        (s < e).then(|| Piece {
            elems: s..e,
            ends: self.ends.map(|(a, b)| {
                let d = s - self.elems.start;
                (a + d, b + d)
            }),
        })
    }
}

/// Cuts elements with block-local ends `ea`, `eb`, in slots `sa`, `sb` of them, into
/// pieces, in element order: a run's pieces end where its node a reaches a multiple
/// of [`NT`] (so at most [`TILE`] long).
pub fn pieces(ea: &[u32], eb: &[u32], sa: &[u8], sb: &[u8]) -> Vec<Piece> {
    let ne = ea.len();
    let next = |j: usize| {
        ea[j] as usize == ea[j - 1] as usize + 1
            && eb[j] as usize == eb[j - 1] as usize + 1
            && (sa[j], sb[j]) == (sa[j - 1], sb[j - 1])
    };
    let mut out = Vec::new();
    // The first element not yet in a piece.
    let mut pending = 0;
    let mut k = 0;
    while k < ne {
        let mut j = k + 1;
        while j < ne && next(j) {
            j += 1;
        }
        if j - k >= MIN_RUN {
            gathered(&mut out, pending..k);
            let mut s = k;
            while s < j {
                let a = ea[s] as usize;
                let e = j.min(s + TILE).min(s + NT - a % NT);
                out.push(Piece {
                    elems: s..e,
                    ends: Some((a, eb[s] as usize)),
                });
                s = e;
            }
            pending = j;
        }
        k = j;
    }
    gathered(&mut out, pending..ne);
    out
}

/// The parts of `pieces` whose elements have their node a (`ea`) among nodes `nr`: a
/// thread that updates nodes `nr` evaluates these elements, so that what it reads and
/// writes stays mostly its own (the threads share only the elements across the
/// border of their node ranges).
pub fn owned(pieces: &[Piece], ea: &[u32], nr: &Range<usize>) -> Vec<Piece> {
    let mut out = Vec::new();
    for p in pieces {
        match p.ends {
            Some((a0, _)) => {
                // Node a runs over `a0..a0 + len`: one stretch of it is in `nr`.
                let (lo, hi) = (nr.start.max(a0), nr.end.min(a0 + p.elems.len()));
                let e0 = p.elems.start;
                out.extend(
                    (lo < hi)
                        .then(|| p.clip(&(e0 + lo - a0..e0 + hi - a0)))
                        .flatten(),
                );
            }
            None => {
                let mine = |e: usize| nr.contains(&(ea[e] as usize));
                let mut k = p.elems.start;
                while k < p.elems.end {
                    let s = k;
                    while k < p.elems.end && mine(k) {
                        k += 1;
                    }
                    if k > s {
                        out.push(Piece {
                            elems: s..k,
                            ends: None,
                        });
                    }
                    k += 1;
                }
            }
        }
    }
    out
}

/// Gathered pieces over elements `r`.
fn gathered(out: &mut Vec<Piece>, r: Range<usize>) {
    for s in r.clone().step_by(TILE) {
        out.push(Piece {
            elems: s..(s + TILE).min(r.end),
            ends: None,
        });
    }
}
