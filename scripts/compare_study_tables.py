#!/usr/bin/env python3
"""How far two runs of the same study differ: members.csv and study.csv of two output
folders (for example the CPU and the GPU run of scripts/study_gpu_speed.sh).

    python3 scripts/compare_study_tables.py OUT/full30-cpu OUT/full30-gpu-f64

For every numeric statistic it prints the largest difference over the members (or sea
states) and channels, relative to the channel's scale (the largest |mean| of that
channel over the rows of the reference run, the first folder), and the largest
difference relative to the value itself; and the row where the largest scaled
difference is. docs/src/studies.md states what GPU f64 and f32 promise against the CPU
study.
"""
import csv
import sys
from pathlib import Path

MEMBER_STATS = ["max", "min", "mean", "std", "time_of_max", "time_of_min"]
STUDY_STATS = ["mean", "std", "max_mean", "max_std", "max_largest", "min_smallest", "mpm",
               "quantile", "design_tension", "utilisation"]


def read(path: Path, key: list) -> dict:
    # `condition` (a study of several mooring conditions) is part of a study.csv row's key.
    with path.open(newline="") as f:
        return {tuple(r.get(k, "") for k in ["condition"] + key): r for r in csv.DictReader(f)}


def compare(name: str, a: dict, b: dict, stats: list) -> None:
    if a.keys() != b.keys():
        print(f"{name}: the rows differ ({len(a)} against {len(b)})")
        return
    scale = {}
    for k, r in a.items():
        ch = r["channel"]
        if r.get("mean"):
            scale[ch] = max(scale.get(ch, 0.0), abs(float(r["mean"])))
    print(f"{name}: {len(a)} rows")
    for s in stats:
        worst, worst_row, worst_rel, count = 0.0, None, 0.0, 0
        for k, r in a.items():
            x, y = r.get(s, ""), b[k].get(s, "")
            if x == "" and y == "":
                continue
            if (x == "") != (y == ""):
                print(f"  {s}: empty in one run only at {k}")
                continue
            x, y = float(x), float(y)
            count += 1
            sc = 1.0 if s.startswith("time_of") or s == "utilisation" else scale[r["channel"]]
            d = abs(x - y) / sc
            if d > worst:
                worst, worst_row = d, (k, x, y)
            if x != 0.0:
                worst_rel = max(worst_rel, abs(x - y) / abs(x))
        if count == 0:
            print(f"  {s}: empty in both runs")
            continue
        unit = "s" if s.startswith("time_of") else ("" if s == "utilisation" else "of scale")
        where = f" at {worst_row[0]}: {worst_row[1]:.9g} against {worst_row[2]:.9g}" if worst_row else ""
        print(f"  {s}: largest difference {worst:.3g} {unit}, {worst_rel:.3g} of the value{where}")


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    a, b = Path(sys.argv[1]), Path(sys.argv[2])
    compare("members.csv", read(a / "members.csv", ["member", "channel"]),
            read(b / "members.csv", ["member", "channel"]), MEMBER_STATS)
    compare("study.csv", read(a / "study.csv", ["sea_state", "channel"]),
            read(b / "study.csv", ["sea_state", "channel"]), STUDY_STATS)
    return 0


if __name__ == "__main__":
    sys.exit(main())
