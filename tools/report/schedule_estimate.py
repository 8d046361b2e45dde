#!/usr/bin/python3
"""Wall time and idle fraction of a study on W workers, from its measured per-case CPU seconds.

Usage: schedule_estimate.py CASES.csv [W ...]. Replays the task pool of cluster/
(one case at a time to the first free worker) in the order `asperity study` hands the cases out
(study_run.cpp, case_weight: the most expensive first) and, for comparison, in the study's plan
order; each case takes its measured cpu_seconds (meshing and messages left out). docs/cluster.md
quotes its output.
"""
import heapq
import sys

from tabular import read_csv  # beside this file


def weight(model, resolution):
    """study_run.cpp case_weight."""
    n = (float(resolution) / 100.0) ** 1.4 if resolution else 0.0
    return {"fem": n, "rigid": 0.5 * n, "sphere": 0.01}[model]


def replay(costs, workers):
    """(makespan, idle fraction, seconds from the first idle worker to the end)."""
    free = [0.0] * workers
    for c in costs:
        heapq.heappush(free, heapq.heappop(free) + c)
    ends = sorted(free)
    makespan = ends[-1]
    first_idle = ends[0]
    return makespan, 1 - sum(costs) / (workers * makespan), makespan - first_idle


rows = [r for r in read_csv(sys.argv[1]) if r["cpu_seconds"]]
plan = [float(r["cpu_seconds"]) for r in rows]
# Python's sort is stable, as std::stable_sort: equal weights keep the plan order.
ordered = [float(r["cpu_seconds"]) for r in sorted(rows, key=lambda r: -weight(r["model"], r["resolution"]))]
total = sum(plan)
print(f"{len(rows)} cases, {total:.0f} s CPU, longest case {max(plan):.1f} s")
print("workers | expensive first: wall s, idle %, end with idle workers s | plan order: wall s, idle %")
for w in [int(x) for x in sys.argv[2:]] or [1, 2, 4, 8, 16, 32, 64]:
    a = replay(ordered, w)
    b = replay(plan, w)
    print(f"{w:7d} | {a[0]:8.1f} {100 * a[1]:5.1f} {a[2]:7.1f} | {b[0]:8.1f} {100 * b[1]:5.1f}")
