#!/usr/bin/env python3
"""Compares two study tables (cases.csv) in every column but timing (cpu_seconds, wall_seconds,
..._seconds): the regression check of a refactoring (issue 17: the default study's cases.csv must
equal the committed one). Rows are matched by (particle, model, resolution, placement). Prints,
per differing column, how many rows differ and the largest relative difference with its row;
exit 0 when every non-timing cell is equal (numbers within --rel, default 0: bit for bit as
printed), 1 otherwise.

  python3 tools/compare_study_cases.py reports/study/cases.csv /tmp/ren-study/cases.csv
"""
import argparse
import csv
import math
import sys

KEY = ("particle", "model", "resolution", "placement")


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {tuple(r[k] for k in KEY): r for r in rows}, list(rows[0].keys()) if rows else []


def timing(column):
    return column.endswith("_seconds")


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reference")
    ap.add_argument("candidate")
    ap.add_argument("--rel", type=float, default=0.0, help="relative tolerance for numbers")
    a = ap.parse_args()
    ref, ref_cols = load(a.reference)
    new, new_cols = load(a.candidate)
    problems = 0
    for name, missing in (("candidate", set(ref) - set(new)), ("reference", set(new) - set(ref))):
        for k in sorted(missing):
            print(f"row {' '.join(k)}: missing from the {name}")
            problems += 1
    if ref_cols != new_cols:
        print(f"columns differ: {ref_cols} vs {new_cols}")
        problems += 1
    for col in (c for c in ref_cols if c in new_cols and not timing(c)):
        differ, worst, worst_row = 0, 0.0, None
        for k in sorted(set(ref) & set(new)):
            x, y = ref[k][col], new[k][col]
            if x == y:
                continue
            fx, fy = number(x), number(y)
            if fx is not None and fy is not None and math.isfinite(fx) and math.isfinite(fy):
                rel = abs(fy - fx) / max(abs(fx), abs(fy), 1e-300)
                if rel <= a.rel:
                    continue
            else:
                rel = math.inf
            differ += 1
            if rel >= worst:
                worst, worst_row = rel, (k, x, y)
        if differ:
            problems += 1
            k, x, y = worst_row
            print(f"{col}: {differ} rows differ; largest relative difference {worst:.3g} at "
                  f"{' '.join(k)}: {x!r} -> {y!r}")
    print(f"{len(set(ref) & set(new))} rows compared, "
          f"{len([c for c in ref_cols if not timing(c)])} columns (timing left out): "
          + ("equal" if problems == 0 else f"{problems} differences"))
    return 0 if problems == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
