#!/usr/bin/env python3
"""Compare cablesim with its real peers, MoorDyn (C++ core) and MoorPy, on one line.

Run by hand, not by `cargo test`:

    python3 scripts/compare_peers.py --out target/peers

The first run makes a virtualenv at `.venv-peers/` in the repository root, installs
`scripts/requirements-peers.txt` into it from PyPI (moordyn, MoorPy and their
dependencies, pinned) and re-runs itself with that interpreter (`--no-venv` uses the
current interpreter as it is).

What it does, in one run on one machine:

1. MoorPy (quasi-static elastic catenary with seabed contact): a System with the one
   line, solved; fairlead and anchor forces, touchdown point.
2. MoorDyn v2 (its C++ core through the `moordyn` Python bindings): writes a v2 input
   file for the same line, initialises it (MoorDyn's own static solver), then steps
   it with the fairlead held still, with tScheme Euler and with tScheme RK2 (MoorDyn's
   default). Reports the end forces at the end and the stepping speed in node-steps/s
   = (segments + 1) * steps / wall seconds of stepping (initialisation excluded),
   best of `--repeats` runs. Each MoorDyn case runs in a child process of its own.
3. cablesim: `cablesim run SCENARIO --out DIR --scheme symplectic|rk2`, read back from
   `DIR/summary.json` (skipped, with the reason, where the binary or its `run`
   command is missing).
4. Speed across many cables: N identical lines in one system (N = 1, 10, 100 by
   default), MoorDyn and cablesim, single-threaded.
5. Prints the tables and writes them to OUT/peers.json and OUT/peers.md (markdown
   ready to paste into BENCHMARKS.md, with the CPU model and the peers' versions).

The line is read from the cablesim scenario (default `examples/catenary.toml`), so
the three tools get the same numbers; where the scenario file is missing, the values
below (`DEFAULT_LINE`, the same line) are used and cablesim is skipped.

Exit status: 0 when the sanity checks pass (every dynamic result's fairlead tension
within --tolerance of MoorPy's, the wet weight as expected), 2 when one fails, 1 on
an error.

Unit conventions, and how this script converts cablesim's inputs for MoorDyn
(sources: the MoorDyn docs, https://moordyn.readthedocs.io/en/latest/inputs.html, page
"Input Files", sections "The V2 Input File" -> "Line Types" and "Options"; and MoorDyn-C
v2.7 source, source/Line.cpp, Line::getStateDeriv, which the PyPI wheel is built from):

* Diam [m]: "the volume-equivalent diameter"; buoyancy and added mass use
  A = pi d^2 / 4, as cablesim does. Used unchanged.
* Mass/m [kg/m]: mass per length in air; MoorDyn's wet weight per node is
  g (m_i - rho_w A l_i). Unchanged.
* EA [N]: unchanged; MoorDyn, like cablesim, gives a slack segment no stiffness
  (Line.cpp: T = 0 when the stretched length is below the unstretched one).
* BA/-zeta [N s]: a positive value is the internal damping coefficient BA; the
  damping force of a segment is BA * (d l_stretched/dt) / l_unstretched = BA * epsdot
  (Line.cpp: `Td[i] = BA * ldstr[i] / l[i] * qs[i]`). cablesim's is EA c epsdot
  (docs/src/model/glmf.md), so BA = EA * c. A negative value would be a ratio of critical damping
  per segment instead; not used here.
* Cd (normal drag) w.r.t. the frontal area d l: 1/2 rho Cd d l |vp| vp, cablesim's
  Cn unchanged.
* Ca (normal added mass) w.r.t. the displaced volume: Ca rho A l (I - q q^T),
  cablesim's Cm unchanged.
* CdAx (tangential drag) w.r.t. the surface area pi d l: 1/2 rho CdAx pi d l |vq| vq
  (docs: "with respect to surface area, pi*d*l"; Line.cpp:
  `Dq[i] = vq_mag * Cdt * pi * shared_part * vq` with shared_part = 1/2 rho d l).
  cablesim's tangential drag is 1/2 rho Ct pi d l |vt| vt: the same, CdAx = Ct.
* CaAx (tangential added mass): 0, as cablesim has none.
* kBot [Pa/m = N/m^3] and cBot [Pa s/m = N s/m^3]: docs: "a pressure which is then
  applied to the cross-sectional area (d*l) of each contacting line segment";
  Line.cpp: B_z = ((z_seabed - z) kBot - zdot cBot) d l_node, l_node = half the
  unstretched lengths of the node's segments. cablesim's seabed is
  F = K lt (z_b - z) - C lt zdot with K in N/m per m of cable [N/m^2] and lt the same
  tributary length, so kBot = K / d and cBot = C / d.
* FrictionCoefficient: cablesim's mu (0 here, so the friction models don't matter).
* g, rho, WtrDpth: options of the same names (MoorDyn's seabed is z = -WtrDpth).
* Lengths: MoorDyn lumps drag on the unstretched node length, cablesim on the
  stretched element length: a difference of the strain (1e-4 here), and zero at rest.
* End forces: MoorDyn's `Fnet` of an end node (the line's pull plus the half segment's
  wet weight and loads lumped on it) is what the line exerts on the end point; the
  force a coupled point gets back from `moordyn.Step` is the sum of those. cablesim's
  end_forces are the same quantity (docs/src/model/constraints.md, "End forces"). MoorPy's are the
  continuous catenary's end tensions, which have no lumped half segment: at the anchor
  MoorDyn and cablesim report a vertical pull of -w l0 / 2 (-91.7 N here) where
  MoorPy reports 0.

MoorPy computes the wet weight itself from d_vol and m: w = (m - rho pi d^2 / 4) g.

Time schemes: MoorDyn's `Euler` is the explicit forward Euler on positions and
velocities (source/Time.cpp, EulerScheme::Step), not cablesim's symplectic Euler. With
the Kelvin-Voigt damping of a segment (BA = EA c) its highest axial mode
(omega^2 = 4 EA / (m l0^2), decay gamma = 4 EA c / (m l0^2)) is stable only while
1 - gamma dt + omega^2 dt^2 < 1, i.e. dt < gamma / omega^2 = c (1e-5 s here), far below
the wave-crossing bound l0 / sqrt(EA/m) (1.4e-3 s) that limits a symplectic scheme;
so the Euler case runs at 5e-6 s by default. `RK2` (MoorDyn's default, the midpoint
rule) needs omega^4 dt^3 / 4 < gamma, dt < 2.7e-4 s here; it runs at 1e-4 s.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import hashlib
import json
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
VENV = REPO / ".venv-peers"
REQUIREMENTS = REPO / "scripts" / "requirements-peers.txt"
DEFAULT_SCENARIO = REPO / "examples" / "catenary.toml"

# The line of examples/catenary.toml, used where that file is missing. Defaults of
# cablesim's scenario format (src/model/line_type.rs, src/model/environment.rs) fill
# fields a scenario leaves out.
DEFAULT_LINE = {
    "depth": 100.0,  # m, seabed at z = -depth
    "rho": 1025.0,  # kg/m^3
    "g": 9.81,  # m/s^2
    "seabed_k": 3.0e6,  # N/m per m of cable (N/m^2)
    "seabed_c": 3.0e4,  # N s/m per m of cable (N s/m^2)
    "friction": 0.0,
    "line_type": "wire",
    "d": 0.04,  # m
    "m": 5.0265,  # kg/m
    "ea": 6.2832e7,  # N
    "c": 1.0e-5,  # s, axial damping time constant: force EA c epsdot
    "cn": 1.0,
    "ct": 0.01,
    "cm": 0.2,
    "length": 250.0,  # m, unstretched
    "segments": 50,
    "anchor": [-220.0, 0.0, -100.0],
    "fairlead": [0.0, 0.0, -10.0],
    "cable_name": "line1",
}


# ---------------------------------------------------------------------------------
# virtualenv bootstrap
# ---------------------------------------------------------------------------------


def _venv_python() -> Path:
    return VENV / "bin" / "python"


def _in_venv() -> bool:
    try:
        return Path(sys.prefix).resolve() == VENV.resolve()
    except OSError:
        return False


def _base_python() -> str:
    """An interpreter for making the venv: this one if it is 3.11 or newer (tomllib)."""
    if sys.version_info >= (3, 11):
        return sys.executable
    for name in ("python3.11", "python3.12", "python3.13"):
        p = shutil.which(name)
        if p:
            return p
    sys.exit("compare_peers: needs Python 3.11 or newer to make .venv-peers")


def ensure_venv_and_reexec(script: Path | None = None) -> None:
    """Makes .venv-peers with the pinned peers and re-runs `script` (default: this
    script; scripts/compare_peers_waves.py passes itself) inside it."""
    if _in_venv():
        return
    req_hash = hashlib.sha256(REQUIREMENTS.read_bytes()).hexdigest()
    stamp = VENV / ".peers-requirements.sha256"
    if not _venv_python().exists():
        print(f"compare_peers: making {VENV.relative_to(REPO)}/ ...", flush=True)
        subprocess.run([_base_python(), "-m", "venv", str(VENV)], check=True)
    if not stamp.exists() or stamp.read_text().strip() != req_hash:
        print(
            f"compare_peers: installing {REQUIREMENTS.relative_to(REPO)} into "
            f"{VENV.relative_to(REPO)}/ ...",
            flush=True,
        )
        pip = [str(_venv_python()), "-m", "pip", "--disable-pip-version-check"]
        subprocess.run(pip + ["install", "-q", "-r", str(REQUIREMENTS)], check=True)
        stamp.write_text(req_hash + "\n")
    py = str(_venv_python())
    os.execv(py, [py, str((script or Path(__file__)).resolve())] + sys.argv[1:])


# ---------------------------------------------------------------------------------
# the line
# ---------------------------------------------------------------------------------


def load_line(scenario: Path | None) -> tuple[dict, dict | None]:
    """The line's constants, from the scenario when it exists; and the parsed scenario."""
    line = dict(DEFAULT_LINE)
    if scenario is None or not scenario.exists():
        return line, None
    import tomllib

    sc = tomllib.loads(scenario.read_text())
    env = sc.get("environment", {})
    sb = env.get("seabed", {})
    cur = env.get("current", [0.0, 0.0, 0.0])
    if any(abs(c) > 0 for c in cur) or env.get("current_profile"):
        raise SystemExit(f"{scenario}: has a current; this comparison is for still water")
    cables = sc.get("cables", [])
    if len(cables) != 1:
        raise SystemExit(f"{scenario}: expected one cable, found {len(cables)}")
    cab = cables[0]
    if "fixed" not in cab.get("start", {}) or "fixed" not in cab.get("end", {}):
        raise SystemExit(f"{scenario}: both ends of the cable must be `fixed`")
    lts = {t["name"]: t for t in sc.get("line_types", [])}
    lt = lts[cab["line_type"]]
    if lt.get("ei", 0.0) != 0.0:
        print(f"warning: {scenario}: ei is ignored (GLMF, MoorDyn EI = 0)")
    if "depth" not in env:
        raise SystemExit(f"{scenario}: needs environment.depth (a seabed)")
    line.update(
        depth=float(env["depth"]),
        rho=float(env.get("water_density", 1025.0)),
        g=float(env.get("gravity", 9.81)),
        seabed_k=float(sb.get("stiffness", 3.0e6)),
        seabed_c=float(sb.get("damping", 3.0e4)),
        friction=float(sb.get("friction", 0.0)),
        line_type=lt["name"],
        d=float(lt["diameter"]),
        m=float(lt["mass_per_length"]),
        ea=float(lt["ea"]),
        c=float(lt.get("damping", 0.0)),
        cn=float(lt.get("cn", 1.0)),
        ct=float(lt.get("ct", 0.01)),
        cm=float(lt.get("cm", 1.0)),
        length=float(cab["length"]),
        segments=int(cab["segments"]),
        anchor=[float(v) for v in cab["start"]["fixed"]],
        fairlead=[float(v) for v in cab["end"]["fixed"]],
        cable_name=cab["name"],
    )
    return line, sc


