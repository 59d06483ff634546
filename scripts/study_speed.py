#!/usr/bin/env python3
"""How fast a full mooring design-check study runs on this machine's CPU, and MoorDyn
on one member of it.

Run by hand (it takes minutes; nothing here is a test):

    python3 scripts/study_speed.py --out target/study-speed

The study is `examples/study_design_check.toml`: 8 studless chains of 900 m (40
segments each) on an RAO-driven semi-submersible in 320 m of water, 3 sea states x 10
seeds x 3 hours (30 members, 328 nodes each). Running all of it takes long on a
shared machine, so the script measures shorter runs and says what it extrapolates:

1. `cablesim run` of the base scenario for 1 s: the auto step (`dt`, what limits it)
   and the node count.
2. Growth with duration: one member (sea state `design`, seed 1) for `--durations`
   (default 20, 40, 80 s simulated; transient a quarter of it).
3. Growth with members: `--members` (default 1, 10, 100, 1000) members of
   `--member-duration` (default 4 s; transient 1 s), seeds 1..N of the `design` sea
   state, all threads (`RAYON_NUM_THREADS` unset: the machine's cores).
4. MoorDyn (PyPI `moordyn`, from `.venv-peers/` as scripts/compare_peers.py makes it):
   the same 8 lines (line type converted as in compare_peers.py), fairleads as coupled
   points held still (still water: MoorDyn's cheapest case), RK2 at `--md-dt` (5e-4 s,
   the step of the issue's MoorDyn figure), `--md-duration` (default 20 s) simulated
   after its static solve; the CPU seconds of stepping, scaled to 3 hours and to the
   30 members. With `--md-waves N` also with N wave components summed at the nodes
   (`WaveKin 7`), MoorDyn's way of running an irregular sea at its nodes.

Every cablesim run reports wall seconds and CPU seconds (user + system of the child,
from getrusage): on a machine shared with other jobs the wall time includes waiting
for a core, the CPU time much less so. Node-steps/s = nodes x steps / seconds, with
steps = duration / dt of the members. The full study's time is extrapolated from the
per member-second cost of the largest member-count run (the others show whether the
cost per member-second is flat), divided by the cores for the wall time at full
parallel efficiency; the measured parallel efficiency (CPU / (wall x cores)) is
printed beside it so the reader can judge.

Writes OUT/study_speed.json and OUT/study_speed.md (the BENCHMARKS.md section).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import compare_peers as cp  # noqa: E402  (venv bootstrap, MoorDyn conversion, cpu model)

REPO = cp.REPO
STUDY = REPO / "examples" / "study_design_check.toml"
FULL_MEMBERS = 30
FULL_DURATION = 10800.0
GOAL_WALL_S = 8.5 * 60.0


def find_binary(args) -> str:
    if args.cablesim_bin:
        return str(Path(args.cablesim_bin).resolve())
    print("cargo build --release --bin cablesim ...", flush=True)
    subprocess.run(["cargo", "build", "--release", "--bin", "cablesim"], cwd=REPO, check=True)
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    return str((target if target.is_absolute() else REPO / target) / "release" / "cablesim")


def timed(cmd: list, env: dict | None = None, log: Path | None = None) -> dict:
    """Runs cmd; wall and CPU (user + system) seconds of the child."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if log is not None:
        log.write_text(" ".join(cmd) + "\n" + p.stdout + p.stderr)
    if p.returncode != 0:
        raise SystemExit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr[-3000:]}")
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return {"wall_s": wall, "cpu_s": cpu, "loadavg": os.getloadavg()[0]}


def base_run(binary: str, out: Path) -> dict:
    d = out / "base"
    if d.exists():
        shutil.rmtree(d)
    t = timed([binary, "run", str(STUDY), "--out", str(d), "--duration", "1.0",
               "--backend", "cpu"], log=out / "base.log")
    s = json.loads((d / "summary.json").read_text())
    return {"dt": s["dt"], "dt_stable": s.get("dt_stable"), "dt_limited_by": s.get("dt_limited_by"),
            "nodes": s["nodes"], **t}


