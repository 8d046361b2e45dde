#!/usr/bin/env python3
"""The performance record (issue 32): asperity's DEM benchmarks and the peers on the same scenes,
interleaved, in one command.

    perf_table.py BUILD OUT [--pairs N] [--peers lammps,liggghts,yade] [--baseline BUILD0]
                  [--pressed-steps N] [--bed-steps N] [--smoke]

BUILD is a release build folder (BUILD/bin/asperity, BUILD/bin/bench_dem, BUILD/bin/spread_table). N pairs (default 5)
each run, one after the other, so that a change of the machine's load hits every code alike:

1. `bench_dem` BM_Packing10k (mindlin; the pressed 10k lattice, ~29,000 persistent contacts):
   CPU per step and contact updates/s (Google Benchmark JSON into OUT/bench/, the JSON committed);
   with --baseline, the same benchmark of BUILD0 right before it (the "before" column);
2. for each scene, pressed-10k and bed-10k (tools/cases/bed_scene.py): `asperity run SCENE` as a
   process (its whole-process CPU, start to exit; with --baseline also BUILD0's on bed-10k, which it
   can read: it has no allow_initial_overlap), then `asperity crosscheck SCENE --cost-only --peer
   PEERS` (asperity's time loop and each peer's loop CPU in one invocation: docs/crosscheck.md,
   "Cost"; each peer's inputs written by its adapter from the scene).

Every figure is the median over the pairs with its spread (min–max); a peer's ratio to asperity is
taken within each pair (same crosscheck invocation) and its median and spread reported (both
computed by BUILD/bin/spread_table, the C++ that owns the median; this script runs and formats). Writes
OUT/perf.md, OUT/perf.csv and OUT/bench/*.json (the scenes and the runs into BUILD/perf-runs/), with the CPU model (/proc/cpuinfo) and the load
average before and after. Exit 1 when a code failed or could not express a scene (listed, not left
out), 2 on bad arguments.

--smoke: the CI run (ctest perf.smoke, label perf-smoke): one pair, a pressed and a touching
lattice of 4 x 4 x 4 spheres, 20 steps each, the benchmark with --benchmark_min_time=0.001,
LAMMPS alone; it checks that the command and its tables work, not the figures.
"""
import csv
import json
import os
import pathlib
import platform
import resource
import subprocess
import sys

from tabular import spread  # beside this file

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "cases"))
import bed_scene  # noqa: E402

BENCH = "BM_Packing10k/mindlin:1"


def option(rest, name, default, kind=str):
    if name in rest:
        i = rest.index(name)
        if i + 1 >= len(rest):
            raise ValueError(f"{name} needs a value")
        value = kind(rest[i + 1])
        del rest[i:i + 2]
        return value
    return default


def cpu_model():
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def process(cmd):
    """Runs cmd; returns (its CPU seconds, start to exit, the completed process)."""
    c0 = children_cpu()
    p = subprocess.run(cmd, capture_output=True, text=True)
    return children_cpu() - c0, p


def bench(exe, out_json, smoke):
    """BM_Packing10k mindlin of one bench_dem: (ms of CPU per step, contact updates/s, contacts)."""
    cmd = [str(exe), f"--benchmark_filter=^{BENCH}$", "--benchmark_out_format=json",
           f"--benchmark_out={out_json}"]
    if smoke:
        cmd.append("--benchmark_min_time=0.001")
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{exe}: exit {p.returncode}: {p.stderr.strip()[-300:]}")
    b = next(b for b in json.loads(pathlib.Path(out_json).read_text())["benchmarks"] if b["name"] == BENCH)
    # One iteration is 20 steps (benchmarks/dem_bench.cpp); cpu_time is per iteration.
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    return b["cpu_time"] * scale / 20, b["contacts/s"], b["contacts"]


class Samples:
    """Figures by (figure, code, build) over the pairs, and peer/asperity ratios by (figure, code)."""

    def __init__(self):
        self.values, self.ratios, self.errors = {}, {}, {}

    def add(self, key, value):
        self.values.setdefault(key, []).append(value)

    def ratio(self, key, value):
        self.ratios.setdefault(key, []).append(value)

    def error(self, what, why):
        self.errors.setdefault(what, why)