def wet_weight(line: dict) -> float:
    """N/m: (m - rho pi d^2 / 4) g."""
    return (line["m"] - line["rho"] * math.pi * line["d"] ** 2 / 4.0) * line["g"]


def moordyn_params(line: dict) -> dict:
    """cablesim's inputs converted to MoorDyn's (see the module docstring for sources)."""
    return {
        "Diam": line["d"],  # m, volume-equivalent diameter: same
        "MassDen": line["m"],  # kg/m: same
        "EA": line["ea"],  # N: same
        "BA": line["ea"] * line["c"],  # N s: damping force BA*epsdot = EA c epsdot
        "EI": 0.0,  # GLMF has no bending stiffness
        "Cd": line["cn"],  # normal drag on d*l: same
        "Ca": line["cm"],  # normal added mass on A*l: same
        "CdAx": line["ct"],  # tangential drag on pi*d*l: same (cablesim: pi d l too)
        "CaAx": 0.0,  # no tangential added mass in cablesim
        "kBot": line["seabed_k"] / line["d"],  # Pa/m: K [N/m^2] / d, MoorDyn multiplies by d l
        "cBot": line["seabed_c"] / line["d"],  # Pa s/m: C [N s/m^2] / d, likewise
        "FrictionCoefficient": line["friction"],
        "WtrDpth": line["depth"],
        "rho": line["rho"],
        "g": line["g"],
    }