def still_water_run(binary: str, out: Path, duration: float) -> dict:
    """The same model without waves (`cablesim run`, one thread): the cost a step in
    waves is compared with. The RAO body then stays in its mean pose."""
    text = STUDY.read_text()
    i, j = text.index("[[environment.waves.trains]]"), text.index("# Studless chain")
    text = text[:i] + text[j:]
    text = text.replace('rao_file = "spread_mooring_rao.csv"',
                        f'rao_file = {json.dumps(str(STUDY.parent / "spread_mooring_rao.csv"))}')
    scen = out / "still_water.toml"
    scen.write_text("# written by scripts/study_speed.py: study_design_check.toml without "
                    "waves\n" + text)
    d = out / "still-water"
    if d.exists():
        shutil.rmtree(d)
    t = timed([binary, "run", str(scen), "--out", str(d), "--duration", repr(duration),
               "--backend", "cpu"], env=dict(os.environ, RAYON_NUM_THREADS="1"),
              log=out / "still-water.log")
    s = json.loads((d / "summary.json").read_text())
    ns = s["nodes"] * s["steps"]
    return {"name": "still water (cablesim run, 1 thread)", "members": 1, "duration": duration,
            "node_steps": ns, "stepping_s": s["wall_seconds"],
            "node_steps_per_stepping_s": ns / s["wall_seconds"],
            "cpu_s_per_member_s": t["cpu_s"] / duration, **t}


def callgrind_profile(binary: str, out: Path, duration: float) -> dict | None:
    """Instruction counts of one member in waves (`cablesim run` of the base scenario,
    one thread) and of the same model in still water, by valgrind's callgrind: what a
    node-step costs and where it goes. Independent of the machine's load."""
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        return None
    res = {"duration": duration}
    for name, scen in (("waves", STUDY), ("still", out / "still_water.toml")):
        f = out / f"callgrind.{name}.out"
        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={f}", binary,
                        "run", str(scen), "--out", str(out / f"cg-{name}"), "--duration",
                        repr(duration), "--backend", "cpu"], capture_output=True,
                       env=dict(os.environ, RAYON_NUM_THREADS="1"), check=True)
        s = json.loads((out / f"cg-{name}" / "summary.json").read_text())
        ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", str(f)],
                             capture_output=True, text=True).stdout
        total, parts = None, {}
        keys = {"wave kinematics refresh (sea::kinematics::wave_kinematics_tau)":
                "cablesim::sea::kinematics::wave_kinematics_tau [",
                "body motion from RAOs (body::Body::state)": "cablesim::body::Body::state [",
                "initial equilibrium (statics::Sys::newton)": "cablesim::statics::Sys::newton [",
                }
        for ln in ann.splitlines():
            ln = ln.strip()
            if ln.endswith("PROGRAM TOTALS"):
                total = int(ln.split()[0].replace(",", ""))
            for k, pat in keys.items():
                if pat in ln and k not in parts:
                    parts[k] = int(ln.split()[0].replace(",", ""))
        # the rest: the cable step itself (forces, masses, integration), output
        parts["everything else (the cable step itself, output, start-up)"] = \
            total - sum(parts.values())
        node_steps = s["nodes"] * s["steps"]
        res[name] = {"instructions": total, "node_steps": node_steps,
                     "per_node_step": total / node_steps,
                     "parts_per_node_step": {k: v / node_steps for k, v in parts.items()}}
    return res


def study_file(out: Path, name: str, members: int, duration: float, transient: float) -> Path:
    """A study file naming the design-check scenario: `members` seeds of one sea state."""
    p = out / f"{name}.toml"
    p.write_text(f"""# written by scripts/study_speed.py
[study]
scenario = {json.dumps(str(STUDY))}
seed = 320
seeds = {members}
duration = {duration!r}
transient = {transient!r}
sea_states = [
  {{ name = "design", hs = 9.0, tp = 13.0, gamma = 2.5, heading = 210.0, current_speed = 0.9, current_heading = 200.0 }},
]
channels = ["default"]
""")
    return p


def study_run(binary: str, out: Path, name: str, members: int, duration: float,
              transient: float, base: dict) -> dict:
    f = study_file(out, name, members, duration, transient)
    d = out / name
    if d.exists():
        shutil.rmtree(d)
    t = timed([binary, "study", "run", str(f), "--out", str(d)], log=out / f"{name}.log")
    res = json.loads((d / "study.json").read_text())
    failed = res["failed"]
    steps = math.ceil(duration / base["dt"] - 1e-9)
    node_steps = members * base["nodes"] * steps
    row = {"name": name, "members": members, "duration": duration, "steps_per_member": steps,
           "node_steps": node_steps, "failed_members": failed, **t}
    row["node_steps_per_wall_s"] = node_steps / t["wall_s"]
    row["node_steps_per_cpu_s"] = node_steps / t["cpu_s"]
    row["cpu_s_per_member_s"] = t["cpu_s"] / (members * duration)
    return row


