//! The fast path of the CPU stepper for blocks that are one chain in node order
//! (mooring lines, towed cables: the common case).
//!
//! It runs the same two passes as the general path ([`super::passes`]), on the same
//! physics, but over structure-of-arrays scratch and without branches in the loops,
//! so the compiler vectorises them (8 lanes of f64 with AVX-512 or 4 with AVX2, chosen
//! at run time; the columns padded to whole chunks of lanes, [`lanes`]):
//! - the element pass reads node `k` and `k+1` for element `k` (no index arrays);
//! - element results are stored with a zero "ghost" element at each end, so node `i`
//!   always gathers padded elements `i` (element `i-1`, as its node b) and `i+1`
//!   (element `i`, as its node a);
//! - the 3x3 mass block `s I - a1 t1 t1^T - a2 t2 t2^T` of a chain node is solved in
//!   closed form (Woodbury identity: a 2x2 system instead of a 3x3 adjugate);
//! - the rare per-node extras (constrained nodes, point-mass drag) are fixed up after
//!   the vectorised loop, from short index lists.
//!
//! A test checks it against the general path (`tests/cpu/chain_kernel.rs`).
//!
//! Its parts: [`consts`] (the block's constants as columns), [`lanes`] (the columns as
//! whole chunks of lanes), [`elements`] (the element pass), [`nodes`] (the node pass
//! and its mass solve), [`advance`] (scratch, AVX-512 / AVX2 dispatch, time schemes), [`winch`] (winch cables' variable elements), [`bending`] (a chain's
//! bending hinges, as extra forces of the node pass), [`net`] (the
//! same kernels over a network's blocks).

mod advance;
pub(crate) mod bending;
mod consts;
pub(crate) mod elements;
pub(crate) mod lanes;
pub(crate) mod net;
mod nodes;
mod winch;
pub(crate) use advance::{advance_chain, ChainScratch, Held as ChainHeld};
pub(crate) use consts::ChainConsts;
pub(crate) use lanes::column_stride;
pub(crate) use net::{advance_net, advance_net_threaded, NetConsts, NetScratch};
