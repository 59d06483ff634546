#!/usr/bin/env python3
"""Bytes and flops per node-step of the GPU step in waves against still water, counted
from the shaders (benchmarks/history/BENCHMARKS-2026-12.md, "The GPU step in waves: a per-element cache").

Every read and write of the waves' cache is counted as memory traffic (no device cache
assumed); the `WaveStep` rows (one per band and step, shared by every invocation) and
the components buffer the refresh sums over (the same for every node) are not, as in
the section "The water surface and waves". The still-water figures (316 / 575 B, 454 /
322 flops) are that section's. A refresh is amortised over the steps between two
refreshes of each node's (element's) band; the refresh dispatches run at every step of
the finest band's grid.

    python3 scripts/gpu_wave_counts.py
"""

STILL_BYTES = {"f32": 316, "f64": 575}
STILL_FLOPS = {"f32": 454, "f64": 322}
SCALAR = {"f32": 4, "f64": 8}
NODE_STATE = {"f32": 48, "f64": 96}  # three vec4: position pair, velocity
ELEM_PARAMS = {"f32": 32, "f64": 40}
# Flops of one node's refresh (wave_kinematics_rates_tau, shaders/shared/waves.wgsl),
# counted from the shader, a multiply or an add one flop each (branch `hwgpu`):
# - the elevation pass, every component whatever the depth: the phase (6), sin_cos
#   (reduction 7, two polynomials 31: 39), the elevation and its rate (9): 54;
# - the decay cut's bisection, ceil(log2(n + 1)) = 8 steps at 200 components, each a
#   wave_exp and the bound (5);
# - the decay pass, over the prefix the node needs (sea::cut): wave_depth_decay, the
#   phase and sin_cos (45), the phase rate (4), the twelve value and rate terms of u
#   and a and their sums (about 50): 101 per component besides wave_depth_decay.
# wave_exp: the reduction 7, Taylor 26, then 2^n: before branch `hgpuref` about 8
# squarings and 4 products for the depths here and the final product (46 in all);
# since, one ldexp (counted as the one multiply it replaces: 34 in all).
# wave_depth_decay: before `hgpuref` two wave_exp, their exponents (1 and 3) and the
# two sums (98); since, the test 2 k (zs + h) > 39 (3) and the seabed's wave_exp with
# its exponent only where it fails (benchmarks/history/BENCHMARKS-2026-12.md, "The seabed term and ldexp in the
# GPU refresh"): 77 with it, 40 without.
# (Branch `hwgpu`: 240 per component over all 200 before it, about 48,000 per node and
# refresh, the section "The water surface and waves"; with it 54 + 199 = 253 per
# component where the prefix is whole, plus the bisection.)
N_COMPS = 200
ELEVATION_FLOPS = 54
DECAY_OTHER_FLOPS = 101
EXP_FLOPS = {"squaring": 46, "ldexp": 34}
BISECTION_STEPS = 8
# This branch's wave_exp and wave_depth_decay (False: as before `hgpuref`, for the
# before column).
NEW_EXP = True


def exp_flops(new):
    return EXP_FLOPS["ldexp" if new else "squaring"]


def decay_flops(new, seabed):
    """Flops of one component of the decay pass, with or without the seabed term."""
    e = exp_flops(new)
    if not new:
        return DECAY_OTHER_FLOPS + 2 * e + 6
    return DECAY_OTHER_FLOPS + 3 + e + 3 + (e + 3 if seabed else 0)


# A proposal, not built (benchmarks/history/BENCHMARKS-2026-12.md, "The seabed term and ldexp in the GPU
# refresh"): the decay pass taking each component's sine, cosine and phase rate from
# the elevation pass (kept per invocation, 3 scalars a component) instead of forming
# them again: the same bits, the phase (6), sin_cos (39) and the phase rate (4) saved
# per prefix component.
REUSED_PHASE_FLOPS = 6 + 39 + 4


