#!/usr/bin/env python3
"""Free decay of a moored free body: cablesim against MoorDyn 2.7.2, from one MoorDyn
input file with a BODIES section.

    python3 scripts/compare_free_decay.py [--cablesim target/ci/cablesim] [--out DIR]

The system (our own design): a subsurface buoy, a MoorDyn `Free` body of 2000 kg and
3 m^3 (centre of gravity and of buoyancy at its reference point, inertia 2000, 2000,
3000 kg m^2, Ca 1, translational CdA 2 m^2 and rotational 5 m^5), on three ropes of
68 m (2.5 kg/m, 0.05 m, EA 1e7 N) to anchors 60 m away on the seabed in 50 m of water,
held at points 1.5 m out and 1 m below its reference point (points `Body1`).

1. cablesim finds the equilibrium (the file with TmaxIC > 0 converted: the body
   relaxed with its lines, `initial = "equilibrium"`).
2. The same file with the body placed 3 m off that equilibrium in x and 1 m in z, and
   TmaxIC = 0: both tools start from that pose with their lines hanging between their
   ends (MoorDyn: its catenaries; cablesim: `initial = "pose"`, the lines relaxed with
   their ends held), and the run is the release. cablesim runs the file as `cablesim
   convert` writes it.

The body's motion series (x, y, z, roll, pitch, yaw every 0.1 s for 60 s) of the two
are compared: the rms difference of each translation over the initial offset (3.16 m),
of each angle in degrees. Writes decay.csv and decay.png into --out (default
target/free_decay/) and prints the table of docs/src/validation.md.

Runs inside .venv-peers/ (made by scripts/compare_peers.py; moordyn pinned in
scripts/requirements-peers.txt).
"""

import argparse
import csv
import math
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "scripts"))
import compare_peers  # noqa: E402  (its virtualenv set-up)

DEPTH, RHO, G = 50.0, 1025.0, 9.81
DT_MD = 2.0e-4
DURATION, DT_OUT = 60.0, 0.1
OFFSET = (3.0, 0.0, 1.0)


def moordyn_file(pose: list[float], tmax_ic: float) -> str:
    """The MoorDyn v2 input file, the body at `pose` (x, y, z, r, p, y in degrees)."""
    s = f"""MoorDyn v2 input file: a free buoy on three ropes (cablesim's free-decay comparison)
---------------------- LINE TYPES -----------------------------------
TypeName  Diam   Mass/m  EA     BA/-zeta  EI   Cd   Ca   CdAx  CaAx
(name)    (m)    (kg/m)  (N)    (N-s/-)   (-)  (-)  (-)  (-)   (-)
rope      0.05   2.5     1.0e7  2.0e4     0    1.2  1.0  0.2   0.0
---------------------- BODIES ---------------------------------------
ID  Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG  I  Volume  CdA  Ca
(#) (word)      (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)
1   Free  {pose[0]!r} {pose[1]!r} {pose[2]!r} {pose[3]!r} {pose[4]!r} {pose[5]!r}  2000.0  0.0  2000|2000|3000  3.0  2.0|5.0  1.0
---------------------- POINTS ---------------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(#) (word)  (m) (m) (m) (kg) (m^3) (m^2) (-)
"""
    for k in range(3):
        a = math.radians(120.0 * k)
        s += f"{2 * k + 1}  Fixed  {60.0 * math.cos(a)!r}  {60.0 * math.sin(a)!r}  {-DEPTH!r}  0 0 0 0\n"
        s += f"{2 * k + 2}  Body1  {1.5 * math.cos(a)!r}  {1.5 * math.sin(a)!r}  -1.0  0 0 0 0\n"
    s += """---------------------- LINES ----------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(#) (name)    (#)      (#)      (m)       (-)      (-)
"""
    for k in range(3):
        s += f"{k + 1}  rope  {2 * k + 1}  {2 * k + 2}  68.0  20  -\n"
    s += f"""---------------------- OPTIONS --------------------------------------
{DT_MD!r}  dtM
{G!r}  g
{RHO!r}  rho
{DEPTH!r}  WtrDpth
RK2  tScheme
{tmax_ic!r}  TmaxIC
{DT_OUT!r}  dtOut
1  disableOutput
---------------------- OUTPUTS --------------------------------------
END
------------------------- need this line ----------------------------
"""
    return s


