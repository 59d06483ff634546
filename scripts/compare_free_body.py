#!/usr/bin/env python3
"""Static equilibrium of a free body on three lines: cablesim against MoorPy 1.3.0 (its
equilibrium solver), intact (cablesim's statics with the body's degrees of freedom,
`initial = "equilibrium"`, and the same buoy released off its equilibrium and run
until it is at rest) and after one line has failed (the run through the failure).

    python3 scripts/compare_free_body.py [--cablesim target/ci/cablesim]

The system is the one of tests/cpu/free_bodies.rs: a buoy of 2000 kg and 3 m^3
(centre of gravity 0.5 m below its reference point, the centre of buoyancy at it), on
three ropes of 68 m (2.5 kg/m, 0.05 m, EA 1e7 N) to anchors 60 m away on the seabed
in 50 m of water, fairleads 1.5 m out and 1 m below the reference point. The failed
case: leg 0 (towards +x) fails at 5 s; MoorPy solves the body on the other two.

Runs inside .venv-peers/ (made by scripts/compare_peers.py; MoorPy pinned in
scripts/requirements-peers.txt). Prints one line per case: the pose of each tool and
the differences (m, degrees).
"""

import argparse
import math
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "scripts"))
import compare_peers  # noqa: E402  (its virtualenv set-up)

DEPTH, RHO, G = 50.0, 1025.0, 9.81
MASS, VOLUME, CG = 2000.0, 3.0, (0.0, 0.0, -0.5)
LINE = dict(d=0.05, m=2.5, ea=1.0e7, length=68.0, segments=20)
ANCHOR_R, FAIRLEAD_R, FAIRLEAD_Z = 60.0, 1.5, -1.0
REFERENCE_Z = -20.0


def scenario(failed: bool, duration: float, initial: str = "pose") -> str:
    s = f"""
[simulation]
duration = {duration}
output_interval = 5.0
backend = "cpu"

[environment]
depth = {DEPTH}
water_density = {RHO}
gravity = {G}

[[line_types]]
name = "rope"
diameter = {LINE['d']}
mass_per_length = {LINE['m']}
ea = {LINE['ea']}
damping = 2.0e-3
cn = 1.2
ct = 0.2
cm = 1.0

[[bodies]]
name = "buoy"
motion = "free"
initial = "{initial}"
reference = [0.0, 0.0, {REFERENCE_Z}]
offset = [3.0, -2.0, 1.0]
angles = [4.0, -3.0, 5.0]
mass = {MASS}
cg = [{CG[0]}, {CG[1]}, {CG[2]}]
inertia = [2000.0, 2000.0, 3000.0]
volume = {VOLUME}
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]
damping = [[1500.0, 0, 0, 0, 0, 0], [0, 1500.0, 0, 0, 0, 0], [0, 0, 3000.0, 0, 0, 0], [0, 0, 0, 2.0e4, 0, 0], [0, 0, 0, 0, 2.0e4, 0], [0, 0, 0, 0, 0, 500.0]]
"""
    for k in range(3):
        a = math.radians(120.0 * k)
        fail = ", fail_time = 5.0" if failed and k == 0 else ""
        s += f"""
[[cables]]
name = "leg{k}"
line_type = "rope"
length = {LINE['length']}
segments = {LINE['segments']}
initial = "catenary"
start = {{ fixed = [{ANCHOR_R * math.cos(a)}, {ANCHOR_R * math.sin(a)}, {-DEPTH}] }}
end = {{ body = "buoy", at = [{FAIRLEAD_R * math.cos(a)}, {FAIRLEAD_R * math.sin(a)}, {FAIRLEAD_Z}]{fail} }}
"""
    return s


def run_cablesim(exe: str, failed: bool, initial: str = "pose") -> list[float]:
    """The pose at the end of the run (released from the file's pose), or at t = 0
    (`initial = "equilibrium"`: the statics' pose)."""
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "buoy.toml"
        statics = initial == "equilibrium"
        p.write_text(scenario(failed, 0.01 if statics else 300.0, initial))
        subprocess.run([exe, "run", str(p), "--out", str(Path(d) / "out")], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rows = (Path(d) / "out" / "bodies.csv").read_text().splitlines()
        row = rows[1] if statics else rows[-1]
        v = [float(x) if i != 1 else 0.0 for i, x in enumerate(row.split(","))]
        speed = max(abs(x) for x in v[14:20])
        if speed > 1e-4:
            print(f"  cablesim: not at rest at the end ({speed:.2e})")
        return v[2:8]


def run_moorpy(failed: bool) -> list[float]:
    import moorpy as mp

    ms = mp.System(depth=DEPTH, rho=RHO, g=G)
    ms.setLineType(lineType=dict(name="rope", d_vol=LINE["d"], m=LINE["m"], EA=LINE["ea"]),
                   name="rope")
    body = ms.addBody(0, [0, 0, REFERENCE_Z, 0, 0, 0], m=MASS, v=VOLUME, rCG=list(CG),
                      rM=[0, 0, 0])
    for k in range(3):
        if failed and k == 0:
            continue
        a = math.radians(120.0 * k)
        ms.addPoint(1, [ANCHOR_R * math.cos(a), ANCHOR_R * math.sin(a), -DEPTH])
        anchor = len(ms.pointList)
        ms.addPoint(1, [FAIRLEAD_R * math.cos(a), FAIRLEAD_R * math.sin(a), FAIRLEAD_Z],
                    body=1)
        ms.addLine(LINE["length"], "rope", nSegs=LINE["segments"], pointA=anchor,
                   pointB=anchor + 1)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-5, maxIter=2000)
    r6 = body.r6
    return [float(r6[0]), float(r6[1]), float(r6[2])] + [math.degrees(float(x)) for x in r6[3:]]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cablesim", default=str(REPO / "target" / "ci" / "cablesim"))
    ap.add_argument("--python", help="use this interpreter as it is, no .venv-peers")
    args = ap.parse_args()
    if not args.python:
        compare_peers.ensure_venv_and_reexec(Path(__file__))
    names = ["x", "y", "z", "roll", "pitch", "yaw"]
    for failed, initial in ((False, "equilibrium"), (False, "pose"), (True, "pose")):
        c = run_cablesim(args.cablesim, failed, initial)
        m = run_moorpy(failed)
        how = "statics" if initial == "equilibrium" else "released, at rest after 300 s"
        print(("after leg 0 failed" if failed else "intact") + f" (cablesim: {how}):")
        for n, a, b in zip(names, c, m):
            print(f"  {n:5s} cablesim {a:12.5f}  moorpy {b:12.5f}  diff {a - b:+.5f}")


if __name__ == "__main__":
    main()
