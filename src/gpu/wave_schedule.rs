//! The host's side of the waves on the GPU: one kinematics-cache schedule per sea
//! ([`WaveSchedule`], [`SeaSchedules`]) with a clock per depth band (`sea::bands`) on
//! the same refresh grid as the CPU path (`sea::schedule`), and how a submission of
//! the fused kernel is cut into dispatches at the refresh steps ([`fused_segments`],
//! [`fused_max_steps`]).
//!
//! Split out of `solver.rs` so that the refresh schedule, which decides where the
//! fused kernel's dispatches end, reads in one place with its unit tests.

use super::kernel::STEPS_PER_SUBMISSION;
use super::layout::*;
use crate::model::{Layout, Route};
use crate::sea::bands::{BandPlan, BAND_LOOK_AHEAD, MAX_BANDS};
use crate::sea::cache::hermite_weights;
use crate::sea::kinematics::{wave_ramp, wave_ramp_rate, WaveField};
use crate::sea::schedule::{RefreshClock, Tick};
use crate::sea::{SeaSet, SeaState, Stretching, GPU_DEEP};

// A step row carries the tops of bands 1 to 6 (`WaveStep::top1` to `top6`, WGSL
// `wave_step_tops`): more bands would need more.
const _: () = assert!(MAX_BANDS <= 7, "WaveStep carries the tops of bands 1 to 6");

/// Scalars per node and cache slot on the GPU: the values `eta, u, a` and their rates
/// along the node's path (`WAVE_CACHE_STRIDE` in `shaders/shared/waves.wgsl`); after
/// the two slots, three per node: its velocity at the last refresh; then one per
/// node: its depth band; then one per node: its breaches (`sea::bands`).
pub(super) const WAVE_CACHE_STRIDE: usize = 14;

/// Scalars per element after the nodes' part of the cache (`WAVE_ELEM_STRIDE` in
/// `shaders/shared/waves.wgsl`): its band (or the mark of an element across a band
/// top). Its entry is in a buffer of its own ([`WAVE_ELEM_ROWS`]).
pub(super) const WAVE_ELEM_STRIDE: usize = 1;

/// `vec4` rows per element of the elements' cache (`wave_elems`, `WAVE_ELEM_ROWS` in
/// `shaders/shared/waves.wgsl`): the surface over its two nodes and the mean of their
/// wave velocity and acceleration, values and rates at both times (4 sides of two
/// rows), then, for an element across a band top, node b's velocity and acceleration
/// on the four sides (six rows). Rows, not scalars, because on a software adapter
/// (lavapipe) each storage load is a loop over the SIMD lanes whatever its width.
pub(super) const WAVE_ELEM_ROWS: usize = 14;

/// Scalars per entry of the refresh's work list, at most two entries per node, after
/// the nodes' beyond-margin records (`WAVE_DUE_STRIDE` in
/// `shaders/shared/waves.wgsl`): the node, which evaluation, the position and the
/// velocity to evaluate at.
pub(super) const WAVE_DUE_STRIDE: usize = 8;

/// The most nodes a layout in waves may have: the work list stores node indices as
/// scalars of the run's precision, exact in f32 below 2^24.
pub(super) const WAVE_MAX_NODES: usize = 1 << 24;

/// The host's side of the waves' kinematics cache: the components (rebased at each
/// submission) and when each depth band's two times are (`sea::bands`): the same
/// [`RefreshClock`]s as the CPU path's `sea::cache::WaveCache`, on the same grid
/// (`sea::schedule`), so that both refresh the same nodes at the same steps and
/// interpolate with the same Hermite weights, and the same band plan (tops, look-ahead),
/// so that the shader's `wave_band` puts each node in the band the CPU path does.
pub(super) struct WaveSchedule {
    pub(super) field: WaveField,
    /// Its first component in the components buffer.
    pub(super) first: u32,
    /// Per band: the band's times and refresh grid (nested rungs).
    pub(super) clocks: Vec<RefreshClock>,
    /// Per band: the highest height its nodes may reach, m (`tops[0]` infinite).
    tops: Vec<f64>,
    /// How far ahead a decision into band 0 looks, s (into band `m`, `2^m` times it:
    /// `sea::bands::wave_band`).
    look0: f64,
}

