//! The finite-depth dispersion relation of linear waves, `w^2 = g k tanh(k h)`.

/// Wave number `k`, rad/m, of a linear wave of angular frequency `omega` (rad/s) in
/// water of depth `depth` (m; `f64::INFINITY` for deep water) under gravity `g`
/// (m/s^2), solved to round-off.
///
/// In the variable `y = k h` the relation is `y tanh(y) = a` with `a = w^2 h / g`.
/// Newton's method starts from Eckart's estimate `y0 = a / sqrt(tanh(a))` (within 5%
/// everywhere: exact in both limits), and stops when the step is at round-off; it
/// converges in three to five iterations. Where `tanh(y)` is 1 to round-off
/// (`y > 19`, `a > 19`) the deep-water `k = w^2 / g` is already exact; in shallow water
/// the start tends to the long-wave `k = w / sqrt(g h)`.
pub fn wave_number(omega: f64, depth: f64, g: f64) -> f64 {
    let k_deep = omega * omega / g;
    let a = k_deep * depth;
    if !(a < 19.0) {
        // Deep water (also `depth = inf`): tanh(k h) = 1 in f64.
        return k_deep;
    }
    if a <= 0.0 {
        return 0.0;
    }
    let mut y = a / a.tanh().sqrt();
    for _ in 0..50 {
        let t = y.tanh();
        // f(y) = y tanh(y) - a, f'(y) = tanh(y) + y (1 - tanh(y)^2).
        let f = y * t - a;
        let df = t + y * (1.0 - t * t);
        let step = f / df;
        y -= step;
        if step.abs() <= 2.0 * f64::EPSILON * y {
            break;
        }
    }
    y / depth
}

/// Wave number of a period `period` (s): `wave_number(2 pi / period, ...)`.
pub fn wave_number_of_period(period: f64, depth: f64, g: f64) -> f64 {
    wave_number(2.0 * std::f64::consts::PI / period, depth, g)
}
