#!/usr/bin/env python3
"""The rainflow reference of the fatigue tests: counts a run's own tension records with
the `rainflow` Python package (an independent implementation of ASTM E1049-85), so that
`tests/units/fatigue.rs` can compare cablesim's counting with it cycle by cycle.

    python3 -m venv /tmp/rf && /tmp/rf/bin/pip install rainflow==3.2.0
    /tmp/rf/bin/python scripts/rainflow_reference.py OUT_DIR

OUT_DIR is the output folder of
`cablesim run examples/fatigue_spread_mooring.toml --duration 1200` (the stored
reference: 2281 samples per record, 110 to 207 cycles and half cycles each).
Writes, into tests/data/fatigue/:

- `record.csv`: `location,time,value` (N): the force magnitude at both ends of line1
  (from end_forces.csv) and the tension of its element 20 (from tensions.csv), every
  output time from t = 60 s (the example's fatigue transient) on, values written with
  repr (they read back to the same doubles);
- `cycles.csv`: `location,range,mean,count`: `rainflow.extract_cycles` of each record,
  in the order the package yields them (full cycles 1.0, half cycles 0.5, the residue's
  half cycles last), and the package's version in a comment line.
"""

import csv
import math
import sys
from pathlib import Path

import rainflow

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data" / "fatigue"
TRANSIENT = 60.0


def main():
    out = Path(sys.argv[1])
    records = {"start": [], "end": [], "20": []}
    with open(out / "end_forces.csv") as f:
        for r in csv.DictReader(f):
            t = float(r["time"])
            if r["cable"] == "line1" and t >= TRANSIENT:
                fx, fy, fz = float(r["fx"]), float(r["fy"]), float(r["fz"])
                records[r["end"]].append((t, math.sqrt(fx * fx + fy * fy + fz * fz)))
    with open(out / "tensions.csv") as f:
        for r in csv.DictReader(f):
            t = float(r["time"])
            if r["cable"] == "line1" and r["element"] == "20" and t >= TRANSIENT:
                records["20"].append((t, float(r["tension"])))
    DATA.mkdir(parents=True, exist_ok=True)
    with open(DATA / "record.csv", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["location", "time", "value"])
        for loc, rec in records.items():
            for t, v in rec:
                w.writerow([loc, repr(t), repr(v)])
    with open(DATA / "cycles.csv", "w", newline="") as f:
        f.write(f"# rainflow {rainflow.__version__} extract_cycles\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["location", "range", "mean", "count"])
        for loc, rec in records.items():
            for rng, mean, count, _, _ in rainflow.extract_cycles([v for _, v in rec]):
                w.writerow([loc, repr(rng), repr(mean), repr(count)])
    print({k: len(v) for k, v in records.items()})


if __name__ == "__main__":
    main()
