//! The device side of a solver at one precision: the [`Engine`] trait that
//! `GpuSolver` holds boxed (f32 or f64) and [`GpuEngine`], its one implementation:
//! stepping (the fused kernel's dispatches or the two-pass kernel's two per step, the
//! status read at the end of each `advance`), state download and upload, kernel and
//! sea changes, re-installing a remeshed layout, and evaluation.
//!
//! Building the pipelines, buffers and bind group and the per-submission writes live
//! in [`install`]. Split out of `solver.rs` (one concept per file; the solver keeps
//! its public API).

use super::context::GpuContext;
use super::host::{split, Host, NodeStates};
use super::kernel::{GpuKernel, FUSED_FAILED, STEPS_PER_SUBMISSION};
use super::layout::*;
use super::wave_schedule::{check_wave_components, fused_segments, SeaSchedules, WAVE_MAX_NODES};
use crate::error::Error;
use crate::model::Layout;
use crate::options::SolverOptions;
use crate::sea::bands::BandCensus;
use crate::sea::SeaSet;
use crate::step::Evaluation;
use std::marker::PhantomData;
use std::time::Instant;

/// Where [`GpuSolver::advance`](super::GpuSolver::advance)'s wall time went, summed over its calls: recording the
/// command buffers on the host, submitting them, and waiting for the device at the end
/// of each call (the one read-back of the status). The device runs while the host
/// records the next submission, so `wait_seconds` is the device time the host could
/// not hide; on a software adapter (lavapipe) the "device" is the same CPU cores.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GpuTimings {
    /// Steps taken.
    pub steps: u64,
    /// Compute dispatches recorded (two per step on the two-pass path, one per
    /// submission on the fused path).
    pub dispatches: u64,
    /// Command buffers submitted.
    pub submissions: u64,
    /// Recording (route and parameter writes, encoding the dispatches), s.
    pub encode_seconds: f64,
    /// `Queue::submit`, s.
    pub submit_seconds: f64,
    /// Waiting for the device and reading the status back, s.
    pub wait_seconds: f64,
    /// All of `advance`, s.
    pub advance_seconds: f64,
}

mod install;

/// The device side of a solver at one precision.
pub(super) trait Engine: Send {
    /// Runs `n` steps from step `step0`; `Some((step, node))` names the first blow-up
    /// (`step` counted from `step0`).
    fn advance(
        &mut self,
        lay: &Layout,
        host: &Host,
        step0: u64,
        n: u64,
    ) -> Result<Option<(u64, u32)>, Error>;
    /// Reads positions and velocities back (absolute positions).
    fn download(&mut self, host: &Host) -> Result<NodeStates, Error>;
    /// Writes positions and velocities.
    fn upload(&mut self, host: &Host, r: &[[f64; 3]], v: &[[f64; 3]]);
    /// Writes the elements' internal states (viscoelastic lines, packed element order).
    fn write_visco(&mut self, x: &[f64]);
    /// Reads the elements' internal states back.
    fn read_visco(&mut self) -> Result<Vec<f64>, Error>;
    /// Starts the waves' kinematics cache afresh at the next step (after the state was
    /// put back to an earlier time).
    fn restart_waves(&mut self);
    /// Per depth band, its nodes now; and the breaches counted (`sea::bands`).
    fn wave_band_census(&self) -> Result<BandCensus, Error>;
    /// Loads, accelerations and reactions at step `step`.
    fn evaluate(&mut self, lay: &Layout, host: &Host, step: u64) -> Result<Evaluation, Error>;
    /// Where the host's time went in `advance` so far.
    fn timings(&self) -> GpuTimings;
    /// The kernel `advance` uses.
    fn kernel(&self) -> GpuKernel;
    /// Why the fused kernel cannot step the current layout, or `None`.
    fn fused_unavailable(&self) -> Option<&str>;
    /// Chooses the kernel (`Fused` only when available).
    fn set_kernel(&mut self, k: GpuKernel) -> Result<(), Error>;
    /// Runs in `seas` from now on (still water without components), keeping the state.
    fn set_seas(&mut self, lay: &Layout, host: &Host, seas: &SeaSet) -> Result<(), Error>;
    /// The free bodies' and line failures' records (values of `body_rows` from
    /// `free_at`, as f64) and the reactions' flags (one per route): what a checkpoint
    /// keeps and the host reads after each `advance`.
    fn read_free(&mut self) -> Result<(Vec<f64>, Vec<f64>), Error>;
    /// Writes back what [`Engine::read_free`] read.
    fn write_free(&mut self, rec: &[f64], flags: &[f64]);
    /// Writes the line failures' records (values from `fail_at`), `n` of them.
    fn write_failures(&mut self, rec: &[f64], n: usize);
    /// Where the line failures' records start, relative to the free bodies'.
    fn fail_offset(&self) -> usize;
    /// Replaces the layout (after a remeshing) with state `r`, `v`.
    fn install(
        &mut self,
        lay: &Layout,
        host: &Host,
        r: &[[f64; 3]],
        v: &[[f64; 3]],
    ) -> Result<(), Error>;
}