def refresh_flops(prefix, seabed_skip=0.0, new=NEW_EXP, reuse_phases=False):
    """Flops of one node refresh whose decay pass sums `prefix` components, of which
    `seabed_skip` leave out the seabed term (counted only with `new`); `reuse_phases`:
    the proposal above."""
    skip = seabed_skip if new else 0.0
    saved = prefix * REUSED_PHASE_FLOPS if reuse_phases else 0.0
    return (N_COMPS * ELEVATION_FLOPS + BISECTION_STEPS * (exp_flops(new) + 5)
            + (prefix - skip) * decay_flops(new, True) + skip * decay_flops(new, False)
            - saved)

# The refresh's work list (branch `hcompact`): per due evaluation the first pass
# writes an entry (node, which, position, velocity: 8) and the second reads it back
# with the node's band (1) and block index (4 B); per node and refresh dispatch the
# second pass's two invocations (two entries per node at most) read the list's
# length (4 B each).
LIST_DUE = 8 + 8 + 1
LIST_DUE_BYTES = 4
LIST_ALWAYS_BYTES = 2 * 4

# Scalars of the cache per element at a step that does not refresh.
OLD_ELEM = 2 * (1 + 28)  # both nodes' band and their 28 (values, rates, two times)
NEW_ELEM = 1 + 32  # the element's band mark and its 32
# An element across a band top: the mark, its 32 (node a's values and both nodes'
# surface), node b's velocity and acceleration (24; branch `hlava`: before, the mark
# and both nodes' band and 28, 59; since branch `hlavastep` the 24 are copies in the
# element's entry, as vec4 rows, not the nodes' cache: the same bytes).
MIXED_ELEM = 1 + 32 + 24
# Flops per element at a step that does not refresh.
OLD_ELEM_FLOPS = 117  # two Hermite interpolations of 7, the means, the surface
NEW_ELEM_FLOPS = 8 * 7 + 3 + 2  # one Hermite interpolation of 8, u +=, the surface
MIXED_ELEM_FLOPS = OLD_ELEM_FLOPS  # 8 x 7 + 7 + 6 x 7 + 6 + 5 = 116 since `hlava`

# wave_refresh_node, per node and refresh dispatch: always its state, its block index
# (4 B) and its band; when its band refreshes also its last velocity (3) and the 14
# t1 scalars it copies (reads), the copy, the new 14, the velocity and the band
# (writes).
NODE_ALWAYS = 1
NODE_DUE = 3 + 14 + 14 + 14 + 3 + 1
# wave_elem_form (this branch), per element and refresh dispatch: always its
# parameters and its nodes' bands; when one of its nodes' bands refreshes, the nodes'
# 2 x 28 (reads) and its 33 (writes); an element across a band top the same (since
# branch `hlava`: node a's values and both surfaces; before, only its mark), and
# since branch `hlavastep` a copy of node b's velocity and acceleration too (24 more
# writes).
ELEM_ALWAYS = 2
ELEM_DUE = 56 + 33
MIXED_DUE = ELEM_DUE + 24
ELEM_FORM_FLOPS = 4 * 6 * 2


