#!/usr/bin/env python3
"""Run MoorDyn input files through MoorDyn and cablesim; print the static end forces.

Run by hand, not by `cargo test`:

    cargo build --release
    python3 scripts/compare_moordyn_inputs.py DIR [--out target/moordyn-inputs]

DIR holds MoorDyn input files (for instance the `tests/Mooring` folder of MoorDyn's
public repository; nothing of MoorDyn is kept in this repository). Every `*.txt` and
`*.dat` file under DIR with MoorDyn `--- LINE TYPES ---` and `--- LINES ---` headers is
tried:

1. `cablesim convert FILE -o OUT/NAME.toml --duration 1`: a file using a feature
   cablesim refuses (rods, bodies, waves, current grids, nonlinear stiffness, ...) is
   listed with cablesim's message, naming the file's line, and not run.
2. cablesim: `cablesim run OUT/NAME.toml --backend cpu`; the end forces at t = 0 (the
   static equilibrium cablesim's Newton solver finds from the elastic catenary) are
   read from `end_forces.csv`.
3. MoorDyn (its C++ core through the `moordyn` Python bindings, from PyPI; each file
   in a child process of its own, with the file's folder as working directory):
   `moordyn.Create(FILE)`, `moordyn.Init` with the coupled points where the file puts
   them (MoorDyn's own initial-condition solver, which stops at the file's threshIC
   and TmaxIC, or at once where a dynamic test sets TmaxIC = 0), then MoorDyn steps on
   with the coupled points still, sampling every 0.5 s, until over the last 20 s every
   end force stays within 0.1 % of its mean (at most --settle simulated and
   --settle-wall wall seconds); that mean is MoorDyn's static force. End forces are
   `GetLineNodeForce` of each line's end nodes: the net force of the end node, which is
   what the line exerts on the point it hangs from, as cablesim's end forces are.

The table has, for each line, the fairlead (end B) force magnitude of both tools and
the difference of the force vectors relative to the larger magnitude,
|F_cablesim - F_moordyn| / max(|F_cablesim|, |F_moordyn|);
also the anchor (end A). A line whose file sets EI > 0 is marked: cablesim's lumped
mass lines have no bending stiffness (convert warns of it). Written as markdown to
OUT/moordyn_inputs.md and as JSON to OUT/moordyn_inputs.json.

The first run makes `.venv-peers/` in the repository root with
`scripts/requirements-peers.txt` (as scripts/compare_peers.py does); `--no-venv` uses
the current interpreter as it is.

Exit status: 0 when every compared fairlead force (MoorDyn settled, no EI) agrees
within --tolerance (default 0.5 %), 2 when one does not, 1 on an error.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import math
import os
import platform
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
VENV = REPO / ".venv-peers"
REQUIREMENTS = REPO / "scripts" / "requirements-peers.txt"


def ensure_venv_and_reexec() -> None:
    """Makes .venv-peers with the pinned peers and re-runs this script inside it."""
    try:
        if Path(sys.prefix).resolve() == VENV.resolve():
            return
    except OSError:
        pass
    py = VENV / "bin" / "python"
    req_hash = hashlib.sha256(REQUIREMENTS.read_bytes()).hexdigest()
    stamp = VENV / ".peers-requirements.sha256"
    if not py.exists():
        print(f"making {VENV.relative_to(REPO)}/ ...", flush=True)
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
    if not stamp.exists() or stamp.read_text().strip() != req_hash:
        print(f"installing {REQUIREMENTS.relative_to(REPO)} ...", flush=True)
        pip = [str(py), "-m", "pip", "--disable-pip-version-check"]
        subprocess.run(pip + ["install", "-q", "-r", str(REQUIREMENTS)], check=True)
        stamp.write_text(req_hash + "\n")
    os.execv(str(py), [str(py), str(Path(__file__).resolve())] + sys.argv[1:])


def is_moordyn_file(path: Path) -> bool:
    """The same test as cablesim's: `---` headers naming line types and lines."""
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return False
    heads = [l.upper() for l in text.splitlines() if "---" in l]
    types = any("LINE TYPES" in h or "LINE DICTIONARY" in h for h in heads)
    lines = any(
        ("LINES" in h or "LINE LIST" in h or "LINE PROPERTIES" in h) for h in heads
    )
    return types and lines