struct Buffers {
    params: wgpu::Buffer,
    step: wgpu::Buffer,
    routes: wgpu::Buffer,
    state: wgpu::Buffer,
    elem_loads: wgpu::Buffer,
    node_out: wgpu::Buffer,
    reactions: wgpu::Buffer,
    status: wgpu::Buffer,
    payout: wgpu::Buffer,
    body_rows: wgpu::Buffer,
    wave_comps: wgpu::Buffer,
    wave_steps: wgpu::Buffer,
    staging: wgpu::Buffer,
}

pub(super) struct GpuEngine<R: GpuReal> {
    ctx: GpuContext,
    opts: SolverOptions,
    /// The layout's buffers (replaced at each remeshing).
    inst: Installed<R>,
    bgl: wgpu::BindGroupLayout,
    pipe_elem: wgpu::ComputePipeline,
    pipe_node: wgpu::ComputePipeline,
    pipe_eval: wgpu::ComputePipeline,
    pipe_refresh: wgpu::ComputePipeline,
    /// The refresh's evaluations over its work list (`wave_refresh_due`), after it.
    pipe_refresh_due: wgpu::ComputePipeline,
    /// The element part of the refresh (`wave_refresh_elems`), right after it.
    pipe_refresh_elems: wgpu::ComputePipeline,
    /// The free bodies' stage (`free_bodies`), after the node pass of each step.
    pipe_free: wgpu::ComputePipeline,
    /// The line failures' check (`line_failures`), after the bodies.
    pipe_fail: wgpu::ComputePipeline,
    /// The waves (`None`: still water).
    waves: Option<SeaSchedules>,
    /// The fused kernel's pipelines and workgroup size, or why there is none.
    pipe_fused: Result<FusedPipelines, String>,
    /// The layout every pipeline is built with (kept for the fused kernel's waves
    /// pipeline, built when a sea has waves).
    pipe_layout: wgpu::PipelineLayout,
    /// Whether `advance` uses the fused kernel.
    use_fused: bool,
    step_stride: u64,
    /// The time step in f64 (the shaders hold it in `R`; route times are formed in f64).
    dt64: f64,
    /// The run's first breach of a depth band beyond the margin, `[t, z, top]`
    /// (`note_beyond_margin`).
    first_beyond_margin: Option<[f64; 3]>,
    timings: GpuTimings,
    _r: PhantomData<R>,
}

/// The fused kernel's pipelines: one without the waves' code for still water, built
/// with the engine, and one with it, built when a sea with waves is set
/// (`shaders::header_with`: a software adapter pays for a branch no lane takes).
struct FusedPipelines {
    /// The workgroup size (`FUSED_WG`).
    wg: u32,
    still: wgpu::ComputePipeline,
    waves: Option<wgpu::ComputePipeline>,
}

impl FusedPipelines {
    /// The pipeline for a run with waves (`waves`) or in still water.
    fn pick(&self, waves: bool) -> &wgpu::ComputePipeline {
        match (&self.waves, waves) {
            (Some(p), true) => p,
            (None, true) => unreachable!("set_seas builds the waves pipeline with the waves"),
            (_, false) => &self.still,
        }
    }
}

/// Bytes of `v`, or of one zeroed element when `v` is empty (bindings may not be empty).
fn bytes_or_one<T: bytemuck::Pod>(v: &[T]) -> Vec<u8> {
    if v.is_empty() {
        vec![0u8; std::mem::size_of::<T>()]
    } else {
        bytemuck::cast_slice(v).to_vec()
    }
}

