//! `src/cpu/chain/net/pieces.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::cpu_chain_net_pieces::*;

/// A ring of 40 nodes (its closing element breaks the run), 300 elements `i, i + 40`
/// (in-place ends: cut where a slot changes and where node a enters a new tile of `NT`
/// nodes), 5 scattered elements (gathered).
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
            // Node a in one tile.
            assert_eq!(a0 / NT, (a0 + p.elems.len() - 1) / NT, "{p:?}");
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
    // The ring's 39 elements in order, then the 300 cut where the slot changes (node a
    // 100) and where node a enters the second tile (`NT`).
    assert_eq!(NT, 256);
    assert_eq!(direct.len(), 4, "{ps:?}");
    assert_eq!(direct[0].elems, 0..39);
    assert_eq!(direct[1].elems, 40..140);
    assert_eq!(direct[2].elems, 140..296);
    assert_eq!(direct[3].elems, 296..340);
    assert_eq!(direct[3].ends, Some((256, 296)));
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