def has_bending(path: Path) -> bool:
    """True when a v2 line-type row sets EI (the 6th column) above zero."""
    rows, in_types, skip = [], False, 0
    for line in path.read_text(errors="replace").splitlines():
        if "---" in line:
            u = line.upper()
            in_types = "LINE TYPES" in u or "LINE DICTIONARY" in u
            skip = 2
            continue
        if in_types:
            if skip:
                skip -= 1
                continue
            f = line.split("#")[0].split()
            if len(f) >= 10:
                rows.append(f)
    for f in rows:
        try:
            if float(f[5]) > 0.0:
                return True
        except ValueError:
            pass
    return False


# ---------------------------------------------------------------------------------
# MoorDyn, in a child process
# ---------------------------------------------------------------------------------


def moordyn_worker(input_path: str, result_path: str, settle: float, wall_limit: float) -> None:
    import time

    import moordyn as md

    s = md.Create(input_path)
    x = []
    for i in range(1, md.GetNumberPoints(s) + 1):
        p = md.GetPoint(s, i)
        if md.GetPointType(p) == md.POINT_TYPE_COUPLED:
            x += list(md.GetPointPos(p))
    v = [0.0] * len(x)
    err = md.Init(s, x, v)
    if err != 0:
        raise SystemExit(f"moordyn.Init failed with code {err}")
    lines = [md.GetLine(s, i) for i in range(1, md.GetNumberLines(s) + 1)]

    def forces():
        return [
            {
                "anchor": list(md.GetLineNodeForce(ln, 0)),
                "fairlead": list(md.GetLineNodeForce(ln, md.GetLineN(ln))),
            }
            for ln in lines
        ]

    md.Step(s, x, v, 0.0, 0.0)  # dt = 0: the forces of the initial state, no stepping
    init = forces()
    # MoorDyn's initial-condition solver stops at the file's threshIC/TmaxIC; some test
    # files skip it on purpose (dynamic tests), and lightly damped lines keep a small
    # slow swing after it. So step on with the coupled points still, sampling the end
    # forces every 0.5 s, until over the last `window` seconds every end force stays
    # within `spread` of its mean: that mean is MoorDyn's static state.
    dt_s, window, spread = 0.5, 20.0, 1e-3
    n_win = int(window / dt_s)
    t, hist, settled, worst = 0.0, [], False, math.inf
    w0 = time.perf_counter()
    while t < settle and time.perf_counter() - w0 < wall_limit:
        md.Step(s, x, v, t, dt_s)
        t += dt_s
        hist.append(forces())
        if len(hist) < n_win:
            continue
        win = hist[-n_win:]
        worst = 0.0
        for li in range(len(lines)):
            for k in ("anchor", "fairlead"):
                mean = [sum(h[li][k][c] for h in win) / n_win for c in range(3)]
                m = max(norm(mean), 1e-9)
                for h in win:
                    worst = max(worst, norm([a - b for a, b in zip(h[li][k], mean)]) / m)
        if worst < spread:
            settled = True
            break
    win = hist[-n_win:] if hist else [init]
    mean_forces = [
        {
            k: [sum(h[li][k][c] for h in win) / len(win) for c in range(3)]
            for k in ("anchor", "fairlead")
        }
        for li in range(len(lines))
    ]
    Path(result_path).write_text(
        json.dumps({"init": init, "lines": mean_forces, "settled": settled,
                    "settle_time": t, "spread": worst})
    )


def run_moordyn(path: Path, work: Path, settle: float, wall_limit: float) -> dict:
    result = work / "moordyn.json"
    log = work / "moordyn.log"
    with open(log, "w") as lf:
        r = subprocess.run(
            [sys.executable, str(Path(__file__).resolve()), "--moordyn-worker",
             str(path.resolve()), str(result.resolve()), str(settle), str(wall_limit)],
            cwd=path.parent, stdout=lf, stderr=subprocess.STDOUT, timeout=1800,
        )
    if r.returncode != 0 or not result.exists():
        tail = log.read_text(errors="replace").strip().splitlines()[-3:]
        return {"error": f"MoorDyn failed (exit {r.returncode}): " + " | ".join(tail)}
    return json.loads(result.read_text())


