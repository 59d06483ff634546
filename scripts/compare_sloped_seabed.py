#!/usr/bin/env python3
"""A chain on a sloped seabed: cablesim's static equilibrium on a seabed grid (a plane
rising along the line at angle alpha, `[environment] seabed_file`) against MoorPy
1.3.0's catenary with `alpha`, frictionless.

    python3 scripts/compare_sloped_seabed.py [--cablesim target/ci/cablesim] [--segments 100]

The line is the one of tests/cpu/seabed_slope.rs: 500 m of chain (100 kg/m, 0.1 m,
EA 7.5e9 N) from an anchor on the seabed at z = -100 m to a fairlead 470 m away and
90 m above it; the seabed rises by tan(alpha) along x. cablesim's end forces are those
of `end_forces.csv` at t = 0 (the relaxed initial state). MoorPy's are those of
`moorpy.Catenary.catenary(XF, ZF, L, EA, W, CB=0, alpha)`. Prints, per slope, both
tools' fairlead and anchor tensions and the differences.

Needs MoorPy 1.3.0 importable (`pip install moorpy==1.3.0`, or the .venv-peers of
scripts/compare_peers.py).
"""

import argparse
import math
import subprocess
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SPAN, RISE, LENGTH, EA = 470.0, 90.0, 500.0, 7.5e9
D, M, RHO, G = 0.1, 100.0, 1025.0, 9.81
Z_ANCHOR = -100.0


def wet_weight() -> float:
    return (M - RHO * math.pi * D * D / 4.0) * G


def scenario(segments: int) -> str:
    return f"""
[simulation]
duration = 0.001
dt = "auto"
output_interval = 1.0
backend = "cpu"

[environment]
gravity = {G}
water_density = {RHO}
seabed_file = "slope.txt"

[environment.seabed]
stiffness = 3.0e6
damping = 3.0e4

[[line_types]]
name = "chain"
diameter = {D}
mass_per_length = {M}
ea = {EA}
damping = 1.0e-3
cn = 2.4
ct = 0.4
cm = 1.0

[[cables]]
name = "line1"
line_type = "chain"
length = {LENGTH}
segments = {segments}
start = {{ fixed = [0.0, 0.0, {Z_ANCHOR}] }}
end = {{ fixed = [{SPAN}, 0.0, {Z_ANCHOR + RISE}] }}
initial = "catenary"
"""


def grid(alpha_deg: float) -> str:
    t = math.tan(math.radians(alpha_deg))
    xs, ys = [-50.0, 200.0, 600.0], [-50.0, 50.0]
    rows = [f"{len(xs)} {len(ys)}", " ".join(map(str, xs)), " ".join(map(str, ys))]
    rows += [f"{x} {y} {Z_ANCHOR + x * t!r}" for x in xs for y in ys]
    return "\n".join(rows) + "\n"


def run_cablesim(exe: str, alpha_deg: float, segments: int) -> tuple[float, float]:
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "slope.txt").write_text(grid(alpha_deg))
        p = Path(d) / "slope.toml"
        p.write_text(scenario(segments))
        subprocess.run([exe, "run", str(p), "--out", str(Path(d) / "out")], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rows = (Path(d) / "out" / "end_forces.csv").read_text().splitlines()
        head = rows[0].split(",")
        t = {}
        for r in rows[1:]:
            v = dict(zip(head, r.split(",")))
            if float(v["time"]) != 0.0:
                continue
            f = [float(v[k]) for k in ("fx", "fy", "fz")]
            t[v["end"]] = math.sqrt(sum(x * x for x in f))
        return t["end"], t["start"]


def run_moorpy(alpha_deg: float) -> tuple[float, float]:
    from moorpy.Catenary import catenary

    fah, fav, fbh, fbv, _ = catenary(SPAN, RISE, LENGTH, EA, wet_weight(), CB=0.0,
                                     alpha=alpha_deg)
    return math.hypot(fbh, fbv), math.hypot(fah, fav)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cablesim", default=str(REPO / "target" / "ci" / "cablesim"))
    ap.add_argument("--segments", type=int, default=100)
    args = ap.parse_args()
    print(f"{'alpha':>6} | {'fairlead cablesim':>17} {'MoorPy':>10} {'diff':>8} | "
          f"{'anchor cablesim':>15} {'MoorPy':>10} {'diff':>8}")
    for alpha in (0.0, 2.0, 4.0, -4.0):
        cf, ca = run_cablesim(args.cablesim, alpha, args.segments)
        mf, ma = run_moorpy(alpha)
        print(f"{alpha:6.1f} | {cf:17.1f} {mf:10.1f} {100 * (cf - mf) / mf:+7.3f}% | "
              f"{ca:15.1f} {ma:10.1f} {100 * (ca - ma) / ma:+7.2f}%")


if __name__ == "__main__":
    main()