def line_offsets(n_lines: int, spacing: float = 10.0) -> list[float]:
    """y offsets of the N identical lines of the scaling runs (they never touch)."""
    return [spacing * i for i in range(n_lines)]


def write_moordyn_input(path: Path, line: dict, n_lines: int, scheme: str, dt: float) -> None:
    """A MoorDyn v2 input file with n_lines copies of the line, y-offset by 10 m.

    dtM is `dt`; the worker sets the stepping dt after the initial-condition solve with
    moordyn.SetDt, since MoorDyn's stationary IC solver pseudo-steps with dtM and at
    dtM = 5e-6 s it runs to TmaxIC (120 s of pseudo-time, minutes of wall) unconverged.

    Anchors are `Fixed` points; fairleads are `Coupled` points held still by the caller
    (moordyn.Step with the same position and zero velocity), so the force the lines
    exert on them comes back from Step, as in a coupled simulation.
    """
    p = moordyn_params(line)
    ax, ay, az = line["anchor"]
    fx, fy, fz = line["fairlead"]
    out = [
        "--------------------- MoorDyn Input File ------------------------------------",
        f"cablesim peer comparison: {n_lines} x line type {line['line_type']} (written by scripts/compare_peers.py)",
        "---------------------- LINE TYPES ----------------------------------------------------",
        "TypeName  Diam    Mass/m    EA        BA/-zeta  EI       Cd     Ca     CdAx   CaAx",
        "(name)    (m)     (kg/m)    (N)       (N-s/-)   (N-m^2)  (-)    (-)    (-)    (-)",
        f"{line['line_type']}  {p['Diam']!r}  {p['MassDen']!r}  {p['EA']!r}  {p['BA']!r}  "
        f"{p['EI']!r}  {p['Cd']!r}  {p['Ca']!r}  {p['CdAx']!r}  {p['CaAx']!r}",
        "---------------------- POINTS ---------------------------------------------------------",
        "ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca",
        "(#) (word)     (m) (m) (m) (kg) (m^3) (m^2) (-)",
    ]
    for i, y in enumerate(line_offsets(n_lines)):
        out.append(f"{2 * i + 1} Fixed {ax!r} {ay + y!r} {az!r} 0 0 0 0")
        out.append(f"{2 * i + 2} Coupled {fx!r} {fy + y!r} {fz!r} 0 0 0 0")
    out += [
        "---------------------- LINES -----------------------------------------------------------",
        "ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs",
        "(#) (name)    (ID)     (ID)     (m)       (-)      (-)",
    ]
    for i in range(n_lines):
        out.append(
            f"{i + 1} {line['line_type']} {2 * i + 1} {2 * i + 2} {line['length']!r} {line['segments']} -"
        )
    out += [
        "---------------------- OPTIONS ---------------------------------------------------------",
        "0          writeLog",
        f"{dt!r}     dtM           time step (s)",
        f"{scheme}   tScheme       time integrator",
        f"{p['g']!r}  g",
        f"{p['rho']!r}  rho",
        f"{p['WtrDpth']!r}  WtrDpth",
        f"{p['kBot']!r}  kBot          Pa/m = K/d",
        f"{p['cBot']!r}  cBot          Pa-s/m = C/d",
        f"{p['FrictionCoefficient']!r}  FrictionCoefficient",
        "1          disableOutput",
        "------------------------- need this line -------------------------------------",
        "",
    ]
    path.write_text("\n".join(out))


# ---------------------------------------------------------------------------------
# shared post-processing
# ---------------------------------------------------------------------------------


def touchdown_x(positions: list, anchor: list, fairlead: list, seabed_z: float) -> dict:
    """Where a discrete line leaves the seabed.

    Contact nodes are those below the seabed plane (both MoorDyn and cablesim push
    only on a node with z < z_b). Past the last contact node of the run that starts at
    the anchor, the catenary rises as h ~ (s - s_td)^2, so sqrt(h) is linear in s: the
    touchdown is extrapolated from the next two nodes, and clamped between the last
    contact node and the first free one. Returns the global x of the touchdown and of
    the last contact node (None where the line does not touch).
    """
    ux, uy = fairlead[0] - anchor[0], fairlead[1] - anchor[1]
    n = math.hypot(ux, uy)
    ux, uy = ux / n, uy / n
    s = [(p[0] - anchor[0]) * ux + (p[1] - anchor[1]) * uy for p in positions]
    h = [p[2] - seabed_z for p in positions]
    k = -1
    for i, hi in enumerate(h):
        if hi < 0.0 or (i == 0 and hi <= 1e-9):
            k = i
        else:
            break
    if k < 1:
        return {"touchdown_x": None, "last_contact_x": None}
    if k + 2 >= len(h):
        return {"touchdown_x": None, "last_contact_x": positions[k][0]}
    s1, s2 = s[k + 1], s[k + 2]
    r1, r2 = math.sqrt(max(h[k + 1], 0.0)), math.sqrt(max(h[k + 2], 0.0))
    if r2 > r1:
        std = s1 - r1 * (s2 - s1) / (r2 - r1)
    else:
        std = s[k]
    std = min(max(std, s[k]), s1)
    return {
        "touchdown_x": anchor[0] + std * ux,
        "last_contact_x": positions[k][0],
    }


def forces_row(fair: list, anch: list) -> dict:
    """H, V at both ends from the forces the line exerts on them (positive when pulling
    the fairlead down and towards the anchor, and the anchor up and towards the fairlead)."""
    return {
        "fairlead_force": list(fair),
        "anchor_force": list(anch),
        "fairlead_H": math.hypot(fair[0], fair[1]),
        "fairlead_V": -fair[2],
        "fairlead_T": math.sqrt(sum(c * c for c in fair)),
        "anchor_H": math.hypot(anch[0], anch[1]),
        "anchor_V": anch[2],
        "anchor_T": math.sqrt(sum(c * c for c in anch)),
    }


# ---------------------------------------------------------------------------------
# MoorPy
# ---------------------------------------------------------------------------------


