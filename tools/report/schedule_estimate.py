#!/usr/bin/python3
"""Wall time and idle fraction of a study on W workers, from its measured per-case CPU seconds.

Usage: schedule_estimate.py CASES.csv [W ...]
       schedule_estimate.py --cluster-study FULL_CASES.csv [W ...] [--bin DIR]
Replays the task pool of cluster/ (one case at a time to the first free worker) in the
order `asperity study` hands the cases out (study_run.cpp, case_weight: the most expensive first)
and, for comparison, in the study's plan order; each case takes its measured cpu_seconds (meshing
and messages left out). docs/cluster.md quotes its output.

--cluster-study: the cases of data/study/cluster.json (every particle of the full study, both
placements, fem coarse and refined to h = 0.08, 0.04 and 0.02 R at every resolution, rigid,
rigid-penalty and the spheres), each costed from the full study's measured cases
(reports/study-full/cases.csv: lowest placement, refined at 500, 1000 and 2000 triangles):
  - the centroid placement costs what the lowest does (same meshes, same steps);
  - a refined level at 100 or 250 triangles costs what it does at 500 (the refined element size,
    not the surface, sets its elements and step: docs/study.md, "The full study");
  - h = 0.02 R costs what 0.04 R does times the measured growth from 0.08 to 0.04 R, at least 2
    (each halving of h halves the step, and the growth measured so far repeats);
  - a case that failed in the full study (no CPU) costs the median of the others at its model,
    resolution and level (the C++'s median: DIR/spread_table, default build/bin).
"""
import heapq
import math
import pathlib
import sys
from collections import defaultdict

from tabular import ROOT, read_csv, spread  # beside this file


def weight(model, resolution, relative_size):
    """study_run.cpp case_weight: N^1.4 for fem, scaled by the refined level's edge over h; half
    that for the rigid models; 0.01 for the spheres."""
    n = (float(resolution) / 100.0) ** 1.4 if resolution else 0.0
    if model == "fem":
        if relative_size:
            return n * max(1.0, math.sqrt(29.0 / float(resolution)) / float(relative_size))
        return n
    if model in ("rigid", "rigid-penalty"):
        return 0.5 * n
    return 0.01


def replay(costs, workers):
    """(makespan, idle fraction, seconds from the first idle worker to the end)."""
    free = [0.0] * workers
    for c in costs:
        heapq.heappush(free, heapq.heappop(free) + c)
    ends = sorted(free)
    makespan = ends[-1]
    first_idle = ends[0]
    return makespan, 1 - sum(costs) / (workers * makespan), makespan - first_idle


def cluster_study(rows, program):
    """The cluster study's cases as (model, resolution, relative_size, cpu_seconds) in plan order,
    costed from the full study's rows (the rules in the module's doc); program: spread_table."""
    cost = {}
    by_kind = defaultdict(list)
    for r in rows:
        key = (r["model"], r["resolution"], r["element_size_rel"])
        if r["cpu_seconds"]:
            cost[(r["particle"],) + key] = float(r["cpu_seconds"])
            by_kind[key].append(float(r["cpu_seconds"]))

    medians = spread(((kind, c) for kind, costs in by_kind.items() for c in costs), program)

    def measured(p, model, n, h):
        c = cost.get((p, model, n, h))
        return c if c is not None else medians[(model, n, h)][1]

    cases = []
    particles = list(dict.fromkeys(r["particle"] for r in rows))
    resolutions = ["100", "250", "500", "1000", "2000"]
    for p in particles:
        per_placement = []
        for model in ["fem", "rigid", "rigid-penalty"]:
            per_placement += [(model, n, "", measured(p, model, n, "")) for n in resolutions]
        per_placement += [(m, "", "", measured(p, m, "", "")) for m in ["sphere", "sphere-local"]]
        for n in resolutions:
            at = n if n in ("500", "1000", "2000") else "500"
            c08, c04 = measured(p, "fem", at, "0.08"), measured(p, "fem", at, "0.04")
            c02 = c04 * max(2.0, c04 / c08)
            per_placement += [("fem", n, "0.08", c08), ("fem", n, "0.04", c04), ("fem", n, "0.02", c02)]
        cases += per_placement * 2  # centroid and lowest placements
    return cases


def main():
    args = sys.argv[1:]
    program = ROOT / "build" / "bin" / "spread_table"
    if "--bin" in args:
        i = args.index("--bin")
        program = pathlib.Path(args[i + 1]) / "spread_table"
        del args[i:i + 2]
    modelled = args and args[0] == "--cluster-study"
    if modelled:
        args = args[1:]
    rows = read_csv(args[0])
    if modelled:
        cases = cluster_study(rows, program)
    else:
        cases = [(r["model"], r["resolution"], r["element_size_rel"], float(r["cpu_seconds"]))
                 for r in rows if r["cpu_seconds"]]
    plan = [c[3] for c in cases]
    # Python's sort is stable, as std::stable_sort: equal weights keep the plan order.
    ordered = [c[3] for c in sorted(cases, key=lambda c: -weight(c[0], c[1], c[2]))]
    total = sum(plan)
    print(f"{len(cases)} cases, {total:.0f} s CPU ({total / 3600:.1f} h), longest case {max(plan):.1f} s")
    print("workers | expensive first: wall s, idle %, end with idle workers s | plan order: wall s, idle %")
    for w in [int(x) for x in args[1:]] or [1, 2, 4, 8, 16, 32, 64]:
        a = replay(ordered, w)
        b = replay(plan, w)
        print(f"{w:7d} | {a[0]:8.1f} {100 * a[1]:5.1f} {a[2]:7.1f} | {b[0]:8.1f} {100 * b[1]:5.1f}")


if __name__ == "__main__":
    main()
