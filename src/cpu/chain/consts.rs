//! The per-block constants of a chain ([`ChainConsts`]): the layout's element and node
//! data folded once into structure-of-arrays columns (per element, per padded element
//! with a zero ghost at each end, per node), plus the short lists of the rare per-node
//! extras (constrained nodes, point drag, points with a volume) and the seabed's
//! constants. Fields are `pub(super)`: the kernels and the winch and network paths of
//! `cpu::chain` read them directly.

use crate::model::{Block, Layout, NO_CONSTRAINT};

/// Per-block constants of a chain, built once.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChainConsts {
    pub(super) n: usize,
    // Per element (length ne).
    pub(super) l0: Vec<f64>,
    pub(super) il0: Vec<f64>,
    pub(super) ea: Vec<f64>,
    pub(super) eac: Vec<f64>,
    pub(super) comp: Vec<f64>,
    pub(super) drag_n: Vec<f64>,
    pub(super) drag_t: Vec<f64>,
    /// Half the element's weight less buoyancy (z), N.
    pub(super) half_wz: Vec<f64>,
    /// Half the element's buoyancy `rho A g l0 / 2` (z), N, which its dry part loses.
    pub(super) half_bz: Vec<f64>,
    /// Half the element's water-acceleration coefficient across it, `(1 + Cm) rho A l0
    /// / 2`, kg.
    pub(super) half_fk: Vec<f64>,
    /// The same along it, `(1 + Cat) rho A l0 / 2`, kg.
    pub(super) half_fkt: Vec<f64>,
    /// Half the element's mass `mbar l0 / 2` and half its tangential added mass `Cat
    /// rho A l0 / 2`, kg: a partly wet element's half mass along its tangent is
    /// `hmd + wet hat` (`hm` wholly wet).
    pub(super) hmd: Vec<f64>,
    pub(super) hat: Vec<f64>,
    /// The element's diameter, m (its wetted fraction).
    pub(super) diameter: Vec<f64>,
    /// Current profile per element.
    pub(super) current: Vec<u32>,
    /// Line type per element (for the ALE variable element, evaluated apart).
    pub(super) line: Vec<u32>,
    /// The block's current when every element shares one uniform current.
    pub(super) uniform: Option<[f64; 3]>,
    // Per padded element (length ne + 2, ghosts zero): wholly wet, the half mass along
    // the tangent `hmd + hat` and what the normal plane has more, `(Cm - Cat) rho A l0
    // / 2` (the node's mass block `sum hm I + ha (I - t t^T)`).
    pub(super) hm: Vec<f64>,
    pub(super) ha: Vec<f64>,
    // Per node (length n).
    pub(super) pm: Vec<f64>,
    pub(super) pwz: Vec<f64>,
    /// `K lt`, `C lt`, `mu K lt` of the seabed per node.
    pub(super) kl: Vec<f64>,
    pub(super) cl: Vec<f64>,
    pub(super) mukl: Vec<f64>,
    /// `(node, route index)` of constrained nodes.
    pub(super) constrained: Vec<(usize, usize)>,
    /// `(node, 1/2 rho Cd A, current index, sphere radius)` of nodes with point drag.
    pub(super) point_drag: Vec<(usize, f64, usize, f64)>,
    /// `(node, sphere radius, added mass, buoyancy, displaced mass)` of nodes whose
    /// point mass has a volume (what it loses out of the water, and its
    /// water-acceleration load `(1 + Ca) rho V a` in waves).
    pub(super) point_volume: Vec<(usize, f64, f64, f64, f64)>,
    /// Tributary length per node (seabed contact), m.
    pub(super) trib: Vec<f64>,
    /// Seabed `K`, `C`, `mu` (zero without a seabed).
    pub(super) sb_k: f64,
    pub(super) sb_c: f64,
    pub(super) sb_mu: f64,
    pub(super) zb: f64,
    pub(super) friction: bool,
    pub(super) v_eps: f64,
    /// The chain's bending hinges (`None` without bending stiffness).
    pub(crate) bend: Option<Box<super::bending::ChainBend>>,
}