def run_moorpy(line: dict) -> dict:
    import moorpy as mp

    t0 = time.perf_counter()
    ms = mp.System(depth=line["depth"], rho=line["rho"], g=line["g"])
    # MoorPy derives w = (m - rho pi d_vol^2 / 4) g from d_vol and m itself.
    ms.setLineType(
        lineType=dict(name=line["line_type"], d_vol=line["d"], m=line["m"], EA=line["ea"]),
        name=line["line_type"],
    )
    ms.addPoint(1, list(line["anchor"]))  # 1 = fixed
    ms.addPoint(1, list(line["fairlead"]))
    # cb = seabed friction coefficient (0: none, as in the other two tools).
    ln = ms.addLine(
        line["length"], line["line_type"], nSegs=line["segments"], pointA=1, pointB=2,
        cb=line["friction"],
    )
    ms.initialize()
    ms.solveEquilibrium()
    wall = time.perf_counter() - t0
    fa = [float(v) for v in ln.fA]  # force of the line on end A (anchor), N
    fb = [float(v) for v in ln.fB]  # on end B (fairlead), N
    row = forces_row(fb, fa)
    # Grounded length LBot lies straight on the seabed at tension H (no friction), so
    # it is stretched by 1 + H/EA.
    lbot = float(ln.LBot)
    ux = line["fairlead"][0] - line["anchor"][0]
    uy = line["fairlead"][1] - line["anchor"][1]
    ux /= math.hypot(ux, uy)
    row.update(
        tool="moorpy",
        scheme="static catenary",
        dt=None,
        touchdown_x=line["anchor"][0] + lbot * (1.0 + row["anchor_H"] / line["ea"]) * ux,
        grounded_length=lbot,
        wet_weight=float(ms.lineTypes[line["line_type"]]["w"]),
        wall_seconds=wall,
        node_steps_per_second=None,
    )
    return row


# ---------------------------------------------------------------------------------
# MoorDyn (each case in a child process: its console output goes to a log, and a
# crash or a blow-up stays there)
# ---------------------------------------------------------------------------------


def _md_step_n(md, sys_, x, v, t, n, dt):
    """n internal steps: MoorDyn steps min(dtM, remaining) until the remaining time is
    <= 0 (MoorDyn2.cpp, MoorDyn::Step); asking for n dtM less a hair gives exactly n."""
    return md.Step(sys_, x, v, t, n * dt * (1.0 - 1e-9))


def moordyn_worker(spec_path: str, result_path: str) -> None:
    """Runs one MoorDyn case described by a JSON file; writes the result as JSON."""
    import moordyn as md

    spec = json.loads(Path(spec_path).read_text())
    n_lines = spec["n_lines"]
    nseg = spec["segments"]
    dt = spec["dt"]
    fair = spec["fairleads"]  # coupled points, held still
    x = [c for p in fair for c in p]
    v = [0.0] * len(x)
    res: dict = {"repeats": []}

    def finite(f):
        return all(math.isfinite(c) and abs(c) < 1e9 for c in f)

    if spec["mode"] == "accuracy":
        n_chunk = max(1, round(spec["chunk"] / dt))
        n_chunks = max(1, round(spec["duration"] / (n_chunk * dt)))
        for rep in range(spec["repeats"]):
            s = md.Create(spec["input"])
            t0 = time.perf_counter()
            err = md.Init(s, x, v)  # MoorDyn's own initial-condition (static) solver
            init_wall = time.perf_counter() - t0
            if err != 0:
                raise SystemExit(f"moordyn.Init failed: {err}")
            md.SetDt(s, dt)  # the input file's dtM was the IC solver's (spec["dt_ic"])
            ln = md.GetLine(s, 1)
            f0 = list(md.Step(s, x, v, 0.0, 0.0))  # dt = 0: the forces, no stepping
            a0 = list(md.GetLineNodeForce(ln, 0))
            hist = [[0.0] + f0[:3]]
            t = 0.0
            wall = 0.0
            status = "completed"
            for _ in range(n_chunks):
                w0 = time.perf_counter()
                f = _md_step_n(md, s, x, v, t, n_chunk, dt)
                wall += time.perf_counter() - w0
                t += n_chunk * dt
                f = list(f)
                hist.append([t] + f[:3])
                if not finite(f):
                    status = "diverged"
                    break
            steps = round(t / dt)
            rec = {
                "init_seconds": init_wall,
                "wall_seconds": wall,
                "steps": steps,
                "simulated_time": t,
                "status": status,
            }
            res["repeats"].append(rec)
            if rep == 0 or status != "completed":
                res.update(
                    t0_fairlead_force=f0[:3],
                    t0_anchor_force=a0,
                    fairlead_force=hist[-1][1:],
                    fairlead_force_node=list(md.GetLineNodeForce(ln, nseg)),
                    anchor_force=list(md.GetLineNodeForce(ln, 0)),
                    positions=[list(md.GetLineNodePos(ln, i)) for i in range(nseg + 1)],
                    history=hist,
                    status=status,
                )
            md.Close(s)
            if status != "completed":
                break
    else:  # throughput: one system, initial profile without the static solve
        s = md.Create(spec["input"])
        md.Init_NoIC(s, x, v)  # MoorDyn's catenary first guess; the static solve of
        # 100 lines takes minutes and does not change the cost of a step
        md.SetDt(s, dt)
        t = 0.0
        f = _md_step_n(md, s, x, v, t, 10, dt)  # warm-up
        t += 10 * dt
        n = spec["steps"]
        status = "completed"
        for _ in range(spec["repeats"]):
            w0 = time.perf_counter()
            f = list(_md_step_n(md, s, x, v, t, n, dt))
            wall = time.perf_counter() - w0
            t += n * dt
            res["repeats"].append({"wall_seconds": wall, "steps": n, "simulated_time": n * dt})
            if not finite(f):
                status = "diverged"
                break
        res["status"] = status
        md.Close(s)
    res["nodes"] = n_lines * (nseg + 1)
    Path(result_path).write_text(json.dumps(res))


def run_moordyn_case(workdir: Path, name: str, line: dict, spec: dict) -> dict:
    """Writes the input file, runs the worker in a child process, returns its result."""
    workdir.mkdir(parents=True, exist_ok=True)
    inp = workdir / f"{name}.dat"
    write_moordyn_input(inp, line, spec["n_lines"], spec["scheme"], spec["dt_ic"])
    fair = [
        [line["fairlead"][0], line["fairlead"][1] + y, line["fairlead"][2]]
        for y in line_offsets(spec["n_lines"])
    ]
    spec = dict(spec, input=str(inp), fairleads=fair, segments=line["segments"])
    spec_path = workdir / f"{name}.spec.json"
    res_path = workdir / f"{name}.result.json"
    log_path = workdir / f"{name}.log"
    spec_path.write_text(json.dumps(spec))
    if res_path.exists():
        res_path.unlink()
    env = dict(os.environ, OMP_NUM_THREADS="1")
    with open(log_path, "w") as log:
        proc = subprocess.run(
            [sys.executable, str(Path(__file__).resolve()), "--moordyn-worker",
             str(spec_path), str(res_path)],
            cwd=workdir, stdout=log, stderr=subprocess.STDOUT, env=env,
        )
    if proc.returncode != 0 or not res_path.exists():
        tail = log_path.read_text()[-2000:]
        return {"status": f"failed (exit {proc.returncode}); see {log_path}", "log_tail": tail}
    return json.loads(res_path.read_text())