# ---------------------------------------------------------------------------------
# MoorDyn: the same 8 lines, one member
# ---------------------------------------------------------------------------------


def chain_props(sc: dict) -> dict:
    """The studless-chain line type as cablesim fills it (docs/src/line_types.md)."""
    lt = sc["line_types"][0]
    assert lt.get("material") in ("chain_studless", "chain"), lt
    dn = lt["nominal_diameter"]
    return {"name": lt["name"], "d": 1.80 * dn, "m": 20.0e3 * dn ** 2,
            "ea": 85.6e9 * dn ** 2 - 3.93e7 * dn ** 3, "c": lt.get("damping", 0.0),
            "cn": 1.333, "ct": 0.639, "cm": 1.0}


def write_moordyn_input(path: Path, sc: dict, dt: float, wave_kin: int) -> list:
    """MoorDyn v2 input: the scenario's lines, fairleads as coupled points (their
    static positions with the body at its reference, heading 0). Returns the fairleads."""
    lt = chain_props(sc)
    env = sc["environment"]
    depth = env["depth"]
    sb = env.get("seabed", {})
    k_bot = sb.get("stiffness", 3.0e6) / lt["d"]
    c_bot = sb.get("damping", 3.0e4) / lt["d"]
    ref = sc["bodies"][0]["reference"]
    out = ["--------------------- MoorDyn Input File ------------------------------------",
           "study_design_check.toml, one member (written by scripts/study_speed.py)",
           "---------------------- LINE TYPES ----------------------------------------------",
           "TypeName  Diam  Mass/m  EA  BA/-zeta  EI  Cd  Ca  CdAx  CaAx",
           "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
           f"{lt['name']} {lt['d']!r} {lt['m']!r} {lt['ea']!r} {lt['ea'] * lt['c']!r} 0 "
           f"{lt['cn']!r} {lt['cm']!r} {lt['ct']!r} 0",
           "---------------------- POINTS ----------------------------------------------------",
           "ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca",
           "(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)"]
    fair = []
    for i, c in enumerate(sc["cables"]):
        a = c["start"]["fixed"]
        at = c["end"]["at"]
        f = [ref[0] + at[0], ref[1] + at[1], ref[2] + at[2]]
        fair.append(f)
        out.append(f"{2 * i + 1} Fixed {a[0]!r} {a[1]!r} {a[2]!r} 0 0 0 0")
        out.append(f"{2 * i + 2} Coupled {f[0]!r} {f[1]!r} {f[2]!r} 0 0 0 0")
    out += ["---------------------- LINES -----------------------------------------------------",
            "ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs",
            "(#) (name) (ID) (ID) (m) (-) (-)"]
    for i, c in enumerate(sc["cables"]):
        out.append(f"{i + 1} {lt['name']} {2 * i + 1} {2 * i + 2} {c['length']!r} {c['segments']} -")
    out += ["---------------------- OPTIONS ---------------------------------------------------",
            "0 writeLog", f"{dt!r} dtM", "RK2 tScheme", f"{env.get('gravity', 9.81)!r} g",
            f"{env.get('water_density', 1025.0)!r} rho", f"{depth!r} WtrDpth",
            f"{k_bot!r} kBot", f"{c_bot!r} cBot",
            f"{sb.get('friction', 0.0)!r} FrictionCoefficient"]
    if wave_kin:
        out.append("7 WaveKin")
    out += ["1 disableOutput",
            "------------------------- need this line ----------------------------------------", ""]
    path.write_text("\n".join(out))
    return fair


def write_wave_frequencies(path: Path, n: int, hs: float, tp: float) -> None:
    """n components of a Pierson-Moskowitz sea (Hs, Tp), equal bins over 0.2..2.5 rad/s,
    random phases (the cost does not depend on the exact spectrum)."""
    import random

    rng = random.Random(1)
    wp = 2.0 * math.pi / tp
    lo, hi = 0.2, 2.5
    dw = (hi - lo) / n
    rows = ["0.0 0.0 0.0 0.0"]
    for j in range(n):
        w = lo + (j + 0.5) * dw
        S = 5.0 / 16.0 * hs ** 2 * wp ** 4 * w ** -5 * math.exp(-1.25 * (w / wp) ** -4)
        a = math.sqrt(2.0 * S * dw)
        ph = rng.uniform(0.0, 2.0 * math.pi)
        rows.append(f"{w!r} {a * math.cos(ph)!r} {a * math.sin(ph)!r} 0.0")
    path.write_text("\n".join(rows) + "\n")


