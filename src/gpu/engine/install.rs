//! Setting a [`GpuEngine`] up and feeding it: the bind group layout and pipelines
//! (once), the layout's buffers and bind group ([`Installed`], again at each
//! remeshing), the rows written per submission (payout, bodies, routes, waves) and the
//! dispatch and read-back helpers that `advance` and `evaluate` use.
//!
//! Split out of `engine.rs` to keep each file under ~800 lines: this is the
//! "what goes on the device" half, `engine.rs` the "how a step runs" half.

use super::GpuTimings;
use super::{
    align_up, bytes_or_one, decode, Buffers, Engine, FusedPipelines, GpuEngine, Installed,
};
use crate::error::Error;
use crate::gpu::context::GpuContext;
use crate::gpu::host::{
    body_rows, free_records, pin_row, rebased_route, route_samples, split, HingeRows, Host,
    FAIL_STRIDE, FREE_STRIDE,
};
use crate::gpu::kernel::{fused_workgroup, STEPS_PER_SUBMISSION, WORKGROUP};
use crate::gpu::layout::*;
use crate::gpu::shaders::{self, Stage};
use crate::gpu::wave_schedule::{
    fused_max_steps, SeaSchedules, WAVE_CACHE_STRIDE, WAVE_DUE_STRIDE, WAVE_ELEM_ROWS,
    WAVE_ELEM_STRIDE,
};
use crate::model::{Layout, NO_KNOT};
use crate::options::Precision;
use crate::options::SolverOptions;
use crate::sea::bands::{warn_beyond_margin, BandCensus};
use bytemuck::Zeroable;
use rayon::prelude::*;
use std::marker::PhantomData;
use wgpu::util::DeviceExt;

/// The fused kernel's pipeline of workgroup size `wg`, with the waves' branches
/// (`waves`; those of point masses too with `wave_points`) or without, with or
/// without bending (shaders::header_with).
fn fused_pipeline(
    dev: &wgpu::Device,
    pl: &wgpu::PipelineLayout,
    precision: Precision,
    wg: u32,
    waves: bool,
    wave_points: bool,
    bending: bool,
) -> wgpu::ComputePipeline {
    let m = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(Stage::FusedSteps.file()),
        source: wgpu::ShaderSource::Wgsl(
            shaders::source_with(
                Stage::FusedSteps,
                precision,
                wg,
                waves,
                wave_points,
                bending,
            )
            .into(),
        ),
    });
    dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(if waves {
            "fused_steps (waves)"
        } else {
            "fused_steps (still water)"
        }),
        layout: Some(pl),
        module: &m,
        entry_point: Some("fused_steps"),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// Whether some node of `lay` has a point mass that takes wave loads (drag, displaced
/// or added mass: the shaders' `point_waves` test), or is a screen net's knot (whose
/// panels read their corners' waves: `screen_waves`); without one the fused kernel's
/// waves pipeline leaves the point masses' waves code out (`WAVE_POINTS = false`).
pub(in crate::gpu) fn layout_has_wave_points(lay: &Layout) -> bool {
    !lay.screen.is_empty()
        || lay
            .node_point_drag
            .iter()
            .chain(&lay.node_point_displaced)
            .chain(&lay.node_point_added)
            .any(|&x| x != 0.0)
}