def per_node_step(p, case, new, with_prefix=True, new_exp=NEW_EXP, reuse_phases=False,
                  work_list=True):
    """(bytes, flops) per node-step of `case` at precision `p`, the per-element
    cache (`new`, branch `hwavegpu`) or the nodes' (before it); `with_prefix`: each
    band's refresh sums its measured decay prefix (the case's `prefix`, of which the
    case's `seabed_skip` without the seabed term), else all the components (all with
    it); `new_exp`: wave_exp and wave_depth_decay of branch `hgpuref` (else before);
    `work_list`: the refresh's evaluations over a work list (branch `hcompact`), else
    in the pass over the nodes."""
    s = SCALAR[p]
    n_nodes = sum(case["nodes"].values())
    n_elems = sum(case["elems"].values()) + sum(case["mixed"].values())
    per_node = n_elems / n_nodes
    every = case["interval"][0]  # the refresh dispatches' grid
    frac_mixed = sum(case["mixed"].values()) / n_elems
    # The step that does not refresh.
    if new:
        elem = (1 - frac_mixed) * NEW_ELEM + frac_mixed * MIXED_ELEM
        elem_fl = (1 - frac_mixed) * NEW_ELEM_FLOPS + frac_mixed * MIXED_ELEM_FLOPS
    else:
        elem, elem_fl = OLD_ELEM, OLD_ELEM_FLOPS
    b = STILL_BYTES[p] + per_node * elem * s
    fl = STILL_FLOPS[p] + per_node * elem_fl
    # The refresh, amortised: the nodes'.
    b += (NODE_STATE[p] + 4 + NODE_ALWAYS * s) / every
    if work_list:
        b += LIST_ALWAYS_BYTES / every
    for band, n in case["nodes"].items():
        share = n / n_nodes / case["interval"][band]
        b += share * NODE_DUE * s
        if work_list:
            b += share * (LIST_DUE * s + LIST_DUE_BYTES)
        prefix = case.get("prefix", {}).get(band, N_COMPS) if with_prefix else N_COMPS
        skip = case.get("seabed_skip", {}).get(band, 0.0) if with_prefix else 0.0
        fl += share * refresh_flops(prefix, skip, new_exp, reuse_phases)
    if new:
        b += per_node * (ELEM_PARAMS[p] + ELEM_ALWAYS * s) / every
        for band, n in case["elems"].items():
            share = n / n_nodes / case["interval"][band]
            b += share * ELEM_DUE * s
            fl += share * ELEM_FORM_FLOPS
        for band, n in case["mixed"].items():
            b += n / n_nodes / case["interval"][band] * MIXED_DUE * s
    return b, fl


CASES = {
    # benches/gpu_vs_cpu.rs --waves: 100 lines of 51 nodes, one band (SeaSet::single),
    # refresh every 0.126 s, on the grid 1024 steps of 0.1 ms.
    "bench line, 0.1 ms": {
        "interval": {0: 1024},
        "nodes": {0: 51},
        "elems": {0: 50},
        "mixed": {},
    },
    # examples/study_design_check.toml, 6.667 ms, the bands on the sea's scale (branch
    # `hband`, sea::bands::band_interval; the rise bound with |v_z| of main): every 24,
    # 48, 96, 192, 384, 768 steps under -15.8, -15.8, -34.4, -89.6, -195.3 m (the run's
    # log; band 1 empty). Nodes per band and each band's mean decay prefix: the CPU
    # run sampled every second from 10 s to 200 s (examples/wave_prefix_count.rs,
    # branch `hwgpu`: each node's band and the prefix sea::cut::wave_decay_prefix,
    # the shader's twin, gives at its state); elements estimated from the nodes: each
    # of the 8 chains taken to cross every top between its occupied bands once (an
    # element across a top refreshes with its finer node).
    # The same member with each node's band decided at its own band's refreshes,
    # looking two of the band's intervals ahead (branch `hhorizon`,
    # sea::bands::BAND_LOOK_AHEAD): nodes per band, the CPU run's census logged every
    # second from 10 s to 200 s (RUST_LOG=cablesim=debug); elements estimated from
    # the nodes as below, but with fewer than 8 nodes in a band all of its nodes' upper
    # elements taken as across a top. The decay prefixes and their seabed skips
    # measured with these bands (examples/wave_prefix_count.rs on main after the
    # merge of `hhorizon`, `hgpuref`, `hcompact`, the same samples; its node census
    # equals the log's).
    "design member, 6.7 ms": {
        "interval": {0: 24, 1: 48, 2: 96, 3: 192, 4: 384, 5: 768},
        "nodes": {0: 4.29, 1: 1.14, 2: 10.58, 3: 29.56, 4: 72.73, 5: 209.7},
        "elems": {2: 2.58, 3: 21.56, 4: 64.73, 5: 201.7},
        "mixed": {0: 4.29, 1: 1.14, 2: 8, 3: 8, 4: 8},
        "prefix": {0: 200.0, 1: 200.0, 2: 198.5, 3: 147.5, 4: 85.2, 5: 51.4},
        "seabed_skip": {0: 135.4, 1: 135.0, 2: 131.7, 3: 70.7, 4: 4.4, 5: 0.0},
    },
    # Before branch `hhorizon` (main cf2e924): decided at the coarsest band's refreshes.
    "design member, 6.7 ms, before": {
        "interval": {0: 24, 2: 96, 3: 192, 4: 384, 5: 768},
        "nodes": {0: 10.3, 2: 8.8, 3: 26.0, 4: 58.8, 5: 224.2},
        "elems": {0: 2.3, 2: 0.8, 3: 18.0, 4: 50.8, 5: 216.2},
        "mixed": {0: 8, 2: 8, 3: 8, 4: 8},
        "prefix": {0: 198.9, 2: 190.3, 3: 145.1, 4: 90.3, 5: 52.4},
        # Of each band's prefix, the mean number of components whose seabed term the
        # refresh leaves out (2 k (zs + h) > 39; the same run, branch `hgpuref`).
        "seabed_skip": {0: 133.3, 2: 121.6, 3: 67.9, 4: 5.7, 5: 0.0},
    },
    # The same member with the relative bands (main before the sea's scale): every 24,
    # 48, 96, 192 steps (the run's log); nodes and elements per band estimated from
    # the CPU run's positions at 20 s (z + the 2 m margin against the tops -15.8,
    # -18.8, -99.3 m); an element across a top refreshes with its finer node.
    "design member, relative bands": {
        "interval": {0: 24, 1: 48, 2: 96, 3: 192},
        "nodes": {0: 6, 1: 2, 2: 40, 3: 280},
        "elems": {2: 32, 3: 272},
        "mixed": {0: 6, 1: 2, 2: 8},
    },
    # The same member with every node in band 0 (one band, as main before `hband`, or
    # a sea whose bands all refresh every 24 steps): the worst case for the refresh.
    # The prefix: the mean over every node of the banded run's samples (the nodes'
    # depths hardly depend on the banding).
    "design member, one band": {
        "interval": {0: 24},
        "nodes": {0: 328},
        "elems": {0: 320},
        "mixed": {},
        "prefix": {0: (10.3 * 198.9 + 8.8 * 190.3 + 26.0 * 145.1 + 58.8 * 90.3
                       + 224.2 * 52.4) / 328.1},
        "seabed_skip": {0: (10.3 * 133.3 + 8.8 * 121.6 + 26.0 * 67.9 + 58.8 * 5.7
                            + 224.2 * 0.0) / 328.1},
    },
}


