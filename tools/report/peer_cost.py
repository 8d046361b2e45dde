#!/usr/bin/env python3
"""The peer cost table: asperity, YADE, LAMMPS and LIGGGHTS on the same two-sphere scene and the
same 10,000-sphere bed, same step, same step count, measured in one run of this script.

    peer_cost.py ASPERITY_EXE OUT_DIR [--repeats N] [--peers yade,lammps,liggghts]
                 [--bed-steps N] [--pair-steps N] [--tables-only]

Writes the scenes (tools/cases/bed_scene.py) to OUT_DIR/runs/scenes/, then N times (default 3)
runs `asperity crosscheck SCENE --cost-only --peer ...` on each (OUT_DIR/runs/SCENE/rK/cost.json,
all codes one after the other in each repeat, so a change of load hits every code alike), and
writes OUT_DIR/cost.csv and OUT_DIR/cost.md: per scene and code the median over the repeats of

- the steps' CPU: each code's own CPU clock of its loop (asperity: its time loop's thread CPU;
  YADE: process_time around O.run; LAMMPS: loop time times its CPU use); LIGGGHTS prints only its
  loop's wall time, so for it the process CPU at the scene's step count less the same process at
  0 steps (start, input, set-up, exit), which every peer also gets as a cross-check column;
- that per step and per particle, and its ratio to asperity's;
- the whole run's CPU and wall seconds (a peer: its process, start to exit; asperity: its run from
  the loaded scene to the written outputs).

Every code runs single-threaded, without a per-step recorder or dump. A peer that fails or cannot
express a scene is listed with its error, not left out. Exit 1 if any did. --tables-only rewrites
the tables from the cost.json files an earlier run left in OUT_DIR/runs/.

The medians, the ratios to asperity and the clocks' agreement are computed by
build/bin/peer_cost_table (peers/peer_cost_table.cpp: the C++ median); this script runs the
repeats, hands it their cost.json files and only formats the OUT_DIR/cost.csv it writes.
"""
import json
import os
import pathlib
import platform
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "cases"))
import bed_scene  # noqa: E402
from tabular import num, read_csv  # noqa: E402  (beside this file)



