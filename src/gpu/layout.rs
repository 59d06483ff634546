//! Host twins of the WGSL structs in `shaders/shared/prelude.wgsl`.
//!
//! Each struct is `#[repr(C)]`, generic over the scalar type `R` (`f32` or `f64`, the
//! WGSL alias `R` of the same name), and made only of 32-bit integers, `R` scalars and
//! `[R; 4]` (WGSL `vec4<R>`, in structs made entirely of them, and first in
//! `WaveStep`, whose size is then a multiple of its alignment): no `vec3`, whose
//! 16-byte alignment would open gaps that `#[repr(C)]` does not have. A compile-time
//! assertion per precision shows each struct has no padding (so `Pod` is sound), and
//! `tests/gpu/layout.rs` parses the WGSL with naga and checks every size and member
//! offset against [`GpuStruct::fields`]. Keep both sides in step when editing either.

use crate::math::Real;
use bytemuck::{Pod, Zeroable};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// The scalar type of a GPU computation: `f32` or `f64` (sealed).
pub trait GpuReal: Real + Pod + sealed::Sealed {
    /// The WGSL name of the type.
    const WGSL: &'static str;
}

impl GpuReal for f32 {
    const WGSL: &'static str = "f32";
}

impl GpuReal for f64 {
    const WGSL: &'static str = "f64";
}

/// One member of a struct as the layout test sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// Member name (the same on both sides).
    pub name: &'static str,
    /// Byte offset.
    pub offset: usize,
    /// Byte size.
    pub size: usize,
}

/// A struct shared with WGSL.
pub trait GpuStruct: Pod {
    /// The WGSL struct name.
    const NAME: &'static str;
    /// Members in declaration order.
    fn fields() -> Vec<Field>;
}