impl WaveSchedule {
    pub(super) fn new(sea: &SeaState, first: u32, plan: &BandPlan) -> Self {
        Self {
            field: WaveField::new(sea),
            first,
            clocks: (0..plan.len())
                .map(|m| RefreshClock::on_grid(&plan.band(m)))
                .collect(),
            tops: plan.tops.clone(),
            look0: BAND_LOOK_AHEAD * plan.band(0).interval,
        }
    }

    /// The number of depth bands (rows per step).
    pub(super) fn n_bands(&self) -> usize {
        self.clocks.len()
    }

    /// The row of constants every step and band shares.
    pub(super) fn base<R: GpuReal>(&self) -> WaveStep<R> {
        let top = |m: usize| R::c(self.tops.get(m).copied().unwrap_or(f64::NEG_INFINITY));
        WaveStep {
            n: self.field.comps.len() as u32,
            first: self.first,
            stretching: match self.field.stretching {
                Stretching::Wheeler => 0,
                Stretching::Constant => 1,
            },
            depth: R::c(if self.field.depth.is_finite() {
                self.field.depth
            } else {
                GPU_DEEP
            }),
            slot0: 0,
            slot1: 1,
            n_bands: self.n_bands() as u32,
            band_rows: STEPS_PER_SUBMISSION,
            look0: R::c(if self.look0.is_finite() {
                self.look0
            } else {
                0.0
            }),
            top1: top(1),
            top2: top(2),
            top3: top(3),
            top4: top(4),
            top5: top(5),
            top6: top(6),
            ..Default::default()
        }
    }

    /// The rows of the step at time `t` (s; phases referred to `t_ref`), band `m`'s
    /// at `rows[m * STEPS_PER_SUBMISSION]`, refreshing the bands the CPU path's cache
    /// would (`sea::cache::WaveCache::refresh_if_due`: nothing while band 0 covers
    /// `t`; every band restarts when band 0 would; when bands `0..=M` refresh, `M >
    /// 0`, the decision of their nodes' bands among them). Returns whether some band
    /// refreshes.
    pub(super) fn step<R: GpuReal>(
        &mut self,
        t: f64,
        t_ref: f64,
        rows: &mut [WaveStep<R>],
    ) -> bool {
        let nb = self.n_bands();
        let mut ticks: [Option<Tick>; MAX_BANDS] = [None; MAX_BANDS];
        if !self.clocks[0].covers(t) {
            if self.clocks[0].would_restart(t) {
                self.clocks.iter_mut().for_each(RefreshClock::reset);
            }
            for (m, c) in self.clocks.iter_mut().enumerate() {
                ticks[m] = c.tick(t);
            }
        }
        let restart = ticks[0].is_some_and(|k| k.restart);
        // The coarsest band refreshing now (every band up to it does): the nodes of
        // the bands that refresh are decided among them, as on the CPU path.
        let coarsest = ticks.iter().take(nb).rposition(Option::is_some);
        let decide = match coarsest {
            Some(m) if m > 0 && !restart => m as u32 + 1,
            _ => 0,
        };
        let watch = nb > 1 && !restart && ticks[0].is_some();
        let ramp = self.field.ramp_duration;
        let per = STEPS_PER_SUBMISSION as usize;
        for (m, tick) in ticks.iter().take(nb).enumerate() {
            let mut row = self.base::<R>();
            row.decide = decide;
            row.watch = watch as u32;
            let clock = &self.clocks[m];
            if let Some(tick) = tick {
                row.refresh = 1;
                row.track = 1;
                row.acc_rate = R::c(tick.acc_rate);
                if tick.restart {
                    row.restart = 1;
                    row.tau0 = R::c(t - t_ref);
                    row.ramp0 = R::c(wave_ramp(t, ramp));
                    row.ramp_rate0 = R::c(wave_ramp_rate(t, ramp));
                }
                let t1 = clock.t1;
                row.ahead = R::c(tick.ahead);
                row.tau1 = R::c(t1 - t_ref);
                row.ramp1 = R::c(wave_ramp(t1, ramp));
                row.ramp_rate1 = R::c(wave_ramp_rate(t1, ramp));
            }
            let (t0, t1) = (clock.t0, clock.t1);
            let delta = t1 - t0;
            let s = ((t - t0) / delta).clamp(0.0, 1.0);
            let w = hermite_weights(s, delta);
            row.w = [R::c(w[0]), R::c(w[1]), R::c(w[2]), R::c(w[3])];
            rows[m * per] = row;
        }
        ticks[0].is_some()
    }
}