def option(rest, name, default, kind=str):
    if name in rest:
        i = rest.index(name)
        value = kind(rest[i + 1])
        del rest[i:i + 2]
        return value
    return default


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    exe, out = argv[0], pathlib.Path(argv[1])
    rest = argv[2:]
    repeats = option(rest, "--repeats", 3, int)
    peers = option(rest, "--peers", "yade,lammps,liggghts").split(",")
    bed_steps = option(rest, "--bed-steps", 500, int)
    pair_steps = option(rest, "--pair-steps", 1_000_000, int)
    # The table program is built beside the asperity given (build/bin/ of the same build).
    program = option(rest, "--table-program", str(pathlib.Path(exe).parent / "peer_cost_table"))
    tables_only = "--tables-only" in rest
    if tables_only:
        rest.remove("--tables-only")
    if rest:
        print(f"peer_cost.py: unknown arguments {rest}", file=sys.stderr)
        return 2
    scenes = bed_scene.write(out / "runs" / "scenes", bed_steps=bed_steps, pair_steps=pair_steps)
    if not os.access(program, os.X_OK):
        print(f"{program}: not built (cmake --build build --target peer_cost_table); it computes "
              "the table", file=sys.stderr)
        return 2
    files = {s.stem: [] for s in scenes}  # scene -> [cost.json per repeat]
    errors = {s.stem: {} for s in scenes}  # scene -> {peer: error}
    contacts = {}
    for r in range(repeats):
        for s in scenes:
            d = out / "runs" / s.stem / f"r{r + 1}"
            if not tables_only:
                p = subprocess.run([exe, "crosscheck", str(s), "--out", str(d), "--peer", ",".join(peers),
                                    "--cost-only", "--only-expressible", "--quiet"], capture_output=True, text=True)
            cost_file = d / "cost.json"
            if tables_only and not cost_file.exists():
                continue
            if not cost_file.exists():
                errors[s.stem]["asperity"] = f"exit {p.returncode}: {p.stderr.strip()}"
                print(f"{s.stem} r{r + 1}: FAILED {p.stderr.strip()}", file=sys.stderr)
                continue
            c = json.loads(cost_file.read_text())
            files[s.stem].append(str(cost_file))
            errors[s.stem].update(c.get("failed", {}))
            errors[s.stem].update(c.get("not_run", {}))
            a = json.loads((d / "asperity" / "summary.json").read_text())
            contacts[s.stem] = a.get("contact_updates", 0) / max(1, a["steps"])
            print(f"{s.stem} r{r + 1}: " + ", ".join(f"{k} {v['step_cpu_seconds']:.3f} s"
                                                     for k, v in c["codes"].items()), file=sys.stderr)

    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as d:
        given = pathlib.Path(d) / "runs.json"
        given.write_text(json.dumps({"codes": ["asperity"] + peers, "scenes": [
            {"scene": s.stem, "costs": files[s.stem], "errors": errors[s.stem]} for s in scenes]}))
        agreement_csv = pathlib.Path(d) / "agreement.csv"
        subprocess.run([program, str(given), str(out / "cost.csv"), str(agreement_csv)], check=True)
        gaps = read_csv(agreement_csv)
    rows = read_csv(out / "cost.csv")

    def f(x, spec, scale=1):
        return "" if x is None or x == "" else format(num(x) * scale, spec)

    # How far the two measures of a peer's steps agree where the peer has its own CPU clock: the
    # noise the 0-step difference carries (two process start-ups) for LIGGGHTS.
    agreement = ("; where a peer has its own CPU clock the two agree within " +
                 ", ".join(f"{num(g['largest_difference_seconds']):.3f} s ({g['code']})"
                           for g in gaps)) if gaps else ""

    lines = [
        "# Cost per step: asperity, YADE, LAMMPS and LIGGGHTS on the same scenes",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, {platform.platform()}; shared with other jobs, "
        f"so wall times are inflated and CPU times are the measure. One run of `tools/report/peer_cost.py` "
        f"({repeats} repeats, every code one after the other in each, medians shown): each scene through "
        "`asperity crosscheck --cost-only` (docs/crosscheck.md, \"Cost\"), every code single-threaded, same "
        "scene, same dt, same step count, no per-step recorder or dump.",
        "",
        "Scenes (tools/cases/bed_scene.py): glass spheres of radius 1 mm, Hertz–Mindlin, e = 0.8, μ = 0.3, "
        f"dt = {bed_scene.DT:g} s. **pair**: two spheres head-on at 0.1 m/s each, {pair_steps:,} steps (one "
        f"contact, then free flight). **bed-10k**: 10,000 spheres on a simple-cubic lattice settling on a plane "
        f"under gravity, {bed_steps:,} steps"
        + (f" (asperity: {contacts['bed-10k']:,.0f} touching contacts per step on average)" if "bed-10k" in contacts
           else "") + ".",
        "",
        "*steps CPU*: each code's own CPU clock of its loop (asperity: time-loop thread CPU; YADE: process_time "
        "around O.run; LAMMPS: loop time × its CPU use); LIGGGHTS prints its loop's wall time only, so for it the "
        "process CPU at the step count less the same process at 0 steps (*process − 0 steps*, given for every "
        "peer as a cross-check" + agreement + "). *per step·particle*: steps CPU over steps × particles. *whole "
        "run*: a peer's process from start to exit; asperity's run from the loaded scene to its written outputs.",
        "",
        "| scene | code | steps CPU s | per step·particle | × asperity | process − 0 steps s | whole run CPU s "
        "| whole run wall s | version |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["repeats"] == "0":
            lines.append(f"| {r['scene']} | {r['code']} | not run: {r['error']} | | | | | | |")
            continue
        lines.append(f"| {r['scene']} | {r['code']} | {f(r['step_cpu_seconds'], '.4f')} | "
                     f"{f(r['cpu_per_step_per_particle'], '.1f', 1e9)} ns | {f(r['over_asperity'], '.2f')} | "
                     f"{f(r['process_step_cpu_seconds'], '.4f')} | {f(r['run_cpu_seconds'], '.3f')} | "
                     f"{f(r['run_wall_seconds'], '.2f')} | {r['version']} |")
    (out / "cost.md").write_text("\n".join(lines) + "\n")
    print(f"-> {out / 'cost.md'}", file=sys.stderr)
    return 1 if any(errors[s.stem] for s in scenes) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
