#!/usr/bin/env python3
"""cablesim against MoorDyn on one line in regular Airy waves (finite depth).

Run by hand, not by `cargo test`:

    python3 scripts/compare_peers_waves.py --out target/peers-waves --caax 0,1

Like scripts/compare_peers.py (whose helpers, virtualenv and MoorDyn input conversion
it reuses), it makes `.venv-peers/` on first use and re-runs itself there.

The line is the one of `examples/catenary.toml` (250 m of 4 cm wire in 100 m of
water, fairlead 10 m below the mean level, anchor 220 m away along -x). The sea is
one regular wave train, `--height` 4 m, `--period` 12 s, travelling along +x
(`--direction` 0, from the anchor towards the fairlead), Wheeler stretching. Two cases:

* `fixed`: the fairlead held still; the tension varies only through the wave loads
  (drag on the relative velocity, Froude-Krylov and added mass) on the line.
* `moving`: the fairlead moves on a vertical circle in the x-z plane of radius
  `--radius` (1 m) at the wave period, starting at the top of the circle with the
  crest over the fairlead at t = 0, plus the same waves on the line. The fairlead goes
  round against the wave's water particles (at the top it moves along -x, towards the
  anchor, where a particle under the crest moves along +x): both tools are given the
  same circle, so the comparison holds, but it is not the particle's orbit.
  cablesim: `route = "circle"`, axis [0, -1, 0], phase 90 degrees, centre 1 m below
  the static fairlead, so the fairlead starts where it hangs statically. MoorDyn: a
  coupled point given the same circle's position at the start of every `--chunk`
  (0.01 s) and the secant velocity to its position at the chunk's end (MoorDyn moves a
  coupled point linearly in time within a call; the secant keeps the path continuous).

The same kinematics in both tools. MoorDyn v2's `WaveKin 7` (WAVES_SUM_COMPONENTS_NODE,
source/Waves/SpectrumKin.cpp) sums the components of `wave_frequencies.txt` (rows
`omega  Re(A)  Im(A)  beta`, omega in rad/s, beta in rad; the first row must be
omega = 0) at every node at every stage of its integrator, with finite-depth dispersion
and Wheeler stretching, and writes `eta = |A| sin(w t - k (x cos b + y sin b) + arg A)`.
cablesim writes `eta = A cos(k (x cos b + y sin b) - w t + phi)` (docs/src/sea_states.md)
= `A sin(w t - k x' - phi + pi/2)`, so the same wave is MoorDyn's complex amplitude
`A exp(i (pi/2 - phi))`, beta = b. The script checks this: MoorDyn's own kinematics
(`moordyn.GetWavesKin`) at 9 points from the seabed to the crest against the closed
form that cablesim implements, before any run (`kinematics check` in the output).
MoorDyn has no start-up ramp, so cablesim runs with `ramp = 0`; both start from their
still-water static shapes with the full wave at t = 0, and the analysis window is the
last `--window` periods of `--duration` (150 s), after the start transient.

Each case runs once per tangential added-mass coefficient of `--caax` (a list, default
0): MoorDyn's `CaAx` and cablesim's `cat`, the same number (`--md-caax` gives MoorDyn
another one, for experiments). The issue's criteria are checked: the fairlead tension's
first-harmonic amplitude within 2% and its phase within 3 degrees of MoorDyn's.

What is compared, per case: the fairlead tension over the window, as its mean and its
first harmonic (least-squares fit of `T0 + a cos(w t) + b sin(w t)`: amplitude and the
phase of its maximum, in degrees of the wave period after the crest passes x = 0), the
extremes, the RMS of the difference of the two time series (both sampled at the same
times) relative to the tension's amplitude, and the line shape: the largest distance
between the two tools' node positions (same segment count) over the window.

Known differences of the models (see benchmarks/history/BENCHMARKS-2026-12.md "cablesim against MoorDyn in
regular waves" for the measured sizes):

* Water acceleration: the same terms, `(1 + Ca) rho V a_n + (1 + CaAx) rho V a_t`
  (MoorDyn's Line.cpp `Ap`, `Aq`; cablesim's docs/src/model/glmf.md, `cm`, `cat`), and
  the same tangential added mass `CaAx rho V` in the mass; MoorDyn splits the
  acceleration at each node along the node's tangent, cablesim at each element's
  midpoint along the element's.
* Where the kinematics are taken: MoorDyn per node (node velocity against the water
  velocity at the node); cablesim per element (the mean of its two nodes' wave
  velocities plus the current at the midpoint, against the element's velocity), from
  its kinematics cache (values at refresh times, linear in time between, tolerance
  1e-3 of the acceleration).
* Drag on the stretched (cablesim) or unstretched (MoorDyn) length; time schemes
  (cablesim symplectic Euler at its auto step, MoorDyn RK2 at 1e-4 s).
"""