/// The waves of a run: one schedule per sea (`sea::set`), their components back to
/// back in the components buffer, and `STEPS_PER_SUBMISSION` rows per sea and depth
/// band in the rows buffer (sea `q`'s band `m` at `(row_start[q] + m) *
/// STEPS_PER_SUBMISSION`). Each sea refreshes on its own schedule, as its blocks'
/// caches do on the CPU path.
pub struct SeaSchedules {
    /// Per sea: its schedule (`None`: still water, rows of zeros).
    pub(super) seas: Vec<Option<WaveSchedule>>,
    /// Per cable: its sea (empty: all in sea 0).
    pub(super) cable_sea: Vec<u32>,
    /// Components of every sea.
    pub(super) n_comps: usize,
    /// Per sea: its first band's row block (in units of `STEPS_PER_SUBMISSION` rows).
    pub(super) row_start: Vec<u32>,
    /// Row blocks of every sea and band (at least one).
    pub(super) n_row_blocks: usize,
}

impl SeaSchedules {
    /// The schedules of `set`'s seas stepping by `dt` (each on its own
    /// [`SeaSet::band_plan`], as the CPU path's caches).
    pub fn new(set: &SeaSet, dt: f64) -> Self {
        let mut first = 0u32;
        let seas = set
            .seas
            .iter()
            .enumerate()
            .map(|(q, sea)| {
                (!sea.is_still()).then(|| {
                    let w = WaveSchedule::new(sea, first, &set.band_plan(q, dt));
                    first += sea.components.len() as u32;
                    w
                })
            })
            .collect::<Vec<_>>();
        let mut row_start = Vec::with_capacity(seas.len());
        let mut next = 0u32;
        for w in &seas {
            row_start.push(next);
            next += w.as_ref().map_or(1, |w| w.n_bands() as u32);
        }
        Self {
            seas,
            cable_sea: set.cable_sea.clone(),
            n_comps: first as usize,
            row_start,
            n_row_blocks: (next as usize).max(1),
        }
    }

    /// Rows of every sea and band for `n` steps from time `t_of(0)`: `rows` (of
    /// `n_row_blocks * STEPS_PER_SUBMISSION`) filled, and which steps refresh some
    /// band of some sea.
    pub fn rows<R: GpuReal>(
        &mut self,
        n: usize,
        t_of: impl Fn(usize) -> f64,
        t_ref: f64,
    ) -> (Vec<WaveStep<R>>, Vec<bool>) {
        let per = STEPS_PER_SUBMISSION as usize;
        let mut rows = vec![WaveStep::<R>::default(); self.n_row_blocks * per];
        let mut refresh = vec![false; n];
        for (q, sea) in self.seas.iter_mut().enumerate() {
            let Some(sea) = sea else { continue };
            let r0 = self.row_start[q] as usize * per;
            for (k, r) in refresh.iter_mut().enumerate() {
                *r |= sea.step::<R>(t_of(k), t_ref, &mut rows[r0 + k..]);
            }
        }
        (rows, refresh)
    }

    /// The first row of the sea of the block starting at packed node `n0`.
    pub(super) fn block_rows(&self, lay: &Layout, n0: u32) -> u32 {
        let c = lay.node_cable.get(n0 as usize).copied().unwrap_or(0) as usize;
        let q = self.cable_sea.get(c).copied().unwrap_or(0) as usize;
        self.row_start.get(q).copied().unwrap_or(0) * STEPS_PER_SUBMISSION
    }

    /// Starts every cache afresh (after a remesh, as the CPU path's caches do).
    pub(super) fn restart(&mut self) {
        for w in self.seas.iter_mut().flatten() {
            w.clocks.iter_mut().for_each(RefreshClock::reset);
        }
    }
}

