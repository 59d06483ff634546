//! The node pass's WGSL functions against their Rust twins (moved from `step_functions`,
//! which runs them in `check_all`): the symplectic Euler update (`node_advance`, through
//! `node_accel`) and the blow-up check (`node_check`).

use super::*;

/// `node_advance` (and `node_accel`): symplectic Euler `v += a dt; r += v dt`, `r` kept
/// as a compensated pair, with `a` the mass block's solve for free nodes and the
/// Baumgarte law `a = a_d - beta (v - v_d) - alpha (r - r_d)` onto a fixed, line or
/// circle route for driven ones.
pub(super) fn check_advance<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 600;
    let dt = 5e-4;
    let eps = R::epsilon().f64();
    let sb = SeabedCoefs {
        z: 0.0,
        k: 0.0,
        c: 0.0,
        mu: 0.0,
        mu_axial: 0.0,
        v_eps: 1.0,
    };
    let (mut nodes, mut routes, mut x, mut cases) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for i in 0..n {
        let driven = i % 2 == 1;
        let origin = rv(rng, 500.0).map(|c: f64| c.round());
        let route = match i % 6 {
            1 => Route::Fixed {
                position: rv(rng, 500.0),
            },
            3 => Route::Line {
                start: rv(rng, 500.0),
                velocity: rv(rng, 3.0),
            },
            _ => Route::Circle {
                center: rv(rng, 500.0),
                radius: rng.gen_range(1.0..30.0),
                period: rng.gen_range(5.0..100.0),
                axis: (unit(rng)).to_f64(),
                phase: rng.gen_range(-3.0..3.0),
                advance: rng.gen_range(-70.0..70.0),
            },
        };
        let t0 = rng.gen_range(0.0..2000.0);
        let tau = R::c(rng.gen_range(0.0..0.5)).f64();
        // A driven node near its target (Baumgarte pulls it back), a free one anywhere.
        let target = route.eval(t0 + tau);
        let rel = V3::from_f64(target.r) - V3::from_f64(origin);
        let r = if driven {
            rel + v3(&rv(rng, 0.5))
        } else {
            v3(&rv(rng, 100.0))
        };
        let v = if driven {
            V3::from_f64(target.v) + v3(&rv(rng, 0.5))
        } else {
            v3(&rv(rng, 3.0))
        };
        let (row, rg, vg) = state_row::<R>(r, v);
        x.extend(row);
        // The mass block as a node gathers it: scalar masses and normal added masses.
        let s = rng.gen_range(1.0..100.0);
        let mut m = Sym3::scalar(s);
        let mut a_tot = 0.0;
        for _ in 0..2 {
            let a = rng.gen_range(0.0..50.0);
            m.add_normal_projection(a, unit(rng));
            a_tot += a;
        }
        let f = rv(rng, 1e4);
        let (mr, mg) = to_r::<R>(&[m.xx, m.yy, m.zz, m.xy, m.xz, m.yz]);
        let (fr, fg) = to_r::<R>(&f);
        x.extend(fr);
        x.extend(mr);
        x.push(R::c(tau));
        // The seabed's damping slopes (c_h, c_h, c_z), taken implicitly: none on a
        // third of the nodes, up to dt c = 50 s (far beyond an explicit step) on others.
        let cd = if i % 3 == 0 {
            [0.0; 3]
        } else {
            let ch = rng.gen_range(0.0..1e5);
            [ch, ch, rng.gen_range(0.0..1e5)]
        };
        let (cr, cg) = to_r::<R>(&cd);
        x.extend(cr);
        nodes.push(NodeParams::<R> {
            constraint: if driven {
                routes.len() as u32
            } else {
                u32::MAX
            },
            screen: u32::MAX,
            screen_net: u32::MAX,
            ..Default::default()
        });
        if driven {
            routes.push(rebased_route::<R>(&route, i as u32, t0, origin, 0));
        }
        let mg = Sym3 {
            xx: mg[0],
            yy: mg[1],
            zz: mg[2],
            xy: mg[3],
            xz: mg[4],
            yz: mg[5],
        };
        cases.push((
            driven,
            route,
            t0,
            tau,
            origin,
            rg,
            vg,
            v3(&fg),
            mg,
            s,
            a_tot,
            v3(&cg),
        ));
    }
    let samples = vec![RouteSample::<R>::default()];
    let group0 = [
        (0, run_params::<R>(n, 0, dt, &sb)),
        (4, bytes(&nodes)),
        (6, bytes(&routes)),
        // The blocks and the current profiles' buffer, where node_advance finds a
        // seabed grid (none here: params.seabed < 2, so they are not read).
        (
            7,
            bytes(&[<BlockParams<R> as bytemuck::Zeroable>::zeroed()]),
        ),
        (
            8,
            bytes(&[<CurrentPoint<R> as bytemuck::Zeroable>::zeroed()]),
        ),
        (9, bytes(&[<CurrentRange as bytemuck::Zeroable>::zeroed()])),
        (15, bytes(&samples)),
        // The released flags `node_held` reads (no line failures here: never read).
        (13, bytes(&[R::c(0.0); 4])),
        // The body rows `constraint_target` reads (none of these routes is on a body).
        (18, bytes(&[<BodyRow<R> as bytemuck::Zeroable>::zeroed()])),
    ];
    let out = run(ctx, p, "t_advance", &group0, &x, n, 9 * n);
    let mut w = Worst::new::<R>("node_advance (node_accel: mass solve, Baumgarte)");
    let (alpha, beta, dt) = (R::c(400.0).f64(), R::c(40.0).f64(), R::c(dt).f64());
    for (i, (driven, route, t0, tau, origin, r, v, f, m, s, a_tot, cd)) in
        cases.into_iter().enumerate()
    {
        // cpu::stepper node_accel_of, then the symplectic arm of advance_block_in.
        let (a, a_scale) = if driven {
            let d = route.eval(t0 + tau);
            let rd = V3::from_f64(d.r) - V3::from_f64(origin);
            let (vd, ad) = (V3::from_f64(d.v), V3::from_f64(d.a));
            let a = ad - (v - vd) * beta - (r - rd) * alpha;
            // The target's own rounding (`functions`, route_eval): the displacement
            // since the rebase in f32, the absolute angle and coordinates in f64.
            let (rad, w_ang, speed) = match route {
                Route::Circle {
                    radius,
                    period,
                    advance,
                    ..
                } => (
                    radius,
                    std::f64::consts::TAU / period,
                    (advance / period).abs(),
                ),
                Route::Line { velocity, .. } => (0.0, 0.0, V3::from_f64(velocity).norm()),
                _ => (0.0, 0.0, 0.0),
            };
            let mut r_err = rad * w_ang * tau + speed * tau + 1e-3 * rd.norm();
            let mut v_err = rad * w_ang * (1.0 + w_ang * (t0 + tau) + 7.0) + speed;
            if p == Precision::F64 {
                r_err += rad * w_ang * (t0 + tau) + rd.norm() + speed * (t0 + tau);
                v_err += rad * w_ang * w_ang * (t0 + tau);
            }
            let a_err = rad * w_ang * w_ang * (1.0 + w_ang * (t0 + tau) + 7.0);
            let scale = a_err
                + ad.norm()
                + beta * (v.norm() + vd.norm() + v_err)
                + alpha * ((r - rd).norm() + r_err);
            (a, scale)
        } else {
            // Eigenvalues in [s, s + a_tot]: the solve's error is the condition number
            // squared times eps times |f| / s (`functions`, mass block).
            // The seabed's damping implicit (cpu::stepper node_accel_of with
            // implicit_dt): (M + dt diag(c)) a = F.
            let mut mi = m;
            mi.xx += dt * cd.x;
            mi.yy += dt * cd.y;
            mi.zz += dt * cd.z;
            let cond = (s + a_tot + dt * cd.x.max(cd.z)) / s;
            (mi.solve(f), cond * cond * f.norm() / s)
        };
        let vn = v + a * dt;
        let rn = r + vn * dt;
        let v_scale = v.norm() + a_scale * dt;
        // f32: the compensated pair keeps r to about eps^2 |r|; in f64 the twin itself
        // rounds r + v dt at eps |r|.
        let r_scale = v_scale * dt
            + if p == Precision::F64 {
                r.norm()
            } else {
                eps * eps * r.norm()
            };
        let o = &out[9 * i..9 * i + 9];
        let r_gpu = [o[0] + o[3], o[1] + o[4], o[2] + o[5]];
        w.v("r", i, &r_gpu, rn, r_scale);
        w.v("v", i, &o[6..9], vn, v_scale);
    }
    w.report(p);
}

