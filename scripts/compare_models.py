#!/usr/bin/env python3
"""Runs one scenario with the lumped-mass model (GLMF) and with the ANCF reference
(`--formulation ancf`) and compares them, as the paper's Cases 2 and 3 do.

    python3 scripts/compare_models.py examples/case2_circle.toml [--duration 2000]
        [--out out/compare/case2_circle]

Reports, per cable:
- the last node's position difference divided by the deployed unstretched length, over
  time (the paper's Fig. 22 measure): maximum, maximum after the start-up transient
  (the first tenth of the run), and the value at a few times;
- for winch cables, the final positions at the physical coordinates both meshes share
  (distance from the far end; for Case 3 the laid cable): largest difference;
- the mean and spread of the force on the start end over the last third of the run;
- the stepping wall time of each run.
The time series goes to OUT/comparison.csv. Only the Python standard library is used.
"""

import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tomllib



def with_final_positions(summary: dict, out) -> dict:
    """Puts each cable's node positions at the end of the run (``final_state.csv``,
    beside ``summary.json``) into its summary entry as ``final_positions``."""
    import csv as _csv
    import os as _os
    nodes = {}
    path = _os.path.join(str(out), "final_state.csv")
    if _os.path.exists(path):
        with open(path, newline="") as f:
            for r in _csv.DictReader(f):
                nodes.setdefault(r["cable"], []).append(
                    [float(r["x"]), float(r["y"]), float(r["z"])])
    for c in summary.get("cables", []):
        c["final_positions"] = nodes.get(c["name"], [])
    return summary

def run(binary, scenario, out, extra):
    cmd = [binary, "run", scenario, "--out", out, "-q"] + extra
    print("$", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"run failed:\n{r.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        return with_final_positions(json.load(f), out)


def last_nodes(out):
    """{cable: {time: (x, y, z)}} of each cable's last node."""
    d = {}
    with open(os.path.join(out, "positions.csv")) as f:
        for r in csv.DictReader(f):
            c, t, n = r["cable"], float(r["time"]), int(r["node"])
            cur = d.setdefault(c, {}).get(t)
            if cur is None or n > cur[0]:
                d[c][t] = (n, (float(r["x"]), float(r["y"]), float(r["z"])))
    return {c: {t: v[1] for t, v in ts.items()} for c, ts in d.items()}


def deployed(out):
    """{cable: {time: deployed length}} from winches.csv, if any."""
    d = {}
    path = os.path.join(out, "winches.csv")
    if os.path.exists(path):
        with open(path) as f:
            for r in csv.DictReader(f):
                d.setdefault(r["cable"], {})[float(r["time"])] = float(r["deployed_length"])
    return d


def start_forces(out, t_from):
    d = {}
    with open(os.path.join(out, "end_forces.csv")) as f:
        for r in csv.DictReader(f):
            if r["end"] == "start" and float(r["time"]) >= t_from:
                d.setdefault(r["cable"], []).append(
                    (float(r["fx"]), float(r["fy"]), float(r["fz"])))
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario")
    ap.add_argument("--duration", type=float, help="simulated time, s (default: the scenario's)")
    ap.add_argument("--out", help="output directory (default: out/compare/<scenario name>)")
    ap.add_argument("--binary", default="target/release/cablesim")
    a = ap.parse_args()
    if not os.path.exists(a.binary):
        subprocess.run(["cargo", "build", "--release"], check=True)
    name = os.path.splitext(os.path.basename(a.scenario))[0]
    out = a.out or os.path.join("out", "compare", name)
    extra = ["--duration", str(a.duration)] if a.duration else []
    with open(a.scenario, "rb") as f:
        sc = tomllib.load(f)
    lengths = {c["name"]: float(c["length"]) for c in sc.get("cables", [])}
    sg = run(a.binary, a.scenario, os.path.join(out, "glmf"), extra)
    sa = run(a.binary, a.scenario, os.path.join(out, "ancf"), extra + ["--formulation", "ancf"])
    g, an = last_nodes(os.path.join(out, "glmf")), last_nodes(os.path.join(out, "ancf"))
    lg = deployed(os.path.join(out, "glmf"))
    t_end = sg["simulated_time"]
    fg = start_forces(os.path.join(out, "glmf"), 2.0 * t_end / 3.0)
    fa = start_forces(os.path.join(out, "ancf"), 2.0 * t_end / 3.0)
    rows = []
    print(f"\n{a.scenario}: {t_end:g} s simulated")
    print(f"  GLMF: {sg['nodes']} nodes at the end, dt {sg['dt']:.4e} s, {sg['wall_seconds']:.2f} s of stepping")
    print(f"  ANCF: {sa['nodes']} nodes at the end, dt {sa['dt']:.4e} s, {sa['wall_seconds']:.2f} s of stepping")
    for cable in sorted(g):
        ts = sorted(set(g[cable]) & set(an.get(cable, {})))
        if not ts:
            continue
        rel = []
        for t in ts:
            length = lg.get(cable, {}).get(t, lengths.get(cable))
            d = math.dist(g[cable][t], an[cable][t])
            rel.append(d / length if length else float("nan"))
            rows.append((cable, t, length, *g[cable][t], *an[cable][t], d, rel[-1]))
        skip = [r for t, r in zip(ts, rel) if t >= 0.1 * t_end]
        imax = max(range(len(rel)), key=lambda i: rel[i])
        print(f"  cable '{cable}': last node |GLMF - ANCF| / deployed length:")
        print(f"    max {rel[imax]:.3e} (t = {ts[imax]:g} s); after the first tenth {max(skip):.3e}; "
              f"mean after it {statistics.mean(skip):.3e}")
        step = max(1, len(ts) // 10)
        print("    " + "  ".join(f"t={ts[i]:g}: {rel[i]:.2e}" for i in range(0, len(ts), step)))
        cg = next((c for c in sg["cables"] if c["name"] == cable), None)
        ca = next((c for c in sa["cables"] if c["name"] == cable), None)
        if cg and ca and cg.get("winch") and ca.get("winch"):
            pg = {round(p, 6): x for p, x in zip(cg["winch"]["physical_coordinates"], cg["final_positions"])}
            pa = {round(p, 6): x for p, x in zip(ca["winch"]["physical_coordinates"], ca["final_positions"])}
            common = sorted(set(pg) & set(pa))
            diffs = [(p, math.dist(pg[p], pa[p])) for p in common]
            if diffs:
                worst = max(diffs, key=lambda x: x[1])
                print(f"    final positions at the {len(common)} shared physical coordinates: largest difference "
                      f"{worst[1]:.3e} m (p = {worst[0]:g} m from the far end)")
                print("    " + "  ".join(f"p={p:g}: {d:.2f}" for p, d in diffs))
        for label, f in (("GLMF", fg), ("ANCF", fa)):
            v = f.get(cable, [])
            if v:
                comp = list(zip(*v))
                print(f"    {label} start-end force over the last third: "
                      + ", ".join(f"{statistics.mean(x):.1f} +- {statistics.pstdev(x):.1f}" for x in comp) + " N")
    with open(os.path.join(out, "comparison.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["cable", "time", "deployed_length", "glmf_x", "glmf_y", "glmf_z",
                    "ancf_x", "ancf_y", "ancf_z", "difference", "relative"])
        w.writerows(rows)
    print(f"\ntime series: {os.path.join(out, 'comparison.csv')}")


if __name__ == "__main__":
    main()