def run_pair(k, a, s, scenes, peers, out, work, baseline, smoke):
    bdir = out / "bench"
    bdir.mkdir(parents=True, exist_ok=True)
    if baseline:
        try:
            ms, rate, _ = bench(baseline / "bin" / "bench_dem", bdir / f"bench_dem.before.r{k}.json", smoke)
            s.add(("packing10k_step_ms", "asperity", "before"), ms)
            s.add(("packing10k_contact_updates_per_s", "asperity", "before"), rate)
        except RuntimeError as e:
            s.error("bench_dem (before)", str(e))
    try:
        ms, rate, contacts = bench(a / "bin" / "bench_dem", bdir / f"bench_dem.r{k}.json", smoke)
        s.add(("packing10k_step_ms", "asperity", "after"), ms)
        s.add(("packing10k_contact_updates_per_s", "asperity", "after"), rate)
        s.add(("packing10k_contacts", "asperity", "after"), contacts)
    except RuntimeError as e:
        s.error("bench_dem", str(e))
    for scene in scenes:
        name = scene.stem
        d = work / name / f"r{k}"
        builds = [("after", a)] + ([("before", baseline)] if baseline and not name.startswith("pressed") else [])
        for build, b in builds:
            cpu, p = process([str(b / "bin" / "asperity"), "run", str(scene), "--out", str(d / f"run-{build}"),
                              "--quiet"])
            if p.returncode != 0:
                s.error(f"{name}: asperity run ({build})", f"exit {p.returncode}: {p.stderr.strip()[-300:]}")
                continue
            s.add((f"{name}_process_cpu_s", "asperity", build), cpu)
            summary = json.loads((d / f"run-{build}" / "summary.json").read_text())
            s.add((f"{name}_step_ms", "asperity", build), 1e3 * summary["cpu_seconds"] / max(1, summary["steps"]))
            s.add((f"{name}_contacts", "asperity", build), summary["contact_updates"] / max(1, summary["steps"]))
        p = subprocess.run([str(a / "bin" / "asperity"), "crosscheck", str(scene), "--out", str(d / "crosscheck"),
                            "--peer", ",".join(peers), "--cost-only", "--only-expressible", "--quiet"],
                           capture_output=True, text=True)
        cost_file = d / "crosscheck" / "cost.json"
        if not cost_file.exists():
            s.error(f"{name}: crosscheck", f"exit {p.returncode}: {p.stderr.strip()[-300:]}")
            continue
        c = json.loads(cost_file.read_text())
        for peer, why in {**c.get("failed", {}), **c.get("not_run", {})}.items():
            s.error(f"{name}: {peer}", why)
        codes = c["codes"]
        base = codes["asperity"]["step_cpu_seconds"]
        for code, e in codes.items():
            s.add((f"{name}_loop_step_ms", code, "after"), 1e3 * e["step_cpu_seconds"] / max(1, c["steps"]))
            if code != "asperity":
                s.add((f"{name}_process_cpu_s", code, "after"), e["run_cpu_seconds"])
                s.ratio((f"{name}_loop_step_ms", code), e["step_cpu_seconds"] / base)
        print(f"pair {k} {name}: " + ", ".join(f"{code} {1e3 * e['step_cpu_seconds'] / max(1, c['steps']):.3f} ms/step"
                                               for code, e in codes.items()), file=sys.stderr)
    # Whole process: each peer's process against asperity's `run` process of the same pair.
    for scene in scenes:
        name = scene.stem
        key = (f"{name}_process_cpu_s", "asperity", "after")
        if key not in s.values or len(s.values[key]) < k:
            continue
        for code in peers:
            pk = (f"{name}_process_cpu_s", code, "after")
            if pk in s.values and len(s.values[pk]) == k:
                s.ratio((f"{name}_process_cpu_s", code), s.values[pk][-1] / s.values[key][-1])


FIGURES = [
    ("packing10k_step_ms", "BM_Packing10k mindlin (pressed lattice), CPU per step", "ms"),
    ("packing10k_contact_updates_per_s", "BM_Packing10k mindlin, contact updates per second", "M/s"),
    ("packing10k_contacts", "BM_Packing10k mindlin, touching contacts per step", ""),
    ("pressed-10k_loop_step_ms", "pressed-10k scene, time loop CPU per step", "ms"),
    ("pressed-10k_step_ms", "pressed-10k scene, `asperity run` time loop CPU per step", "ms"),
    ("pressed-10k_process_cpu_s", "pressed-10k scene, whole process CPU", "s"),
    ("pressed-10k_contacts", "pressed-10k scene, touching contacts per step (asperity)", ""),
    ("bed-10k_loop_step_ms", "bed-10k touching lattice, time loop CPU per step", "ms"),
    ("bed-10k_step_ms", "bed-10k, `asperity run` time loop CPU per step", "ms"),
    ("bed-10k_process_cpu_s", "bed-10k, whole process CPU", "s"),
    ("bed-10k_contacts", "bed-10k, touching contacts per step (asperity)", ""),
]


def fmt(x, unit):
    if unit == "M/s":
        return f"{x / 1e6:.1f}"
    if abs(x) >= 100:
        return f"{x:,.0f}"
    return f"{x:.3f}" if abs(x) < 10 else f"{x:.2f}"


