#!/usr/bin/python3
"""Wall time of one study at several ranks x threads through Slurm (docs/cluster.md, "Speed-up
through Slurm").

Usage (a cluster up, SLURM_CONF set: scripts/slurm/local-cluster.sh start):
  tools/measure_scaling.py STUDY.json OUT_DIR CSV [--repeats N] [--layouts 1x1,2x1,1x2] [--bin DIR]
  tools/measure_scaling.py --table CSV [--bin DIR]    (the table again, from the CSV)

Each repeat runs every layout RxT (R ranks per node, T threads each) once, in turn, as its own
srun job (scripts/slurm/submit.sh --srun) into a fresh folder, so a change in the machine's load
falls on every layout alike. Writes one CSV row per run: the layout, the study's own wall time
and summed case CPU, the task pool's accounting of its cases phase (share of worker time idle,
seconds the end ran with idle workers), the job's elapsed time as Slurm saw it, and the load
average before and after. Prints the medians per layout with the speed-up and efficiency against
the first layout; the medians are computed by the C++ (DIR/spread_table, default build/bin: the
one quantile), this script only formats them.
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "report"))
from tabular import ROOT, spread  # noqa: E402

submit = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "slurm", "submit.sh")
LINE = re.compile(r"(\d+) cases \((\d+) run.*?in ([\d.]+) s wall, ([\d.]+) s CPU; (\d+) ranks, "
                  r"(\d+) workers, ([\d.]+) % idle, ([\d.]+) s at the end")


def load1():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def run_layout(study, out, ranks, threads):
    shutil.rmtree(out, ignore_errors=True)
    job = subprocess.run([submit, "--srun", study, out,
                          f"--ntasks-per-node={ranks}", f"--cpus-per-task={threads}"],
                         capture_output=True, text=True, check=True).stdout.split()[0]
    while subprocess.run(["squeue", "--noheader", f"--jobs={job}"], capture_output=True,
                         text=True).stdout.strip():
        time.sleep(0.5)
    info = subprocess.run(["scontrol", "show", "job", job], capture_output=True, text=True).stdout
    times = [time.mktime(time.strptime(re.search(k + r"=(\S+)", info).group(1), "%Y-%m-%dT%H:%M:%S"))
             for k in ("StartTime", "EndTime")]
    with open(os.path.join(out, "slurm", f"asperity-study-{job}.out")) as f:
        m = LINE.search(f.read())
    if m is None or "COMPLETED" not in info:
        raise SystemExit(f"job {job} ({ranks}x{threads}) did not complete: see {out}/slurm/")
    return {"cases": int(m[1]), "ran": int(m[2]), "wall_s": float(m[3]), "cpu_s": float(m[4]),
            "ranks": int(m[5]), "workers": int(m[6]), "idle_pct": float(m[7]),
            "drain_s": float(m[8]), "job_elapsed_s": times[1] - times[0]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("study", help="the study definition, or --table: the CSV of an earlier run")
    ap.add_argument("out", nargs="?")
    ap.add_argument("csv", nargs="?")
    ap.add_argument("--table", action="store_true", help="only print the table of STUDY (a CSV)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--layouts", default="1x1,2x1,1x2")
    ap.add_argument("--bin", default=str(ROOT / "build" / "bin"), help="the build's bin folder (spread_table)")
    a = ap.parse_args()
    program = os.path.join(a.bin, "spread_table")
    layouts = [tuple(int(x) for x in s.split("x")) for s in a.layouts.split(",")]
    if a.table:
        with open(a.study, newline="") as f:
            print_table(list(csv.DictReader(f)), [f"{r}x{t}" for r, t in layouts], program)
        return
    keys = ["repeat", "layout", "ranks", "workers", "cases", "ran", "wall_s", "job_elapsed_s",
            "cpu_s", "idle_pct", "drain_s", "load_before", "load_after"]
    rows = []
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for rep in range(1, a.repeats + 1):
            for ranks, threads in layouts:
                before = load1()
                r = run_layout(a.study, os.path.join(a.out, f"{ranks}x{threads}-{rep}"), ranks, threads)
                r.update(repeat=rep, layout=f"{ranks}x{threads}", load_before=before, load_after=load1())
                rows.append(r)
                w.writerow(r)
                f.flush()
                print(f"repeat {rep} {ranks}x{threads}: {r['wall_s']:.1f} s wall, {r['cpu_s']:.1f} s CPU, "
                      f"{r['idle_pct']:.1f} % idle, load {before:.1f} -> {r['load_after']:.1f}", flush=True)
    print_table(rows, [f"{r}x{t}" for r, t in layouts], program)


def print_table(rows, layouts, program):
    """Medians per layout (spread_table's): speed-up and efficiency against the 1x1 median, and
    why: the speed-up is (1x1 CPU / CPU) x (cores had / 1x1's cores had), cores had = CPU / wall."""
    medians = spread((((r["layout"], key), float(r[key])) for r in rows
                      for key in ("wall_s", "cpu_s", "idle_pct", "drain_s")), program)

    def med(layout, key):
        return medians[(layout, key)][1]
    base, base_cores = med("1x1", "wall_s"), med("1x1", "cpu_s") / med("1x1", "wall_s")
    print("| ranks x threads | wall | case CPU | cores had (CPU / wall) | speed-up | efficiency | "
          "pool idle | end with idle workers |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for layout in layouts:
        wall, cpu = med(layout, "wall_s"), med(layout, "cpu_s")
        workers = int(next(r["workers"] for r in rows if r["layout"] == layout))
        print(f"| {layout} | {wall:.1f} s | {cpu:.1f} s | {cpu / wall:.2f} (x{cpu / wall / base_cores:.2f}) | "
              f"{base / wall:.2f} | {base / wall / workers:.2f} | {med(layout, 'idle_pct'):.1f} % | "
              f"{med(layout, 'drain_s'):.1f} s |")


if __name__ == "__main__":
    main()