def moordyn_accuracy(out: Path, line: dict, scheme: str, dt: float, args) -> dict:
    spec = {
        "mode": "accuracy", "n_lines": 1, "scheme": scheme, "dt": dt, "dt_ic": args.md_dt_ic,
        "duration": args.duration, "chunk": args.chunk, "repeats": args.repeats,
    }
    r = run_moordyn_case(out / "moordyn", f"line-{scheme.lower()}", line, spec)
    row = {"tool": "moordyn", "scheme": scheme, "dt": dt, "status": r.get("status")}
    if "fairlead_force" not in r:
        row["error"] = r.get("log_tail", r.get("status"))
        return row
    row.update(forces_row(r["fairlead_force"], r["anchor_force"]))
    row.update(touchdown_x(r["positions"], line["anchor"], line["fairlead"], -line["depth"]))
    reps = [x for x in r["repeats"] if x["status"] == "completed"]
    nodes = line["segments"] + 1
    if reps:
        walls = [x["wall_seconds"] for x in reps]
        best, med = min(walls), statistics.median(walls)
        steps = reps[0]["steps"]
        row.update(
            steps=steps,
            simulated_time=reps[0]["simulated_time"],
            wall_seconds_best=best,
            wall_seconds_median=med,
            wall_seconds_all=walls,
            init_seconds=statistics.median(x["init_seconds"] for x in reps),
            node_steps_per_second=nodes * steps / best,
            node_steps_per_second_median=nodes * steps / med,
            realtime_factor=reps[0]["simulated_time"] / best,
        )
    hist = r["history"]
    tail = [h for h in hist if h[0] >= hist[-1][0] - 10.0 - 1e-9]
    tens = [math.sqrt(h[1] ** 2 + h[2] ** 2 + h[3] ** 2) for h in tail]
    row.update(
        fairlead_T_last10s_mean=statistics.fmean(tens),
        fairlead_T_last10s_peak_to_peak=max(tens) - min(tens),
        fairlead_force_node=r["fairlead_force_node"],
        history=hist,
        positions=r["positions"],
    )
    row["static_ic"] = forces_row(r["t0_fairlead_force"], r["t0_anchor_force"])
    return row


def moordyn_throughput(out: Path, line: dict, scheme: str, dt: float, n_lines: int, args) -> dict:
    nodes = n_lines * (line["segments"] + 1)
    steps = max(100, int(args.scale_node_steps / nodes))
    spec = {
        "mode": "throughput", "n_lines": n_lines, "scheme": scheme, "dt": dt,
        "dt_ic": args.md_dt_ic,
        "steps": steps, "repeats": args.repeats,
    }
    r = run_moordyn_case(out / "moordyn", f"scale-{scheme.lower()}-{n_lines}", line, spec)
    row = {"tool": "moordyn", "scheme": scheme, "dt": dt, "lines": n_lines, "nodes": nodes,
           "status": r.get("status")}
    reps = r.get("repeats", [])
    if reps and r.get("status") == "completed":
        walls = [x["wall_seconds"] for x in reps]
        row.update(
            steps=steps,
            wall_seconds_all=walls,
            node_steps_per_second=nodes * steps / min(walls),
            node_steps_per_second_median=nodes * steps / statistics.median(walls),
            realtime_factor=steps * dt / min(walls),
        )
    else:
        row["error"] = r.get("log_tail", r.get("status"))
    return row


# ---------------------------------------------------------------------------------
# cablesim
# ---------------------------------------------------------------------------------


def find_cablesim(args) -> tuple[str | None, str]:
    """The cablesim binary, or None and why not."""
    if args.cablesim_bin:
        b = Path(args.cablesim_bin)
        if not b.exists():
            return None, f"--cablesim-bin {b} does not exist"
        binary = str(b.resolve())
    else:
        cargo = shutil.which("cargo")
        if cargo is None:
            return None, "cargo not found (give --cablesim-bin PATH)"
        print("cablesim: cargo build --release --bin cablesim ...", flush=True)
        log = args.out / "cablesim" / "build.log"
        log.parent.mkdir(parents=True, exist_ok=True)
        with open(log, "w") as f:
            p = subprocess.run(
                [cargo, "build", "--release", "--bin", "cablesim"],
                cwd=REPO, stdout=f, stderr=subprocess.STDOUT,
            )
        if p.returncode != 0:
            return None, f"cargo build failed (see {log})"
        target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
        if not target.is_absolute():
            target = REPO / target
        binary = str(target / "release" / "cablesim")
    p = subprocess.run([binary, "run", "--help"], capture_output=True, text=True)
    if p.returncode != 0 or "--scheme" not in p.stdout:
        return None, f"{binary} has no `run` command with --scheme yet (the CLI is not there)"
    return binary, ""



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

def cablesim_run(binary: str, scenario: Path, outdir: Path, scheme: str, threads: int,
                 dt: float | None = None, duration: float | None = None) -> dict:
    """One `cablesim run`; returns summary.json (plus `error` where it failed)."""
    if outdir.exists():
        shutil.rmtree(outdir)
    outdir.parent.mkdir(parents=True, exist_ok=True)
    cmd = [binary, "run", str(scenario), "--out", str(outdir), "--scheme", scheme,
           "--backend", "cpu"]
    if dt is not None:
        cmd += ["--dt", repr(dt)]
    if duration is not None:
        cmd += ["--duration", repr(duration)]
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    (outdir.parent / (outdir.name + ".log")).write_text(
        " ".join(cmd) + "\n" + p.stdout + p.stderr)
    summ = outdir / "summary.json"
    if not summ.exists():
        return {"error": f"exit {p.returncode}: {(p.stderr or p.stdout)[-1500:]}",
                "command": cmd}
    s = with_final_positions(json.loads(summ.read_text()), outdir)
    s["command"] = cmd
    s["warnings"] = [ln.strip() for ln in (p.stderr + p.stdout).splitlines() if "WARN" in ln]
    if p.returncode != 0:
        s["error"] = f"exit {p.returncode}: {p.stderr[-1500:]}"
    return s