/// `node_check`: `FAIL_SPEED` (1) when a velocity component's magnitude is not below
/// the limit, else `FAIL_DISTANCE` (2) when an absolute coordinate's (block origin plus
/// the compensated pair) is not, else 0; NaN and infinity fail. Exact agreement, but
/// where an absolute coordinate lies within the rounding of `origin + (r_hi + r_lo)`
/// (`4 eps (|origin| + |r|)`) of the limit, where either answer is right (unless every
/// sum is exact).
pub(super) fn check_node_check<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 1000;
    let (max_speed, max_distance) = (100.0, 1e4);
    let eps = R::epsilon().f64();
    let mut x: Vec<R> = Vec::new();
    let mut cases = Vec::new();
    for i in 0..n {
        let mut origin = rv(rng, 5000.0).map(|c: f64| c.round());
        let mut r = rv(rng, 100.0);
        let mut v = rv(rng, 10.0);
        let k = rng.gen_range(0..3);
        let sign = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        match i % 8 {
            0 => {}
            // Exactly at the speed limit (fails: not below), or just either side.
            1 => v[k] = sign * max_speed,
            2 => v[k] = sign * max_speed * (1.0 + rng.gen_range(-1e-3..1e-3)),
            // A coordinate near the distance limit, or exactly at it (fails: not below;
            // every sum exact, so no rounding band).
            3 => {
                origin[k] = sign * (max_distance - 50.0);
                r[k] = sign * 50.0;
                if i % 16 != 3 {
                    r[k] += rng.gen_range(-1.0..1.0);
                }
            }
            4 => v[k] = f64::NAN,
            5 => r[k] = f64::NAN,
            6 => r[k] = sign * f64::INFINITY,
            // Too fast and too far: the speed is reported.
            _ => {
                v[k] = sign * 2.0 * max_speed;
                origin[k] = sign * 2.0 * max_distance;
            }
        }
        let (o, _) = to_r::<R>(&origin);
        let (row, rg, vg) = state_row::<R>(v3(&r), v3(&v));
        x.extend(o.iter().copied());
        x.extend(row);
        let og: Vec<f64> = o.iter().map(|c| c.f64()).collect();
        cases.push((v3(&og), rg, vg, i % 16 == 3));
    }
    let sb = SeabedCoefs {
        z: 0.0,
        k: 0.0,
        c: 0.0,
        mu: 0.0,
        mu_axial: 0.0,
        v_eps: 1.0,
    };
    let out = run(
        ctx,
        p,
        "t_check",
        &[(0, run_params::<R>(n, 0, 1e-3, &sb))],
        &x,
        n,
        n,
    );
    let (mut counts, mut band) = ([0usize; 3], 0);
    for (i, (o, r, v, exact)) in cases.into_iter().enumerate() {
        let ra = o + r;
        let all_below = |c: V3<f64>, lim: f64| [c.x, c.y, c.z].iter().all(|c| c.abs() < lim);
        let expected = if !all_below(v, max_speed) {
            1.0
        } else if !all_below(ra, max_distance) {
            2.0
        } else {
            0.0
        };
        let near = [0, 1, 2].iter().any(|&k| {
            let (c, oc, rc) = (
                [ra.x, ra.y, ra.z][k],
                [o.x, o.y, o.z][k],
                [r.x, r.y, r.z][k],
            );
            (c.abs() - max_distance).abs() <= 4.0 * eps * (oc.abs() + rc.abs())
        });
        if expected != 1.0 && near && !exact {
            band += 1;
            assert!(out[i] == 0.0 || out[i] == 2.0, "case {i}: {}", out[i]);
            continue;
        }
        assert_eq!(
            out[i],
            expected,
            "node_check ({}) case {i}: origin {o:?}, r {r:?}, v {v:?}",
            p.name()
        );
        counts[expected as usize] += 1;
    }
    eprintln!(
        "node_check ({}): {} sane, {} too fast, {} too far, {band} within rounding of the limit",
        p.name(),
        counts[0],
        counts[1],
        counts[2]
    );
    assert!(counts.iter().all(|&c| c > n / 10));
}