def moordyn_worker(spec_path: str, result_path: str) -> None:
    import moordyn as md

    spec = json.loads(Path(spec_path).read_text())
    fair, dt, dur = spec["fairleads"], spec["dt"], spec["duration"]
    x = [c for p in fair for c in p]
    v = [0.0] * len(x)
    s = md.Create(spec["input"])
    c0 = time.process_time()
    if md.Init(s, x, v) != 0:
        raise SystemExit("moordyn.Init failed")
    init_cpu = time.process_time() - c0
    md.SetDt(s, dt)
    chunk = min(1.0, dur)
    n = max(1, round(chunk / dt))
    t = 0.0
    c0, w0 = time.process_time(), time.perf_counter()
    f = None
    while t < dur - 1e-9:
        f = md.Step(s, x, v, t, n * dt * (1.0 - 1e-9))
        t += n * dt
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    md.Close(s)
    ok = f is not None and all(math.isfinite(c) for c in f)
    Path(result_path).write_text(json.dumps({
        "status": "completed" if ok else "diverged", "simulated_s": t, "steps": round(t / dt),
        "cpu_s": cpu, "wall_s": wall, "init_cpu_s": init_cpu,
        "fairlead_tension_N": [math.sqrt(sum(f[3 * i + k] ** 2 for k in range(3)))
                               for i in range(len(fair))] if ok else None}))


def run_moordyn(out: Path, dt: float, duration: float, n_waves: int) -> dict:
    import tomllib

    sc = tomllib.loads(STUDY.read_text())
    name = f"moordyn-{'still' if not n_waves else f'waves{n_waves}'}"
    d = out / name
    d.mkdir(parents=True, exist_ok=True)
    fair = write_moordyn_input(d / "member.dat", sc, dt, 7 if n_waves else 0)
    if n_waves:
        write_wave_frequencies(d / "wave_frequencies.txt", n_waves, 9.0, 13.0)
    spec = {"input": str(d / "member.dat"), "fairleads": fair, "dt": dt, "duration": duration}
    (d / "spec.json").write_text(json.dumps(spec))
    rp = d / "result.json"
    if rp.exists():
        rp.unlink()
    with open(d / "worker.log", "w") as log:
        p = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--moordyn-worker",
                            str(d / "spec.json"), str(rp)], cwd=d, stdout=log,
                           stderr=subprocess.STDOUT, env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode != 0 or not rp.exists():
        return {"name": name, "status": f"failed ({p.returncode}), see {d / 'worker.log'}"}
    r = json.loads(rp.read_text())
    nodes = sum(c["segments"] + 1 for c in sc["cables"])
    r.update(name=name, dt=dt, nodes=nodes, wave_components=n_waves,
             node_steps_per_cpu_s=nodes * r["steps"] / r["cpu_s"],
             cpu_s_per_member_3h=r["cpu_s"] * FULL_DURATION / r["simulated_s"])
    r["cpu_s_study"] = r["cpu_s_per_member_3h"] * FULL_MEMBERS
    return r


# ---------------------------------------------------------------------------------
# report
# ---------------------------------------------------------------------------------