/// Refuses a layout in waves with more nodes than the refresh's work list can name
/// (`WAVE_MAX_NODES`).
fn check_wave_nodes(n_nodes: usize) -> Result<(), Error> {
    if n_nodes > WAVE_MAX_NODES {
        return Err(Error::GpuUnsupported(format!(
            "{n_nodes} nodes in waves: the GPU path's waves refresh handles at most {WAVE_MAX_NODES}"
        )));
    }
    Ok(())
}

fn align_up(x: u64, a: u64) -> u64 {
    x.div_ceil(a) * a
}

/// Everything on the device that depends on the layout (rebuilt at each remeshing of
/// a winch cable); the pipelines do not.
struct Installed<R: GpuReal> {
    /// Free and pinned bodies.
    n_free: usize,
    /// Where their records, and the line failures', start in `body_rows` (values).
    free_at: usize,
    fail_at: usize,
    /// Values of `body_rows`.
    body_values: usize,
    params: Params<R>,
    buf: Buffers,
    bind_group: wgpu::BindGroup,
    /// The waves' per-node cache (`shaders/shared/waves.wgsl`).
    wave_cache: wgpu::Buffer,
    n_nodes: usize,
    n_elems: usize,
    /// Invocations of the element pass: the elements, or the nodes where there are
    /// more and some node is a screen net's knot (`element_forces.wgsl`).
    n_elem_threads: usize,
    n_routes: usize,
    n_blocks: usize,
    /// The most steps of one fused dispatch ([`fused_max_steps`](super::wave_schedule::fused_max_steps)).
    fused_max_steps: u64,
}

/// Decodes read-back bytes (the staging copy is not aligned for `T`).
fn decode<T: bytemuck::Pod>(b: &[u8]) -> Vec<T> {
    b.chunks_exact(std::mem::size_of::<T>())
        .map(bytemuck::pod_read_unaligned)
        .collect()
}

fn v3<R: GpuReal>(a: &[R]) -> [f64; 3] {
    [a[0].f64(), a[1].f64(), a[2].f64()]
}

