//! Screen-model net loads on the CPU path (docs/src/model/screen.md): each panel's
//! force (`physics::screen_panel_force`) is formed once per step from the state at the
//! start of the step ([`BlockPanels::panel_forces`]), then each knot gathers a quarter
//! of each panel it is a corner of, in a fixed order ([`BlockPanels::gather`]), for the
//! general passes ([`super::passes`]) and the network fast path ([`super::chain`]).
//! The GPU path computes the same per knot (`screen_knot_force` in WGSL).

use super::water::node_water;
use crate::math::V3;
use crate::model::screen::knot_panels;
use crate::model::Layout;
use crate::physics::{screen_panel_force, ScreenCoefs};

type V = V3<f64>;

/// No panel (a knot at the edge of its net has fewer than four).
const NO_PANEL: u32 = u32::MAX;

/// The panels of the screen-net knots of a block of nodes, each once: what the knots
/// of a panel would each form alike (the same corners in the same order,
/// `model::screen::KNOT_PANELS`) is formed by one pass over the panels, and every knot
/// then adds a quarter of each of its panels in the order [`knot_panels`] gives them,
/// so the sums are those of forming the panels knot by knot, bit for bit.
#[derive(Clone, Debug, Default)]
pub(crate) struct BlockPanels {
    /// Per panel: its corners (block-local nodes), its net, the current of its first
    /// corner's cable.
    corners: Vec<[u32; 4]>,
    net: Vec<u32>,
    current: Vec<u32>,
    /// Per knot, by node: its block-local node and its panels (indices into
    /// `corners`, [`NO_PANEL`] where it has fewer than four).
    knots: Vec<(u32, [u32; 4])>,
    /// The runs of panels of one net: `(first, end, net)`.
    runs: Vec<(usize, usize, u32)>,
}

/// Columns of [`PanelScratch::cols`]: the corners' positions and velocities, the water.
const PCOLS: usize = 27;

/// The panel pass's scratch: the panels' inputs as columns (a panel per entry), so that
/// the force loop runs over several panels at once, and their forces.
#[derive(Clone, Debug, Default)]
pub(crate) struct PanelScratch {
    /// Column `q` of panel `j` at `q np + j`: corner `k`'s position `x, y, z` in columns
    /// `3 k ..`, its velocity in `12 + 3 k ..`, the water's velocity in 24, 25, 26.
    cols: Vec<f64>,
    /// Each panel's force, `x`, `y`, `z`.
    f: [Vec<f64>; 3],
}

impl PanelScratch {
    /// Panel `j`'s force.
    #[inline(always)]
    fn force(&self, j: usize) -> V {
        V::new(self.f[0][j], self.f[1][j], self.f[2][j])
    }
}

impl BlockPanels {
    /// The panels of the screen knots whose nodes are in `n0..n1`; every corner of
    /// their panels is in the block (a net is one block).
    pub(crate) fn new(lay: &Layout, n0: usize, n1: usize) -> Self {
        let knots = lay.screen.knots_in(n0 as u32, n1 as u32);
        let mut bp = Self::default();
        // Panel of each (corners, net): found by the knot that lists it first. A
        // knot's panels are owned by the knots to its upper left (the first corner of
        // its cells), so a panel is looked up among at most four candidates.
        let mut index = std::collections::HashMap::with_capacity(knots.len());
        for k in knots {
            let mut ps = [NO_PANEL; 4];
            for (q, c) in knot_panels(k).enumerate() {
                assert!(c.iter().all(|&i| (n0..n1).contains(&(i as usize))));
                let local = c.map(|i| i - n0 as u32);
                let next = bp.corners.len() as u32;
                let j = *index.entry((local, k.net)).or_insert(next);
                if j == next {
                    bp.corners.push(local);
                    bp.net.push(k.net);
                    bp.current.push(lay.node_current[c[0] as usize]);
                }
                ps[q] = j;
            }
            bp.knots.push((k.node - n0 as u32, ps));
        }
        let mut j = 0;
        while j < bp.net.len() {
            let e = j + bp.net[j..].iter().take_while(|&&k| k == bp.net[j]).count();
            bp.runs.push((j, e, bp.net[j]));
            j = e;
        }
        bp
    }

    /// Whether it holds no knot.
    pub(crate) fn is_empty(&self) -> bool {
        self.knots.is_empty()
    }