# ---------------------------------------------------------------------------------
# cablesim
# ---------------------------------------------------------------------------------


def run_cablesim(binary: Path, path: Path, work: Path) -> dict:
    toml = work / "scenario.toml"
    r = subprocess.run(
        [str(binary), "convert", str(path), "-o", str(toml), "--duration", "1"],
        capture_output=True, text=True,
    )
    if r.returncode != 0:
        msg = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "failed"
        return {"refused": msg.replace("error: ", "")}
    warnings = [l for l in r.stderr.splitlines() if "WARN" in l]
    out = work / "cablesim"
    r = subprocess.run(
        [str(binary), "run", str(toml), "--out", str(out), "--backend", "cpu", "-q"],
        capture_output=True, text=True,
    )
    if r.returncode != 0:
        return {"error": "cablesim run failed: " + r.stderr.strip().splitlines()[-1]}
    forces: dict = {}
    with open(out / "end_forces.csv") as f:
        for row in csv.DictReader(f):
            if float(row["time"]) != 0.0:
                continue
            forces.setdefault(row["cable"], {})[row["end"]] = [
                float(row["fx"]), float(row["fy"]), float(row["fz"])
            ]
    lines = []
    k = 1
    while f"line{k}" in forces:
        e = forces[f"line{k}"]
        lines.append({"anchor": e["start"], "fairlead": e["end"]})
        k += 1
    return {"lines": lines, "warnings": warnings}


def norm(v) -> float:
    return math.sqrt(sum(c * c for c in v))


def rel(a, b) -> float:
    """|a - b| relative to the larger of |a| and |b| (0 when both vanish)."""
    d = norm([x - y for x, y in zip(a, b)])
    return d / max(norm(a), norm(b)) if d > 0.0 else 0.0