from __future__ import annotations

import argparse
import csv
import datetime as _dt
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import compare_peers as cp  # noqa: E402  (the still-water comparison's helpers)

REPO = cp.REPO


# ---------------------------------------------------------------------------------
# Airy kinematics, the closed form cablesim implements (docs/src/sea_states.md)
# ---------------------------------------------------------------------------------


def wave_number(w: float, h: float, g: float) -> float:
    """k of w^2 = g k tanh(k h), Newton's method on y = k h from Eckart's estimate."""
    a = w * w * h / g
    if a > 19.0:
        return w * w / g
    y = a / math.sqrt(math.tanh(a))
    for _ in range(50):
        t = math.tanh(y)
        f = y * t - a
        y_new = y - f / (t + y * (1.0 - t * t))
        if abs(y_new - y) < 1e-15 * y:
            y = y_new
            break
        y = y_new
    return y / h


def airy(wave: dict, x: float, y: float, z: float, t: float) -> tuple:
    """eta, u (3), a (3) of one regular train, Wheeler-stretched, cablesim's phase."""
    A, w, k, b, phi, h = (wave[n] for n in ("amplitude", "omega", "k", "beta", "phi", "depth"))
    th = k * (x * math.cos(b) + y * math.sin(b)) - w * t + phi
    eta = A * math.cos(th)
    zs = (z - eta) / (1.0 + eta / h)  # Wheeler: [-h, eta] onto [-h, 0]
    zs = min(max(zs, -h), 0.0)
    C = math.cosh(k * (zs + h)) / math.sinh(k * h)
    S = math.sinh(k * (zs + h)) / math.sinh(k * h)
    uh, uz = A * w * C * math.cos(th), A * w * S * math.sin(th)
    ah, az = A * w * w * C * math.sin(th), -A * w * w * S * math.cos(th)
    e = (math.cos(b), math.sin(b))
    return eta, (uh * e[0], uh * e[1], uz), (ah * e[0], ah * e[1], az)


def make_wave(args, line: dict) -> dict:
    w = 2.0 * math.pi / args.period
    k = wave_number(w, line["depth"], line["g"])
    return {
        "height": args.height, "amplitude": args.height / 2.0, "period": args.period,
        "omega": w, "k": k, "wavelength": 2.0 * math.pi / k, "kh": k * line["depth"],
        "direction_deg": args.direction, "beta": math.radians(args.direction),
        "phase_deg": args.phase, "phi": math.radians(args.phase), "depth": line["depth"],
    }


def fairlead_motion(case: str, line: dict, wave: dict, radius: float, t: float) -> tuple:
    """Position and velocity of the fairlead: fixed, or the circle of the cablesim
    route (axis [0, -1, 0]: e1 = +x, e2 = +z; phase 90 deg; centre r below)."""
    fx, fy, fz = line["fairlead"]
    if case == "fixed" or radius == 0.0:
        return [fx, fy, fz], [0.0, 0.0, 0.0]
    w = wave["omega"]
    th = w * t + math.pi / 2.0
    cz = fz - radius
    pos = [fx + radius * math.cos(th), fy, cz + radius * math.sin(th)]
    vel = [-radius * w * math.sin(th), 0.0, radius * w * math.cos(th)]
    return pos, vel


# ---------------------------------------------------------------------------------
# cablesim
# ---------------------------------------------------------------------------------