def write_tables(s, out, meta, figure_names, program):
    """perf.csv and perf.md; the medians and spreads are spread_table's (program)."""
    figures = spread(((key, v) for key, vals in s.values.items() for v in vals), program)
    ratios = spread(((key, v) for key, vals in s.ratios.items() for v in vals), program)
    rows = []
    for key, title, unit in FIGURES:
        key = key.replace("pressed-10k", figure_names["pressed"]).replace("bed-10k", figure_names["bed"])
        title = title.replace("pressed-10k", figure_names["pressed"]).replace("bed-10k", figure_names["bed"])
        for (fig, code, build), vals in sorted(s.values.items()):
            if fig != key:
                continue
            _, med, lo, hi = figures[(fig, code, build)]
            row = {"figure": fig, "title": title, "unit": unit or "count", "code": code, "build": build,
                   "pairs": len(vals), "median": med, "min": lo, "max": hi}
            if (fig, code) in ratios:
                _, row["over_asperity_median"], row["over_asperity_min"], row["over_asperity_max"] = ratios[(fig, code)]
            rows.append(row)
    fields = ["figure", "title", "unit", "code", "build", "pairs", "median", "min", "max", "over_asperity_median",
              "over_asperity_min", "over_asperity_max"]
    with open(out / "perf.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)

    lines = [
        "# Performance record: asperity's sphere DEM and its peers, one run",
        "",
        f"Written by `python3 tools/report/perf_table.py {meta['command']}` (docs/performance.md). "
        f"CPU: {meta['cpu']}, {os.cpu_count()} CPUs; load average {meta['load_before']} before, "
        f"{meta['load_after']} after (the machine is shared: CPU seconds are the measure, wall times are not). "
        f"{meta['pairs']} pairs, run one after the other: every figure is the median over the pairs, with the "
        "spread (min–max); a peer's ratio to asperity is taken within each pair (one `crosscheck --cost-only` "
        "invocation: asperity's time loop, then each peer's loop, each code single-threaded, no recorder or dump) "
        "and its median and spread given. *before*: the build given as --baseline"
        + (f" ({meta['baseline']})" if meta["baseline"] else " (none this run)") + ", run in the same pairs.",
        "",
        "| figure | code | build | median | spread | peer / asperity (median, spread) |",
        "|---|---|---|---:|---|---|",
    ]
    for r in rows:
        unit = "" if r["unit"] == "count" else " " + r["unit"]
        ratio = ""
        if "over_asperity_median" in r:
            ratio = (f"**{r['over_asperity_median']:.2f}** ({r['over_asperity_min']:.2f}–"
                     f"{r['over_asperity_max']:.2f})")
        lines.append(f"| {r['title']} | {r['code']} | {r['build']} | {fmt(r['median'], r['unit'])}{unit} | "
                     f"{fmt(r['min'], r['unit'])}–{fmt(r['max'], r['unit'])} | {ratio} |")
    if s.errors:
        lines += ["", "Failed or not expressible (not left out):", ""]
        lines += [f"- {what}: {why}" for what, why in s.errors.items()]
    lines += ["", "Scenes: tools/cases/bed_scene.py (docs/performance.md). Bench JSON of each pair: `bench/`.", ""]
    (out / "perf.md").write_text("\n".join(lines))
    print(f"-> {out / 'perf.md'}", file=sys.stderr)


def main(argv):
    if len(argv) < 2 or argv[0].startswith("-") or argv[1].startswith("-"):
        print(__doc__)
        return 2
    build, out = pathlib.Path(argv[0]).resolve(), pathlib.Path(argv[1]).resolve()
    rest = argv[2:]
    try:
        smoke = "--smoke" in rest
        if smoke:
            rest.remove("--smoke")
        pairs = option(rest, "--pairs", 1 if smoke else 5, int)
        peers = option(rest, "--peers", "lammps" if smoke else "lammps,liggghts,yade").split(",")
        baseline = option(rest, "--baseline", None, lambda v: pathlib.Path(v).resolve())
        pressed_steps = option(rest, "--pressed-steps", 20 if smoke else 500, int)
        bed_steps = option(rest, "--bed-steps", 20 if smoke else 500, int)
    except ValueError as e:
        print(f"perf_table.py: {e}", file=sys.stderr)
        return 2
    if rest:
        print(f"perf_table.py: unknown arguments {rest}", file=sys.stderr)
        return 2
    for b in [build] + ([baseline] if baseline else []):
        for exe in ("asperity", "bench_dem") + (("spread_table",) if b == build else ()):
            if not (b / "bin" / exe).exists():
                print(f"perf_table.py: {b / 'bin' / exe}: not built", file=sys.stderr)
                return 2
    side = (4, 4, 4) if smoke else (bed_scene.NX, bed_scene.NY, bed_scene.NZ)
    # The scenes and the runs' outputs (megabytes) go beside the build, not into OUT.
    work = build / ("perf-smoke-runs" if smoke else "perf-runs")
    sdir = work / "scenes"
    scenes = [bed_scene.write_one(sdir, bed_scene.pressed(pressed_steps, *side)),
              bed_scene.write_one(sdir, bed_scene.bed(bed_steps, *side))]
    names = {"pressed": scenes[0].stem, "bed": scenes[1].stem}
    load_before = " ".join(f"{x:.1f}" for x in os.getloadavg())
    s = Samples()
    for k in range(1, pairs + 1):
        run_pair(k, build, s, scenes, peers, out, work, baseline, smoke)
    meta = {"command": " ".join(argv), "cpu": cpu_model(), "pairs": pairs, "baseline": str(baseline or ""),
            "load_before": load_before, "load_after": " ".join(f"{x:.1f}" for x in os.getloadavg())}
    write_tables(s, out, meta, names, build / "bin" / "spread_table")
    for what, why in s.errors.items():
        print(f"perf_table.py: {what}: {why}", file=sys.stderr)
    return 1 if s.errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