def main() -> int:
    if len(sys.argv) == 6 and sys.argv[1] == "--moordyn-worker":
        moordyn_worker(sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5]))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir", type=Path, help="folder of MoorDyn input files")
    ap.add_argument("--out", type=Path, default=REPO / "target" / "moordyn-inputs")
    ap.add_argument("--cablesim", type=Path, default=REPO / "target" / "release" / "cablesim")
    ap.add_argument("--tolerance", type=float, default=0.005)
    ap.add_argument("--settle", type=float, default=600.0,
                    help="most simulated seconds MoorDyn steps after its IC solver (s)")
    ap.add_argument("--settle-wall", type=float, default=180.0,
                    help="most wall seconds MoorDyn steps after its IC solver (s)")
    ap.add_argument("--no-venv", action="store_true")
    args = ap.parse_args()
    if not args.no_venv:
        ensure_venv_and_reexec()
    if not args.cablesim.exists():
        print(f"no cablesim binary at {args.cablesim}: run `cargo build --release`")
        return 1
    import moordyn  # noqa: F401  (fails early when the peers are missing)

    files = sorted(
        p for p in args.dir.rglob("*")
        if p.suffix in (".txt", ".dat") and p.is_file() and is_moordyn_file(p)
    )
    args.out.mkdir(parents=True, exist_ok=True)
    rows, refused, failed = [], [], []
    worst = 0.0
    for path in files:
        name = str(path.relative_to(args.dir))
        work = args.out / name.replace("/", "__")
        if work.exists():
            shutil.rmtree(work)
        work.mkdir(parents=True)
        cs = run_cablesim(args.cablesim, path, work)
        if "refused" in cs:
            refused.append((name, cs["refused"].replace(str(path), name)))
            print(f"{name}: refused by cablesim: {refused[-1][1]}", flush=True)
            continue
        if "error" in cs:
            failed.append((name, cs["error"]))
            print(f"{name}: {cs['error']}", flush=True)
            continue
        md = run_moordyn(path, work, args.settle, args.settle_wall)
        if "error" in md:
            failed.append((name, md["error"]))
            print(f"{name}: {md['error']}", flush=True)
            continue
        bend = has_bending(path)
        settled = md["settled"]
        for k, (c, m, mi) in enumerate(zip(cs["lines"], md["lines"], md["init"]), start=1):
            row = {
                "file": name,
                "line": k,
                "ei": bend,
                "settled": settled,
                "settle_time": md["settle_time"],
                "fair_md_ic": norm(mi["fairlead"]),
                "fair_md": norm(m["fairlead"]),
                "fair_cs": norm(c["fairlead"]),
                "fair_diff": rel(c["fairlead"], m["fairlead"]),
                "anch_md": norm(m["anchor"]),
                "anch_cs": norm(c["anchor"]),
                "anch_diff": rel(c["anchor"], m["anchor"]),
                "fair_vec_md": m["fairlead"],
                "fair_vec_cs": c["fairlead"],
            }
            rows.append(row)
            compared = settled and not bend
            if compared:
                worst = max(worst, row["fair_diff"])
            note = []
            if bend:
                note.append("EI ignored by cablesim")
            if not settled:
                note.append("MoorDyn did not settle")
            print(
                f"{name} line {k}: fairlead |F| MoorDyn {row['fair_md']:.6g} N "
                f"(after its IC solver {row['fair_md_ic']:.6g} N), "
                f"cablesim {row['fair_cs']:.6g} N, diff {100 * row['fair_diff']:.3f} %"
                + (f" ({'; '.join(note)})" if note else ""),
                flush=True,
            )
    import moordyn as _md

    ver = getattr(_md, "__version__", None)
    if ver is None:
        from importlib.metadata import version

        ver = version("moordyn")
    md_lines = [
        f"MoorDyn {ver} (PyPI) vs cablesim, static end forces, {platform.machine()}; "
        f"files from `{args.dir}`.",
        "",
        "| file | line | fairlead MoorDyn after IC (N) | fairlead MoorDyn settled (N) | "
        "fairlead cablesim (N) | diff | anchor MoorDyn (N) | anchor cablesim (N) | diff |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        mark = (" (EI)" if r["ei"] else "") + ("" if r["settled"] else " (not settled)")
        md_lines.append(
            f"| {r['file']}{mark} | {r['line']} | {r['fair_md_ic']:.6g} | {r['fair_md']:.6g} | "
            f"{r['fair_cs']:.6g} | "
            f"{100 * r['fair_diff']:.3f} % | {r['anch_md']:.6g} | {r['anch_cs']:.6g} | "
            f"{100 * r['anch_diff']:.3f} % |"
        )
    if refused:
        md_lines += ["", "Refused by `cablesim convert` (the message names the file's line):", ""]
        md_lines += [f"- {n}: {m}" for n, m in refused]
    if failed:
        md_lines += ["", "Failed:", ""]
        md_lines += [f"- {n}: {m}" for n, m in failed]
    md_lines += [
        "",
        "MoorDyn settled: stepped on after its IC solver, coupled points still, until every "
        "end force stayed within 0.1 % of its mean over 20 s (sampled every 0.5 s); the "
        "mean is shown. \"(EI)\": the file sets "
        "a bending stiffness, which cablesim's lumped-mass lines do not have; "
        "\"(not settled)\": MoorDyn was still moving after --settle simulated or "
        "--settle-wall wall seconds (undamped pendulums, the local-Euler scheme's files, "
        "dynamic tests that start far from rest); not held to the tolerance.",
        "",
        f"Largest fairlead difference (settled, without EI): {100 * worst:.3f} % "
        f"(tolerance {100 * args.tolerance:.2f} %).",
    ]
    text = "\n".join(md_lines) + "\n"
    (args.out / "moordyn_inputs.md").write_text(text)
    (args.out / "moordyn_inputs.json").write_text(
        json.dumps({"rows": rows, "refused": refused, "failed": failed}, indent=1)
    )
    print()
    print(text)
    if failed:
        return 1
    return 0 if worst <= args.tolerance else 2


if __name__ == "__main__":
    sys.exit(main())