impl ChainConsts {
    /// Folds the layout's constants for chain block `b`.
    pub(crate) fn new(lay: &Layout, b: &Block) -> Self {
        let n0 = b.node_start as usize;
        let n = (b.node_end - b.node_start) as usize;
        let (e0, e1) = (b.elem_start as usize, b.elem_end as usize);
        let ne = e1 - e0;
        let env = &lay.env;
        let mut c = ChainConsts {
            n,
            ..Default::default()
        };
        c.hm = vec![0.0; ne + 2];
        c.ha = vec![0.0; ne + 2];
        for (k, e) in (e0..e1).enumerate() {
            let lc = &lay.line_coefs[lay.elem_line[e] as usize];
            let l0 = lay.elem_l0[e];
            c.l0.push(l0);
            c.il0.push(1.0 / l0);
            c.ea.push(lc.ea);
            c.eac.push(lc.ea_c);
            c.comp.push(lc.compression);
            c.drag_n.push(lc.drag_n);
            c.drag_t.push(lc.drag_t);
            c.half_wz.push(0.5 * lc.wet_weight_z * l0);
            c.half_bz
                .push(0.5 * (lc.wet_weight_z + lc.mass * env.gravity) * l0);
            c.half_fk.push(0.5 * lc.froude_krylov * l0);
            c.half_fkt.push(0.5 * lc.froude_krylov_t * l0);
            let (hmd, hat) = (0.5 * lc.mass * l0, 0.5 * lc.added_mass_t * l0);
            c.hmd.push(hmd);
            c.hat.push(hat);
            c.diameter
                .push(lay.line_types[lay.elem_line[e] as usize].diameter);
            c.current.push(lay.elem_current[e]);
            c.line.push(lay.elem_line[e]);
            // `hmd + wet hat` at `wet = 1`, the same bits as a partly wet element's.
            c.hm[k + 1] = hmd + hat;
            c.ha[k + 1] = 0.5 * (lc.added_mass - lc.added_mass_t) * l0;
        }
        let first = c.current.first().copied().unwrap_or(0);
        if c.current.iter().all(|&x| x == first) && lay.currents[first as usize].table.len() <= 1 {
            c.uniform = Some(lay.currents[first as usize].at::<f64>(0.0).to_f64());
        }
        let has_seabed = env.depth.is_finite();
        for li in 0..n {
            let i = n0 + li;
            c.pm.push(lay.node_point_mass[i]);
            c.pwz.push(lay.node_point_weight_z[i]);
            let lt = if has_seabed {
                lay.node_tributary[i]
            } else {
                0.0
            };
            c.trib.push(lt);
            c.kl.push(env.seabed.stiffness * lt);
            c.cl.push(env.seabed.damping * lt);
            c.mukl.push(env.seabed.friction * env.seabed.stiffness * lt);
            let k = lay.node_constraint[i];
            if k != NO_CONSTRAINT {
                c.constrained.push((li, k as usize));
            }
            if lay.node_point_drag[i] > 0.0 {
                c.point_drag.push((
                    li,
                    lay.node_point_drag[i],
                    lay.node_current[i] as usize,
                    lay.node_point_radius[i],
                ));
            }
            if lay.node_point_radius[i] > 0.0 {
                c.point_volume.push((
                    li,
                    lay.node_point_radius[i],
                    lay.node_point_added[i],
                    lay.node_point_displaced[i] * env.gravity,
                    lay.node_point_displaced[i],
                ));
            }
        }
        if has_seabed {
            (c.sb_k, c.sb_c, c.sb_mu) = (
                env.seabed.stiffness,
                env.seabed.damping,
                env.seabed.friction,
            );
        }
        c.zb = if has_seabed {
            -env.depth
        } else {
            f64::NEG_INFINITY
        };
        c.friction = has_seabed && env.seabed.friction > 0.0;
        c.v_eps = env.seabed.friction_velocity;
        c.shrink();
        c
    }

    /// Gives back the room the columns' growth left (a 50-element column grows to 64):
    /// a fleet holds thousands of these.
    fn shrink(&mut self) {
        for col in [
            &mut self.l0,
            &mut self.il0,
            &mut self.ea,
            &mut self.eac,
            &mut self.comp,
            &mut self.drag_n,
            &mut self.drag_t,
            &mut self.half_wz,
            &mut self.half_bz,
            &mut self.half_fk,
            &mut self.half_fkt,
            &mut self.hmd,
            &mut self.hat,
            &mut self.diameter,
            &mut self.pm,
            &mut self.pwz,
            &mut self.kl,
            &mut self.cl,
            &mut self.mukl,
            &mut self.trib,
        ] {
            col.shrink_to_fit();
        }
        self.current.shrink_to_fit();
        self.line.shrink_to_fit();
        self.constrained.shrink_to_fit();
        self.point_drag.shrink_to_fit();
        self.point_volume.shrink_to_fit();
    }
}