def main():
    print("| case | precision | still B | B without the work list | B (ratio) "
          "| still flops | flops, every refresh over all 200 (ratio) "
          "| flops, the decay prefix counted, before `hgpuref` (ratio) "
          "| flops, the decay prefix counted (ratio) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, case in CASES.items():
        for p in ("f32", "f64"):
            nb, full = per_node_step(p, case, True, False)
            _, before = per_node_step(p, case, True, True, False)
            _, cut = per_node_step(p, case, True, True)
            ob, _ = per_node_step(p, case, True, True, work_list=False)
            sb, sf = STILL_BYTES[p], STILL_FLOPS[p]

            def measured(v):
                return f"{v:.0f} ({v / sf:.2f}x)" if "prefix" in case else "(not measured)"
            print(f"| {name} | {p} | {sb} | {ob:.1f} ({ob / sb:.3f}x) "
                  f"| {nb:.1f} ({nb / sb:.3f}x) | {sf} | "
                  f"{full:.0f} ({full / sf:.2f}x) | {measured(before)} | {measured(cut)} |")
    print()
    print("Proposal (not built): the decay pass reusing the elevation pass's phases")
    print()
    print("| case | precision | still flops | flops, the decay prefix counted (ratio) |")
    print("|---|---|---:|---:|")
    for name, case in CASES.items():
        if "prefix" not in case:
            continue
        for p in ("f32", "f64"):
            _, fl = per_node_step(p, case, True, True, NEW_EXP, True)
            sf = STILL_FLOPS[p]
            print(f"| {name} | {p} | {sf} | {fl:.0f} ({fl / sf:.2f}x) |")


if __name__ == "__main__":
    main()
