#!/usr/bin/env python3
"""The Hertz convergence table (issue 11, item 2) from bench_hertz's JSON output
(`bench_hertz --benchmark_filter=... --benchmark_out=RUN.json`, a gate's `ctest -V` log, or a CSV
this script wrote before; several files may be given, a later one's level replacing an earlier
one's):

- per level (setup, grading, a/R, s): element size, tetrahedra, steps, run CPU, peak and duration
  errors against Hertz, impulse/2mv; written as CSV to --csv;
- per sequence, its finest three levels (s falling by sqrt2): the observed order, the finest level's own error
  (Richardson) and the extrapolated limit's distance from Hertz, as build/bin/hertz_rates computes
  them (solver/core/richardson.hpp; --rates-program);
- the limits against a/R: a least-squares line dev = c0 + c1 a/R, with the standard errors of
  c0 (the test of "converges to Hertz" as a/R -> 0) and c1 (the finite-sphere coefficient), as
  hertz_rates --line computes them (solver/core/least_squares.hpp).

Prints Markdown. Usage: hertz_convergence_table.py [--csv OUT.csv] RUN.json [RUN.json ...]"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys


# The C++ that owns the Richardson rule and the least-squares line (solver/core/richardson.hpp,
# least_squares.hpp, benchmarks/hertz_rates.cpp): this script groups the levels into sequences
# and reads the order, the finest level's own error, the limit and the limits' lines it writes;
# it computes none of them.
RATES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "bin",
                     "hertz_rates")


def ask_rates(program, rows, *flags):
    """Each row of numbers a line to hertz_rates (repr: to the last bit), each answer line a tuple
    of floats."""
    if not rows:
        return []
    if not os.access(program, os.X_OK):
        sys.exit(f"{program}: not built (cmake --build build --target hertz_rates); it computes "
                 "the Richardson columns and the limits' lines")
    text = "".join(" ".join(repr(x) for x in row) + "\n" for row in rows)
    out = subprocess.run([program, *flags], input=text, capture_output=True, text=True,
                         check=True).stdout
    return [tuple(float(x) for x in line.split()) for line in out.splitlines()]


def richardson_rates(sequences, program, r=math.sqrt(2)):
    """(order, finest level's own error, limit) of each (coarse, middle, fine) in `sequences`,
    refined by r each, as hertz_rates computes them (to the last bit)."""
    return ask_rates(program, [(e1, e2, e3, r) for e1, e2, e3 in sequences])


def limit_lines(points, program):
    """(intercept, slope, intercept's standard error, slope's) of the least-squares line through
    each list of (x, y) in `points`, as hertz_rates --line computes them (to the last bit)."""
    return ask_rates(program, [[v for xy in pts for v in xy] for pts in points], "--line")


def finite(ref, ar):
    """The reference's row nearest a/R (within 0.002), as 'peak, duration'."""
    near = [k for k in ref if abs(k - ar) < 0.002]
    if not near:
        return "–"
    p, d = ref[min(near, key=lambda k: abs(k - ar))]
    return f"{100 * p:+.2f} %, {100 * d:+.2f} %"


def pct(x):
    return "–" if x is None or x != x else f"{100 * x:+.2f} %"


def gate_log(path):
    """Levels from the lines the gates print (tests/fdem/hertz_gate.hpp), e.g. a ctest -V log."""
    out = {}
    pat = re.compile(r"(block|pair) +a/R ([\d.]+) +s ([\d.]+) +h ([\d.]+) mm +tets +(\d+) +run "
                     r"([\d.]+) s CPU +peak ([-+\d.]+) \(filtered ([-+\d.]+)\) +duration "
                     r"([-+\d.]+) +impulse/2mv ([\d.]+) +momentum/mv ([-+\d.e]+) +\((\d+) steps, "
                     r"dt ([-+\d.e]+) s\)")
    for line in open(path):
        m = pat.search(line)
        if not m:
            continue
        g = m.groups()
        ar = {"0.05": "0.050", "0.08": "0.080", "0.15": "0.150"}.get(f"{float(g[1]):.2f}",
                                                                        f"{float(g[1]):.3f}")
        key = (g[0].strip(), "graded", ar, round(float(g[2]), 3))
        out[key] = {"a_over_R": float(g[1]), "h_mm": float(g[3]), "tets": float(g[4]),
                    "nodes": float("nan"), "steps": float(g[11]), "dt": float(g[12]),
                    "dt_by_contact": float("nan"), "cpu_s": float(g[5]),
                    "mesh_cpu_s": float("nan"), "err_peak": float(g[6]),
                    "err_peak_filtered": float(g[7]), "err_duration": float(g[8]),
                    "impulse_ratio": float(g[9]), "momentum": float(g[10])}
    return out


def nominal(a):
    """The a/R label of a level (as bench_hertz names it) from its measured a/R."""
    return {"0.05": "0.050", "0.08": "0.080", "0.15": "0.150"}.get(f"{a:.2f}", f"{a:.3f}")


def previous_csv(path):
    """Levels from a table this script wrote before (--csv), so a new run adds to it."""
    out = {}
    for row in csv.DictReader(open(path)):
        b = {k: float(v) for k, v in row.items() if k not in ("setup", "grading", "s")}
        out[(row["setup"], row["grading"], nominal(b["a_over_R"]), round(float(row["s"]), 3))] = b
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv")
    ap.add_argument("--reference", help="reports/fem/finite_sphere.csv: the finite sphere's "
                    "impact by a/R, printed beside the limits")
    ap.add_argument("--rates-program", default=RATES, help="build/bin/hertz_rates (the C++ that "
                    "computes the Richardson columns)")
    ap.add_argument("runs", nargs="+")
    args = ap.parse_args()
    levels = {}
    for path in args.runs:
        if path.endswith(".csv"):
            levels.update(previous_csv(path))
            continue
        if not path.endswith(".json"):
            levels.update(gate_log(path))
            continue
        for b in json.load(open(path))["benchmarks"]:
            m = re.match(r"Hertz(Block|Pair)/([\w.]+)/aR:([\d.]+)/s:([\d.]+)", b["name"])
            if not m or b.get("error_occurred"):
                continue
            levels[(m.group(1).lower(), m.group(2), m.group(3), round(float(m.group(4)), 3))] = b
    keys = sorted(levels, key=lambda k: (k[0], k[1], k[2], -k[3]))
    cols = ["setup", "grading", "a_over_R", "s", "h_mm", "tets", "nodes", "steps", "dt",
            "dt_by_contact", "cpu_s", "mesh_cpu_s", "err_peak", "err_peak_filtered", "err_duration",
            "impulse_ratio", "momentum"]
    if args.csv:
        with open(args.csv, "w") as f:
            f.write(",".join(cols) + "\n")
            for k in keys:
                b = levels[k]
                f.write(",".join([k[0], k[1], f"{b['a_over_R']:.4f}", f"{k[3]:.4f}"] +
                                 [f"{b.get(c, float('nan')):.6g}" for c in cols[4:]]) + "\n")
    print("| setup | grading | a/R | s | h (mm) | tetrahedra | steps | dt (s) | run CPU (s) | "
          "peak error | filtered peak error | duration error | impulse/2mv |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for k in keys:
        b = levels[k]
        print(f"| {k[0]} | {k[1]} | {b['a_over_R']:.3f} | {k[3]:.3f} | {b['h_mm']:.2f} | "
              f"{b['tets']:.0f} | {b['steps']:.0f} | {b['dt']:.3g} | {b['cpu_s']:.1f} | "
              f"{100 * b['err_peak']:+.2f} % | {pct(b.get('err_peak_filtered'))} | "
              f"{100 * b['err_duration']:+.2f} % | "
              f"{b['impulse_ratio']:.4f} |")
    print()
    ref = {}
    if args.reference:
        for row in csv.DictReader(open(args.reference)):
            ref[float(row["a_over_R_hertz"])] = (float(row["peak_error"]),
                                                 float(row["duration_error"]))
    print("| setup | grading | a/R | levels s | order (peak, duration) | finest level's own error "
          "(peak, duration) | limit's distance from Hertz (peak, duration) | filtered peak: order, "
          "limit | finite sphere's (peak, duration) |")
    print("| --- | --- | ---: | --- | --- | --- | --- | --- | --- |")
    limits = {}
    # Every three consecutive levels (s falling by sqrt2 each); the limit against a/R is the
    # one of the gates' levels (the three ending at s = 1), or the finest three.
    triples = []
    for (setup, grading, a) in sorted({k[:3] for k in keys}):
        scales = sorted((k[3] for k in keys if k[:3] == (setup, grading, a)), reverse=True)
        gate = [i for i in range(len(scales) - 2) if scales[i + 2] == 1.0]
        for i in range(len(scales) - 2):
            seq = [levels[(setup, grading, a, s)] for s in scales[i:i + 3]]
            filt = [b.get("err_peak_filtered", float("nan")) for b in seq]
            triples.append((setup, grading, scales, gate, i, seq, all(f == f for f in filt)))
    # The three metrics' sequences of every triple, in one call of the C++ (the filtered peak's
    # only where all three levels have it).
    asked = []
    for (_, _, _, _, _, seq, has_filtered) in triples:
        asked += [tuple(b["err_peak"] for b in seq), tuple(b["err_duration"] for b in seq)]
        if has_filtered:
            asked.append(tuple(b["err_peak_filtered"] for b in seq))
    rates = iter(richardson_rates(asked, args.rates_program))
    for (setup, grading, scales, gate, i, seq, has_filtered) in triples:
        triple = scales[i:i + 3]
        rp, rd = next(rates), next(rates)
        rf = next(rates) if has_filtered else None
        ar = seq[2]["a_over_R"]
        filtered = f"{rf[0]:.2f}, {100 * rf[2]:+.2f} %" if rf else "–"
        if i == (gate[0] if gate else len(scales) - 3):
            limits.setdefault((setup, grading), []).append((ar, rp[2], rd[2]))
        print(f"| {setup} | {grading} | {ar:.3f} | {', '.join(f'{s:.3f}' for s in triple)} | "
              f"{rp[0]:.2f}, {rd[0]:.2f} | "
              f"{100 * rp[1]:+.2f} %, {100 * rd[1]:+.2f} % | "
              f"{100 * rp[2]:+.2f} %, {100 * rd[2]:+.2f} % | {filtered} | {finite(ref, ar)} |")
    print()
    fitted = [(setup, grading, pts) for (setup, grading), pts in sorted(limits.items())
              if len(pts) >= 2]
    lines = iter(limit_lines([[(p[0], p[i]) for p in pts] for _, _, pts in fitted for i in (1, 2)],
                             args.rates_program))
    for setup, grading, pts in fitted:
        xs = [p[0] for p in pts]
        for what in ("peak", "duration"):
            c0, c1, se0, se1 = next(lines)
            print(f"- {setup} ({grading}), {what}: limit − Hertz = ({100 * c0:+.2f} ± "
                  f"{100 * se0:.2f}) % + ({c1:+.3f} ± {se1:.3f}) × a/R over a/R = "
                  f"{', '.join(f'{x:.3f}' for x in xs)}")


if __name__ == "__main__":
    main()