/// Defines a shared struct generic over `R`, its `Pod` impls (with a no-padding
/// assertion for both precisions) and its [`GpuStruct`] impl.
macro_rules! gpu_struct {
    ($(#[$m:meta])* $name:ident { $($(#[$fm:meta])* $field:ident : $ty:ty),* $(,)? }) => {
        $(#[$m])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct $name<R> {
            $($(#[$fm])* pub $field: $ty,)*
        }
        const _: () = {
            type R = f32;
            assert!(std::mem::size_of::<$name<R>>() == 0 $(+ std::mem::size_of::<$ty>())*);
        };
        const _: () = {
            type R = f64;
            assert!(std::mem::size_of::<$name<R>>() == 0 $(+ std::mem::size_of::<$ty>())*);
        };
        // SAFETY: `repr(C)`, every field is `Pod` for the two sealed scalar types, and
        // the assertions above show there are no padding bytes.
        unsafe impl<R: GpuReal> Zeroable for $name<R> {}
        // SAFETY: as above.
        unsafe impl<R: GpuReal> Pod for $name<R> {}
        impl<R: GpuReal> GpuStruct for $name<R> {
            const NAME: &'static str = stringify!($name);
            fn fields() -> Vec<Field> {
                vec![$(Field {
                    name: stringify!($field),
                    offset: std::mem::offset_of!($name<R>, $field),
                    size: std::mem::size_of::<$ty>(),
                }),*]
            }
        }
    };
}

/// Defines a shared struct without scalars of type `R`.
macro_rules! gpu_struct_u32 {
    ($(#[$m:meta])* $name:ident { $($(#[$fm:meta])* $field:ident : $ty:ty),* $(,)? }) => {
        $(#[$m])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
        pub struct $name {
            $($(#[$fm])* pub $field: $ty,)*
        }
        impl GpuStruct for $name {
            const NAME: &'static str = stringify!($name);
            fn fields() -> Vec<Field> {
                vec![$(Field {
                    name: stringify!($field),
                    offset: std::mem::offset_of!($name, $field),
                    size: std::mem::size_of::<$ty>(),
                }),*]
            }
        }
    };
}

gpu_struct! {
    /// Run constants (WGSL `Params`).
    Params {
        /// Number of nodes.
        n_nodes: u32,
        /// Number of elements.
        n_elems: u32,
        /// Number of routes (constrained nodes).
        n_routes: u32,
        /// 0 without a seabed, 1 for the plane, `2 + i` for a seabed grid packed in
        /// the current profiles' range `i` (WGSL `seabed_grid_value`).
        seabed: u32,
        /// Steps taken in this `advance` call before the current submission (so a
        /// blow-up's step is `step_base + StepInfo::k`).
        step_base: u32,
        /// Number of winch cables (rows of the `payout` buffer per step).
        n_winch: u32,
        /// Steps of the current submission.
        n_steps: u32,
        /// Number of bodies (rows of the `body_rows` buffer per step).
        n_bodies: u32,
        /// Number of free and pinned bodies.
        n_free: u32,
        /// Where their records start in `body_rows` (values of `R`).
        free_at: u32,
        /// Number of line failures.
        n_fail: u32,
        /// Where their records start in `body_rows` (values of `R`).
        fail_at: u32,
        /// 1 while the element pass runs for an evaluation (output): the elements'
        /// internal states are not advanced then (viscoelastic lines); 0 while stepping.
        evaluate: u32,
        /// Padding.
        pad_eval: u32,
        /// Time step, s.
        dt: R,
        /// Baumgarte position gain, s^-2.
        alpha: R,
        /// Baumgarte velocity gain, s^-1.
        beta: R,
        /// Blow-up speed, m/s.
        max_speed: R,
        /// Blow-up distance from the global origin, m.
        max_distance: R,
        /// Seabed stiffness per metre of cable, N/m^2.
        seabed_k: R,
        /// Seabed damping per metre of cable, N s/m^2.
        seabed_c: R,
        /// Seabed friction coefficient.
        seabed_mu: R,
        /// Friction regularisation velocity, m/s.
        seabed_v_eps: R,
        /// Axial seabed friction coefficient (`seabed_mu` the transverse one).
        seabed_mu_axial: R,
        /// Always 1.0 (read at run time, so compensated sums are not folded away).
        one: R,
        /// Gravity, m/s^2 (the dry weight of what is above the water surface).
        gravity: R,
        /// Water density, kg/m^3 (free bodies).
        water_density: R,
    }
}

gpu_struct_u32! {
    /// The step index within a submission (WGSL `StepInfo`, a dynamic-offset uniform).
    StepInfo {
        /// Step index since the routes were last rebased.
        k: u32,
        /// The fused kernel's end: it steps `k .. end` (written by the host for the
        /// first step of each fused dispatch; the two-pass stages read `k` only).
        end: u32,
        /// Padding.
        pad1: u32,
        /// Padding.
        pad2: u32,
    }
}

gpu_struct! {
    /// Folded line constants (WGSL `LineParams`, [`crate::physics::Coefs`]).
    LineParams {
        /// `EA`, N.
        ea: R,
        /// `EA c`, N s.
        ea_c: R,
        /// `1/2 rho Cn d`, kg/m^2.
        drag_n: R,
        /// `1/2 rho Ct pi d`, kg/m^2.
        drag_t: R,
        /// `(1 + Cm) rho A`, kg/m.
        froude_krylov: R,
        /// `(1 + Cat) rho A`, kg/m.
        froude_krylov_t: R,
        /// `mbar`, kg/m.
        mass: R,
        /// `Cm rho A`, kg/m.
        added_mass: R,
        /// `Cat rho A`, kg/m.
        added_mass_t: R,
        /// z component of weight less buoyancy per length, N/m.
        wet_weight_z: R,
        /// 1 when the elastic force acts in compression, else 0.
        compression: R,
        /// 1 + the index in `current_ranges` of the line's strain-tension curve (its
        /// rows packed in `current_pts` after the current profiles', `z` the strain and
        /// `ux` the tension), 0 without one.
        table: R,
        /// Viscoelastic lines (`physics::visco`; `ea` is the static stiffness): the
        /// dynamic stiffness `EA_d`, N (at zero mean tension with a slope).
        ea_d: R,
        /// The slope of the dynamic stiffness against the mean tension.
        ea_d_slope: R,
        /// The static branch's damping `BA_s`, N s (0: not a viscoelastic line).
        ba_s: R,
        /// The dynamic spring's damping `BA_d`, N s.
        ba_d: R,
    }
}

gpu_struct! {
    /// One element (WGSL `ElemParams`).
    ElemParams {
        /// Node a.
        a: u32,
        /// Node b.
        b: u32,
        /// Line type.
        line: u32,
        /// Current profile.
        current: u32,
        /// Block (for its origin's height; saves reading the node's parameters).
        block: u32,
        /// The variable element of a winch cable: `2 x` its winch index, plus 1 when
        /// the winch node is node b; `u32::MAX` for every other element.
        winch: u32,
        /// Unstretched length, high part, m.
        l0: R,
        /// Unstretched length, low part (`l0 + l0_lo`; zero in f64), m.
        l0_lo: R,
        /// The line's diameter, m (the element's wetted fraction).
        diameter: R,
    }
}

gpu_struct! {
    /// One node (WGSL `NodeParams`).
    NodeParams {
        /// First incidence entry.
        inc_start: u32,
        /// One past the last incidence entry.
        inc_end: u32,
        /// Route index, or `u32::MAX`.
        constraint: u32,
        /// Block index (origin, seabed height).
        block: u32,
        /// Current profile (for point drag).
        current: u32,
        /// The winch index of a node of a variable element (its material node `m` or
        /// its winch node `w`), or `u32::MAX`.
        winch: u32,
        /// A knot of a screen-model net: where its 8 grid neighbours start in `inc`,
        /// else `u32::MAX`.
        screen: u32,
        /// A knot's net: the first of its 2 rows in `current_pts`, else `u32::MAX`.
        screen_net: u32,
        /// Point mass plus its added mass, kg.
        point_mass: R,
        /// z component of the point's weight less buoyancy, N.
        point_weight_z: R,
        /// `1/2 rho Cd A` of the point, kg/m.
        point_drag: R,
        /// Tributary length for seabed contact, m.
        tributary: R,
        /// The point's added mass `Ca rho V` (part of `point_mass`), kg.
        point_added: R,
        /// The mass of water the point displaces, `rho V`, kg.
        point_displaced: R,
        /// Radius of the sphere of the point's volume, m.
        point_radius: R,
    }
}

gpu_struct! {
    /// The variable element of one winch cable at one step (WGSL `Payout`), computed
    /// on the host from the schedule as the CPU path computes it (`crate::ale`).
    Payout {
        /// `l0_v = l0_base + (dL(t) - dL_base)`, high part, m.
        l0: R,
        /// Low part of `l0_v` (zero in f64), m.
        l0_lo: R,
        /// Payout rate `Ldot`, m/s.
        rate: R,
        /// Payout acceleration `Lddot`, m/s^2.
        accel: R,
        /// Change of the tributary length of `m` and `w` since the last remeshing,
        /// `(l0_v - l0_base) / 2`, m.
        trib: R,
    }
}

gpu_struct! {
    /// A route rebased to a time and to its block's origin (WGSL `RouteParams`).
    RouteParams {
        /// Position at the rebase time (a circle's: on the circle), relative to the
        /// origin, high part, m.
        p_hi_x: R,
        /// See `p_hi_x`.
        p_hi_y: R,
        /// See `p_hi_x`.
        p_hi_z: R,
        /// Low part of the position (`p = p_hi + p_lo`), m.
        p_lo_x: R,
        /// See `p_lo_x`.
        p_lo_y: R,
        /// See `p_lo_x`.
        p_lo_z: R,
        /// Line velocity, or the screw's axial velocity, m/s.
        vel_x: R,
        /// See `vel_x`.
        vel_y: R,
        /// See `vel_x`.
        vel_z: R,
        /// Circle: radius times the first in-plane direction, m.
        e1_x: R,
        /// See `e1_x`.
        e1_y: R,
        /// See `e1_x`.
        e1_z: R,
        /// Circle: radius times the second in-plane direction, m.
        e2_x: R,
        /// See `e2_x`.
        e2_y: R,
        /// See `e2_x`.
        e2_z: R,
        /// Circle: angular velocity, rad/s.
        w: R,
        /// Circle: cosine of the angle at the rebase time.
        c0: R,
        /// Circle: sine of the angle at the rebase time.
        s0: R,
        /// Table: the rebase time (absolute), high part, s.
        t0_hi: R,
        /// Table: low part of the rebase time (`t0 = t0_hi + t0_lo`), s.
        t0_lo: R,
        /// 0 fixed, 1 line, 2 circle or screw, 3 table, 4 a point on a body (then
        /// `p` is the point at the rebase time, `e1` is `R(t0) at`, `e2` is `at`).
        kind: u32,
        /// The node it drives.
        node: u32,
        /// Table: first sample in the `route_samples` buffer.
        table_start: u32,
        /// Table: number of samples.
        table_len: u32,
        /// Table: samples at or before the rebase time (where the search starts).
        cursor: u32,
        /// Body: its body's index (its column of the `body_rows` buffer).
        body: u32,
    }
}

gpu_struct! {
    /// One body at one step (WGSL `BodyRow`), relative to its state at the routes'
    /// rebase time `t0` (formed in f64 on the host, so the differences are small and
    /// keep their precision in f32): see `gpu::solver::body_rows`.
    BodyRow {
        /// Reference point displacement since `t0`, x, m.
        dx: R,
        /// See `dx`.
        dy: R,
        /// See `dx`.
        dz: R,
        /// `R(t) - R(t0)`, row 0, column 0.
        dr00: R,
        /// See `dr00`.
        dr01: R,
        /// See `dr00`.
        dr02: R,
        /// See `dr00`.
        dr10: R,
        /// See `dr00`.
        dr11: R,
        /// See `dr00`.
        dr12: R,
        /// See `dr00`.
        dr20: R,
        /// See `dr00`.
        dr21: R,
        /// See `dr00`.
        dr22: R,
        /// Reference point velocity x, m/s.
        vx: R,
        /// See `vx`.
        vy: R,
        /// See `vx`.
        vz: R,
        /// Reference point acceleration x, m/s^2.
        ax: R,
        /// See `ax`.
        ay: R,
        /// See `ax`.
        az: R,
        /// Angular velocity x, rad/s.
        wx: R,
        /// See `wx`.
        wy: R,
        /// See `wx`.
        wz: R,
        /// Angular acceleration x, rad/s^2.
        alx: R,
        /// See `alx`.
        aly: R,
        /// See `alx`.
        alz: R,
    }
}

gpu_struct! {
    /// One sample of a table route (WGSL `RouteSample`): time and position relative to
    /// the driven node's block origin, each as a compensated pair (`hi + lo`).
    RouteSample {
        /// Time (absolute), high part, s.
        t_hi: R,
        /// Time, low part, s.
        t_lo: R,
        /// Position x relative to the origin, high part, m.
        x_hi: R,
        /// See `x_hi`.
        y_hi: R,
        /// See `x_hi`.
        z_hi: R,
        /// Position x, low part, m.
        x_lo: R,
        /// See `x_lo`.
        y_lo: R,
        /// See `x_lo`.
        z_lo: R,
    }
}

gpu_struct! {
    /// A block's origin, seabed height, and node and element ranges (WGSL
    /// `BlockParams`).
    BlockParams {
        /// Origin x (absolute), m.
        ox: R,
        /// Origin y, m.
        oy: R,
        /// Origin z, m.
        oz: R,
        /// Seabed height relative to the origin, m.
        zb: R,
        /// First node.
        node_start: u32,
        /// One past the last node.
        node_end: u32,
        /// First element.
        elem_start: u32,
        /// One past the last element.
        elem_end: u32,
        /// The block's first `WaveStep` row: its sea's rows (`sea::set`).
        wave_rows: u32,
        /// Padding (zero).
        pad: u32,
    }
}

gpu_struct! {
    /// One row of a current profile (WGSL `CurrentPoint`).
    CurrentPoint {
        /// Height, m.
        z: R,
        /// Current x, m/s.
        ux: R,
        /// Current y, m/s.
        uy: R,
        /// Current z, m/s.
        uz: R,
    }
}

gpu_struct_u32! {
    /// The rows of one current profile (WGSL `CurrentRange`).
    CurrentRange {
        /// First row.
        start: u32,
        /// Number of rows.
        len: u32,
    }
}

gpu_struct! {
    /// Node state (WGSL `NodeState`): position `r_hi + r_lo` relative to the block
    /// origin, and velocity; the fourth components are unused.
    NodeState {
        /// Position, high part, m.
        r_hi: [R; 4],
        /// Position, low part, m.
        r_lo: [R; 4],
        /// Velocity, m/s.
        v: [R; 4],
    }
}

gpu_struct! {
    /// What an element gives its nodes (WGSL `ElemLoads`, [`crate::physics::ElementLoads`]).
    ElemLoads {
        /// Tangent x.
        tx: R,
        /// Tangent y.
        ty: R,
        /// Tangent z.
        tz: R,
        /// Axial force, N.
        tension: R,
        /// Half external load x, N.
        fx: R,
        /// Half external load y, N.
        fy: R,
        /// Half external load z, N.
        fz: R,
        /// Half mass, kg.
        half_mass: R,
        /// Half normal added mass, kg.
        half_added: R,
        /// The element's internal state (a viscoelastic line's static-branch strain,
        /// `physics::visco`): the element pass reads it and writes it advanced by the
        /// step; zero for every other line.
        visco: R,
    }
}

gpu_struct! {
    /// Per node output of the evaluate pass (WGSL `NodeOut`).
    NodeOut {
        /// Total force, N.
        force: [R; 4],
        /// Acceleration, m/s^2.
        acc: [R; 4],
    }
}

gpu_struct_u32! {
    /// First blow-up of an `advance` call, and its breaches of a depth band beyond
    /// the margin, and the waves' refresh's work-list counter (WGSL `Status`;
    /// `failed`, `step`, `beyond`, `beyond_step` and `refresh_due` are atomic there).
    Status {
        /// Nonzero once a node has failed: 1 from the two-pass path; from the fused
        /// kernel `FUSED_FAILED | (0x7fff - k) << 16 | (0xffff - block)` of the
        /// earliest failing step `k` of the submission.
        failed: u32,
        /// Two-pass: the failing step within the `advance` call (`step_base + k`);
        /// fused: the `step_base` of the submission that failed.
        step: u32,
        /// Packed node index (two-pass; the host finds the fused kernel's node).
        node: u32,
        /// 1: speed over the limit (or non-finite), 2: too far (or non-finite)
        /// (two-pass only).
        what: u32,
        /// Waves: how many times a node was found more than `sea::bands::BAND_MARGIN`
        /// above its band's top in this call (atomic in WGSL).
        beyond: u32,
        /// `0xffffffff` less the earliest step of this call (`step_base + k`) at which
        /// one was (atomic in WGSL; 0: none).
        beyond_step: u32,
        /// Waves: how many evaluations a refresh's first pass (`wave_refresh`) put on
        /// its work list for the second (`wave_refresh_due`); set back to 0 by the
        /// third (`wave_refresh_elems`), so 0 between refreshes (atomic in WGSL).
        refresh_due: u32,
    }
}

gpu_struct! {
    /// One wave component (WGSL `WaveComp` in `shaders/shared/waves.wgsl`), as
    /// `sea::kinematics::PackedComponent`, in four vec4 grouped by the loops that
    /// read them (one load each on a software adapter instead of up to four).
    WaveComp {
        /// `k cos b`, `k sin b` (rad/m), the phase at the host's reference time (rad),
        /// the angular frequency `w` (rad/s).
        phase: [R; 4],
        /// The amplitude `A` (m), `A w / (1 - e^{-2 k h})` (m/s),
        /// `A w^2 / (1 - e^{-2 k h})` (m/s^2), the wave number `k` (rad/m).
        amps: [R; 4],
        /// `cos b`, `sin b`, 0, 0.
        dir: [R; 4],
        /// `k` (rad/m) and the decay cut's bounds (`sea::cut::decay_cut_bounds`): the
        /// constant, the factor of the node's speed (s/m), of the ramp's rate (s).
        cut: [R; 4],
    }
}

gpu_struct! {
    /// The waves at one step of a submission (WGSL `WaveStep` in
    /// `shaders/shared/waves.wgsl`): where the kinematics cache's two times are, the
    /// Hermite weights, and what a refresh at this step evaluates. Times are
    /// relative to the components' reference time `t_ref`, formed in f64 on the host.
    WaveStep {
        /// Hermite weights of the step's time, `s = (t - t0) / (t1 - t0)`
        /// (`sea::cache::hermite_weights`): `h00(s)` of the values at `t0`,
        /// `(t1 - t0) h10(s)` of the rates at `t0`, `h01(s)` of the values at `t1`,
        /// `(t1 - t0) h11(s)` of the rates at `t1`. A `vec4` (one load a step for every
        /// element on a software adapter, four as scalars), first so that it is
        /// aligned at both precisions.
        w: [R; 4],
        /// Cache slot of the values at `t0` (always 0 since the depth bands: a
        /// refresh copies a node's `t1` values to slot 0; kept as a field so that the
        /// shader names the slot it reads).
        slot0: u32,
        /// Cache slot of the values at `t1`.
        slot1: u32,
        /// 1 when a refresh at this step evaluates the `t0` values afresh.
        restart: u32,
        /// 1 when this step refreshes the cache before its element pass.
        refresh: u32,
        /// Number of wave components (0: still water).
        n: u32,
        /// 0: Wheeler stretching, 1: the profile held at `z = 0`.
        stretching: u32,
        /// The sea's first component in the components buffer (the seas of a packed
        /// run are back to back, `sea::set`).
        first: u32,
        /// 1 when the refresh records each node's velocity for the next refresh's
        /// acceleration estimate (every refresh does since an output-time evaluation
        /// refreshes as a step would; kept as a switch of the shader's).
        track: u32,
        /// The sea's number of depth bands (`sea::bands`; rows of band `m` are
        /// `m * band_rows` after band 0's).
        n_bands: u32,
        /// Rows between one band's row of a step and the next band's.
        band_rows: u32,
        /// How many bands this step's decision is among: `M + 1`, `M > 0` the coarsest
        /// band that refreshes (so every band up to it does), not a restart; the nodes
        /// of those bands are decided anew among them (`wave_band`); 0: no decision.
        decide: u32,
        /// 1 when this step counts the nodes above their band's top (band 0
        /// refreshes, not a restart, more than one band).
        watch: u32,
        /// Unused: the row's size a multiple of `vec4<f64>`'s alignment (32 bytes;
        /// 144 bytes in f32, 224 in f64).
        pad0: u32,
        /// Unused.
        pad1: u32,
        /// Unused.
        pad2: u32,
        /// Unused.
        pad3: u32,
        /// `t - t_ref` of the step, s (refresh with restart).
        tau0: R,
        /// Start-up ramp factor at the step's time (refresh with restart).
        ramp0: R,
        /// Its rate, 1/s (refresh with restart).
        ramp_rate0: R,
        /// `t1 - t_ref`, s (refresh).
        tau1: R,
        /// Start-up ramp factor at `t1` (refresh).
        ramp1: R,
        /// Its rate at `t1`, 1/s (refresh).
        ramp_rate1: R,
        /// `t1 - t`, s: the `t1` values are evaluated at `x + v h + acc h^2 / 2`
        /// with velocity `v + acc h`, `h = t1 - t` (refresh).
        ahead: R,
        /// `1 / (t - t_prev)`, 1/s, `t_prev` the previous refresh's time; 0 on a
        /// restart: `acc = (v - v_prev) / (t - t_prev)` (refresh).
        acc_rate: R,
        /// Water depth, m (`sea::GPU_DEEP` for deep water).
        depth: R,
        /// How far ahead a decision into band 0 looks, s (`sea::bands::BAND_LOOK_AHEAD`
        /// band 0 intervals); into band `m`, `2^m` times it (`sea::bands::wave_band`).
        look0: R,
        /// The tops of bands 1 to 6, m (`sea::bands::BandPlan::tops`; band 0's is
        /// infinite; those past `n_bands` unused; `sea::bands::MAX_BANDS` at most 7).
        top1: R,
        /// Band 2's top, m.
        top2: R,
        /// Band 3's top, m.
        top3: R,
        /// Band 4's top, m.
        top4: R,
        /// Band 5's top, m.
        top5: R,
        /// Band 6's top, m.
        top6: R,
    }
}

impl<R: GpuReal> WaveComp<R> {
    /// The component at precision `R`.
    pub fn from_packed(c: &crate::sea::kinematics::PackedComponent) -> Self {
        let v = |x: [f64; 4]| x.map(R::c);
        Self {
            phase: v([c.kx, c.ky, c.phase_ref, c.omega]),
            amps: v([c.amp, c.amp_u, c.amp_a, c.k]),
            dir: v([c.cos_b, c.sin_b, 0.0, 0.0]),
            cut: v([c.k, c.cut0, c.cut1, c.cut2]),
        }
    }
}

/// Every shared struct's name and fields at precision `R` (for the layout test).
pub fn all_structs<R: GpuReal>() -> Vec<(&'static str, usize, Vec<Field>)> {
    fn one<S: GpuStruct>() -> (&'static str, usize, Vec<Field>) {
        (S::NAME, std::mem::size_of::<S>(), S::fields())
    }
    vec![
        one::<Params<R>>(),
        one::<StepInfo>(),
        one::<LineParams<R>>(),
        one::<ElemParams<R>>(),
        one::<NodeParams<R>>(),
        one::<RouteParams<R>>(),
        one::<RouteSample<R>>(),
        one::<BlockParams<R>>(),
        one::<CurrentPoint<R>>(),
        one::<CurrentRange>(),
        one::<NodeState<R>>(),
        one::<ElemLoads<R>>(),
        one::<NodeOut<R>>(),
        one::<Status>(),
        one::<Payout<R>>(),
        one::<BodyRow<R>>(),
        one::<WaveComp<R>>(),
        one::<WaveStep<R>>(),
    ]
}
