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
//! before it, starts a new run.

use std::ops::Range;

/// Elements per piece: the piece's scratch stays in the core's own cache (a net cage's
/// block is far bigger).
pub(super) const TILE: usize = 256;

/// The shortest run read in place; the elements of shorter runs are gathered.
const MIN_RUN: usize = 16;

/// A stretch of the element pass.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Piece {
    /// Block-local elements.
    pub(super) elems: Range<usize>,
    /// `Some((a0, b0))`: element `elems.start + k` has ends `a0 + k` and `b0 + k`, in
    /// the same slots of them as element `elems.start`; `None`: its ends are gathered.
    pub(super) ends: Option<(usize, usize)>,
}

impl Piece {
    /// The part of this piece within elements `er`, if any.
    pub(super) fn clip(&self, er: &Range<usize>) -> Option<Piece> {
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
/// pieces, in element order.
pub(super) fn pieces(ea: &[u32], eb: &[u32], sa: &[u8], sb: &[u8]) -> Vec<Piece> {
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
            for s in (k..j).step_by(TILE) {
                out.push(Piece {
                    elems: s..(s + TILE).min(j),
                    ends: Some((ea[s] as usize, eb[s] as usize)),
                });
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
pub(super) fn owned(pieces: &[Piece], ea: &[u32], nr: &Range<usize>) -> Vec<Piece> {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring of 40 nodes (its closing element breaks the run), 300 elements `i, i + 40`
    /// (two pieces of in-place ends), 5 scattered elements (gathered).
    #[test]
    fn pieces_cover_every_element_once_with_its_ends() {
        let (mut ea, mut eb) = (Vec::new(), Vec::new());
        for i in 0..40u32 {
            ea.push(i);
            eb.push((i + 1) % 40);
        }
        for i in 0..300u32 {
            ea.push(i);
            eb.push(i + 40);
        }
        for i in 0..5u32 {
            ea.push(7 * i);
            eb.push(3 * i);
        }
        // Slots: one along each run but the 300's, whose node a changes slot at its
        // element 100 (runs of 100 and 200).
        let sa: Vec<u8> = (0..ea.len()).map(|e| (e >= 140) as u8).collect();
        let sb = vec![0u8; ea.len()];
        let ps = pieces(&ea, &eb, &sa, &sb);
        let mut k = 0;
        for p in &ps {
            assert_eq!(p.elems.start, k, "{ps:?}");
            assert!(p.elems.len() <= TILE);
            if let Some((a0, b0)) = p.ends {
                assert!(p.elems.len() >= MIN_RUN);
                for (d, e) in p.elems.clone().enumerate() {
                    assert_eq!((ea[e] as usize, eb[e] as usize), (a0 + d, b0 + d));
                    let e0 = p.elems.start;
                    assert_eq!((sa[e], sb[e]), (sa[e0], sb[e0]));
                }
            }
            k = p.elems.end;
        }
        assert_eq!(k, ea.len());
        let direct: Vec<_> = ps.iter().filter(|p| p.ends.is_some()).collect();
        // The ring's 39 elements in order, then the 300 cut where the slot changes.
        assert_eq!(direct.len(), 3, "{ps:?}");
        assert_eq!(direct[0].elems, 0..39);
        assert_eq!(direct[1].elems, 40..140);
        assert_eq!(direct[2].elems, 140..340);
        // The closing element and the scattered ones are gathered.
        assert!(ps.contains(&Piece {
            elems: 39..40,
            ends: None
        }));
        assert!(ps.contains(&Piece {
            elems: 340..345,
            ends: None
        }));
        // Split between two threads by node a: each element once, in order.
        let (n0, n1) = (0..150, 150..340);
        let (p0, p1) = (owned(&ps, &ea, &n0), owned(&ps, &ea, &n1));
        let mut all: Vec<usize> = p0.iter().chain(&p1).flat_map(|p| p.elems.clone()).collect();
        for (p, nr) in p0
            .iter()
            .map(|p| (p, &n0))
            .chain(p1.iter().map(|p| (p, &n1)))
        {
            for (d, e) in p.elems.clone().enumerate() {
                assert!(nr.contains(&(ea[e] as usize)), "{p:?}");
                if let Some((a0, b0)) = p.ends {
                    assert_eq!((ea[e] as usize, eb[e] as usize), (a0 + d, b0 + d));
                }
            }
        }
        all.sort();
        assert_eq!(all, (0..ea.len()).collect::<Vec<_>>());
        // Clipping to a thread's range shifts the ends with it.
        let c = direct[1].clip(&(100..120)).unwrap();
        assert_eq!(c.ends, Some((60, 100)));
        assert!(direct[1].clip(&(140..150)).is_none());
        assert!(direct[1].clip(&(0..40)).is_none());
    }
}