def cablesim_accuracy(binary: str, scenario: Path, out: Path, line: dict, scheme: str,
                      args) -> dict:
    runs = []
    for k in range(args.repeats):
        s = cablesim_run(binary, scenario, out / "cablesim" / f"line-{scheme}-{k}", scheme,
                         args.cablesim_threads, dt=args.cablesim_dt, duration=args.duration)
        runs.append(s)
        if "error" in s or s.get("status") != "completed":
            break
    row = {"tool": "cablesim", "scheme": scheme}
    last = runs[-1]
    if "error" in last or last.get("status") != "completed":
        row.update(status=last.get("status", "failed"),
                   error=last.get("error", last.get("status")), dt=last.get("dt"))
        return row
    cab = next((c for c in last["cables"] if c["name"] == line["cable_name"]), last["cables"][0])
    row.update(forces_row(cab["end_forces"]["end"], cab["end_forces"]["start"]))
    row.update(touchdown_x(cab["final_positions"], line["anchor"], line["fairlead"],
                           -line["depth"]))
    walls = [r["wall_seconds"] for r in runs]
    best = min(walls)
    nodes = last["nodes"]
    row.update(
        status="completed",
        dt=last["dt"],
        dt_stable=last.get("dt_stable"),
        dt_limited_by=last.get("dt_limited_by"),
        backend=last.get("backend"),
        precision=last.get("precision"),
        threads=last.get("threads"),
        steps=last["steps"],
        simulated_time=last["simulated_time"],
        wall_seconds_best=best,
        wall_seconds_median=statistics.median(walls),
        wall_seconds_all=walls,
        node_steps_per_second=nodes * last["steps"] / best,
        node_steps_per_second_median=nodes * last["steps"] / statistics.median(walls),
        node_steps_per_second_reported=[r["node_steps_per_second"] for r in runs],
        realtime_factor=last["simulated_time"] / best,
        relax_residual=last.get("relax_residual"),
        positions=cab["final_positions"],
        command=" ".join(last["command"]),
        warnings=last.get("warnings", []),
    )
    return row


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v)} to TOML")


def _toml_table(name: str, d: dict, out: list, array: bool = False) -> None:
    out.append(f"[[{name}]]" if array else f"[{name}]")
    subs = []
    for k, v in d.items():
        if isinstance(v, dict) and not array:
            subs.append((k, v))
        else:
            out.append(f"{k} = {_toml_value(v)}")
    out.append("")
    for k, v in subs:
        _toml_table(f"{name}.{k}", v, out)


def write_scaled_scenario(sc: dict, n_lines: int, path: Path) -> None:
    """The scenario with its one cable copied n_lines times, y-offset by 10 m each."""
    cab = sc["cables"][0]
    out = [f"# {n_lines} copies of the cable of the comparison scenario "
           "(written by scripts/compare_peers.py)", ""]
    for k, v in sc.items():
        if k == "cables":
            continue
        if isinstance(v, dict):
            _toml_table(k, v, out)
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                _toml_table(k, item, out, array=True)
        else:
            out.insert(2, f"{k} = {_toml_value(v)}")
    for i, y in enumerate(line_offsets(n_lines)):
        c = dict(cab)
        c["name"] = f"{cab['name']}_{i}"
        for end in ("start", "end"):
            p = list(cab[end]["fixed"])
            c[end] = {"fixed": [p[0], p[1] + y, p[2]]}
        _toml_table("cables", c, out, array=True)
    path.write_text("\n".join(out))


def cablesim_throughput(binary: str, sc: dict, out: Path, line: dict, scheme: str,
                        n_lines: int, args) -> dict:
    nodes = n_lines * (line["segments"] + 1)
    dt = args.md_dt_rk2  # the cost of a step does not depend on dt
    steps = max(100, int(args.scale_node_steps / nodes))
    scen = out / "cablesim" / f"scale-{n_lines}.toml"
    scen.parent.mkdir(parents=True, exist_ok=True)
    write_scaled_scenario(sc, n_lines, scen)
    row = {"tool": "cablesim", "scheme": scheme, "dt": dt, "lines": n_lines, "nodes": nodes}
    walls, rates = [], []
    for k in range(args.repeats):
        s = cablesim_run(binary, scen, out / "cablesim" / f"scale-{scheme}-{n_lines}-{k}",
                         scheme, args.cablesim_threads, dt=dt, duration=steps * dt)
        if "error" in s or s.get("status") != "completed":
            row.update(status=s.get("status", "failed"), error=s.get("error", s.get("status")))
            return row
        walls.append(s["wall_seconds"])
        rates.append(s["node_steps_per_second"])
        steps_done = s["steps"]
        row["threads"] = s.get("threads")
    best = min(walls)
    row.update(
        status="completed",
        steps=steps_done,
        wall_seconds_all=walls,
        node_steps_per_second=nodes * steps_done / best,
        node_steps_per_second_median=nodes * steps_done / statistics.median(walls),
        node_steps_per_second_reported=rates,
        realtime_factor=steps_done * dt / best,
    )
    return row


# ---------------------------------------------------------------------------------
# report
# ---------------------------------------------------------------------------------


def cpu_model() -> str:
    try:
        for ln in Path("/proc/cpuinfo").read_text().splitlines():
            if ln.lower().startswith("model name"):
                return ln.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def git_rev() -> str:
    try:
        p = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO,
                           capture_output=True, text=True)
        rev = p.stdout.strip()
        if p.returncode != 0 or not rev:
            return "unknown"
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=REPO, capture_output=True, text=True).stdout.strip()
        return rev + ("-dirty" if dirty else "")
    except OSError:
        return "unknown"


def versions() -> dict:
    from importlib.metadata import version

    v = {"python": platform.python_version()}
    for pkg in ("moordyn", "MoorPy", "numpy", "scipy"):
        try:
            v[pkg.lower()] = version(pkg)
        except Exception:
            v[pkg.lower()] = None
    return v


def _f(v, fmt="{:.1f}") -> str:
    return "-" if v is None else fmt.format(v)


def _sci(v) -> str:
    return "-" if v is None else f"{v:.3g}"


MAIN_COLS = ["tool", "scheme", "dt (s)", "fairlead H (N)", "fairlead V (N)", "anchor H (N)",
             "anchor V (N)", "touchdown x (m)", "fairlead T vs MoorPy", "node-steps/s",
             "sim s / wall s"]


def main_table_rows(rows: list, ref: dict | None) -> list:
    out = []
    for r in rows:
        if r.get("fairlead_H") is None:
            out.append([r["tool"], r["scheme"], _sci(r.get("dt")), "-", "-", "-", "-", "-",
                        r.get("status", "skipped"), "-", "-"])
            continue
        dT = None
        if ref is not None and r is not ref:
            dT = (r["fairlead_T"] - ref["fairlead_T"]) / ref["fairlead_T"] * 100.0
        out.append([
            r["tool"], r["scheme"], _sci(r.get("dt")), _f(r["fairlead_H"]), _f(r["fairlead_V"]),
            _f(r["anchor_H"]), _f(r["anchor_V"]), _f(r.get("touchdown_x"), "{:.2f}"),
            "ref" if r is ref else _f(dT, "{:+.3f} %"),
            _f(r.get("node_steps_per_second"), "{:.3e}"),
            _f(r.get("realtime_factor"), "{:.2f}"),
        ])
    return out


SCALE_COLS = ["tool", "scheme", "lines", "nodes", "dt (s)", "node-steps/s (best)",
              "node-steps/s (median)", "sim s / wall s"]