    /// Each panel's force, into `sc` (resized), from its corners' positions `pos(i)`,
    /// velocities `vel(i)` and wave velocities `wave(i)` (`None` in still water; `i`
    /// block-local). The water at a panel is the current at the height of its centre
    /// plus the mean of its corners' wave velocities. The inputs are gathered panel by
    /// panel into columns, then [`screen_panel_force`] runs over them in a loop that
    /// vectorises (its branches turned into selects: the same arithmetic per panel).
    #[inline]
    pub(crate) fn panel_forces(
        &self,
        lay: &Layout,
        sc: &mut PanelScratch,
        pos: impl Fn(usize) -> V,
        vel: impl Fn(usize) -> V,
        wave: impl Fn(usize) -> Option<[f64; 3]>,
    ) {
        let np = self.corners.len();
        sc.cols.resize(PCOLS * np, 0.0);
        for f in &mut sc.f {
            f.resize(np, 0.0);
        }
        let cols = &mut sc.cols;
        for (j, c) in self.corners.iter().enumerate() {
            let current = &lay.currents[self.current[j] as usize];
            let p = c.map(|i| pos(i as usize));
            let v = c.map(|i| vel(i as usize));
            let zc = 0.25 * (p[0].z + p[1].z + p[2].z + p[3].z);
            let mut u = current.at(zc);
            let mut uw = V::zero();
            for &i in c {
                if let Some(w) = wave(i as usize) {
                    uw += V::from_f64(w);
                }
            }
            u += uw * 0.25;
            for k in 0..4 {
                for (q, x) in [p[k].x, p[k].y, p[k].z].into_iter().enumerate() {
                    cols[(3 * k + q) * np + j] = x;
                }
                for (q, x) in [v[k].x, v[k].y, v[k].z].into_iter().enumerate() {
                    cols[(12 + 3 * k + q) * np + j] = x;
                }
            }
            for (q, x) in [u.x, u.y, u.z].into_iter().enumerate() {
                cols[(24 + q) * np + j] = x;
            }
        }
        let rho = lay.env.water_density;
        for &(a, e, net) in &self.runs {
            let co = lay.screen.nets[net as usize].coefs(rho, [0.0, 0.0]);
            let input: [&[f64]; PCOLS] = std::array::from_fn(|q| &sc.cols[q * np + a..q * np + e]);
            let [fx, fy, fz] = sc.f.each_mut().map(|f| &mut f[a..e]);
            panel_run(&co, input, fx, fy, fz);
        }
    }

    /// Each knot's force: a quarter of each of its panels' (`sc`, from
    /// [`BlockPanels::panel_forces`]), into `out` as `(block-local node, force)`
    /// sorted by node; cleared first.
    #[inline]
    pub(crate) fn gather<F>(
        &self,
        sc: &PanelScratch,
        out: &mut Vec<(usize, F)>,
        conv: impl Fn(V) -> F,
    ) {
        out.clear();
        for &(node, ps) in &self.knots {
            let mut f = V::zero();
            for j in ps {
                if j != NO_PANEL {
                    f += sc.force(j as usize) * 0.25;
                }
            }
            out.push((node as usize, conv(f)));
        }
    }
}

/// The screen forces on the knots of the block of nodes `n0..n0 + r.len()` (block-local
/// `r`, `v`, water `w` as [`node_water`] reads it, empty in still water), into `out`
/// as `(block-local node, force)` sorted by node; cleared first. The general passes'
/// entry: the block's panels are found anew at each call ([`BlockPanels::new`]).
pub(crate) fn screen_block_forces(
    lay: &Layout,
    n0: usize,
    r: &[V],
    v: &[V],
    w: &[f64],
    out: &mut Vec<(usize, V)>,
) {
    let bp = BlockPanels::new(lay, n0, n0 + r.len());
    let mut sc = PanelScratch::default();
    bp.panel_forces(
        lay,
        &mut sc,
        |i| r[i],
        |i| v[i],
        |i| (!w.is_empty()).then(|| node_water(w, i).1),
    );
    bp.gather(&sc, out, |f| f);
}

