//! The driven ends' routes (`route_eval` on fixed, line, circle and table routes, rebased
//! on a block origin) and the current profile (`current_at`) against their Rust twins, run
//! by `functions`'s `check_all` (moved from `functions.rs`).

use super::*;

pub(super) fn check_route<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let n = 300;
    let mut routes = Vec::new();
    let mut q = Vec::new();
    let mut tau = Vec::new();
    let mut meta = Vec::new();
    let mut samples = Vec::new();
    for i in 0..n {
        let route = match i % 4 {
            3 => random_table(rng),
            0 => Route::Fixed {
                position: rv(rng, 500.0),
            },
            1 => Route::Line {
                start: rv(rng, 500.0),
                velocity: rv(rng, 3.0),
            },
            _ => {
                let ax = V3::<f64>::from_f64(rv(rng, 1.0));
                Route::Circle {
                    center: rv(rng, 500.0),
                    radius: rng.gen_range(1.0..30.0),
                    period: rng.gen_range(5.0..100.0),
                    axis: (ax / ax.norm()).to_f64(),
                    phase: rng.gen_range(-3.0..3.0),
                    advance: rng.gen_range(-70.0..70.0),
                }
            }
        };
        let t0 = match &route {
            // Before, inside and after the table's span, often a sample or more within
            // the 0.5 s of tau.
            Route::Table { t, .. } => rng.gen_range(t[0] - 3.0..t[t.len() - 1] + 1.0),
            _ => rng.gen_range(0.0..2000.0),
        };
        let o = rv(rng, 500.0).map(|x: f64| x.round());
        q.push(rebased_route::<R>(&route, 0, t0, o, samples.len() as u32));
        samples.extend(route_samples::<R>(&route, o));
        let tr = R::c(rng.gen_range(0.0..0.5));
        tau.push(tr);
        meta.push((t0, o, tr.f64()));
        routes.push(route);
    }
    let out = run::<R>(
        ctx,
        p,
        "t_route",
        &[
            (6, bytemuck::cast_slice(&q).to_vec()),
            (15, bytemuck::cast_slice(&samples).to_vec()),
        ],
        &tau,
        n,
        12 * n,
    );
    let mut w = Worst::new::<R>("route_eval (rebased; fixed, line, circle, screw)");
    let mut wt = Worst::new::<R>("route_eval (rebased; table: search, interpolation, hold)");
    for i in 0..n {
        let (t0, o, tau) = meta[i];
        let s = routes[i].eval(t0 + tau);
        let r = V3::from_f64(s.r) - V3::from_f64(o);
        let o12: Vec<f64> = out[12 * i..12 * (i + 1)].iter().map(|v| v.f64()).collect();
        let r_gpu = [0, 1, 2].map(|d| o12[d] + o12[3 + d]);
        let (rad, w_ang, speed) = match &routes[i] {
            Route::Circle {
                radius,
                period,
                advance,
                ..
            } => (
                *radius,
                2.0 * std::f64::consts::PI / period,
                (advance / period).abs(),
            ),
            Route::Line { velocity, .. } => (0.0, 0.0, norm(V3::from_f64(*velocity))),
            Route::Table { t, p } => {
                check_table(&mut wt, p, t, i, t0, tau, o, &o12, s, r);
                continue;
            }
            _ => (0.0, 0.0, 0.0),
        };
        // The rebase time, its angle, the point on the circle there and the origin
        // shift are formed in f64; in the shader only the displacement since the
        // rebase rounds: of size rad w tau (arc) and speed tau (advance). (Rounding
        // the rebase angle itself in f32 would cost rad 2 pi eps, a hundred times
        // more for the short tau of a submission: micrometres on a 20 m circle,
        // tens of newtons in a stiff fairlead element.)
        let r_scale = rad * w_ang * tau + speed * tau + 1e-3 * r.norm();
        let r_scale = if p == Precision::F64 {
            // f64: the CPU's own angle w (t0 + tau) carries |w t| eps.
            r_scale + rad * w_ang * (t0 + tau) + r.norm() + speed * (t0 + tau)
        } else {
            r_scale
        };
        w.v("r", i, &r_gpu, r, r_scale.max(1e-300));
        let v_scale = rad * w_ang * (1.0 + w_ang * (t0 + tau) + 7.0) + speed;
        w.v("v", i, &o12[6..9], V3::from_f64(s.v), v_scale.max(1e-300));
        let a_scale = rad * w_ang * w_ang * (1.0 + w_ang * (t0 + tau) + 7.0);
        w.v("a", i, &o12[9..12], V3::from_f64(s.a), a_scale.max(1e-300));
    }
    w.report(p);
    wt.report(p);
}

