#!/usr/bin/env python3
"""Reads `cablesim run --vtk` output back with VTK itself (the `vtk` package from PyPI),
as ParaView would, and checks it against the CSV files of the same run.

    python3 scripts/check_vtk.py [OUTDIR]

Without OUTDIR it runs tests/data/buoy_three_chains.toml with $CABLESIM_BIN (else
target/release/cablesim) into a temporary directory first. For every file of
vtk/cablesim.pvd: the point count (every cable node of positions.csv at that time, or
the bodies and shared points), the
line count (one two-point line per element), and, for the cables, one node's position
against positions.csv, its tension against the mean of its two elements in tensions.csv
and the next element's own tension (cell data); for the points, the
position and force against points.csv. Exits non-zero on the first mismatch.
"""

import csv
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from collections import defaultdict
from pathlib import Path

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

ROOT = Path(__file__).resolve().parent.parent


def read(path):
    r = vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    if r.GetErrorCode():
        sys.exit(f"check_vtk: VTK could not read {path}")
    return r.GetOutput()


def close(a, b, tol=1e-9):
    return abs(a - b) <= tol * max(1.0, abs(b))


def check(out):
    out = Path(out)
    pos = defaultdict(list)  # time -> [(cable, node, xyz)]
    for r in csv.DictReader(open(out / "positions.csv")):
        pos[float(r["time"])].append((r["cable"], int(r["node"]), [float(r[k]) for k in "xyz"]))
    ten = {}
    for r in csv.DictReader(open(out / "tensions.csv")):
        ten[(float(r["time"]), r["cable"], int(r["element"]))] = float(r["tension"])
    pts = defaultdict(list)
    if (out / "points.csv").exists():
        for r in csv.DictReader(open(out / "points.csv")):
            pts[float(r["time"])].append([float(r[k]) for k in ("x", "y", "z", "fx", "fy", "fz")])
    sets = ET.parse(out / "vtk" / "cablesim.pvd").getroot().iter("DataSet")
    n = 0
    for ds in sets:
        t, part, name = float(ds.get("timestep")), ds.get("part"), ds.get("file")
        poly = read(out / "vtk" / name)
        xyz = vtk_to_numpy(poly.GetPoints().GetData())
        if part == "0":
            rows = pos[t]
            cables = sorted({c for c, _, _ in rows}, key=[c for c, _, _ in rows].index)
            # Each element is a two-point line: a cable of n nodes has n - 1.
            if poly.GetNumberOfPoints() != len(rows) or poly.GetNumberOfLines() != len(rows) - len(cables):
                sys.exit(f"check_vtk: {name}: {poly.GetNumberOfPoints()} points, "
                         f"{poly.GetNumberOfLines()} lines; positions.csv has {len(rows)} nodes "
                         f"of {len(cables)} cables at t = {t}")
            tension = vtk_to_numpy(poly.GetPointData().GetArray("tension"))
            # An inner node of the last cable: its position and its elements' mean tension.
            k = len(rows) - 3
            cable, node, x = rows[k]
            want = 0.5 * (ten[(t, cable, node - 1)] + ten[(t, cable, node)])
            if not all(close(a, b) for a, b in zip(xyz[k], x)) or not close(tension[k], want):
                sys.exit(f"check_vtk: {name}: point {k} ({cable} node {node}) at {[float(v) for v in xyz[k]]} "
                         f"tension {tension[k]}; the CSV files say {x}, {want}")
            # The element from that node on (its cell: the elements of the cables before
            # it, then its index in its cable): its own tension.
            cell = k - len(cables) + 1
            etension = vtk_to_numpy(poly.GetCellData().GetArray("element_tension"))
            if not close(etension[cell], ten[(t, cable, node)]):
                sys.exit(f"check_vtk: {name}: cell {cell} ({cable} element {node}) tension "
                         f"{etension[cell]}; tensions.csv says {ten[(t, cable, node)]}")
        else:
            force = vtk_to_numpy(poly.GetPointData().GetArray("force"))
            want = pts[t]
            if poly.GetNumberOfPoints() != len(want):
                sys.exit(f"check_vtk: {name}: {poly.GetNumberOfPoints()} points, "
                         f"points.csv has {len(want)} at t = {t}")
            for k, w in enumerate(want):
                got = [float(v) for v in list(xyz[k]) + list(force[k])]
                if not all(close(a, b) for a, b in zip(got, w)):
                    sys.exit(f"check_vtk: {name}: point {k} is {got}, points.csv says {w}")
        n += 1
    if n == 0:
        sys.exit(f"check_vtk: {out}/vtk/cablesim.pvd lists no files")
    print(f"check_vtk: ok ({n} files read by VTK match the CSV output)")


def main():
    if len(sys.argv) > 1:
        check(sys.argv[1])
        return
    with tempfile.TemporaryDirectory() as d:
        subprocess.run(
            [os.environ.get("CABLESIM_BIN", ROOT / "target/release/cablesim"), "run", ROOT / "tests/data/buoy_three_chains.toml",
             "--vtk", "-q", "--out", d],
            check=True,
        )
        check(d)


if __name__ == "__main__":
    main()