def write_cablesim_scenario(path: Path, line: dict, wave: dict, case: str, args,
                            caax: float) -> None:
    tv = cp._toml_value
    fx, fy, fz = line["fairlead"]
    if case == "fixed":
        end = {"fixed": line["fairlead"]}
    else:
        end = {"route": "circle", "center": [fx, fy, fz - args.radius],
               "diameter": 2.0 * args.radius, "period": args.period,
               "axis": [0.0, -1.0, 0.0], "phase": 90.0}
    text = f"""# written by scripts/compare_peers_waves.py: the line of {args.scenario.name} in a
# regular wave, case {case!r}
[simulation]
duration = {tv(args.duration)}
dt = "auto"
output_interval = {tv(args.output_interval)}

[environment]
gravity = {tv(line['g'])}
water_density = {tv(line['rho'])}
depth = {tv(line['depth'])}

[environment.seabed]
stiffness = {tv(line['seabed_k'])}
damping = {tv(line['seabed_c'])}
friction = {tv(line['friction'])}

[environment.waves]
stretching = "wheeler"
ramp = 0.0

[[environment.waves.trains]]
type = "regular"
height = {tv(wave['height'])}
period = {tv(wave['period'])}
direction = {tv(wave['direction_deg'])}
phase = {tv(wave['phase_deg'])}

[[line_types]]
name = {tv(line['line_type'])}
diameter = {tv(line['d'])}
mass_per_length = {tv(line['m'])}
ea = {tv(line['ea'])}
damping = {tv(line['c'])}
cn = {tv(line['cn'])}
ct = {tv(line['ct'])}
cm = {tv(line['cm'])}
cat = {tv(caax)}

[[cables]]
name = {tv(line['cable_name'])}
line_type = {tv(line['line_type'])}
length = {tv(line['length'])}
segments = {line['segments']}
start = {tv({'fixed': line['anchor']})}
end = {tv(end)}
initial = "catenary"
output_positions = true
"""
    path.write_text(text)


def read_cablesim(outdir: Path, cable: str) -> tuple[list, dict]:
    """The fairlead force history [[t, fx, fy, fz]] and positions {t: [[x, y, z]]}."""
    hist = []
    with open(outdir / "end_forces.csv") as f:
        for r in csv.DictReader(f):
            if r["cable"] == cable and r["end"] == "end":
                hist.append([float(r["time"]), float(r["fx"]), float(r["fy"]), float(r["fz"])])
    pos: dict = {}
    with open(outdir / "positions.csv") as f:
        for r in csv.DictReader(f):
            if r["cable"] == cable:
                pos.setdefault(round(float(r["time"]), 6), []).append(
                    (int(r["node"]), [float(r["x"]), float(r["y"]), float(r["z"])]))
    pos = {t: [p for _, p in sorted(v)] for t, v in pos.items()}
    return hist, pos


def run_cablesim(binary: str, line: dict, wave: dict, case: str, args, caax: float,
                 tag: str) -> dict:
    d = args.out / "cablesim" / tag
    d.mkdir(parents=True, exist_ok=True)
    scen = d / "scenario.toml"
    write_cablesim_scenario(scen, line, wave, case, args, caax)
    t0 = time.perf_counter()
    s = cp.cablesim_run(binary, scen, d / "out", "symplectic", args.cablesim_threads)
    wall = time.perf_counter() - t0
    if "error" in s or s.get("status") != "completed":
        return {"status": s.get("status", "failed"), "error": s.get("error")}
    hist, pos = read_cablesim(d / "out", line["cable_name"])
    return {"status": "completed", "history": hist, "positions": pos, "dt": s["dt"],
            "steps": s["steps"], "wall_seconds": wall, "scenario": str(scen),
            "command": " ".join(s["command"])}


# ---------------------------------------------------------------------------------
# MoorDyn (in a child process, as in compare_peers.py)
# ---------------------------------------------------------------------------------


