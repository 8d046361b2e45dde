#!/usr/bin/env python3
"""The cost of the bench_fem collision over the particle set (issue 11, item 6), from the console
output of `bench_fem --benchmark_filter=CollisionSet --set-particles=all > LOG` (read line by
line, so a run stopped part-way still gives the particles it finished): per resolution the
median and worst CPU seconds, and per particle the exponent log(cpu_1000 / cpu_100) / log(10)
and the least-squares slope of log cpu against log N over every resolution it ran (100, 250,
500, 1000). Prints a Markdown table; with --csv OUT also writes one row per run.

The statistics are computed by build/bin/collision_cost (benchmarks/collision_cost.cpp: the C++
median and least-squares line); this script parses the log into its runs table and only formats
what that writes. Usage: collision_cost_table.py LOG [--csv OUT] [--cost-program PATH]"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

from tabular import num, read_csv  # beside this file

COST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "bin",
                    "collision_cost")
KEYS = ["cpu_s", "setup_cpu_s", "steps", "dt", "dt_element", "dt_contact", "tets", "peak_N",
        "penalty_scale_min"]


def read_log(path):
    """particle -> {N faces: counters}, the particles in the order they ran."""
    runs = {}
    units = {"": 1, "G": 1e9, "M": 1e6, "k": 1e3, "m": 1e-3, "u": 1e-6, "n": 1e-9, "p": 1e-12,
             "f": 1e-15}
    for line in open(path):
        m = re.match(r"BM_CollisionSet/(\S+)/(\d+)/\S+\s.*?((?:\w+=\S+ ?)+)$", line.strip())
        if not m:
            continue
        counters = {}
        for kv in m.group(3).split():
            k, v = kv.split("=")
            scale = units.get(v[-1], None)
            counters[k] = float(v[:-1]) * scale if scale and v[-1].isalpha() else float(v)
        runs.setdefault(m.group(1), {})[int(m.group(2))] = counters
    return runs


def write_runs(runs, path, number):
    """One row per run, in the order they ran; `number` formats a counter (NaN where absent)."""
    with open(path, "w") as out:
        out.write("particle,faces," + ",".join(KEYS) + "\n")
        for p in runs:
            for n in runs[p]:
                out.write(f"{p},{n}," + ",".join(number(runs[p][n].get(k, float("nan")))
                                                 for k in KEYS) + "\n")


def statistics(runs, program):
    """The tables collision_cost writes from these runs (by_faces, by_particle, summary,
    exponent_bins), each as a list of rows."""
    if not os.access(program, os.X_OK):
        sys.exit(f"{program}: not built (cmake --build build --target collision_cost); it "
                 "computes the medians and exponents")
    with tempfile.TemporaryDirectory() as d:
        write_runs(runs, os.path.join(d, "runs.csv"), repr)
        subprocess.run([program, os.path.join(d, "runs.csv"), d], check=True)
        return {t: read_csv(os.path.join(d, t + ".csv"))
                for t in ("by_faces", "by_particle", "summary", "exponent_bins")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("log")
    ap.add_argument("--csv")
    ap.add_argument("--cost-program", default=COST, help="build/bin/collision_cost (the C++ that "
                    "computes the statistics)")
    args = ap.parse_args()
    runs = read_log(args.log)
    t = statistics(runs, args.cost_program)
    s = t["summary"][0]
    faces = [r["faces"] for r in t["by_faces"]]
    print(f"{s['particles']} particles.\n")
    print("| N faces | particles | CPU median (s) | CPU worst (s) | worst particle | steps median | dt median (s) | tets median |")
    print("| ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: |")
    for r in t["by_faces"]:
        print(f"| {r['faces']} | {r['particles']} | {num(r['cpu_median']):.3g} | "
              f"{num(r['cpu_worst']):.3g} | {r['worst_particle']} | {num(r['steps_median']):.0f} | "
              f"{num(r['dt_median']):.3g} | {num(r['tets_median']):.0f} |")
    if "100" in faces and "1000" in faces:
        print(f"\nExponent 100 → 1000 over {s['exponent_particles']} particles: median "
              f"{num(s['exponent_median']):.2f}, min {num(s['exponent_min']):.2f}, max "
              f"{num(s['exponent_max']):.2f} ({s['exponent_max_particle']}).")
        if s["fit_particles"] != "0":
            print(f"Least-squares exponent over {', '.join(faces)} faces, {s['fit_particles']} "
                  f"particles: median {num(s['fit_median']):.2f}, min {num(s['fit_min']):.2f}, "
                  f"max {num(s['fit_max']):.2f} ({s['fit_max_particle']}); {s['fit_above_high']} "
                  f"above {num(s['high_exponent']):g}.")
        over = sorted(p for p in s["over_budget_particles"].split(";") if p)
        print(f"Over {num(s['budget_seconds']):g} s at 1000 faces: {s['over_budget']} "
              f"({', '.join(over) or 'none'}).")
        print("\nExponents 100 → 1000: " + ", ".join(
            f"{b['particles']} in [{num(b['bin_low']):.1f}, {num(b['bin_high']):.1f})"
            for b in t["exponent_bins"]) + ".")
        # Why a particle's exponent is high: the cost is steps × work per step, so the exponent
        # splits into the steps' (log of the step-count ratio) and the work per step's; dt/dt_element
        # at 1000 faces says whether the contact (< 0.5: the step below half the elements' own
        # limit, at the benchmark's 0.5 × the predicted step) or the elements set the step.
        high = sorted(((num(r["exponent"]), r["particle"], r) for r in t["by_particle"]
                       if num(r["exponent"]) > num(s["high_exponent"])), reverse=True)
        if high:
            print("\n| particle | exponent | steps exponent | work/step exponent | tets 100 → 1000 | "
                  "dt/dt_element at 100 | at 1000 | least penalty factor at 1000 |")
            print("| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |")
            for x, p, r in high:
                print(f"| {p} | {x:.2f} | {num(r['steps_exponent']):.2f} | "
                      f"{num(r['work_per_step_exponent']):.2f} | {num(r['tets_100']):.0f} → "
                      f"{num(r['tets_1000']):.0f} | {num(r['dt_over_element_100']):.2f} | "
                      f"{num(r['dt_over_element_1000']):.2f} | "
                      f"{num(r['penalty_scale_min_1000']):.3g} |")

    if args.csv:
        runs_sorted = {p: dict(sorted(runs[p].items())) for p in sorted(runs)}
        write_runs(runs_sorted, args.csv, lambda x: f"{x:.6g}")


if __name__ == "__main__":
    main()