impl ChainConsts {
    /// Makes `self` a copy of `o`, reusing `self`'s arrays (a run of steps of a winch
    /// cable edits a working copy of its block's constants).
    pub(super) fn copy_from(&mut self, o: &ChainConsts) {
        let ChainConsts {
            n,
            l0,
            il0,
            ea,
            eac,
            comp,
            drag_n,
            drag_t,
            half_wz,
            half_bz,
            half_fk,
            half_fkt,
            hmd,
            hat,
            diameter,
            current,
            line,
            uniform,
            hm,
            ha,
            pm,
            pwz,
            kl,
            cl,
            mukl,
            constrained,
            point_drag,
            point_volume,
            trib,
            sb_k,
            sb_c,
            sb_mu,
            zb,
            friction,
            v_eps,
            bend,
        } = self;
        *n = o.n;
        for (d, s) in [
            (l0, &o.l0),
            (il0, &o.il0),
            (ea, &o.ea),
            (eac, &o.eac),
            (comp, &o.comp),
            (drag_n, &o.drag_n),
            (drag_t, &o.drag_t),
            (half_wz, &o.half_wz),
            (half_bz, &o.half_bz),
            (half_fk, &o.half_fk),
            (half_fkt, &o.half_fkt),
            (hmd, &o.hmd),
            (hat, &o.hat),
            (diameter, &o.diameter),
            (hm, &o.hm),
            (ha, &o.ha),
            (pm, &o.pm),
            (pwz, &o.pwz),
            (kl, &o.kl),
            (cl, &o.cl),
            (mukl, &o.mukl),
            (trib, &o.trib),
        ] {
            d.clone_from(s);
        }
        current.clone_from(&o.current);
        line.clone_from(&o.line);
        *uniform = o.uniform;
        constrained.clone_from(&o.constrained);
        bend.clone_from(&o.bend);
        point_drag.clone_from(&o.point_drag);
        point_volume.clone_from(&o.point_volume);
        (*sb_k, *sb_c, *sb_mu, *zb, *friction, *v_eps) =
            (o.sb_k, o.sb_c, o.sb_mu, o.zb, o.friction, o.v_eps);
    }

    /// Makes `self` a copy of `o` with its per-element, per-padded-element and per-node
    /// columns padded with zeros to `len` entries (the chain loops' whole chunks of
    /// lanes, [`super::lanes`]); `l0`, `current` and `line` keep their length (the
    /// element count).
    pub(super) fn copy_padded_from(&mut self, o: &ChainConsts, len: usize) {
        self.copy_from(o);
        for v in [
            &mut self.il0,
            &mut self.ea,
            &mut self.eac,
            &mut self.comp,
            &mut self.drag_n,
            &mut self.drag_t,
            &mut self.half_wz,
            &mut self.half_bz,
            &mut self.half_fk,
            &mut self.half_fkt,
            &mut self.hmd,
            &mut self.hat,
            &mut self.diameter,
            &mut self.hm,
            &mut self.ha,
            &mut self.pm,
            &mut self.pwz,
            &mut self.kl,
            &mut self.cl,
            &mut self.mukl,
            &mut self.trib,
        ] {
            debug_assert!(v.len() <= len);
            v.resize(len, 0.0);
        }
        if let Some(b) = self.bend.as_deref_mut() {
            b.kh.resize(len, 0.0);
        }
    }

    /// Re-reads the constraint numbers of block `b` of `lay` (the same chain as the one
    /// these constants were made for, possibly renumbered by a rebuild).
    pub(crate) fn refresh_constraints(&mut self, lay: &Layout, b: &Block) {
        debug_assert_eq!(self.n, (b.node_end - b.node_start) as usize);
        self.constrained.clear();
        for li in 0..self.n {
            let k = lay.node_constraint[b.node_start as usize + li];
            if k != NO_CONSTRAINT {
                self.constrained.push((li, k as usize));
            }
        }
    }
}
