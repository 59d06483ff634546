//! `src/ancf/band.rs`: its unit tests, moved here from its `#[cfg(test)]` module so that
//! `cargo test` does not compile the library a second time as a test harness.

use cablesim::ancf::band::*;

fn spd(n: usize) -> Band {
    let mut m = Band::zeros(n);
    for i in 0..n {
        for j in i.saturating_sub(BW)..=i {
            let x = if i == j {
                30.0 + i as f64
            } else {
                ((i * 7 + j * 3) % 5) as f64 * 0.3 - 0.6
            };
            m.add_lower(i, j, x);
        }
    }
    m
}

#[test]
fn cholesky_solves_and_eliminate_prescribes() {
    let n = 40;
    let m = spd(n);
    let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let mut b = vec![0.0; n];
    m.mul_vec(&x, &mut b);
    let mut f = m.clone();
    f.cholesky().unwrap();
    let mut y = b.clone();
    f.solve_in_place(&mut y);
    for i in 0..n {
        assert!((y[i] - x[i]).abs() < 1e-12, "{i}");
    }
    // Prescribing coordinates 3 and 9 to their true values gives the rest back.
    let mut g = m.clone();
    let mut y = b.clone();
    for p in [3, 9] {
        for (i, yi) in y.iter_mut().enumerate() {
            if i != 3 && i != 9 {
                *yi -= m.get(i, p) * x[p];
            }
        }
    }
    for p in [3, 9] {
        y[p] = x[p];
        g.eliminate(p);
    }
    g.cholesky().unwrap();
    g.solve_in_place(&mut y);
    for i in 0..n {
        assert!((y[i] - x[i]).abs() < 1e-12, "{i}");
    }
    assert!(Band::zeros(3).cholesky().is_err());
}