impl<R: GpuReal> Engine for GpuEngine<R> {
    fn advance(
        &mut self,
        lay: &Layout,
        host: &Host,
        step0: u64,
        n: u64,
    ) -> Result<Option<(u64, u32)>, Error> {
        let ctx = &self.ctx.clone();
        ctx.queue.write_buffer(
            &self.inst.buf.status,
            0,
            bytemuck::bytes_of(&Status::default()),
        );
        let dt64 = self.dt64;
        let mut done = 0u64;
        let t_start = Instant::now();
        while done < n {
            let chunk = (n - done).min(STEPS_PER_SUBMISSION as u64);
            let t_enc = Instant::now();
            self.write_routes(lay, host, (step0 + done) as f64 * dt64);
            self.write_payout(host, step0 + done, chunk);
            self.write_bodies(host, step0 + done, chunk);
            let refresh = self.write_waves(step0 + done, chunk);
            self.inst.params.step_base = done as u32;
            self.inst.params.n_steps = chunk as u32;
            ctx.queue.write_buffer(
                &self.inst.buf.params,
                0,
                bytemuck::bytes_of(&self.inst.params),
            );
            let mut enc = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("steps"),
                });
            {
                let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("step"),
                    timestamp_writes: None,
                });
                let bodies = self.inst.n_free > 0 || self.inst.params.n_fail > 0;
                match (&self.pipe_fused, self.use_fused) {
                    (Ok(fused), true) if bodies => {
                        // Free bodies or failures couple the blocks at every step: a
                        // fused dispatch per step, then the bodies and the failures.
                        let pipe = fused.pick(self.waves.is_some());
                        let mut steps = vec![0u8; (chunk * self.step_stride) as usize];
                        for k in 0..chunk {
                            let info = StepInfo {
                                k: k as u32,
                                end: k as u32 + 1,
                                ..Default::default()
                            };
                            let o = (k * self.step_stride) as usize;
                            steps[o..o + 16].copy_from_slice(bytemuck::bytes_of(&info));
                        }
                        ctx.queue.write_buffer(&self.inst.buf.step, 0, &steps);
                        for k in 0..chunk {
                            let off = (k * self.step_stride) as u32;
                            pass.set_bind_group(0, &self.inst.bind_group, &[off]);
                            if refresh[k as usize] {
                                self.dispatch_refresh(&mut pass);
                                self.timings.dispatches += 3;
                            }
                            pass.set_pipeline(pipe);
                            pass.dispatch_workgroups(self.inst.n_blocks as u32, 1, 1);
                            self.dispatch_bodies(&mut pass);
                        }
                    }
                    (Ok(fused), true) => {
                        let pipe = fused.pick(self.waves.is_some());
                        // One workgroup per block, stepping from one refresh of the
                        // waves' cache to the next (all `chunk` steps in still water).
                        for (a, b) in fused_segments(&refresh, self.inst.fused_max_steps) {
                            let off = a * self.step_stride;
                            let info = StepInfo {
                                k: a as u32,
                                end: b as u32,
                                ..Default::default()
                            };
                            ctx.queue.write_buffer(
                                &self.inst.buf.step,
                                off,
                                bytemuck::bytes_of(&info),
                            );
                            pass.set_bind_group(0, &self.inst.bind_group, &[off as u32]);
                            if refresh[a as usize] {
                                self.dispatch_refresh(&mut pass);
                                self.timings.dispatches += 3;
                            }
                            pass.set_pipeline(pipe);
                            pass.dispatch_workgroups(self.inst.n_blocks as u32, 1, 1);
                            self.timings.dispatches += 1;
                        }
                    }
                    _ => {
                        for k in 0..chunk {
                            let off = (k * self.step_stride) as u32;
                            pass.set_bind_group(0, &self.inst.bind_group, &[off]);
                            if refresh[k as usize] {
                                self.dispatch_refresh(&mut pass);
                                self.timings.dispatches += 3;
                            }
                            self.dispatch(&mut pass, &self.pipe_elem, self.inst.n_elem_threads);
                            self.dispatch(&mut pass, &self.pipe_node, self.inst.n_nodes);
                            self.dispatch_bodies(&mut pass);
                        }
                        self.timings.dispatches += 2 * chunk;
                    }
                }
            }
            let cb = enc.finish();
            self.timings.encode_seconds += t_enc.elapsed().as_secs_f64();
            let t_sub = Instant::now();
            ctx.queue.submit([cb]);
            self.timings.submit_seconds += t_sub.elapsed().as_secs_f64();
            self.timings.submissions += 1;
            done += chunk;
        }
        let t_wait = Instant::now();
        let size = std::mem::size_of::<Status>();
        let out = self.read_back(&[(&self.inst.buf.status, size as u64)])?;
        self.timings.wait_seconds += t_wait.elapsed().as_secs_f64();
        self.timings.advance_seconds += t_start.elapsed().as_secs_f64();
        self.timings.steps += n;
        let st: Status = bytemuck::pod_read_unaligned(&out[0][..size]);
        if st.beyond != 0 {
            self.note_beyond_margin(step0, (u32::MAX - st.beyond_step) as u64)?;
        }
        if st.failed & FUSED_FAILED == 0 {
            return Ok((st.failed != 0).then_some((st.step as u64, st.node)));
        }
        // The fused kernel: the earliest failing step of the failing submission and
        // its block; the block stopped there, so its failing node is the first whose
        // state fails the check.
        let k = 0x7fff - ((st.failed >> 16) & 0x7fff);
        let b = &lay.blocks[(0xffff - (st.failed & 0xffff)) as usize];
        let (r, v) = self.download(host)?;
        let bad = |i: usize| {
            !(r[i].iter().all(|x| x.abs() < self.opts.max_distance)
                && v[i].iter().all(|x| x.abs() < self.opts.max_speed))
        };
        let node = (b.node_start..b.node_end)
            .find(|&i| bad(i as usize))
            .unwrap_or(b.node_start);
        Ok(Some((st.step as u64 + k as u64, node)))
    }

    fn timings(&self) -> GpuTimings {
        self.timings
    }

    fn read_free(&mut self) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let body_bytes = (self.inst.body_values.max(1) * std::mem::size_of::<R>()) as u64;
        let react_bytes = (self.inst.n_routes.max(1) * std::mem::size_of::<[R; 4]>()) as u64;
        let out = self.read_back(&[
            (&self.inst.buf.body_rows, body_bytes),
            (&self.inst.buf.reactions, react_bytes),
        ])?;
        let vals: Vec<R> = decode(&out[0]);
        let react: Vec<[R; 4]> = decode(&out[1]);
        Ok((
            vals[self.inst.free_at.min(vals.len())..]
                .iter()
                .map(|x| x.f64())
                .collect(),
            react.iter().map(|x| x[3].f64()).collect(),
        ))
    }

    fn write_free(&mut self, rec: &[f64], flags: &[f64]) {
        let size = std::mem::size_of::<R>() as u64;
        if !rec.is_empty() {
            let v: Vec<R> = rec.iter().map(|&x| R::c(x)).collect();
            self.ctx.queue.write_buffer(
                &self.inst.buf.body_rows,
                self.inst.free_at as u64 * size,
                bytemuck::cast_slice(&v),
            );
        }
        for (c, &f) in flags.iter().enumerate().take(self.inst.n_routes) {
            self.ctx.queue.write_buffer(
                &self.inst.buf.reactions,
                (4 * c as u64 + 3) * size,
                bytemuck::bytes_of(&R::c(f)),
            );
        }
    }

    fn write_failures(&mut self, rec: &[f64], n: usize) {
        let size = std::mem::size_of::<R>() as u64;
        self.inst.params.n_fail = n as u32;
        if !rec.is_empty() {
            let v: Vec<R> = rec.iter().map(|&x| R::c(x)).collect();
            self.ctx.queue.write_buffer(
                &self.inst.buf.body_rows,
                self.inst.fail_at as u64 * size,
                bytemuck::cast_slice(&v),
            );
        }
    }

    fn fail_offset(&self) -> usize {
        self.inst.fail_at - self.inst.free_at
    }

    fn kernel(&self) -> GpuKernel {
        if self.use_fused && self.pipe_fused.is_ok() {
            GpuKernel::Fused
        } else {
            GpuKernel::TwoPass
        }
    }

    fn fused_unavailable(&self) -> Option<&str> {
        self.pipe_fused.as_ref().err().map(|s| s.as_str())
    }

    fn set_kernel(&mut self, k: GpuKernel) -> Result<(), Error> {
        if k == GpuKernel::Fused {
            if let Err(why) = &self.pipe_fused {
                return Err(Error::GpuUnsupported(format!("the fused kernel: {why}")));
            }
        }
        self.use_fused = k == GpuKernel::Fused;
        Ok(())
    }

    fn install(
        &mut self,
        lay: &Layout,
        host: &Host,
        r: &[[f64; 3]],
        v: &[[f64; 3]],
    ) -> Result<(), Error> {
        let scope = self
            .ctx
            .device
            .push_error_scope(wgpu::ErrorFilter::Validation);
        // A new mesh starts the waves' cache afresh (as the CPU path's does).
        if let Some(w) = self.waves.as_mut() {
            check_wave_nodes(lay.n_nodes())?;
            w.restart();
        }
        self.inst = Self::build(
            &self.ctx,
            &self.bgl,
            self.step_stride,
            lay,
            host,
            &self.opts,
            self.waves.as_ref(),
        );
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(Error::Gpu(format!("rebuilding the buffers: {e}")));
        }
        self.upload(host, r, v);
        self.write_visco_rest(lay, r);
        Ok(())
    }

    fn set_seas(&mut self, lay: &Layout, host: &Host, seas: &SeaSet) -> Result<(), Error> {
        if !seas.is_still() {
            check_wave_nodes(lay.n_nodes())?;
            check_wave_components(
                seas,
                std::mem::size_of::<WaveComp<R>>() as u64,
                self.ctx.limits.max_storage_buffer_binding_size,
                self.ctx.info.device_type == wgpu::DeviceType::Cpu,
            )?;
        }
        self.waves = (!seas.is_still()).then(|| SeaSchedules::new(seas, self.dt64));
        let scope = self
            .ctx
            .device
            .push_error_scope(wgpu::ErrorFilter::Validation);
        if self.waves.is_some() {
            self.add_fused_waves(lay);
        }
        let new = Self::build(
            &self.ctx,
            &self.bgl,
            self.step_stride,
            lay,
            host,
            &self.opts,
            self.waves.as_ref(),
        );
        let old = std::mem::replace(&mut self.inst, new);
        // The state moves over bit for bit (no round trip through f64 positions).
        let bytes = (self.inst.n_nodes.max(1) * std::mem::size_of::<NodeState<R>>()) as u64;
        let mut enc = self
            .ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("set_sea"),
            });
        enc.copy_buffer_to_buffer(&old.buf.state, 0, &self.inst.buf.state, 0, bytes);
        // So do the free bodies, the failures and the released constraints' flags.
        let body_bytes = (self.inst.body_values.max(1) * std::mem::size_of::<R>()) as u64;
        enc.copy_buffer_to_buffer(
            &old.buf.body_rows,
            0,
            &self.inst.buf.body_rows,
            0,
            body_bytes,
        );
        let react_bytes = (self.inst.n_routes.max(1) * std::mem::size_of::<[R; 4]>()) as u64;
        enc.copy_buffer_to_buffer(
            &old.buf.reactions,
            0,
            &self.inst.buf.reactions,
            0,
            react_bytes,
        );
        self.inst.params.n_fail = old.params.n_fail;
        self.ctx.queue.submit([enc.finish()]);
        self.write_routes(lay, host, 0.0);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(Error::Gpu(format!("installing the waves: {e}")));
        }
        Ok(())
    }

    fn download(&mut self, host: &Host) -> Result<NodeStates, Error> {
        let bytes = (self.inst.n_nodes * std::mem::size_of::<NodeState<R>>()) as u64;
        let out = self.read_back(&[(&self.inst.buf.state, bytes.max(4))])?;
        let st: Vec<NodeState<R>> = decode(&out[0][..bytes as usize]);
        let mut r = Vec::with_capacity(self.inst.n_nodes);
        let mut v = Vec::with_capacity(self.inst.n_nodes);
        for (i, s) in st.iter().enumerate() {
            let o = host.origin[host.node_block[i] as usize];
            let (h, l) = (v3(&s.r_hi), v3(&s.r_lo));
            r.push([0, 1, 2].map(|d| o[d] + (h[d] + l[d])));
            v.push(v3(&s.v));
        }
        Ok((r, v))
    }

    fn restart_waves(&mut self) {
        if let Some(w) = self.waves.as_mut() {
            w.restart();
        }
    }

    fn wave_band_census(&self) -> Result<BandCensus, Error> {
        self.band_census()
    }

    fn upload(&mut self, host: &Host, r: &[[f64; 3]], v: &[[f64; 3]]) {
        let st: Vec<NodeState<R>> = (0..self.inst.n_nodes)
            .map(|i| {
                let o = host.origin[host.node_block[i] as usize];
                let mut s = NodeState::<R>::default();
                for d in 0..3 {
                    (s.r_hi[d], s.r_lo[d]) = split(r[i][d] - o[d]);
                    s.v[d] = R::c(v[i][d]);
                }
                s
            })
            .collect();
        if !st.is_empty() {
            self.ctx
                .queue
                .write_buffer(&self.inst.buf.state, 0, bytemuck::cast_slice(&st));
        }
    }

    fn write_visco(&mut self, x: &[f64]) {
        // The element pass rewrites every other member of the loads before they are read.
        let loads: Vec<ElemLoads<R>> = x
            .iter()
            .map(|&x| ElemLoads {
                visco: R::c(x),
                ..Default::default()
            })
            .collect();
        if !loads.is_empty() {
            self.ctx
                .queue
                .write_buffer(&self.inst.buf.elem_loads, 0, bytemuck::cast_slice(&loads));
        }
    }

    fn read_visco(&mut self) -> Result<Vec<f64>, Error> {
        let bytes = (self.inst.n_elems * std::mem::size_of::<ElemLoads<R>>()) as u64;
        let out = self.read_back(&[(&self.inst.buf.elem_loads, bytes.max(4))])?;
        let loads: Vec<ElemLoads<R>> = decode(&out[0][..bytes as usize]);
        Ok(loads.iter().map(|l| l.visco.f64()).collect())
    }

    fn evaluate(&mut self, lay: &Layout, host: &Host, step: u64) -> Result<Evaluation, Error> {
        let ctx = &self.ctx.clone();
        self.write_routes(lay, host, step as f64 * self.dt64);
        self.write_payout(host, step, 1);
        self.write_bodies(host, step, 1);
        let t = step as f64 * self.dt64;
        // The components referred to `t`, as the next submission's (it starts at this
        // step), and each sea's row of the step at `t`: the cache interpolated at `t`,
        // refreshed first (the refresh dispatch below) where that step would refresh it,
        // which then finds it covering its time (the CPU path's rule:
        // `cpu::water::BlockWaves::cover`).
        self.write_wave_comps(t);
        if let Some(w) = self.waves.as_mut() {
            let (rows, _) = w.rows::<R>(1, |_| t, t);
            ctx.queue
                .write_buffer(&self.inst.buf.wave_steps, 0, bytemuck::cast_slice(&rows));
        }
        self.inst.params.step_base = 0;
        // The element pass leaves the elements' internal states as they are.
        self.inst.params.evaluate = 1;
        ctx.queue.write_buffer(
            &self.inst.buf.params,
            0,
            bytemuck::bytes_of(&self.inst.params),
        );
        self.inst.params.evaluate = 0;
        // The refresh below watches the bands as a step's does: its breaches beyond
        // the margin counted afresh (the rest of the status left as the last advance
        // call left it) and read back with the loads.
        let beyond_at = std::mem::offset_of!(Status, beyond) as u64;
        ctx.queue
            .write_buffer(&self.inst.buf.status, beyond_at, &[0u8; 8]);
        let mut enc = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("evaluate"),
            });
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("evaluate"),
                timestamp_writes: None,
            });
            pass.set_bind_group(0, &self.inst.bind_group, &[0]);
            if self.waves.is_some() {
                self.dispatch_refresh(&mut pass);
            }
            self.dispatch(&mut pass, &self.pipe_elem, self.inst.n_elem_threads);
            self.dispatch(&mut pass, &self.pipe_eval, self.inst.n_nodes);
        }
        ctx.queue.submit([enc.finish()]);
        // With bending, the elements' shears follow their loads (shaders' shear_of).
        let bending = lay.has_bending();
        let load_rows = if bending { 2 } else { 1 } * self.inst.n_elems;
        let loads_bytes = (load_rows * std::mem::size_of::<ElemLoads<R>>()) as u64;
        let out_bytes = (self.inst.n_nodes * std::mem::size_of::<NodeOut<R>>()) as u64;
        let react_bytes = (self.inst.n_routes * std::mem::size_of::<[R; 4]>()) as u64;
        let out = self.read_back(&[
            (&self.inst.buf.elem_loads, loads_bytes.max(4)),
            (&self.inst.buf.node_out, out_bytes.max(4)),
            (&self.inst.buf.reactions, react_bytes.max(4)),
            (&self.inst.buf.status, std::mem::size_of::<Status>() as u64),
        ])?;
        let st: Status = bytemuck::pod_read_unaligned(&out[3][..std::mem::size_of::<Status>()]);
        if st.beyond != 0 {
            self.note_beyond_margin(step, (u32::MAX - st.beyond_step) as u64)?;
        }
        let mut loads: Vec<ElemLoads<R>> = decode(&out[0][..loads_bytes as usize]);
        let shears = loads.split_off(self.inst.n_elems);
        let shear = |e: usize| {
            shears.get(e).map_or(crate::math::V3::zero(), |l| {
                crate::math::V3::new(l.tx.f64(), l.ty.f64(), l.tz.f64())
            })
        };
        let nout: Vec<NodeOut<R>> = decode(&out[1][..out_bytes as usize]);
        let react: Vec<[R; 4]> = decode(&out[2][..react_bytes as usize]);
        Ok(Evaluation {
            acc: nout.iter().map(|o| v3(&o.acc)).collect(),
            force: nout.iter().map(|o| v3(&o.force)).collect(),
            tension: loads.iter().map(|l| l.tension.f64()).collect(),
            reaction: react.iter().map(|x| v3(x)).collect(),
            elements: loads
                .iter()
                .enumerate()
                .map(|(e, l)| crate::physics::ElementLoads {
                    t: crate::math::V3::new(l.tx.f64(), l.ty.f64(), l.tz.f64()),
                    tension: l.tension.f64(),
                    f_half: crate::math::V3::new(l.fx.f64(), l.fy.f64(), l.fz.f64()),
                    half_mass: l.half_mass.f64(),
                    half_added: l.half_added.f64(),
                    shear: shear(e),
                    rate: 0.0,
                })
                .collect(),
            picked: None,
            picked_nodes: Vec::new(),
        })
    }
}