impl<R: GpuReal> GpuEngine<R> {
    pub(in crate::gpu) fn new(
        ctx: &GpuContext,
        lay: &Layout,
        host: &Host,
        positions: &[[f64; 3]],
        opts: &SolverOptions,
    ) -> Result<Self, Error> {
        let dev = &ctx.device;
        let step_stride = align_up(
            std::mem::size_of::<StepInfo>() as u64,
            ctx.limits.min_uniform_buffer_offset_alignment as u64,
        );
        let scope = dev.push_error_scope(wgpu::ErrorFilter::Validation);
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let mut entries = vec![storage(0, true)];
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 1,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(16),
            },
            count: None,
        });
        entries.extend((2..=9).map(|b| storage(b, true)));
        entries.extend((10..=14).map(|b| storage(b, false)));
        entries.extend((15..=16).map(|b| storage(b, true)));
        // The wave components, bodies, the waves' cache, per-step rows and the
        // elements' cache.
        entries.push(storage(17, true));
        // The bodies' rows, and the free bodies' and line failures' records (written by
        // the body stage).
        entries.push(storage(18, false));
        entries.push(storage(19, false));
        entries.push(storage(20, true));
        entries.push(storage(21, false));
        let bgl = dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cablesim"),
            entries: &entries,
        });
        let pl = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cablesim"),
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        let precision = if R::WGSL == "f64" {
            Precision::F64
        } else {
            Precision::F32
        };
        // Bending stiffness: its hinge rows and shears (shaders::header_with).
        let bending = lay.has_bending();
        let module = |stage: Stage| {
            dev.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(stage.file()),
                source: wgpu::ShaderSource::Wgsl(
                    shaders::source_with(
                        stage,
                        precision,
                        shaders::DEFAULT_FUSED_WORKGROUP,
                        true,
                        true,
                        bending,
                    )
                    .into(),
                ),
            })
        };
        let m_elem = module(Stage::ElementForces);
        let m_node = module(Stage::NodeUpdate);
        let pipeline = |m: &wgpu::ShaderModule, entry: &str| {
            dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pl),
                module: m,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let pipe_elem = pipeline(&m_elem, "element_forces");
        let pipe_node = pipeline(&m_node, "node_update");
        let pipe_eval = pipeline(&m_node, "node_evaluate");
        let pipe_refresh = pipeline(&m_node, "wave_refresh");
        let pipe_refresh_due = pipeline(&m_node, "wave_refresh_due");
        let pipe_refresh_elems = pipeline(&m_node, "wave_refresh_elems");
        let pipe_free = pipeline(&m_node, "free_bodies");
        let pipe_fail = pipeline(&m_node, "line_failures");
        // The fused kernel for still water here; set_seas adds the one with the waves'
        // code when a sea has waves (shaders::header_with).
        let pipe_fused = fused_workgroup(lay, precision, &ctx.limits, !host.winches.is_empty())
            .map(|wg| FusedPipelines {
                wg,
                still: fused_pipeline(dev, &pl, precision, wg, false, false, bending),
                waves: None,
            });
        let use_fused = pipe_fused.is_ok();
        let inst = Self::build(ctx, &bgl, step_stride, lay, host, opts, None);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(Error::Gpu(format!(
                "building the {} pipelines: {e}",
                precision.name()
            )));
        }
        let mut engine = Self {
            ctx: ctx.clone(),
            opts: *opts,
            inst,
            bgl,
            pipe_elem,
            pipe_node,
            pipe_eval,
            pipe_refresh,
            pipe_refresh_due,
            pipe_refresh_elems,
            pipe_free,
            pipe_fail,
            waves: None,
            pipe_fused,
            pipe_layout: pl,
            use_fused,
            step_stride,
            dt64: opts.dt,
            first_beyond_margin: None,
            timings: GpuTimings::default(),
            _r: PhantomData,
        };
        engine.upload(host, positions, &vec![[0.0; 3]; positions.len()]);
        engine.write_visco_rest(lay, positions);
        engine.write_routes(lay, host, 0.0);
        Ok(engine)
    }

    /// The viscoelastic elements' states at rest at positions `r`
    /// (`physics::visco::visco_rest_states`, as the CPU path starts), written to the
    /// device; nothing without viscoelastic lines.
    pub(super) fn write_visco_rest(&mut self, lay: &Layout, r: &[[f64; 3]]) {
        let x = crate::physics::visco::visco_rest_states(lay, |e| {
            let (a, b) = (r[lay.elem_a[e] as usize], r[lay.elem_b[e] as usize]);
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        });
        if !x.is_empty() {
            self.write_visco(&x);
        }
    }

    /// Adds the fused kernel's pipeline with the waves' code (`WAVES = true`) if there
    /// is a fused kernel and it has none yet: built on the first sea with waves, so a
    /// still-water run compiles only the one without; the point masses' waves code
    /// only when a node of `lay` has a point mass that takes wave loads
    /// ([`layout_has_wave_points`]; the fused kernel's layout does not change: no
    /// winches). The caller checks for validation errors.
    pub(super) fn add_fused_waves(&mut self, lay: &Layout) {
        let precision = if R::WGSL == "f64" {
            Precision::F64
        } else {
            Precision::F32
        };
        if let Ok(f) = &mut self.pipe_fused {
            if f.waves.is_none() {
                f.waves = Some(fused_pipeline(
                    &self.ctx.device,
                    &self.pipe_layout,
                    precision,
                    f.wg,
                    true,
                    layout_has_wave_points(lay),
                    lay.has_bending(),
                ));
            }
        }
    }

    /// Creates the layout's buffers and their bind group.
    pub(super) fn build(
        ctx: &GpuContext,
        bgl: &wgpu::BindGroupLayout,
        step_stride: u64,
        lay: &Layout,
        host: &Host,
        opts: &SolverOptions,
        waves: Option<&SeaSchedules>,
    ) -> Installed<R> {
        let n_comps = waves.map_or(0, |w| w.n_comps);
        let n_row_blocks = waves.map_or(1, |w| w.n_row_blocks);
        let dev = &ctx.device;
        let env = &lay.env;
        let seabed = env.depth.is_finite();
        let n_winch = host.winches.len();
        // body_rows: the per-step rows (one more step than a submission: a pinned
        // body reads its pin at the step's end), the free bodies' records and held
        // routes' lists, room for a failure per route.
        let free_at = (STEPS_PER_SUBMISSION as usize + 1) * host.bodies.len() * 24;
        let n_held: usize = host.free.iter().map(|f| f.routes.len()).sum();
        let list_at = free_at + host.free.len() * FREE_STRIDE;
        let fail_at = list_at + n_held;
        let body_values = fail_at + lay.routes.len() * FAIL_STRIDE;
        let params = Params::<R> {
            n_nodes: lay.n_nodes() as u32,
            n_elems: lay.n_elements() as u32,
            n_routes: lay.routes.len() as u32,
            // 0 no seabed, 1 the plane, 2 + i a seabed grid packed in current range
            // i (after the current profiles: see below).
            seabed: match env.seabed.grid {
                Some(_) => 2 + lay.currents.len() as u32,
                None => seabed as u32,
            },
            step_base: 0,
            n_winch: n_winch as u32,
            n_steps: 0,
            n_bodies: host.bodies.len() as u32,
            n_free: host.free.len() as u32,
            free_at: free_at as u32,
            n_fail: 0,
            fail_at: fail_at as u32,
            evaluate: 0,
            pad_eval: 0,
            dt: R::c(opts.dt),
            alpha: R::c(opts.baumgarte.alpha),
            beta: R::c(opts.baumgarte.beta),
            max_speed: R::c(opts.max_speed),
            max_distance: R::c(opts.max_distance),
            seabed_k: R::c(env.seabed.stiffness),
            seabed_c: R::c(env.seabed.damping),
            seabed_mu: R::c(env.seabed.friction),
            seabed_v_eps: R::c(env.seabed.friction_velocity),
            seabed_mu_axial: R::c(env.seabed.mu_axial()),
            one: R::c(1.0),
            gravity: R::c(env.gravity),
            water_density: R::c(env.water_density),
        };
        // The current profiles' rows, a seabed grid's, then each line type's strain-tension
        // curve as rows of its own range (`z` the strain, `ux` the tension): no buffer of their own.
        let mut current_pts = Vec::new();
        let mut current_ranges = Vec::new();
        for c in &lay.currents {
            current_ranges.push(CurrentRange {
                start: current_pts.len() as u32,
                len: c.table.len() as u32,
            });
            for (z, u) in &c.table {
                current_pts.push(CurrentPoint {
                    z: R::c(*z),
                    ux: R::c(u[0]),
                    uy: R::c(u[1]),
                    uz: R::c(u[2]),
                });
            }
        }
        // A seabed grid rides in the current profiles' buffer (no binding of its own):
        // its packed values (physics::seabed_height) four to a row, as one more range,
        // right after the current profiles (Params.seabed counts on it).
        if let Some(g) = env.seabed.grid {
            current_ranges.push(CurrentRange {
                start: current_pts.len() as u32,
                len: g.packed.len().div_ceil(4) as u32,
            });
            for q in g.packed.chunks(4) {
                let at = |k: usize| R::c(q.get(k).copied().unwrap_or(0.0));
                current_pts.push(CurrentPoint {
                    z: at(0),
                    ux: at(1),
                    uy: at(2),
                    uz: at(3),
                });
            }
        }
        let mut line_table = vec![0u32; lay.line_types.len()];
        for (lt, slot) in lay.line_types.iter().zip(&mut line_table) {
            if let Some(rows) = &lt.ea_curve {
                current_ranges.push(CurrentRange {
                    start: current_pts.len() as u32,
                    len: rows.len() as u32,
                });
                *slot = current_ranges.len() as u32;
                for r in rows {
                    current_pts.push(CurrentPoint {
                        z: R::c(r[0]),
                        ux: R::c(r[1]),
                        uy: R::c(0.0),
                        uz: R::c(0.0),
                    });
                }
            }
        }
        // Bending: a hinge row per element after the elements' rows, the held
        // directions of clamped ends as rows of current_pts (HingeRows).
        let bending = lay.has_bending();
        let hinges = if bending {
            HingeRows::new(lay, current_pts.len() as u32)
                .expect("checked by gpu::solver::unsupported_bending")
        } else {
            HingeRows::default()
        };
        for d in &hinges.clamps {
            current_pts.push(CurrentPoint {
                z: R::c(0.0),
                ux: R::c(d[0]),
                uy: R::c(d[1]),
                uz: R::c(d[2]),
            });
        }
        // Screen-model nets ride in the same buffer: two rows per net (its constants,
        // the wake's axis relative to its block's origin: WGSL screen_coefs_at), and
        // each knot's 8 grid neighbours in `inc` after the incidence entries.
        let mut node_screen = vec![(NO_KNOT, NO_KNOT); lay.n_nodes()];
        let mut inc = lay.inc.clone();
        if !lay.screen.is_empty() {
            let mut net_row = vec![u32::MAX; lay.screen.nets.len()];
            for k in &lay.screen.knots {
                let net = k.net as usize;
                if net_row[net] == u32::MAX {
                    let o = host.origin[host.node_block[k.node as usize] as usize];
                    let co = lay.screen.nets[net].coefs(env.water_density, [o[0], o[1]]);
                    net_row[net] = current_pts.len() as u32;
                    current_pts.push(CurrentPoint {
                        z: R::c(co.model as f64),
                        ux: R::c(co.wake as f64),
                        uy: R::c(co.sn),
                        uz: R::c(co.re_scale),
                    });
                    current_pts.push(CurrentPoint {
                        z: R::c(co.half_rho),
                        ux: R::c(co.axis_x),
                        uy: R::c(co.axis_y),
                        uz: R::c(0.0),
                    });
                }
                node_screen[k.node as usize] = (inc.len() as u32, net_row[net]);
                inc.extend_from_slice(&k.around);
            }
        }
        let lines: Vec<LineParams<R>> = lay
            .line_coefs
            .iter()
            .zip(&line_table)
            .zip(&lay.line_types)
            .map(|((c, &table), lt)| LineParams {
                ea: R::c(c.ea),
                ea_c: R::c(c.ea_c),
                drag_n: R::c(c.drag_n),
                drag_t: R::c(c.drag_t),
                froude_krylov: R::c(c.froude_krylov),
                froude_krylov_t: R::c(c.froude_krylov_t),
                mass: R::c(c.mass),
                added_mass: R::c(c.added_mass),
                added_mass_t: R::c(c.added_mass_t),
                wet_weight_z: R::c(c.wet_weight_z),
                compression: R::c(c.compression),
                table: R::c(table as f64),
                ea_d: R::c(lt.viscoelastic.map_or(0.0, |v| v.ea_dynamic)),
                ea_d_slope: R::c(lt.viscoelastic.map_or(0.0, |v| v.ea_dynamic_slope)),
                ba_s: R::c(lt.viscoelastic.map_or(0.0, |v| v.ba_static)),
                ba_d: R::c(lt.viscoelastic.map_or(0.0, |v| v.ba_dynamic)),
            })
            .collect();
        let mut elems: Vec<ElemParams<R>> = (0..lay.n_elements())
            .map(|e| ElemParams {
                a: lay.elem_a[e],
                b: lay.elem_b[e],
                line: lay.elem_line[e],
                current: lay.elem_current[e],
                block: host.node_block[lay.elem_a[e] as usize],
                winch: host.elem_winch[e],
                l0: split::<R>(lay.elem_l0[e]).0,
                l0_lo: split::<R>(lay.elem_l0[e]).1,
                diameter: R::c(lay.line_types[lay.elem_line[e] as usize].diameter),
            })
            .collect();
        elems.extend(hinges.params::<R>());
        let nodes: Vec<NodeParams<R>> = (0..lay.n_nodes())
            .map(|i| NodeParams {
                inc_start: lay.inc_start[i],
                inc_end: lay.inc_start[i + 1],
                constraint: lay.node_constraint[i],
                block: host.node_block[i],
                current: lay.node_current[i],
                winch: host.node_winch[i],
                screen: node_screen[i].0,
                screen_net: node_screen[i].1,
                point_mass: R::c(lay.node_point_mass[i]),
                point_weight_z: R::c(lay.node_point_weight_z[i]),
                point_drag: R::c(lay.node_point_drag[i]),
                tributary: R::c(lay.node_tributary[i]),
                point_added: R::c(lay.node_point_added[i]),
                point_displaced: R::c(lay.node_point_displaced[i]),
                point_radius: R::c(lay.node_point_radius[i]),
            })
            .collect();
        let blocks: Vec<BlockParams<R>> = host
            .origin
            .iter()
            .zip(&lay.blocks)
            .map(|(o, b)| BlockParams {
                ox: R::c(o[0]),
                oy: R::c(o[1]),
                oz: R::c(o[2]),
                zb: R::c(if seabed { -env.depth - o[2] } else { 0.0 }),
                node_start: b.node_start,
                node_end: b.node_end,
                elem_start: b.elem_start,
                elem_end: b.elem_end,
                wave_rows: waves.map_or(0, |w| w.block_rows(lay, b.node_start)),
                pad: 0,
            })
            .collect();
        let n_nodes = lay.n_nodes();
        let n_elems = lay.n_elements();
        let n_routes = lay.routes.len();
        let n_blocks = lay.blocks.len();

        let mut steps = vec![0u8; (step_stride * STEPS_PER_SUBMISSION as u64) as usize];
        for k in 0..STEPS_PER_SUBMISSION as usize {
            let s = StepInfo {
                k: k as u32,
                ..Default::default()
            };
            let off = k * step_stride as usize;
            steps[off..off + 16].copy_from_slice(bytemuck::bytes_of(&s));
        }

        use wgpu::BufferUsages as U;
        let init = |label: &str, contents: &[u8], usage: U| {
            dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let ro = U::STORAGE;
        let rw = U::STORAGE | U::COPY_SRC | U::COPY_DST;
        let state_bytes = (n_nodes.max(1) * std::mem::size_of::<NodeState<R>>()) as u64;
        // With bending, a second row per element holds its shear (shaders' shear_of).
        let load_rows = if bending { 2 * n_elems } else { n_elems };
        let loads_bytes = (load_rows.max(1) * std::mem::size_of::<ElemLoads<R>>()) as u64;
        let out_bytes = (n_nodes.max(1) * std::mem::size_of::<NodeOut<R>>()) as u64;
        let react_bytes = (n_routes.max(1) * std::mem::size_of::<[R; 4]>()) as u64;
        let payout_bytes = ((STEPS_PER_SUBMISSION as usize * n_winch).max(1)
            * std::mem::size_of::<Payout<R>>()) as u64;
        let body_bytes = (body_values.max(1) * std::mem::size_of::<R>()) as u64;
        let mut body_init = vec![R::c(0.0); body_values.max(1)];
        if !host.free.is_empty() {
            let states: Vec<_> = host
                .free
                .iter()
                .map(|f| f.body.dynamic().expect("free").body.clone())
                .collect();
            let rec = free_records::<R>(host, &states, list_at);
            body_init[free_at..free_at + rec.len()].copy_from_slice(&rec);
        }
        let staging_bytes = [
            state_bytes,
            loads_bytes,
            out_bytes,
            react_bytes,
            16,
            body_bytes,
        ]
        .iter()
        .map(|&b| align_up(b, 256))
        .sum();
        let zeros = |n: u64| vec![0u8; n as usize];
        let buf = Buffers {
            params: init("params", bytemuck::bytes_of(&params), ro | U::COPY_DST),
            step: init("step", &steps, U::UNIFORM | U::COPY_DST),
            routes: init(
                "routes",
                &bytes_or_one(&vec![RouteParams::<R>::zeroed(); n_routes]),
                ro | U::COPY_DST,
            ),
            state: init("state", &zeros(state_bytes), rw),
            elem_loads: init("elem_loads", &zeros(loads_bytes), rw),
            node_out: init("node_out", &zeros(out_bytes), rw),
            reactions: init("reactions", &zeros(react_bytes), rw),
            status: init("status", &zeros(std::mem::size_of::<Status>() as u64), rw),
            payout: init("payout", &zeros(payout_bytes), ro | U::COPY_DST),
            body_rows: init("body_rows", bytemuck::cast_slice(&body_init), rw),
            wave_comps: init(
                "wave_comps",
                &zeros((n_comps.max(1) * std::mem::size_of::<WaveComp<R>>()) as u64),
                ro | U::COPY_DST,
            ),
            // Still water: rows of zeros (no components) are never rewritten.
            wave_steps: init(
                "wave_steps",
                &zeros(
                    (n_row_blocks as u64 * STEPS_PER_SUBMISSION as u64)
                        * std::mem::size_of::<WaveStep<R>>() as u64,
                ),
                ro | U::COPY_DST,
            ),
            staging: dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some("staging"),
                size: staging_bytes,
                usage: U::MAP_READ | U::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        let lines_b = init("lines", &bytes_or_one(&lines), ro);
        let elems_b = init("elems", &bytes_or_one(&elems), ro);
        let nodes_b = init("nodes", &bytes_or_one(&nodes), ro);
        let inc_b = init("inc", &bytes_or_one(&inc), ro);
        let blocks_b = init("blocks", &bytes_or_one(&blocks), ro);
        let pts_b = init("current_pts", &bytes_or_one(&current_pts), ro);
        let ranges_b = init("current_ranges", &bytes_or_one(&current_ranges), ro);
        let samples: Vec<RouteSample<R>> = lay
            .routes
            .iter()
            .enumerate()
            .flat_map(|(c, r)| route_samples::<R>(r, host.route_origin(lay, c)))
            .collect();
        let samples_b = init("route_samples", &bytes_or_one(&samples), ro);
        // Two slots (t0, t1) of WAVE_CACHE_STRIDE values per node, then each node's
        // velocity at the last refresh, then per node its depth band and how many
        // times it was found above its band's top, then WAVE_ELEM_STRIDE per element:
        // its band, then four per node: its breaches beyond the band margin
        // and the first one's height, top and step, then the refresh's work list, two
        // entries per node at most (`shaders/shared/waves.wgsl`); one value in still
        // water.
        let cache_len = if n_comps == 0 {
            1
        } else {
            n_nodes * (2 * WAVE_CACHE_STRIDE + 5)
                + n_elems * WAVE_ELEM_STRIDE
                + 4 * n_nodes
                + 2 * n_nodes * WAVE_DUE_STRIDE
        };
        let cache_b = init(
            "wave_cache",
            &zeros((cache_len * std::mem::size_of::<R>()) as u64),
            U::STORAGE | U::COPY_SRC,
        );
        // The elements' midpoint cache, WAVE_ELEM_ROWS vec4 rows per element
        // (`wave_elems`); one row in still water.
        let elem_rows = if n_comps == 0 {
            1
        } else {
            (n_elems * WAVE_ELEM_ROWS).max(1)
        };
        let elems_cache_b = init(
            "wave_elems",
            &zeros((elem_rows * 4 * std::mem::size_of::<R>()) as u64),
            U::STORAGE,
        );
        fn whole(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding,
                resource: b.as_entire_binding(),
            }
        }
        let bind_group = dev.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cablesim"),
            layout: bgl,
            entries: &[
                whole(0, &buf.params),
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &buf.step,
                        offset: 0,
                        size: wgpu::BufferSize::new(16),
                    }),
                },
                whole(2, &lines_b),
                whole(3, &elems_b),
                whole(4, &nodes_b),
                whole(5, &inc_b),
                whole(6, &buf.routes),
                whole(7, &blocks_b),
                whole(8, &pts_b),
                whole(9, &ranges_b),
                whole(10, &buf.state),
                whole(11, &buf.elem_loads),
                whole(12, &buf.node_out),
                whole(13, &buf.reactions),
                whole(14, &buf.status),
                whole(15, &samples_b),
                whole(16, &buf.payout),
                whole(17, &buf.wave_comps),
                whole(18, &buf.body_rows),
                whole(19, &cache_b),
                whole(20, &buf.wave_steps),
                whole(21, &elems_cache_b),
            ],
        });
        Installed {
            n_free: host.free.len(),
            free_at,
            fail_at,
            body_values,
            params,
            buf,
            wave_cache: cache_b,
            bind_group,
            n_nodes,
            n_elems,
            n_elem_threads: if lay.screen.is_empty() {
                n_elems
            } else {
                n_elems.max(n_nodes)
            },
            n_routes,
            n_blocks,
            fused_max_steps: fused_max_steps(lay),
        }
    }

    /// Writes the `payout` rows of steps `step0 .. step0 + n` (rows `0 .. n`): the
    /// variable element of each winch cable at each step's time, from its schedule, in
    /// f64 exactly as the CPU path forms them (`ale::AleElem::l0`).
    pub(super) fn write_payout(&self, host: &Host, step0: u64, n: u64) {
        if host.winches.is_empty() {
            return;
        }
        let mut rows = Vec::with_capacity(n as usize * host.winches.len());
        for k in 0..n {
            // Time from the step count, as the CPU path forms it.
            let t = (step0 + k) as f64 * self.dt64;
            for ae in &host.winches {
                let pay = ae.sched.eval(t);
                let l0 = ae.l0(pay.dl);
                let (hi, lo) = split::<R>(l0);
                rows.push(Payout::<R> {
                    l0: hi,
                    l0_lo: lo,
                    rate: R::c(pay.rate),
                    accel: R::c(pay.accel),
                    trib: R::c(0.5 * (l0 - ae.base_l0)),
                });
            }
        }
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.payout, 0, bytemuck::cast_slice(&rows));
    }

    /// Writes the `body_rows` of steps `step0 .. step0 + n` (rows `0 .. n`, one per
    /// body each), relative to each body's state at `step0` (the routes' rebase time).
    pub(super) fn write_bodies(&self, host: &Host, step0: u64, n: u64) {
        if host.bodies.is_empty() {
            return;
        }
        let dt = self.dt64;
        // Bodies in parallel (a packed study has one per member); each row a function
        // of its time alone, so the rows do not depend on the thread count.
        // One row more than the steps: a pinned body reads its pin at each step's end.
        let per_body: Vec<Vec<BodyRow<R>>> = host
            .bodies
            .par_iter()
            .map(|b| {
                match host
                    .free
                    .iter()
                    .find(|f| std::sync::Arc::ptr_eq(&f.body, b))
                {
                    Some(f) => {
                        let xr = f.xr();
                        (0..=n)
                            .map(|k| pin_row(b, xr, (step0 + k) as f64 * dt))
                            .collect()
                    }
                    None => body_rows(
                        b,
                        step0 as f64 * dt,
                        (0..=n).map(|k| (step0 + k) as f64 * dt),
                    ),
                }
            })
            .collect();
        let rows: Vec<BodyRow<R>> = (0..=n as usize)
            .flat_map(|k| per_body.iter().map(move |b| b[k]))
            .collect();
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.body_rows, 0, bytemuck::cast_slice(&rows));
    }

    pub(super) fn write_routes(&self, lay: &Layout, host: &Host, t0: f64) {
        if lay.routes.is_empty() {
            return;
        }
        let q: Vec<RouteParams<R>> = lay
            .routes
            .iter()
            .enumerate()
            .map(|(c, r)| {
                let mut q = rebased_route(
                    r,
                    lay.constraint_node[c],
                    t0,
                    host.route_origin(lay, c),
                    host.table_start[c],
                );
                q.body = host.route_body[c];
                q
            })
            .collect();
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.routes, 0, bytemuck::cast_slice(&q));
    }

    /// Rebases every sea's wave components to `t_ref` and writes them, back to back
    /// (waves only).
    pub(super) fn write_wave_comps(&mut self, t_ref: f64) {
        let Some(w) = self.waves.as_mut() else {
            return;
        };
        let mut comps: Vec<WaveComp<R>> = Vec::with_capacity(w.n_comps);
        for sea in w.seas.iter_mut().flatten() {
            sea.field.rebase(t_ref);
            comps.extend(sea.field.comps.iter().map(WaveComp::from_packed));
        }
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.wave_comps, 0, bytemuck::cast_slice(&comps));
    }

    /// Writes the `wave_steps` rows of steps `step0 .. step0 + n` of every sea,
    /// components referred to the time of `step0`; returns which steps refresh the
    /// cache of some sea (none in still water).
    pub(super) fn write_waves(&mut self, step0: u64, n: u64) -> Vec<bool> {
        if self.waves.is_none() {
            return vec![false; n as usize];
        }
        let dt = self.dt64;
        let t_ref = step0 as f64 * dt;
        self.write_wave_comps(t_ref);
        let w = self.waves.as_mut().expect("waves");
        let (rows, refresh) = w.rows::<R>(n as usize, |k| (step0 + k as u64) as f64 * dt, t_ref);
        self.ctx
            .queue
            .write_buffer(&self.inst.buf.wave_steps, 0, bytemuck::cast_slice(&rows));
        refresh
    }

    pub(super) fn dispatch(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        pipe: &wgpu::ComputePipeline,
        n: usize,
    ) {
        pass.set_pipeline(pipe);
        pass.dispatch_workgroups((n as u32).div_ceil(WORKGROUP).max(1), 1, 1);
    }

    /// The free bodies' stage and the line failures' check after a step's node pass
    /// (nothing without them).
    pub(super) fn dispatch_bodies(&self, pass: &mut wgpu::ComputePass<'_>) {
        if self.inst.n_free > 0 {
            self.dispatch(pass, &self.pipe_free, self.inst.n_free);
        }
        if self.inst.params.n_fail > 0 {
            self.dispatch(pass, &self.pipe_fail, self.inst.params.n_fail as usize);
        }
    }

    /// The waves' refresh: the nodes' decisions, putting their evaluations on a work
    /// list (`wave_refresh`), the evaluations over the list (`wave_refresh_due`, two
    /// entries per node at most), then the elements' midpoint cache from them
    /// (`wave_refresh_elems`, which empties the list); three dispatches.
    pub(super) fn dispatch_refresh(&self, pass: &mut wgpu::ComputePass<'_>) {
        self.dispatch(pass, &self.pipe_refresh, self.inst.n_nodes);
        self.dispatch(pass, &self.pipe_refresh_due, 2 * self.inst.n_nodes);
        self.dispatch(pass, &self.pipe_refresh_elems, self.inst.n_elems);
    }

    /// Copies `(buffer, bytes)` pairs into the staging buffer, waits, and returns the
    /// bytes of each.
    pub(super) fn read_back(&self, parts: &[(&wgpu::Buffer, u64)]) -> Result<Vec<Vec<u8>>, Error> {
        let ctx = &self.ctx;
        let mut enc = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("read_back"),
            });
        let mut offsets = Vec::new();
        let mut off = 0u64;
        for (b, n) in parts {
            enc.copy_buffer_to_buffer(b, 0, &self.inst.buf.staging, off, *n);
            offsets.push(off);
            off = align_up(off + n, 256);
        }
        ctx.queue.submit([enc.finish()]);
        let slice = self.inst.buf.staging.slice(0..off);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::Gpu(format!("waiting for the device: {e}")))?;
        ctx.take_error()?;
        rx.recv()
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?;
        let out = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| Error::Gpu(format!("read-back: {e}")))?;
            parts
                .iter()
                .zip(&offsets)
                .map(|((_, n), &o)| view[o as usize..(o + n) as usize].to_vec())
                .collect()
        };
        self.inst.buf.staging.unmap();
        Ok(out)
    }

    /// `count` scalars of the waves' cache from scalar `from`, read back through a
    /// buffer of their own (the staging buffer is sized for the state).
    fn read_cache(&self, from: usize, count: usize) -> Result<Vec<R>, Error> {
        let size = std::mem::size_of::<R>() as u64;
        let bytes = count as u64 * size;
        let ctx = &self.ctx;
        let dst = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("wave_cache_read"),
            size: align_up(bytes.max(4), 4),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("wave_cache_read"),
            });
        enc.copy_buffer_to_buffer(&self.inst.wave_cache, from as u64 * size, &dst, 0, bytes);
        ctx.queue.submit([enc.finish()]);
        let slice = dst.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::Gpu(format!("waiting for the device: {e}")))?;
        ctx.take_error()?;
        rx.recv()
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?;
        let view = slice
            .get_mapped_range()
            .map_err(|e| Error::Gpu(format!("read-back: {e}")))?;
        Ok(decode(&view[..bytes as usize]))
    }

    /// Where each node's record of its breaches beyond the band margin starts in the
    /// waves' cache, four scalars per node (WGSL `wave_beyond_at`).
    fn beyond_at(&self) -> usize {
        self.inst.n_nodes * (2 * WAVE_CACHE_STRIDE + 5) + self.inst.n_elems * WAVE_ELEM_STRIDE
    }

    /// Per depth band, how many nodes are in it now, how many times a node was found
    /// above its band's top, and how many of those beyond the margin (`sea::bands`):
    /// the cache's per-node bands, breach counts and records
    /// (`shaders/shared/waves.wgsl`) read back. Empty in still water.
    pub(super) fn band_census(&self) -> Result<BandCensus, Error> {
        if self.waves.as_ref().is_none_or(|w| w.n_comps == 0) {
            return Ok(BandCensus::default());
        }
        let n = self.inst.n_nodes;
        let vals = self.read_cache((2 * WAVE_CACHE_STRIDE + 3) * n, 2 * n)?;
        let beyond = self.read_cache(self.beyond_at(), 4 * n)?;
        let (band, breach) = vals.split_at(n);
        let mut out = BandCensus::default();
        for b in band {
            let b = b.f64() as usize;
            if out.nodes.len() <= b {
                out.nodes.resize(b + 1, 0);
            }
            out.nodes[b] += 1;
        }
        out.breaches = breach.iter().map(|x| x.f64() as u64).sum();
        out.beyond_margin = beyond.chunks_exact(4).map(|r| r[0].f64() as u64).sum();
        out.first_beyond_margin = self.first_beyond_margin;
        Ok(out)
    }

    /// After an `advance` call from step `step0` (or an evaluation at step `step0`)
    /// whose status counted a node more than the band margin above its band's top,
    /// first at step `k` of the call: keeps the first such breach of the run, the
    /// lowest such node at that step from its record (its height and its band's top
    /// then), and warns of it as the CPU path does (`sea::bands::warn_beyond_margin`,
    /// once per process). Reads nothing once the run has one.
    pub(super) fn note_beyond_margin(&mut self, step0: u64, k: u64) -> Result<(), Error> {
        if self.first_beyond_margin.is_some() {
            return Ok(());
        }
        let rec = self.read_cache(self.beyond_at(), 4 * self.inst.n_nodes)?;
        // A node's record keeps its first breach beyond the margin; none can be from
        // an earlier call, which would have set `first_beyond_margin` (and this not
        // be read).
        if let Some(r) = rec
            .chunks_exact(4)
            .find(|r| r[0].f64() > 0.0 && r[3].f64() as u64 == k)
        {
            let t = (step0 + k) as f64 * self.dt64;
            self.first_beyond_margin = Some([t, r[1].f64(), r[2].f64()]);
            warn_beyond_margin(t, r[1].f64(), r[2].f64());
        }
        Ok(())
    }
}
