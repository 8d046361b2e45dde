#!/usr/bin/python3
"""Wall time and idle fraction of a study on W workers, from its measured per-case CPU seconds.

Usage: schedule_estimate.py CASES.csv [W ...] [--bin DIR]
       schedule_estimate.py --cluster-study FULL_CASES.csv [W ...] [--bin DIR]
The task pool of cluster/ (one case at a time to the first free worker) replayed in the order
`asperity study` hands the cases out (case_weight: the most expensive first) and, for comparison,
in the study's plan order; each case takes its measured cpu_seconds (meshing and messages left
out). docs/cluster.md quotes its output.

--cluster-study: the cases of data/study/cluster.json, each costed from the full study's measured
cases (reports/study-full/cases.csv); the rules are study::cluster_study_cases's
(study/schedule_estimate.hpp).

The numbers are the C++'s (DIR/schedule_table, default build/bin: study/schedule_estimate.hpp,
cluster/pool_replay.hpp); this script hands it the table's columns and formats its answer.
"""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile

from tabular import ROOT, read_csv  # beside this file

COLUMNS = ["particle", "model", "resolution", "element_size_rel", "cpu_seconds"]


def schedule(rows, mode, workers, program):
    """schedule_table's answer for the rows (dicts with COLUMNS) in `mode` (measured or
    cluster-study) on each of `workers`."""
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        with open(tmp / "cases.csv", "w", newline="") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(COLUMNS)
            for r in rows:
                w.writerow([r[c] for c in COLUMNS])
        r = subprocess.run([str(program), str(tmp / "cases.csv"), mode, ",".join(map(str, workers)),
                            str(tmp / "schedule.json")], stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            sys.exit(f"schedule_estimate: {program}: exit {r.returncode}: {r.stderr.strip()}")
        with open(tmp / "schedule.json") as fh:
            return json.load(fh)


def main():
    args = sys.argv[1:]
    program = ROOT / "build" / "bin" / "schedule_table"
    if "--bin" in args:
        i = args.index("--bin")
        program = pathlib.Path(args[i + 1]) / "schedule_table"
        del args[i:i + 2]
    mode = "measured"
    if args and args[0] == "--cluster-study":
        mode = "cluster-study"
        args = args[1:]
    workers = [int(x) for x in args[1:]] or [1, 2, 4, 8, 16, 32, 64]
    s = schedule(read_csv(args[0]), mode, workers, program)
    total = s["cpu_seconds"]
    print(f"{s['cases']} cases, {total:.0f} s CPU ({total / 3600:.1f} h), longest case {s['longest']:.1f} s")
    print("workers | expensive first: wall s, idle %, end with idle workers s | plan order: wall s, idle %")
    for r in s["replays"]:
        a, b = r["expensive_first"], r["plan_order"]
        print(f"{r['workers']:7d} | {a['wall_seconds']:8.1f} {100 * a['idle_fraction']:5.1f} "
              f"{a['drain_seconds']:7.1f} | {b['wall_seconds']:8.1f} {100 * b['idle_fraction']:5.1f}")


if __name__ == "__main__":
    main()