def scale_table_rows(rows: list) -> list:
    out = []
    for r in rows:
        out.append([
            r["tool"], r["scheme"], str(r["lines"]), str(r["nodes"]), _sci(r.get("dt")),
            _f(r.get("node_steps_per_second"), "{:.3e}") if r.get("status") == "completed"
            else r.get("status", "skipped"),
            _f(r.get("node_steps_per_second_median"), "{:.3e}"),
            _f(r.get("realtime_factor"), "{:.3f}"),
        ])
    return out


def text_table(cols: list, rows: list) -> str:
    w = [max(len(c), *(len(r[i]) for r in rows)) if rows else len(c) for i, c in enumerate(cols)]
    line = lambda cells: "  ".join(c.rjust(w[i]) if i > 1 else c.ljust(w[i])
                                   for i, c in enumerate(cells))
    return "\n".join([line(cols), line(["-" * x for x in w])] + [line(r) for r in rows])


def md_table(cols: list, rows: list) -> str:
    out = ["| " + " | ".join(cols) + " |",
           "|" + "|".join("---" if i < 2 else "---:" for i in range(len(cols))) + "|"]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out)


def write_markdown(path: Path, rep: dict, main_rows: list, scale_rows: list) -> None:
    L = rep["line"]
    p = rep["moordyn_inputs"]
    m = rep["machine"]
    v = rep["versions"]
    lines = [
        f"## Peers: MoorDyn and MoorPy on one catenary line ({rep['date']})",
        "",
        f"Machine: {m['cpu']}, {m['cores']} cores (load average {m['loadavg_start']} at the "
        f"start); every tool single-threaded. MoorDyn {v['moordyn']} (PyPI `moordyn`, its "
        f"C++ core), MoorPy {v['moorpy']}, Python {v['python']}, cablesim {rep['cablesim_rev']}.",
        "",
        f"Line (`{rep['scenario']}`): depth {L['depth']:g} m, rho {L['rho']:g} kg/m^3, "
        f"g {L['g']:g} m/s^2; d {L['d']:g} m, m {L['m']:g} kg/m, EA {L['ea']:g} N, "
        f"c {L['c']:g} s, Cn {L['cn']:g}, Ct {L['ct']:g}, Cm {L['cm']:g}; "
        f"{L['length']:g} m unstretched in {L['segments']} segments from "
        f"{L['anchor']} to {L['fairlead']}; seabed K {L['seabed_k']:g} N/m^2, "
        f"C {L['seabed_c']:g} N s/m^2, mu {L['friction']:g}. Wet weight "
        f"{rep['wet_weight']:.3f} N/m.",
        "",
        f"MoorDyn inputs: BA = EA c = {p['BA']:g} N s; CdAx = Ct = {p['CdAx']:g} (both on "
        f"pi d l); kBot = K/d = {p['kBot']:g} Pa/m; cBot = C/d = {p['cBot']:g} Pa s/m; "
        f"Cd = Cn, Ca = Cm, CaAx = 0. Fairlead held still as a coupled point.",
        "",
        f"{rep['duration']:g} s simulated with both ends held still, from each tool's own "
        "start (MoorDyn: its static initial-condition solve; cablesim: the scenario's "
        "`initial`); forces at the end are the forces the line exerts on its ends (H horizontal; V positive pulling "
        "the fairlead down and the anchor up). MoorDyn's and cablesim's end nodes carry half "
        "a segment's wet weight, so their anchor V is about -w l0/2 where MoorPy's is 0. "
        "node-steps/s = nodes x steps / wall seconds of stepping only, best of "
        f"{rep['repeats']}.",
        "",
        md_table(MAIN_COLS, main_rows),
        "",
        "MoorDyn's Euler is forward Euler: with Kelvin-Voigt damping it is stable only for "
        f"dt < c = {L['c']:g} s on this line, hence its small step.",
        "",
    ]
    for r in rep["results"]:
        if r.get("fairlead_T_last10s_mean") is not None:
            lines.append(
                f"- {r['tool']} {r['scheme']}: fairlead tension over the last 10 s: mean "
                f"{r['fairlead_T_last10s_mean']:.1f} N, peak-to-peak "
                f"{r['fairlead_T_last10s_peak_to_peak']:.2f} N; static solve "
                f"{r.get('init_seconds', float('nan')):.2f} s.")
        for wmsg in r.get("warnings", []):
            lines.append(f"- {r['tool']} {r['scheme']}: `{wmsg}`")
    lines += [
        "",
        "N identical lines in one system (MoorDyn from its catenary first guess, no static "
        "solve; cablesim at the same dt):",
        "",
        md_table(SCALE_COLS, scale_rows),
        "",
        f"Checks: {'; '.join(rep['checks_text'])}.",
        "",
        f"Command: `{rep['command']}`",
        "",
    ]
    if rep.get("skipped"):
        lines += [f"Skipped: {'; '.join(rep['skipped'])}.", ""]
    path.write_text("\n".join(lines))


# ---------------------------------------------------------------------------------
# main
# ---------------------------------------------------------------------------------


def parse_args(argv=None):
    ap = argparse.ArgumentParser(
        description="Compare cablesim with MoorDyn and MoorPy on one catenary line "
                    "(run by hand; makes .venv-peers/ on first use).")
    ap.add_argument("--out", type=Path, default=REPO / "target" / "peers",
                    help="output folder (default target/peers)")
    ap.add_argument("--scenario", type=Path, default=DEFAULT_SCENARIO,
                    help="cablesim scenario with the one line (default examples/catenary.toml)")
    ap.add_argument("--cablesim-bin", help="use this prebuilt cablesim binary (no cargo build)")
    ap.add_argument("--cablesim-threads", type=int, default=1,
                    help="RAYON_NUM_THREADS for cablesim (default 1, as MoorDyn)")
    ap.add_argument("--cablesim-dt", type=float, default=None,
                    help="cablesim --dt for the line runs (default: the scenario's, e.g. auto)")
    ap.add_argument("--duration", type=float, default=60.0, help="simulated seconds (60)")
    ap.add_argument("--chunk", type=float, default=0.5,
                    help="MoorDyn: seconds per moordyn.Step call; forces recorded each (0.5)")
    ap.add_argument("--md-dt-euler", type=float, default=5e-6,
                    help="MoorDyn Euler dtM (5e-6; forward Euler needs dt < c here)")
    ap.add_argument("--md-dt-rk2", type=float, default=1e-4, help="MoorDyn RK2 dtM (1e-4)")
    ap.add_argument("--md-dt-ic", type=float, default=1e-4,
                    help="MoorDyn dtM of its static initial-condition solve (1e-4)")
    ap.add_argument("--repeats", type=int, default=3, help="timed runs per case (3); best is kept")
    ap.add_argument("--lines", default="1,10,100", help="line counts of the scaling runs")
    ap.add_argument("--scale-node-steps", type=float, default=2e7,
                    help="node-steps per timed scaling run (2e7)")
    ap.add_argument("--tolerance", type=float, default=0.01,
                    help="relative fairlead-tension tolerance against MoorPy (0.01)")
    ap.add_argument("--skip-moordyn", action="store_true")
    ap.add_argument("--skip-cablesim", action="store_true")
    ap.add_argument("--skip-scaling", action="store_true")
    ap.add_argument("--quick", action="store_true",
                    help="a short smoke run: 5 s, 1 repeat, lines 1,10, 2e6 node-steps")
    ap.add_argument("--no-venv", action="store_true",
                    help="use this interpreter as it is, no .venv-peers")
    a = ap.parse_args(argv)
    if a.quick:
        a.duration, a.repeats, a.lines, a.scale_node_steps = 5.0, 1, "1,10", 2e6
    a.out = a.out if a.out.is_absolute() else Path.cwd() / a.out
    a.scenario = a.scenario if a.scenario.is_absolute() else Path.cwd() / a.scenario
    return a


