//! `src/cpu/chain/net/plan.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::testing::cpu_chain_net_pieces::pieces;
use cablesim::testing::cpu_chain_net_plan::*;

/// A cylinder net of 128 x 32 knots (as `model::add_net` numbers it): rows of
/// twines, then the twines down. Every element is evaluated once, every tile
/// updated once, after every group that writes its slots and before any group
/// that reads its nodes; tiles that share a buffer are never live at once.
#[test]
fn wavefront_covers_the_cage_in_order() {
    let (nc, nr) = (128usize, 32usize);
    let (mut ea, mut eb) = (Vec::new(), Vec::new());
    for r in 0..nr {
        for c in 0..nc {
            ea.push((r * nc + c) as u32);
            eb.push((r * nc + (c + 1) % nc) as u32);
        }
    }
    for r in 0..nr - 1 {
        for c in 0..nc {
            ea.push((r * nc + c) as u32);
            eb.push(((r + 1) * nc + c) as u32);
        }
    }
    let n = nc * nr;
    // Slots: the place in each node's incidence list, in element order.
    let mut deg = vec![0u8; n];
    let (mut sa, mut sb) = (Vec::new(), Vec::new());
    for (&a, &b) in ea.iter().zip(&eb) {
        sa.push(deg[a as usize]);
        deg[a as usize] += 1;
        sb.push(deg[b as usize]);
        deg[b as usize] += 1;
    }
    let ps = pieces(&ea, &eb, &sa, &sb);
    for threads in [1, 2, 3] {
        let p = plan(n, 4, &ea, &eb, &ps, threads);
        let nt = n / NT;
        let mut seen = vec![0usize; ea.len()];
        let mut done = vec![false; nt];
        // Per buffer: the tile whose slots it holds now.
        let mut holder = vec![usize::MAX; p.nbuf];
        let late: Vec<usize> = p.threads.iter().flat_map(|th| th.late.clone()).collect();
        for (k, th) in p.threads.iter().enumerate() {
            // This thread's tiles: the others' updates never touch what it reads.
            let mine = nt * k / threads..nt * (k + 1) / threads;
            for op in &th.ops {
                match op {
                    Op::Elems(pc) => {
                        for e in pc.elems.clone() {
                            seen[e] += 1;
                            for i in [ea[e], eb[e]] {
                                let t = i as usize / NT;
                                assert!(mine.contains(&t) || late.contains(&t));
                                assert!(!done[t], "tile {t} read after its update");
                                let b = p.buf[t] as usize;
                                assert!(holder[b] == t || holder[b] == usize::MAX);
                                holder[b] = t;
                            }
                        }
                    }
                    Op::Nodes(t) => {
                        assert!(!done[*t]);
                        done[*t] = true;
                        holder[p.buf[*t] as usize] = usize::MAX;
                    }
                }
            }
        }
        for th in &p.threads {
            for &t in &th.late {
                assert!(!done[t]);
                done[t] = true;
            }
        }
        assert!(seen.iter().all(|&k| k == 1), "{threads} threads");
        assert!(done.iter().all(|&d| d));
        // One thread: two buffers for the 16 tiles.
        if threads == 1 {
            assert_eq!(p.nbuf, 2);
            // The top row's knots have 3 twines: their fourth slot is cleared
            // after tile 14 (tile 0 is the next user of its buffer).
            assert_eq!(p.clear[14], vec![(0, nc as u32, 3)]);
        }
    }
}
