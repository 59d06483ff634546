//! Node positions of a cable's initial shape: a straight line, or the solved catenary
//! laid into the vertical plane through the cable's ends.

use super::catenary;

/// `n + 1` points evenly spaced on the segment from `a` to `b` (`n >= 1`).
pub fn straight_positions(a: [f64; 3], b: [f64; 3], n: usize) -> Vec<[f64; 3]> {
    let n = n.max(1);
    (0..=n)
        .map(|k| {
            let f = k as f64 / n as f64;
            [
                a[0] + f * (b[0] - a[0]),
                a[1] + f * (b[1] - a[1]),
                a[2] + f * (b[2] - a[2]),
            ]
        })
        .collect()
}

/// Vertical distance within which the lower end counts as lying on the seabed, m.
pub const SEABED_TOLERANCE: f64 = 1e-3;

/// Initial node positions, `end_a` to `end_b`, of a cable of unstretched `length` cut
/// into `n` equal elements (`L/n` each), following the analytic elastic catenary (with
/// seabed contact) in the vertical plane through its ends. The lower end is the anchor;
/// it lies on the seabed when it is within [`SEABED_TOLERANCE`] of `seabed_z` (or
/// below it). `ea` is the axial stiffness and `w` the wet weight per unit length
/// (`LineType::wet_weight_per_length`). A line slack on the seabed lays its
/// surplus out as a V on the seabed (see
/// [`Catenary::lateral_offset`](super::Catenary::lateral_offset)).
///
/// Falls back to [`straight_positions`] when no hanging catenary applies: a buoyant or
/// neutral line (`w <= 0`), a non-positive length or stiffness, or any other case where
/// [`catenary`] reports an error (which is logged as a warning). The two ends are
/// returned exactly as given.
pub fn catenary_positions(
    end_a: [f64; 3],
    end_b: [f64; 3],
    length: f64,
    n: usize,
    ea: f64,
    w: f64,
    seabed_z: f64,
) -> Vec<[f64; 3]> {
    let n = n.max(1);
    if !(w > 0.0 && length > 0.0 && ea > 0.0) {
        return straight_positions(end_a, end_b, n);
    }
    let a_is_anchor = end_a[2] <= end_b[2];
    let (anchor, fair) = if a_is_anchor {
        (end_a, end_b)
    } else {
        (end_b, end_a)
    };
    let (dx, dy) = (fair[0] - anchor[0], fair[1] - anchor[1]);
    let xf = dx.hypot(dy);
    let zf = fair[2] - anchor[2];
    let (dir, xf) = if xf > 1e-12 * length {
        ([dx / xf, dy / xf], xf)
    } else {
        ([1.0, 0.0], 0.0)
    };
    let side = [-dir[1], dir[0]];
    let on_seabed = anchor[2] <= seabed_z + SEABED_TOLERANCE;
    let cat = match catenary(xf, zf, length, ea, w, on_seabed) {
        Ok(c) => c,
        Err(e) => {
            log::warn!("no catenary initial shape ({e}); using a straight line");
            return straight_positions(end_a, end_b, n);
        }
    };
    let mut out: Vec<[f64; 3]> = (0..=n)
        .map(|k| {
            let s = length * k as f64 / n as f64;
            let s = if a_is_anchor { s } else { length - s };
            let [x, z] = cat.position(s);
            let y = cat.lateral_offset(s);
            [
                anchor[0] + dir[0] * x + side[0] * y,
                anchor[1] + dir[1] * x + side[1] * y,
                anchor[2] + z,
            ]
        })
        .collect();
    out[0] = end_a;
    out[n] = end_b;
    out
}