/// A table route: 1 to 40 samples, some far apart, some closer than the 0.5 s of tau.
pub(super) fn random_table(rng: &mut ChaCha8Rng) -> Route {
    let n = rng.gen_range(1..=40);
    let fine = rng.gen_bool(0.5);
    let mut t = vec![rng.gen_range(0.0..1500.0)];
    let mut p = vec![rv(rng, 500.0)];
    for _ in 1..n {
        let h = if fine {
            rng.gen_range(0.01..0.3)
        } else {
            rng.gen_range(0.5..60.0)
        };
        t.push(t[t.len() - 1] + h);
        let last = p[p.len() - 1];
        let step = rv(rng, 3.0 * h);
        p.push([0, 1, 2].map(|d| last[d] + step[d]));
    }
    Route::Table { t, p }
}

/// Checks a table route's GPU target against `Route::eval` at `t0 + tau`.
/// Scales: the GPU interpolates in times relative to the rebase time and positions
/// relative to the origin, both as compensated pairs, so its position rounds with the
/// segment's extent `|dp|` and with the time into the segment `u` (times the speed);
/// in f64 the CPU twin's own rounding of absolute coordinates (`|p|`, and `|p| / h` in
/// the velocity) counts too.
#[allow(clippy::too_many_arguments)]
pub(super) fn check_table(
    w: &mut Worst,
    p: &[[f64; 3]],
    t: &[f64],
    i: usize,
    t0: f64,
    tau: f64,
    o: [f64; 3],
    o12: &[f64],
    s: cablesim::model::RouteState,
    r: V3<f64>,
) {
    let tt = t0 + tau;
    let k = t.partition_point(|&x| x <= tt).clamp(1, t.len().max(2) - 1);
    let (dp, h, u) = if t.len() > 1 {
        let dp = V3::from_f64(p[k]) - V3::from_f64(p[k - 1]);
        (dp.norm(), t[k] - t[k - 1], (tt - t[k - 1]).abs())
    } else {
        (0.0, 1.0, 0.0)
    };
    let speed = norm(V3::from_f64(s.v));
    let f64_terms = if w.eps < 1e-10 {
        norm(V3::from_f64(p[k.min(p.len() - 1)])) + norm(V3::from_f64(o))
    } else {
        0.0
    };
    let r_gpu = [0, 1, 2].map(|d| o12[d] + o12[3 + d]);
    let r_scale = dp + speed * (u + h + tau) + 1e-3 * r.norm() + f64_terms;
    w.v("table r", i, &r_gpu, r, r_scale.max(1e-300));
    let v_scale = speed + f64_terms / h;
    w.v(
        "table v",
        i,
        &o12[6..9],
        V3::from_f64(s.v),
        v_scale.max(1e-300),
    );
    w.v("table a", i, &o12[9..12], V3::from_f64(s.a), 1e-300);
}

pub(super) fn check_current<R: GpuReal>(ctx: &GpuContext, p: Precision, rng: &mut ChaCha8Rng) {
    let r = |x: f64| R::c(x).f64();
    let profiles = vec![
        Current::default(),
        Current::uniform([r(0.3), r(-0.2), r(0.05)]),
        Current {
            table: vec![
                (r(-100.0), [r(0.1), r(0.0), r(0.0)]),
                (r(-50.0), [r(0.4), r(0.2), r(0.0)]),
                (r(-10.0), [r(0.7), r(0.25), r(0.01)]),
                (r(0.0), [r(0.8), r(0.3), r(0.0)]),
            ],
        },
    ];
    let mut pts = Vec::new();
    let mut ranges = Vec::new();
    for c in &profiles {
        ranges.push(CurrentRange {
            start: pts.len() as u32,
            len: c.table.len() as u32,
        });
        for (z, u) in &c.table {
            pts.push(CurrentPoint::<R> {
                z: R::c(*z),
                ux: R::c(u[0]),
                uy: R::c(u[1]),
                uz: R::c(u[2]),
            });
        }
    }
    let n = 600;
    let mut x = Vec::new();
    for i in 0..n {
        x.push((i % 3) as f64);
        x.push(rng.gen_range(-130.0..20.0));
    }
    let (xr, x) = to_r::<R>(&x);
    let out = run::<R>(
        ctx,
        p,
        "t_current",
        &[
            (8, bytemuck::cast_slice(&pts).to_vec()),
            (9, bytemuck::cast_slice(&ranges).to_vec()),
        ],
        &xr,
        n,
        3 * n,
    );
    let mut w = Worst::new::<R>("current_at");
    for i in 0..n {
        let u = profiles[x[2 * i] as usize].at::<f64>(x[2 * i + 1]);
        let o: Vec<f64> = out[3 * i..3 * i + 3].iter().map(|v| v.f64()).collect();
        // The slope times the height's scale bounds the interpolation's rounding.
        w.v("u", i, &o, u, 1.0 + 0.01 * x[2 * i + 1].abs());
    }
    w.report(p);
}