def main() -> int:
    if len(sys.argv) == 4 and sys.argv[1] == "--moordyn-worker":
        moordyn_worker(sys.argv[2], sys.argv[3])
        return 0
    if "--no-venv" not in sys.argv and "-h" not in sys.argv and "--help" not in sys.argv:
        ensure_venv_and_reexec()
    args = parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    command = "python3 scripts/compare_peers.py " + " ".join(sys.argv[1:])
    skipped: list[str] = []

    line, sc = load_line(args.scenario)
    scen_name = (str(args.scenario.relative_to(REPO)) if args.scenario.is_relative_to(REPO)
                 else str(args.scenario))
    if sc is None:
        skipped.append(f"cablesim: scenario {scen_name} not found (built-in line used)")
        print(f"warning: {args.scenario} not found; using the built-in line, cablesim skipped")
    w = wet_weight(line)
    print(f"line: {line['length']:g} m, {line['segments']} segments, wet weight {w:.4f} N/m")
    rep: dict = {
        "date": _dt.datetime.now().astimezone().isoformat(timespec="seconds"),
        "command": command,
        "scenario": scen_name,
        "machine": {"cpu": cpu_model(), "cores": os.cpu_count(),
                    "loadavg_start": " ".join(f"{x:.2f}" for x in os.getloadavg()),
                    "platform": platform.platform()},
        "versions": versions(),
        "cablesim_rev": git_rev(),
        "line": line,
        "wet_weight": w,
        "moordyn_inputs": moordyn_params(line),
        "duration": args.duration,
        "repeats": args.repeats,
    }

    rows: list = []
    print("moorpy: static catenary ...", flush=True)
    ref = run_moorpy(line)
    rows.append(ref)

    if not args.skip_moordyn:
        md_rows = []
        for scheme, dt in (("Euler", args.md_dt_euler), ("RK2", args.md_dt_rk2)):
            print(f"moordyn: {scheme} dt={dt:g} s, {args.duration:g} s x {args.repeats} ...",
                  flush=True)
            md_rows.append(moordyn_accuracy(args.out, line, scheme, dt, args))
        ic = next((r for r in reversed(md_rows) if "static_ic" in r), None)  # RK2: the default
        if ic is not None:
            r0 = dict(ic["static_ic"], tool="moordyn", scheme="static IC (t=0)", dt=None)
            r0.update(touchdown_x=None)
            rows.append(r0)
        rows += md_rows
    else:
        skipped.append("moordyn: --skip-moordyn")

    binary = None
    if not args.skip_cablesim and sc is not None:
        binary, why = find_cablesim(args)
        if binary is None:
            print(f"cablesim: SKIPPED: {why}")
            skipped.append(f"cablesim: {why}")
        else:
            for scheme in ("symplectic", "rk2"):
                print(f"cablesim: {scheme}, {args.duration:g} s x {args.repeats} ...", flush=True)
                rows.append(cablesim_accuracy(binary, args.scenario, args.out, line, scheme,
                                              args))
    elif args.skip_cablesim:
        skipped.append("cablesim: --skip-cablesim")

    scale: list = []
    if not args.skip_scaling:
        counts = [int(x) for x in args.lines.split(",") if x.strip()]
        for n in counts:
            if not args.skip_moordyn:
                for scheme, dt in (("Euler", args.md_dt_euler), ("RK2", args.md_dt_rk2)):
                    print(f"moordyn: {n} lines, {scheme} ...", flush=True)
                    scale.append(moordyn_throughput(args.out, line, scheme, dt, n, args))
            if binary is not None:
                for scheme in ("symplectic", "rk2"):
                    print(f"cablesim: {n} lines, {scheme} ...", flush=True)
                    scale.append(cablesim_throughput(binary, sc, args.out, line, scheme, n, args))

    # sanity checks
    checks = []
    w_expected = (5.0265 - 1025 * math.pi * 0.04 ** 2 / 4) * 9.81 if sc is None else w
    checks.append({"what": "MoorPy wet weight = (m - rho pi d^2/4) g",
                   "value": ref["wet_weight"], "expected": w_expected,
                   "ok": abs(ref["wet_weight"] - w_expected) < 1e-6 * w_expected})
    for r in rows:
        if r is ref or r.get("fairlead_T") is None:
            continue
        rel = (r["fairlead_T"] - ref["fairlead_T"]) / ref["fairlead_T"]
        checks.append({"what": f"{r['tool']} {r['scheme']}: fairlead T vs MoorPy",
                       "value": rel, "ok": abs(rel) <= args.tolerance})
    for r in rows:
        if r.get("status") not in (None, "completed"):
            checks.append({"what": f"{r['tool']} {r['scheme']}: run", "value": r.get("status"),
                           "ok": False})
    rep["checks"] = checks
    rep["checks_text"] = [
        f"{c['what']}: {c['value']:+.4%}" if isinstance(c["value"], float) and "vs" in c["what"]
        else f"{c['what']}: {c['value']}" for c in checks]
    rep["checks_text"] = [t + (" ok" if c["ok"] else " FAILED")
                          for t, c in zip(rep["checks_text"], checks)]
    rep["skipped"] = skipped
    rep["results"] = rows
    rep["scaling"] = scale

    main_rows = main_table_rows(rows, ref)
    scale_rows = scale_table_rows(scale)
    print()
    print(text_table(MAIN_COLS, main_rows))
    if scale_rows:
        print()
        print(text_table(SCALE_COLS, scale_rows))
    print()
    for t in rep["checks_text"]:
        print("check:", t)
    for s in skipped:
        print("skipped:", s)

    (args.out / "peers.json").write_text(json.dumps(rep, indent=1))
    write_markdown(args.out / "peers.md", rep, main_rows, scale_rows)
    print(f"\nwrote {args.out / 'peers.json'} and {args.out / 'peers.md'}")
    return 0 if all(c["ok"] for c in checks) else 2


if __name__ == "__main__":
    sys.exit(main())
