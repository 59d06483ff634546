//! Stage 6 of the run pipeline: what a run hands out. At each output time the
//! simulation gives an [`OutputSink`] a [`Snapshot`] (every cable's node positions and
//! velocities, element tensions, end forces, winch state), and at the end the
//! [`Summary`]. [`FileSink`] writes the files users read (`end_forces`, `tensions`,
//! `positions`, `winches`, `bodies`, `points`, `final_state` as CSV or Parquet,
//! `summary.json`); [`VtkSink`] writes ParaView files; [`MemorySink`] keeps everything
//! in memory; [`FanOut`] hands the output to several; a caller may write its own.

mod csv_files;
mod fanout;
mod fatigue;
mod files;
mod guard;
mod memory;
mod nets;
#[cfg(feature = "parquet")]
mod parquet_files;
mod sink;
mod summary;
mod tables;
mod vtk;

pub use fanout::FanOut;
pub use fatigue::FatigueSink;
pub use files::{FileSink, LOCK_FILE, MARKER_FILE, OWN_DIRS, OWN_FILES};
pub use memory::MemorySink;
pub use nets::net_states;
#[cfg(feature = "parquet")]
pub use parquet_files::{read_parquet, Column, ParquetTable};
pub use sink::{BodyState, CableState, NetState, OutputSink, PointState, Snapshot};
pub use summary::{
    summary_text, write_summary, CableSummary, EndForces, Extremes, FailedStart, Summary,
    TensionExtreme, WinchSummary,
};
pub use tables::{Kind as ColumnKind, Table};
pub use vtk::{cables_vtp, points_vtp, VtkSink};

use crate::math::{Sym3, V3};
use crate::model::{CableInfo, Layout, NO_CONSTRAINT};
use crate::step::Evaluation;

/// The elements whose loads the outputs read ([`end_forces`], [`net_states`]),
/// ascending: every cable's two end elements and the twines of the nets that report a
/// volume. An output time's evaluation keeps these only
/// ([`crate::cpu::CpuSolver::evaluate_keeping`]).
pub fn elements_read(lay: &Layout, nets: &[crate::model::cage::NetInfo]) -> Vec<u32> {
    let mut picked: Vec<u32> = lay
        .cables
        .iter()
        .filter(|c| !c.elements.is_empty())
        .flat_map(|c| [c.elements[0], c.elements[c.elements.len() - 1]])
        .collect();
    for n in nets.iter().filter(|n| n.reference_volume > 0.0) {
        for c in &lay.cables[n.twines.clone()] {
            picked.extend_from_slice(&c.elements);
        }
    }
    picked.sort_unstable();
    picked.dedup();
    picked
}

/// The forces a cable exerts at its two end nodes.
///
/// - An end node that only this cable's end element touches: if it is held, the
///   constraint reaction `F_k - M_k a_k` (every force on the node, its point
///   mass and seabed contact included); if it is free, `F_e - M_e a_k`, the end
///   element's lumped force less its share of the node's inertia, which is the force the
///   cable exerts on an attached point mass (zero when nothing is attached).
/// - A node shared by several elements (a `[[points]]` knot): `F_e - M_e a_k` of this
///   cable's end element, its own share; the shares of all cables at a held knot add up
///   to the knot's reaction less the point's own weight and inertia.
pub fn end_forces(lay: &Layout, ev: &Evaluation, cable: &CableInfo) -> EndForces {
    let n = cable.nodes.len();
    let one = |node: u32, elem: u32, sign: f64| -> [f64; 3] {
        let i = node as usize;
        let k = lay.node_constraint[i];
        if k != NO_CONSTRAINT && lay.incidence(i).len() == 1 {
            return ev.reaction[k as usize];
        }
        let el = ev.element(elem);
        let a = V3::from_f64(ev.node_acc(node));
        let mut m = Sym3::scalar(el.half_mass);
        m.add_normal_projection(el.half_added, el.t);
        (el.f_half + (el.t * el.tension - el.shear) * sign - m.mul_vec(a)).to_f64()
    };
    EndForces {
        start: one(cable.nodes[0], cable.elements[0], 1.0),
        end: one(cable.nodes[n - 1], cable.elements[n - 2], -1.0),
    }
}