/// The whole screen-model load on the panels whose corners are all among the packed
/// nodes `knots` (one net's), from the packed positions `r` and velocities `v` in the
/// current alone (no waves): the sum of every panel's force, that is of its knots'
/// quarters. Zero where the knots are no screen net's. The nets' drag of `nets.csv`
/// (`crate::output::net_states`), alike on both paths (from the state read back).
pub(crate) fn screen_net_force(
    lay: &Layout,
    r: &[[f64; 3]],
    v: &[[f64; 3]],
    knots: &[usize],
) -> [f64; 3] {
    let Some(&k0) = knots.first() else {
        return [0.0; 3];
    };
    if lay.screen.knots_in(k0 as u32, k0 as u32 + 1).is_empty() {
        return [0.0; 3];
    }
    let Some(b) = lay
        .blocks
        .iter()
        .find(|b| (b.node_start as usize..b.node_end as usize).contains(&k0))
    else {
        return [0.0; 3];
    };
    let (n0, n1) = (b.node_start as usize, b.node_end as usize);
    let bp = BlockPanels::new(lay, n0, n1);
    let mut sc = PanelScratch::default();
    bp.panel_forces(
        lay,
        &mut sc,
        |i| V::from_f64(r[n0 + i]),
        |i| V::from_f64(v[n0 + i]),
        |_| None,
    );
    let mine: std::collections::HashSet<usize> = knots.iter().copied().collect();
    let mut f = V::zero();
    for (j, c) in bp.corners.iter().enumerate() {
        if c.iter().all(|&i| mine.contains(&(n0 + i as usize))) {
            f += sc.force(j);
        }
    }
    f.to_f64()
}

/// [`screen_panel_force`] over a run of panels of one net (`input`: the columns of
/// [`PanelScratch::cols`] for the run), into `fx`, `fy`, `fz`: the coefficient set and
/// the wake rule made constants, so that the loop has no branch the vectoriser cannot
/// turn into selects, in the widest vectors the CPU has.
fn panel_run(
    co: &ScreenCoefs<f64>,
    input: [&[f64]; PCOLS],
    fx: &mut [f64],
    fy: &mut [f64],
    fz: &mut [f64],
) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, checked just above.
        return unsafe { panel_run_avx2(co, input, fx, fy, fz) };
    }
    panel_run_any(co, input, fx, fy, fz)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn panel_run_avx2(
    co: &ScreenCoefs<f64>,
    input: [&[f64]; PCOLS],
    fx: &mut [f64],
    fy: &mut [f64],
    fz: &mut [f64],
) {
    panel_run_any(co, input, fx, fy, fz)
}

#[inline(always)]
fn panel_run_any(
    co: &ScreenCoefs<f64>,
    input: [&[f64]; PCOLS],
    fx: &mut [f64],
    fy: &mut [f64],
    fz: &mut [f64],
) {
    use crate::physics::screen::{
        SCREEN_AARSNES as A, SCREEN_KRISTIANSEN_FALTINSEN as K, SCREEN_LOLAND as L,
        WAKE_CHENG as C, WAKE_LOLAND as WL, WAKE_NONE as N,
    };
    macro_rules! pick {
        ($(($m:ident, $w:ident)),*) => {
            match (co.model, co.wake) {
                $(($m, $w) => panel_loop::<$m, $w>(co, input, fx, fy, fz),)*
                _ => unreachable!("screen model {} wake {}", co.model, co.wake),
            }
        };
    }
    pick!(
        (A, N),
        (A, WL),
        (A, C),
        (L, N),
        (L, WL),
        (L, C),
        (K, N),
        (K, WL),
        (K, C)
    )
}

/// The loop of [`panel_run`] for coefficient set `M` and wake rule `W`.
#[inline(always)]
fn panel_loop<const M: u32, const W: u32>(
    co: &ScreenCoefs<f64>,
    input: [&[f64]; PCOLS],
    fx: &mut [f64],
    fy: &mut [f64],
    fz: &mut [f64],
) {
    let co = ScreenCoefs {
        model: M,
        wake: W,
        ..*co
    };
    let n = fx.len();
    let (fy, fz) = (&mut fy[..n], &mut fz[..n]);
    let c: [&[f64]; PCOLS] = input.map(|q| &q[..n]);
    for j in 0..n {
        let p = [0, 1, 2, 3].map(|k| V::new(c[3 * k][j], c[3 * k + 1][j], c[3 * k + 2][j]));
        let v = [0, 1, 2, 3].map(|k| V::new(c[12 + 3 * k][j], c[13 + 3 * k][j], c[14 + 3 * k][j]));
        let u = V::new(c[24][j], c[25][j], c[26][j]);
        let f = screen_panel_force(&co, p, v, u);
        fx[j] = f.x;
        fy[j] = f.y;
        fz[j] = f.z;
    }
}