def write_moordyn_case(d: Path, line: dict, wave: dict, args, caax: float) -> Path:
    """The input file (compare_peers.py's, plus WaveKin 7) and wave_frequencies.txt."""
    d.mkdir(parents=True, exist_ok=True)
    inp = d / "line.dat"
    cp.write_moordyn_input(inp, line, 1, "RK2", args.md_dt_ic)
    text = inp.read_text().replace(
        "1          disableOutput",
        "7          WaveKin       sum of wave_frequencies.txt at the nodes\n"
        "1          disableOutput")
    assert "WaveKin" in text
    if caax != 0.0:
        # the line type row ends with CaAx (`--md-caax -1` removes MoorDyn's tangential
        # Froude-Krylov term (1 + CaAx) rho V a_t, at the price of a tangential added
        # mass of -rho V: the axial inertia of the wire less its displaced water)
        rows = text.split("\n")
        k = next(i for i, r in enumerate(rows) if r.startswith(line["line_type"] + " "))
        fields = rows[k].split()
        assert len(fields) == 10, rows[k]
        fields[-1] = repr(caax)
        rows[k] = "  ".join(fields)
        text = "\n".join(rows)
    inp.write_text(text)
    p = math.pi / 2.0 - wave["phi"]  # MoorDyn sin(w t - k x + p) = cablesim cos(k x - w t + phi)
    amp = complex(wave["amplitude"] * math.cos(p), wave["amplitude"] * math.sin(p))
    (d / "wave_frequencies.txt").write_text(
        "0.0 0.0 0.0 0.0\n"
        f"{wave['omega']!r} {amp.real!r} {amp.imag!r} {wave['beta']!r}\n")
    return inp


def moordyn_worker(spec_path: str, result_path: str) -> None:
    import moordyn as md

    spec = json.loads(Path(spec_path).read_text())
    line, wave = spec["line"], spec["wave"]
    case, radius, dt, chunk = spec["case"], spec["radius"], spec["dt"], spec["chunk"]
    s = md.Create(spec["input"])
    x0, v0 = fairlead_motion(case, line, wave, radius, 0.0)
    if md.Init(s, x0, v0) != 0:
        raise SystemExit("moordyn.Init failed")
    md.SetDt(s, dt)
    # the same kinematics: MoorDyn's waves at t = 0 against the closed form
    waves = md.GetWaves(s)
    kin = []
    h = line["depth"]
    for x, z in ((0.0, -h), (0.0, -50.0), (0.0, -10.0), (-60.0, -30.0), (-150.0, -80.0),
                 (0.0, 0.0), (-30.0, -1.0), (37.0, 1.5), (-110.0, -99.0)):
        u, a, zeta, _ = md.GetWavesKin(waves, x, 0.0, z, None)
        eta_r, u_r, a_r = airy(wave, x, 0.0, z, 0.0)
        kin.append({"x": x, "z": z, "moordyn": [zeta, *u, *a], "closed_form": [eta_r, *u_r, *a_r]})
    ln = md.GetLine(s, 1)
    nseg = line["segments"]
    n_chunk = max(1, round(chunk / dt))
    n_out = max(1, round(spec["output_interval"] / (n_chunk * dt)))
    n_total = round(spec["duration"] / (n_chunk * dt))
    hist, pos = [], {}
    t = 0.0
    wall = 0.0
    h_chunk = n_chunk * dt
    for i in range(n_total):
        # MoorDyn moves a coupled point linearly within a call, x + v (t' - t): with the
        # secant velocity it ends the call exactly where the next one starts. (With the
        # tangent velocity it would jump by a h^2 / 2 at every call, 1.4e-5 m here, which
        # the stiff end segment, EA / l = 1.3e7 N/m, turns into tension errors of the order
        # of 100 N and a phase error of degrees.)
        x, _ = fairlead_motion(case, line, wave, radius, t)
        x1, _ = fairlead_motion(case, line, wave, radius, (i + 1) * h_chunk)
        v = [(b - a) / h_chunk for a, b in zip(x, x1)]
        w0 = time.perf_counter()
        f = md.Step(s, x, v, t, n_chunk * dt * (1.0 - 1e-9))
        wall += time.perf_counter() - w0
        t = (i + 1) * n_chunk * dt
        if (i + 1) % n_out == 0:
            hist.append([t, *list(f)[:3]])
            if t >= spec["window_start"] - 1e-9:
                pos[round(t, 6)] = [list(md.GetLineNodePos(ln, j)) for j in range(nseg + 1)]
            if not all(math.isfinite(c) for c in f):
                break
    md.Close(s)
    Path(result_path).write_text(json.dumps({
        "status": "completed", "history": hist, "positions": {str(k): v for k, v in pos.items()},
        "kinematics_check": kin, "wall_seconds": wall, "steps": round(t / dt), "dt": dt}))