def cablesim_run(exe: str, d: Path, text: str, duration: float) -> list[list[float]]:
    """Converts and runs the MoorDyn file `text` in `d`: the rows of bodies.csv."""
    d.mkdir(parents=True, exist_ok=True)
    (d / "buoy.dat").write_text(text)
    subprocess.run([exe, "convert", str(d / "buoy.dat"), "-o", str(d / "buoy.toml"),
                    "--duration", repr(duration)], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    # (a converter older than this script wrote MoorDyn's RK2, which bodies refuse)
    toml = (d / "buoy.toml").read_text().replace('scheme = "rk2"', '')
    (d / "buoy.toml").write_text(toml)
    subprocess.run([exe, "run", str(d / "buoy.toml"), "--out", str(d / "out"), "--backend",
                    "cpu"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = []
    with open(d / "out" / "bodies.csv") as f:
        for r in csv.DictReader(f):
            rows.append([float(r[k]) for k in ("time", "x", "y", "z", "roll", "pitch", "yaw")])
    return rows


def moordyn_run(d: Path, text: str) -> list[list[float]]:
    import moordyn as md

    d.mkdir(parents=True, exist_ok=True)
    (d / "buoy.dat").write_text(text)
    s = md.Create(str(d / "buoy.dat"))
    if md.Init(s, [], []) != 0:
        raise SystemExit("moordyn.Init failed")
    body = md.GetBody(s, 1)
    rows = []
    t = 0.0
    n = round(DURATION / DT_OUT)

    def row(t):
        r, _ = md.GetBodyState(body)
        r = list(r)
        return [t, r[0], r[1], r[2]] + [math.degrees(x) for x in r[3:6]]

    rows.append(row(0.0))
    for i in range(n):
        md.Step(s, [], [], t, DT_OUT)
        t = (i + 1) * DT_OUT
        rows.append(row(t))
    md.Close(s)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cablesim", default=str(REPO / "target" / "ci" / "cablesim"))
    ap.add_argument("--out", type=Path, default=REPO / "target" / "free_decay")
    ap.add_argument("--settle", action="store_true",
                    help="find the equilibrium by a released run instead of the statics")
    ap.add_argument("--python", help="use this interpreter as it is, no .venv-peers")
    args = ap.parse_args()
    if not args.python:
        compare_peers.ensure_venv_and_reexec(Path(__file__))
    out = args.out.resolve()
    # 1. The equilibrium: cablesim's statics with the body's degrees of freedom (TmaxIC
    # > 0), or with --settle, the body released near it and run until at rest.
    if args.settle:
        eq = cablesim_run(args.cablesim, out / "equilibrium",
                          moordyn_file([0.0, 0.0, -14.3, 0.0, 0.0, 0.0], 0.0), 200.0)[-1]
        how = "released and run for 200 s"
    else:
        eq = cablesim_run(args.cablesim, out / "equilibrium",
                          moordyn_file([0.0, 0.0, -20.0, 0.0, 0.0, 0.0], 60.0), 0.2)[0]
        how = "cablesim's statics"
    print(f"equilibrium ({how}): x {eq[1]:.4f} y {eq[2]:.4f} z {eq[3]:.4f} m, "
          f"roll {eq[4]:.4f} pitch {eq[5]:.4f} yaw {eq[6]:.4f} deg")
    pose = [eq[1] + OFFSET[0], eq[2] + OFFSET[1], eq[3] + OFFSET[2], 0.0, 0.0, 0.0]
    text = moordyn_file(pose, 0.0)
    cs = cablesim_run(args.cablesim, out / "cablesim", text, DURATION)
    mdr = moordyn_run(out / "moordyn", text)
    n = min(len(cs), len(mdr))
    cs, mdr = cs[:n], mdr[:n]
    assert all(abs(a[0] - b[0]) < 1e-6 for a, b in zip(cs, mdr)), "output times differ"
    off = math.sqrt(sum(x * x for x in OFFSET))
    names = ["x", "y", "z", "roll", "pitch", "yaw"]
    print(f"release from {OFFSET} m off the equilibrium, {DURATION} s, every {DT_OUT} s:")
    print("| DOF | rms difference | relative to the offset | largest excursion (MoorDyn) |")
    print("|---|---|---|---|")
    for k, nm in enumerate(names):
        d = [a[k + 1] - b[k + 1] for a, b in zip(cs, mdr)]
        rms = math.sqrt(sum(x * x for x in d) / len(d))
        ex = max(abs(b[k + 1] - eq[k + 1]) for b in mdr)
        unit = "m" if k < 3 else "deg"
        rel = f"{100 * rms / off:.2f} %" if k < 3 else "-"
        print(f"| {nm} | {rms:.4f} {unit} | {rel} | {ex:.4f} {unit} |")
    with open(out / "decay.csv", "w") as f:
        w = csv.writer(f)
        w.writerow(["time"] + [f"cablesim_{x}" for x in names] + [f"moordyn_{x}" for x in names])
        for a, b in zip(cs, mdr):
            w.writerow([a[0]] + a[1:] + b[1:])
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axs = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
        for ax, k, unit in zip(axs, (1, 3, 5), ("m", "m", "deg")):
            ax.plot([r[0] for r in mdr], [r[k] for r in mdr], label="MoorDyn 2.7.2", lw=2)
            ax.plot([r[0] for r in cs], [r[k] for r in cs], "--", label="cablesim", lw=1.5)
            ax.set_ylabel(f"{names[k - 1]} ({unit})")
            ax.grid(alpha=0.3)
        axs[0].legend()
        axs[-1].set_xlabel("time (s)")
        fig.suptitle("Free decay of a moored free body (3 m surge, 1 m heave off equilibrium)")
        fig.tight_layout()
        fig.savefig(out / "decay.png", dpi=110)
        print(f"figure: {out / 'decay.png'}")
    except ImportError:
        pass


if __name__ == "__main__":
    main()
