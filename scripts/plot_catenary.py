#!/usr/bin/env python3
"""Draws the picture of a result shown in README.md and the book (docs/src/images/).

Runs nothing itself: it reads the output of

    cablesim run examples/catenary.toml          # writes out/catenary/

and draws the line's final profile, each element coloured by its tension, with the
seabed, the anchor and the fairlead, plus the two end forces as arrows. Needs
matplotlib (`pip install matplotlib`):

    python3 scripts/plot_catenary.py out/catenary docs/src/images/catenary.png
"""

import csv
import sys
from pathlib import Path


def read_last_frame(path, value_columns):
    """Rows of the last output time of a cablesim CSV file, as dicts of floats."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows (did the run write any output?)")
    last = max(float(r["time"]) for r in rows)
    out = []
    for r in rows:
        if float(r["time"]) == last:
            d = dict(r)
            d.update({k: float(r[k]) for k in value_columns})
            out.append(d)
    return last, out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    run_dir, png = Path(sys.argv[1]), Path(sys.argv[2])

    import json

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    summary = json.loads((run_dir / "summary.json").read_text())
    t, nodes = read_last_frame(run_dir / "positions.csv", ("node", "x", "y", "z"))
    _, elems = read_last_frame(run_dir / "tensions.csv", ("element", "tension"))
    _, ends = read_last_frame(run_dir / "end_forces.csv", ("fx", "fy", "fz"))
    cable = nodes[0]["cable"]
    nodes = sorted((n for n in nodes if n["cable"] == cable), key=lambda n: n["node"])
    elems = sorted((e for e in elems if e["cable"] == cable), key=lambda e: e["element"])
    x = [n["x"] for n in nodes]
    z = [n["z"] for n in nodes]
    tension_kn = [e["tension"] / 1e3 for e in elems]

    fig, ax = plt.subplots(figsize=(8, 3.6), dpi=110)
    segments = [[(x[k], z[k]), (x[k + 1], z[k + 1])] for k in range(len(elems))]
    lines = LineCollection(segments, cmap="viridis", linewidths=3)
    lines.set_array(tension_kn)
    ax.add_collection(lines)
    ax.plot(x, z, "o", ms=2.2, color="black")
    cbar = fig.colorbar(lines, ax=ax, pad=0.01)
    cbar.set_label("element tension (kN)")

    # The seabed (this example's depth is 100 m: the anchor lies on it).
    zb = min(z)
    ax.axhspan(zb - 8, zb, color="#c8b68a", zorder=0)
    ax.axhline(0.0, color="#5aa0d8", lw=1)
    ax.text(x[0], 2, "water surface", color="#2f6f9f", fontsize=8, va="bottom")

    # End forces: the force the cable exerts on the anchor and on the fairlead.
    scale = 25.0 / max(
        (e["fx"] ** 2 + e["fz"] ** 2) ** 0.5 for e in ends if e["cable"] == cable
    )
    for e in ends:
        if e["cable"] != cable:
            continue
        px, pz = (x[0], z[0]) if e["end"] == "start" else (x[-1], z[-1])
        mag = (e["fx"] ** 2 + e["fy"] ** 2 + e["fz"] ** 2) ** 0.5
        ax.annotate(
            "",
            xy=(px + scale * e["fx"], pz + scale * e["fz"]),
            xytext=(px, pz),
            arrowprops=dict(arrowstyle="->", color="crimson", lw=1.5),
        )
        label = "anchor" if e["end"] == "start" else "fairlead"
        ax.text(
            px + (6 if e["end"] == "start" else -6),
            pz + (10 if e["end"] == "start" else 4),
            f"{label}: {mag / 1e3:.2f} kN",
            fontsize=8,
            color="crimson",
            ha="left" if e["end"] == "start" else "right",
        )

    ax.set_xlim(min(x) - 10, max(x) + 10)
    ax.set_ylim(zb - 8, 12)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(
        f"{Path(summary['scenario']).name}: cable '{cable}' at t = {t:g} s "
        f"({summary['nodes']} nodes, {summary['backend']}, {summary['scheme']})",
        fontsize=9,
    )
    fig.tight_layout()
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