def run_moordyn(line: dict, wave: dict, case: str, args, window_start: float, caax: float,
                tag: str) -> dict:
    d = args.out / "moordyn" / tag
    inp = write_moordyn_case(d, line, wave, args, caax)
    spec = {"line": line, "wave": wave, "case": case, "radius": args.radius,
            "dt": args.md_dt, "chunk": args.chunk, "duration": args.duration,
            "output_interval": args.output_interval, "window_start": window_start,
            "input": str(inp)}
    sp, rp, lp = d / "spec.json", d / "result.json", d / "worker.log"
    sp.write_text(json.dumps(spec))
    if rp.exists():
        rp.unlink()
    with open(lp, "w") as log:
        p = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--moordyn-worker",
                            str(sp), str(rp)], cwd=d, stdout=log, stderr=subprocess.STDOUT,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode != 0 or not rp.exists():
        return {"status": f"failed (exit {p.returncode}); see {lp}",
                "error": lp.read_text()[-2000:]}
    r = json.loads(rp.read_text())
    r["positions"] = {float(k): v for k, v in r["positions"].items()}
    return r


# ---------------------------------------------------------------------------------
# analysis
# ---------------------------------------------------------------------------------


def harmonic_fit(ts: list, ys: list, w: float) -> dict:
    """Least squares y = c0 + a cos(w t) + b sin(w t) (3x3 normal equations)."""
    rows = [(1.0, math.cos(w * t), math.sin(w * t)) for t in ts]
    M = [[sum(r[i] * r[j] for r in rows) for j in range(3)] for i in range(3)]
    v = [sum(r[i] * y for r, y in zip(rows, ys)) for i in range(3)]
    # Gaussian elimination (3x3, well conditioned over whole periods)
    for c in range(3):
        piv = M[c][c]
        for r in range(c + 1, 3):
            f = M[r][c] / piv
            M[r] = [M[r][j] - f * M[c][j] for j in range(3)]
            v[r] -= f * v[c]
    x = [0.0, 0.0, 0.0]
    for r in (2, 1, 0):
        x[r] = (v[r] - sum(M[r][j] * x[j] for j in range(r + 1, 3))) / M[r][r]
    c0, a, b = x
    amp = math.hypot(a, b)
    # a cos(wt) + b sin(wt) = amp cos(wt - d): the maximum at phase d after t = 0
    lag = math.degrees(math.atan2(b, a)) % 360.0
    resid = [y - (c0 + a * math.cos(w * t) + b * math.sin(w * t)) for t, y in zip(ts, ys)]
    return {"mean": c0, "amplitude": amp, "phase_of_max_deg": lag,
            "residual_rms": math.sqrt(sum(r * r for r in resid) / len(resid))}


def tension_series(hist: list, t0: float, t1: float) -> tuple[list, list]:
    sel = [h for h in hist if t0 - 1e-9 <= h[0] <= t1 + 1e-9]
    return [h[0] for h in sel], [math.sqrt(h[1] ** 2 + h[2] ** 2 + h[3] ** 2) for h in sel]


def compare_case(cs: dict, mdr: dict, wave: dict, t0: float, t1: float) -> dict:
    out: dict = {}
    series = {}
    for name, r in (("cablesim", cs), ("moordyn", mdr)):
        if r is None or r.get("status") != "completed":
            continue
        ts, T = tension_series(r["history"], t0, t1)
        series[name] = dict(zip((round(t, 6) for t in ts), T))
        fit = harmonic_fit(ts, T, wave["omega"])
        out[name] = dict(fit, max=max(T), min=min(T), samples=len(T))
    if len(series) == 2:
        common = sorted(set(series["cablesim"]) & set(series["moordyn"]))
        d = [series["cablesim"][t] - series["moordyn"][t] for t in common]
        amp = out["moordyn"]["amplitude"]
        out["difference"] = {
            "samples": len(common),
            "rms_N": math.sqrt(sum(x * x for x in d) / len(d)) if d else None,
            "max_abs_N": max(abs(x) for x in d) if d else None,
            "mean_rel": (out["cablesim"]["mean"] - out["moordyn"]["mean"]) / out["moordyn"]["mean"],
            "amplitude_rel": (out["cablesim"]["amplitude"] - amp) / amp if amp > 0 else None,
            "phase_deg": ((out["cablesim"]["phase_of_max_deg"] - out["moordyn"]["phase_of_max_deg"]
                           + 180.0) % 360.0) - 180.0,
        }
        pc, pm = cs["positions"], mdr["positions"]
        shared = sorted(t for t in pc if t in pm and t0 - 1e-9 <= t <= t1 + 1e-9)
        worst, worst_t, worst_node = 0.0, None, None
        for t in shared:
            for j, (a, b) in enumerate(zip(pc[t], pm[t])):
                dist = math.dist(a, b)
                if dist > worst:
                    worst, worst_t, worst_node = dist, t, j
        out["difference"].update(shape_max_distance_m=worst, shape_worst_time=worst_t,
                                 shape_worst_node=worst_node, shape_times=len(shared))
    return out