def report(rep: dict, path: Path) -> None:
    b, m = rep["base"], rep["machine"]
    L = [f"## A full design-check study on the CPU ({rep['date']})", "",
         f"`examples/study_design_check.toml`: 8 x 900 m studless chain (102 mm, 40 segments: "
         f"{b['nodes']} nodes per member) on an RAO-driven semi-submersible in 320 m of "
         f"water; the study is 3 sea states x 10 seeds x 3 h = 30 members. Machine: "
         f"{m['cpu']}, {m['cores']} cores, shared with other jobs (load average "
         f"{m['loadavg_start']} at the start, {m['loadavg_end']} at the end). cablesim "
         f"{rep['cablesim_rev']}, CPU backend (f64), symplectic Euler at the auto step "
         f"dt = {b['dt']:.4g} s (limited by {b['dt_limited_by']}).", "",
         "| run | members | simulated s each | wall s | CPU s | node-steps / wall s | "
         "node-steps / CPU s | CPU s per member-s | load |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rep["runs"]:
        L.append(f"| {r['name']} | {r['members']} | {r['duration']:g} | {r['wall_s']:.1f} | "
                 f"{r['cpu_s']:.1f} | {r['node_steps_per_wall_s']:.3g} | "
                 f"{r['node_steps_per_cpu_s']:.3g} | {r['cpu_s_per_member_s']:.4f} | "
                 f"{r['loadavg']:.1f} |")
    e = rep["extrapolation"]
    L += ["", f"Extrapolated full study ({FULL_MEMBERS} members x {FULL_DURATION:g} s, from "
          f"run `{e['from']}`: {e['cpu_s_per_member_s']:.4f} CPU s per member-second): "
          f"{e['cpu_s']:.0f} CPU s, so {e['wall_s_ideal']:.0f} s = {e['wall_s_ideal'] / 60:.1f} min "
          f"of wall time on {e['cores']} cores at full parallel efficiency (measured "
          f"efficiency of that run: {e['parallel_efficiency']:.0%}, which gives "
          f"{e['wall_s_measured_eff'] / 60:.1f} min). Goal: {GOAL_WALL_S / 60:.1f} min: "
          f"{'met' if e['wall_s_ideal'] <= GOAL_WALL_S else 'missed'} (ideal), "
          f"{'met' if e['wall_s_measured_eff'] <= GOAL_WALL_S else 'missed'} (measured "
          "efficiency).", ""]
    sw = rep["still_water"]
    cpu_still = sw["cpu_s_per_member_s"] * FULL_MEMBERS * FULL_DURATION
    L += [f"The same model in still water (`cablesim run`, one thread, {sw['duration']:g} s "
          f"simulated): {sw['node_steps_per_stepping_s']:.3g} node-steps per second of "
          f"stepping, {sw['cpu_s_per_member_s']:.5f} CPU s per member-second with start-up "
          f"and output: the 30 members would take {cpu_still:.0f} CPU s "
          f"({cpu_still / e['cores'] / 60:.1f} min on {e['cores']} cores); in waves a "
          f"member-second costs {e['cpu_s_per_member_s'] / sw['cpu_s_per_member_s']:.1f}x "
          "that.", ""]
    cg = rep.get("callgrind")
    if cg:
        w, st = cg["waves"], cg["still"]
        L += [f"Instructions per node-step (callgrind, `cablesim run` of one member for "
              f"{cg['duration']:g} s, one thread, start-up included): in waves "
              f"{w['per_node_step']:.0f}, in still water {st['per_node_step']:.0f} "
              f"({w['per_node_step'] / st['per_node_step']:.1f}x). In waves:", ""]
        for k, v in w["parts_per_node_step"].items():
            L.append(f"- {k}: {v:.0f} per node-step ({v / w['per_node_step']:.0%})")
        L.append("")
    for r in rep.get("moordyn", []):
        if r.get("status") != "completed":
            L.append(f"- MoorDyn {r['name']}: {r.get('status')}")
            continue
        L.append(f"- MoorDyn {rep['versions']['moordyn']} ({r['name']}: "
                 f"{r['wave_components'] or 'no'} wave components), same 8 lines, RK2 at "
                 f"dt = {r['dt']:g} s, {r['simulated_s']:g} s simulated: {r['cpu_s']:.1f} CPU s "
                 f"({r['node_steps_per_cpu_s']:.3g} node-steps / CPU s), so "
                 f"{r['cpu_s_per_member_3h'] / 60:.1f} CPU min for one 3 h member and "
                 f"{r['cpu_s_study'] / 3600:.1f} CPU h for the 30 members; cablesim's study "
                 f"takes {e['cpu_s'] / r['cpu_s_study']:.2%} of that CPU time "
                 f"({r['cpu_s_study'] / e['cpu_s']:.0f}x less).")
    L += ["", f"Command: `{rep['command']}`", ""]
    path.write_text("\n".join(L))


def main() -> int:
    if len(sys.argv) == 4 and sys.argv[1] == "--moordyn-worker":
        moordyn_worker(sys.argv[2], sys.argv[3])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=REPO / "target" / "study-speed")
    ap.add_argument("--cablesim-bin")
    ap.add_argument("--durations", default="20,40,80")
    ap.add_argument("--members", default="1,10,100,1000")
    ap.add_argument("--member-duration", type=float, default=4.0)
    ap.add_argument("--still-duration", type=float, default=200.0,
                    help="simulated s of the still-water run of the same model (200)")
    ap.add_argument("--callgrind", type=float, default=3.0,
                    help="simulated s of the callgrind profiles (3; 0: none)")
    ap.add_argument("--md-dt", type=float, default=5e-4)
    ap.add_argument("--md-duration", type=float, default=20.0)
    ap.add_argument("--md-waves", type=int, default=0,
                    help="also run MoorDyn with this many wave components (WaveKin 7)")
    ap.add_argument("--md-waves-duration", type=float, default=2.0,
                    help="simulated s of the MoorDyn run with waves (2)")
    ap.add_argument("--skip-moordyn", action="store_true")
    ap.add_argument("--no-venv", action="store_true")
    if "--no-venv" not in sys.argv and "--skip-moordyn" not in sys.argv \
            and "-h" not in sys.argv and "--help" not in sys.argv:
        cp.ensure_venv_and_reexec(Path(__file__))
    a = ap.parse_args()
    a.out = (a.out if a.out.is_absolute() else Path.cwd() / a.out).resolve()
    a.out.mkdir(parents=True, exist_ok=True)
    binary = find_binary(a)
    rep: dict = {"date": _dt.datetime.now().astimezone().isoformat(timespec="seconds"),
                 "command": "python3 scripts/study_speed.py " + " ".join(sys.argv[1:]),
                 "machine": {"cpu": cp.cpu_model(), "cores": os.cpu_count(),
                             "loadavg_start": " ".join(f"{x:.2f}" for x in os.getloadavg())},
                 "cablesim_rev": cp.git_rev(), "versions": cp.versions(), "runs": []}
    base = base_run(binary, a.out)
    rep["base"] = base
    print(f"base: dt {base['dt']:.4g} s ({base['dt_limited_by']}), {base['nodes']} nodes", flush=True)
    for dur in [float(x) for x in a.durations.split(",") if x]:
        r = study_run(binary, a.out, f"one-member-{dur:g}s", 1, dur, dur / 4.0, base)
        rep["runs"].append(r)
        print(f"  {r['name']}: wall {r['wall_s']:.1f} s, CPU {r['cpu_s']:.1f} s, "
              f"{r['node_steps_per_cpu_s']:.3g} node-steps/CPU s", flush=True)
    for n in [int(x) for x in a.members.split(",") if x]:
        md_ = a.member_duration
        r = study_run(binary, a.out, f"members-{n}", n, md_, md_ / 4.0, base)
        rep["runs"].append(r)
        print(f"  {r['name']}: wall {r['wall_s']:.1f} s, CPU {r['cpu_s']:.1f} s, "
              f"{r['node_steps_per_cpu_s']:.3g} node-steps/CPU s", flush=True)
    rep["still_water"] = still_water_run(binary, a.out, a.still_duration)
    print(f"  still water: {rep['still_water']['cpu_s_per_member_s']:.5f} CPU s per member-s",
          flush=True)
    if a.callgrind:
        rep["callgrind"] = callgrind_profile(binary, a.out, a.callgrind)
    last = max(rep["runs"], key=lambda r: r["members"] * r["duration"])
    cores = os.cpu_count() or 1
    cpu_full = last["cpu_s_per_member_s"] * FULL_MEMBERS * FULL_DURATION
    eff = last["cpu_s"] / (last["wall_s"] * cores)
    rep["extrapolation"] = {"from": last["name"], "cpu_s_per_member_s": last["cpu_s_per_member_s"],
                            "cpu_s": cpu_full, "cores": cores, "wall_s_ideal": cpu_full / cores,
                            "parallel_efficiency": eff,
                            "wall_s_measured_eff": cpu_full / (cores * min(eff, 1.0))}
    if not a.skip_moordyn:
        rep["moordyn"] = []
        for nw in ([0] + ([a.md_waves] if a.md_waves else [])):
            dur = a.md_waves_duration if nw else a.md_duration
            print(f"moordyn: {nw} wave components, {dur:g} s at {a.md_dt:g} s ...", flush=True)
            r = run_moordyn(a.out, a.md_dt, dur, nw)
            rep["moordyn"].append(r)
            print(f"  {r}", flush=True)
    rep["machine"]["loadavg_end"] = " ".join(f"{x:.2f}" for x in os.getloadavg())
    (a.out / "study_speed.json").write_text(json.dumps(rep, indent=1))
    report(rep, a.out / "study_speed.md")
    print((a.out / "study_speed.md").read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