/// The fused kernel's dispatches of a submission, as step ranges `a .. b`: a new one
/// starts at every step that refreshes the waves' cache (`refresh[k]`), after a
/// `wave_refresh` dispatch, and after at most `max_len` steps. Why: on llvmpipe
/// (lavapipe) all the loops of a shader invocation share one budget of 65535
/// iterations, after which each loop stops after one iteration without a word
/// (`shaders/fused_chain.wgsl`). The refresh's sums over the wave components spent it
/// within a submission, so the fused kernel does not refresh; `max_len`
/// ([`fused_max_steps`]) keeps the loops of its steps within it.
pub fn fused_segments(refresh: &[bool], max_len: u64) -> Vec<(u64, u64)> {
    let n = refresh.len() as u64;
    let max_len = max_len.max(1);
    let mut segs = Vec::new();
    let mut a = 0;
    for k in 1..=n {
        if k == n || refresh[k as usize] || k - a == max_len {
            segs.push((a, k));
            a = k;
        }
    }
    segs
}

/// The most steps one fused dispatch may take on this layout: half of llvmpipe's
/// budget of 65535 loop iterations per shader invocation over an upper bound of one
/// step's iterations (the step loop, a node's incidence list, the linear search of the
/// longest current profile, the binary search of the longest route table). 512 steps
/// (a whole submission) fit unless a current profile has more than some 50 points.
pub(super) fn fused_max_steps(lay: &Layout) -> u64 {
    const LOOP_BUDGET: u64 = 65535 / 2;
    let incidence = lay
        .inc_start
        .windows(2)
        .map(|w| w[1] - w[0])
        .max()
        .unwrap_or(0) as u64;
    let profile = lay
        .currents
        .iter()
        .map(|c| c.table.len())
        .max()
        .unwrap_or(0) as u64;
    let table = lay
        .routes
        .iter()
        .map(|r| match r {
            Route::Table { t, .. } => t.len(),
            _ => 0,
        })
        .max()
        .unwrap_or(0) as u64;
    let search = 64 - table.leading_zeros() as u64 + 1;
    let per_step = 1 + incidence + profile + search;
    (LOOP_BUDGET / per_step).max(1)
}

/// The most wave components one sea may have on a software adapter (lavapipe,
/// llvmpipe, WARP): a refresh evaluation (`wave_kinematics_rates_tau`, one invocation
/// per node) loops over the components twice (the elevation pass and the decay pass)
/// plus a bisection, and llvmpipe ends every loop of an invocation after its first
/// iteration, silently, once 65,535 iterations are spent.
pub const SOFTWARE_MAX_COMPONENTS: usize = 32_000;

/// Refuses seas the GPU path cannot hold: more components in all than one storage
/// binding of `component_bytes` each holds (`max_storage_buffer_binding_size`), or, on
/// a software adapter (`software`), a sea of more than [`SOFTWARE_MAX_COMPONENTS`].
pub(super) fn check_wave_components(
    seas: &SeaSet,
    component_bytes: u64,
    max_binding: u64,
    software: bool,
) -> Result<(), crate::error::Error> {
    let total: u64 = seas.seas.iter().map(|s| s.components.len() as u64).sum();
    if total * component_bytes > max_binding {
        return Err(crate::error::Error::GpuUnsupported(format!(
            "{total} wave components: the GPU path holds them in one storage buffer of at \
             most {max_binding} bytes on this adapter, {component_bytes} bytes each, so at \
             most {} (use the CPU path, or fewer components)",
            max_binding / component_bytes
        )));
    }
    if software {
        if let Some(n) = seas
            .seas
            .iter()
            .map(|s| s.components.len())
            .find(|&n| n > SOFTWARE_MAX_COMPONENTS)
        {
            return Err(crate::error::Error::GpuUnsupported(format!(
                "a sea of {n} wave components on a software adapter: llvmpipe ends every \
                 loop of a shader invocation once 65,535 iterations are spent, and a refresh \
                 loops over the components twice, so at most {SOFTWARE_MAX_COMPONENTS} (use \
                 the CPU path, a hardware adapter, or fewer components)"
            )));
        }
    }
    Ok(())
}