# ---------------------------------------------------------------------------------
# report
# ---------------------------------------------------------------------------------


def write_markdown(path: Path, rep: dict) -> None:
    L, W = rep["line"], rep["wave"]
    m, v = rep["machine"], rep["versions"]
    lines = [
        f"## cablesim against MoorDyn in regular waves ({rep['date']})",
        "",
        f"MoorDyn {v['moordyn']} (PyPI `moordyn`), cablesim {rep['cablesim_rev']}, "
        f"{m['cpu']}. Line of `{rep['scenario']}`; regular wave H = {W['height']:g} m, "
        f"T = {W['period']:g} s, travelling along {W['direction_deg']:g} deg, "
        f"depth {L['depth']:g} m: k = {W['k']:.5f} rad/m, L = {W['wavelength']:.1f} m, "
        f"kh = {W['kh']:.3f}; Wheeler stretching, no ramp. MoorDyn `WaveKin 7` "
        f"(components summed at its nodes), RK2 at "
        f"{rep['md_dt']:g} s; cablesim symplectic "
        "at its auto step, kinematics cache at its default tolerance; each case with "
        "the tangential added-mass coefficient in its name (MoorDyn's CaAx, cablesim's "
        f"cat{rep['md_caax_note']}). Window: "
        f"t = {rep['window'][0]:g} to {rep['window'][1]:g} s.",
        "",
        f"Kinematics check (MoorDyn's `GetWavesKin` against the closed form cablesim "
        f"implements, 9 points from the seabed to above the mean level, at t = 0): largest "
        f"difference {rep['kinematics_check_max']:.2e} of A, A w, A w^2 for eta, u, a "
        "(MoorDyn's wave number is good to seven digits).",
        "",
        "| case | tool | dt (s) | mean T (kN) | 1st harmonic (kN) | phase of max (deg) | "
        "min / max (kN) | wall (s) |",
        "|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for case, c in rep["cases"].items():
        for tool in ("moordyn", "cablesim"):
            r = c["results"].get(tool)
            run = c["runs"].get(tool, {})
            if r is None:
                lines.append(f"| {case} | {tool} | - | {run.get('status', 'skipped')} | | | | |")
                continue
            lines.append(
                f"| {case} | {tool} | {run.get('dt', 0):.3g} | {r['mean'] / 1e3:.4f} | "
                f"{r['amplitude'] / 1e3:.4f} | {r['phase_of_max_deg']:.1f} | "
                f"{r['min'] / 1e3:.3f} / {r['max'] / 1e3:.3f} | {run.get('wall_seconds', 0):.1f} |")
    lines += ["", "| case | mean | amplitude | phase (deg) | RMS of T difference | "
              "largest node distance |", "|---|---:|---:|---:|---:|---:|"]
    for case, c in rep["cases"].items():
        d = c["results"].get("difference")
        if d is None:
            continue
        amp = c["results"]["moordyn"]["amplitude"]
        lines.append(
            f"| {case} | {d['mean_rel']:+.3%} | {d['amplitude_rel']:+.2%} | "
            f"{d['phase_deg']:+.2f} | {d['rms_N']:.1f} N ({d['rms_N'] / amp:.1%} of the "
            f"amplitude) | {d['shape_max_distance_m'] * 100:.2f} cm (node "
            f"{d['shape_worst_node']}, t = {d['shape_worst_time']:g} s) |")
    lines += ["", f"Command: `{rep['command']}`", ""]
    path.write_text("\n".join(lines))


def parse_args():
    ap = argparse.ArgumentParser(description="cablesim against MoorDyn on a line in regular "
                                             "waves (run by hand; makes .venv-peers/).")
    ap.add_argument("--out", type=Path, default=REPO / "target" / "peers-waves")
    ap.add_argument("--scenario", type=Path, default=cp.DEFAULT_SCENARIO,
                    help="the still-water line (default examples/catenary.toml)")
    ap.add_argument("--cablesim-bin", help="a prebuilt cablesim binary (no cargo build)")
    ap.add_argument("--cablesim-threads", type=int, default=1)
    ap.add_argument("--height", type=float, default=4.0, help="wave height, m (4)")
    ap.add_argument("--period", type=float, default=12.0, help="wave period, s (12)")
    ap.add_argument("--direction", type=float, default=0.0, help="direction of travel, deg (0)")
    ap.add_argument("--phase", type=float, default=0.0, help="cablesim phase phi, deg (0)")
    ap.add_argument("--radius", type=float, default=1.0,
                    help="radius of the moving fairlead's circle, m (1)")
    ap.add_argument("--cases", default="fixed,moving")
    ap.add_argument("--duration", type=float, default=150.0, help="simulated s (150)")
    ap.add_argument("--window", type=int, default=4, help="periods analysed at the end (4)")
    ap.add_argument("--output-interval", type=float, default=0.1)
    ap.add_argument("--md-dt", type=float, default=1e-4, help="MoorDyn RK2 dtM (1e-4)")
    ap.add_argument("--md-dt-ic", type=float, default=1e-4)
    ap.add_argument("--caax", default="0",
                    help="tangential added-mass coefficients, comma-separated: each case "
                         "runs with each, as MoorDyn's CaAx and cablesim's cat (0)")
    ap.add_argument("--md-caax", type=float, default=None,
                    help="MoorDyn's CaAx whatever --caax says (an experiment: -1 removes "
                         "its tangential Froude-Krylov force)")
    ap.add_argument("--chunk", type=float, default=0.01,
                    help="MoorDyn: seconds per moordyn.Step call (0.01)")
    ap.add_argument("--skip-moordyn", action="store_true")
    ap.add_argument("--skip-cablesim", action="store_true")
    ap.add_argument("--no-venv", action="store_true")
    a = ap.parse_args()
    a.caax = [float(x) for x in a.caax.split(",") if x.strip()]
    if any(not (math.isfinite(x) and x >= 0.0) for x in a.caax):
        ap.error(f"--caax: coefficients must be finite and not negative, got {a.caax}")
    a.out = a.out if a.out.is_absolute() else Path.cwd() / a.out
    a.scenario = a.scenario if a.scenario.is_absolute() else Path.cwd() / a.scenario
    # find_cablesim() reads these two
    a.repeats = 1
    return a


def main() -> int:
    if len(sys.argv) == 4 and sys.argv[1] == "--moordyn-worker":
        moordyn_worker(sys.argv[2], sys.argv[3])
        return 0
    if "--no-venv" not in sys.argv and "-h" not in sys.argv and "--help" not in sys.argv:
        cp.ensure_venv_and_reexec(Path(__file__))
    args = parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    line, sc = cp.load_line(args.scenario)
    if sc is None:
        raise SystemExit(f"{args.scenario}: not found")
    wave = make_wave(args, line)
    t1 = args.duration
    t0 = t1 - args.window * args.period
    print(f"wave: H {wave['height']:g} m, T {wave['period']:g} s, L {wave['wavelength']:.2f} m, "
          f"kh {wave['kh']:.3f}; window {t0:g}..{t1:g} s", flush=True)
    binary = None
    if not args.skip_cablesim:
        binary, why = cp.find_cablesim(args)
        if binary is None:
            print(f"cablesim: SKIPPED: {why}")
    rep: dict = {
        "date": _dt.datetime.now().astimezone().isoformat(timespec="seconds"),
        "command": "python3 scripts/compare_peers_waves.py " + " ".join(sys.argv[1:]),
        "scenario": str(args.scenario.relative_to(REPO)) if args.scenario.is_relative_to(REPO)
        else str(args.scenario),
        "machine": {"cpu": cp.cpu_model(), "cores": os.cpu_count(),
                    "loadavg_start": " ".join(f"{x:.2f}" for x in os.getloadavg()),
                    "platform": platform.platform()},
        "versions": cp.versions(), "cablesim_rev": cp.git_rev(), "line": line, "wave": wave,
        "md_dt": args.md_dt, "caax": args.caax, "md_caax": args.md_caax,
        "md_caax_note": "" if args.md_caax is None else
        f"; MoorDyn's CaAx {args.md_caax:g} in every case",
        "window": [t0, t1], "cases": {},
    }
    checks, kin_max = [], 0.0
    plan = [(case, caax) for case in [c.strip() for c in args.cases.split(",") if c.strip()]
            for caax in args.caax]
    for case, caax in plan:
        md_caax = caax if args.md_caax is None else args.md_caax
        tag = f"{case}_caax{caax:g}"
        label = f"{case}, CaAx {caax:g}"
        runs: dict = {}
        if not args.skip_moordyn:
            print(f"moordyn: {label}, RK2 dt {args.md_dt:g} s, {args.duration:g} s ...",
                  flush=True)
            runs["moordyn"] = run_moordyn(line, wave, case, args, t0, md_caax, tag)
            # relative to the scales A, A w, A w^2 of eta, u, a
            A, w = wave["amplitude"], wave["omega"]
            scale = [A] + [A * w] * 3 + [A * w * w] * 3
            for k in runs["moordyn"].get("kinematics_check", []):
                kin_max = max(kin_max, *(abs(a - b) / s for a, b, s
                                         in zip(k["moordyn"], k["closed_form"], scale)))
        if binary is not None:
            print(f"cablesim: {label}, symplectic, {args.duration:g} s ...", flush=True)
            runs["cablesim"] = run_cablesim(binary, line, wave, case, args, caax, tag)
        for tool, r in runs.items():
            if r.get("status") != "completed":
                print(f"{tool} {label}: {r.get('status')}: {str(r.get('error'))[-800:]}")
                checks.append((f"{tool} {label} run", False))
        res = compare_case(runs.get("cablesim"), runs.get("moordyn"), wave, t0, t1)
        case = label
        rep["cases"][case] = {
            "results": res,
            "runs": {k: {n: v for n, v in r.items() if n not in ("history", "positions")}
                     for k, r in runs.items()},
            "history": {k: r.get("history") for k, r in runs.items()},
        }
        for tool in ("moordyn", "cablesim"):
            if tool in res:
                r = res[tool]
                print(f"  {case} {tool:8s}: mean {r['mean']:.1f} N, amplitude {r['amplitude']:.1f} N,"
                      f" phase of max {r['phase_of_max_deg']:.2f} deg, min {r['min']:.1f}, "
                      f"max {r['max']:.1f}, fit residual {r['residual_rms']:.1f} N")
        if "difference" in res:
            d = res["difference"]
            print(f"  {case} cablesim - moordyn: mean {d['mean_rel']:+.3%}, amplitude "
                  f"{d['amplitude_rel']:+.2%}, phase {d['phase_deg']:+.2f} deg, RMS {d['rms_N']:.1f} N, "
                  f"max |dT| {d['max_abs_N']:.1f} N, shape {d['shape_max_distance_m']:.4f} m")
            if md_caax == caax:
                checks.append((f"{case}: first-harmonic amplitude within 2% of MoorDyn's "
                               f"({d['amplitude_rel']:+.2%})", abs(d["amplitude_rel"]) <= 0.02))
                checks.append((f"{case}: phase within 3 deg of MoorDyn's "
                               f"({d['phase_deg']:+.2f} deg)", abs(d["phase_deg"]) <= 3.0))
    rep["kinematics_check_max"] = kin_max
    if not args.skip_moordyn:
        # MoorDyn's wave number (J. N. Newman's one-step Newton, Waves.cpp WaveNumber)
        # is good to seven significant digits: differences of order 1e-8 are that.
        checks.append((f"MoorDyn's kinematics = closed form (largest difference "
                       f"{kin_max:.2e} of A, A w, A w^2)", kin_max < 1e-6))
    rep["checks"] = [{"what": w, "ok": ok} for w, ok in checks]
    for w, ok in checks:
        print("check:", w, "ok" if ok else "FAILED")
    (args.out / "peers_waves.json").write_text(json.dumps(rep, indent=1))
    write_markdown(args.out / "peers_waves.md", rep)
    print(f"wrote {args.out / 'peers_waves.json'} and {args.out / 'peers_waves.md'}")
    return 0 if all(ok for _, ok in checks) else 2


if __name__ == "__main__":
    sys.exit(main())
