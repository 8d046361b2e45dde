"""The YADE polyhedra cross-check's table: agreement and cost side by side, from the comparison.json
that each `yade.polyhedra.*` gate writes (`ctest -L yade` first).

  python3 tools/report/polyhedra_table.py build/yade/polyhedra reports/yade [BEFORE.csv]

Writes OUT/polyhedra.md and OUT/polyhedra.csv: per case the body's vertex count, the step count and
YADE's contact steps, the relative differences (asperity − YADE)/YADE of peak force, impulse and
contact duration, both codes' CPU seconds for the whole impact (YADE's engine loop alone, a second
run without its recorder) and their ratio, and YADE's CPU seconds per step in free flight, in
contact on average, and in its first and last contact steps, beside asperity's CPU over its step
count (mesh loading and tetrahedralization included). With BEFORE.csv (an earlier polyhedra.csv),
each case's asperity CPU from it beside today's (reports/yade/polyhedra-before-broad-phase.csv:
the table before the broad phase stopped comparing tetrahedra of the same body).
Every number comes from one run of both codes on one machine."""
import csv
import glob
import json
import os
import sys


def vertices(case_file):
    with open(case_file) as f:
        scene = json.load(f)["scene"]
    mesh = next(b["shape"]["file"] for b in scene["bodies"] if b["shape"]["type"] == "mesh")
    with open(os.path.join(os.path.dirname(case_file), mesh)) as f:
        tokens = f.read().split()
    return int(tokens[1])


def row(path):
    with open(path) as f:
        c = json.load(f)
    y = c.get("step_seconds", {}).get("yade", {})
    a = c.get("step_seconds", {}).get("asperity", {})
    cpu_a, cpu_y = c["cpu_seconds"]["asperity"], c["cpu_seconds"]["yade"]
    return {
        "case": c["scene"],
        "vertices": vertices(c["file"]),
        "steps": c["steps"],
        "yade_contact_steps": y.get("contact_steps"),
        "peak_force_rel_diff": c["peak_force"]["rel_diff"]["yade"],
        "impulse_rel_diff": c["impulse"]["rel_diff"]["yade"],
        "contact_duration_rel_diff": c["contact_duration"]["rel_diff"]["yade"],
        "asperity_cpu_s": cpu_a,
        "yade_cpu_s": cpu_y,
        "yade_over_asperity": cpu_y / cpu_a if cpu_a > 0 else None,
        "asperity_cpu_per_step_s": a.get("cpu_mean"),
        "yade_free_step_s": y.get("free_mean"),
        "yade_contact_step_s": y.get("contact_mean"),
        "yade_first_contact_step_s": y.get("first_contact_step"),
        "yade_last_contact_step_s": y.get("last_contact_step"),
    }


def fmt(v, spec):
    return "" if v is None else format(v, spec)


def main():
    src, out = sys.argv[1], sys.argv[2]
    rows = sorted((row(p) for p in glob.glob(os.path.join(src, "*", "comparison.json"))),
                  key=lambda r: (r["vertices"], r["case"]))
    before = {}
    if len(sys.argv) > 3:
        with open(sys.argv[3]) as f:
            before = {r["case"]: float(r["asperity_cpu_s"]) for r in csv.DictReader(f)}
    for r in rows:
        r["asperity_cpu_s_before"] = before.get(r["case"])
    if not rows:
        sys.exit(f"polyhedra_table.py: {src}: no */comparison.json (run ctest -L yade first)")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "polyhedra.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = [
        "# Rigid convex polyhedra: asperity against YADE's Polyhedra",
        "",
        "Written by `tools/report/polyhedra_table.py` from the `yade.polyhedra.*` gates "
        "(`validation/cases/polyhedra/volume-linear-*`, volume-linear, same scene, step and step "
        "count in both codes). Differences are (asperity − YADE)/YADE. CPU: the whole impact "
        "(YADE: its engine loop alone, a second run without the per-step recorder). Step costs: "
        "YADE's CPU seconds per step (free flight, mean in contact, its first and last contact "
        "steps), asperity's CPU over its step count (mesh loading and tetrahedralization "
        "included, so not a per-step cost at ~100 steps; `bench_rigid` times the narrow phase). "
        "One run of both codes on one machine; the machine was shared and loaded (load ~16 on "
        "2 cores), so the ratios matter more than the seconds.",
        "",
        "| case | vertices | steps | in contact (YADE) | peak force | impulse | duration | "
        "asperity CPU s | asperity CPU s before | YADE CPU s | YADE / asperity | asperity CPU / steps | YADE free s/step | "
        "YADE contact s/step | YADE first contact step s | YADE last contact step s |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        lines.append(
            f"| {r['case']} | {r['vertices']} | {r['steps']} | {fmt(r['yade_contact_steps'], 'd')} | "
            f"{r['peak_force_rel_diff']:.1e} | {r['impulse_rel_diff']:.1e} | "
            f"{r['contact_duration_rel_diff']:.1e} | {r['asperity_cpu_s']:.3g} | "
            f"{fmt(r['asperity_cpu_s_before'], '.3g')} | {r['yade_cpu_s']:.3g} | {fmt(r['yade_over_asperity'], '.0f')} | "
            f"{fmt(r['asperity_cpu_per_step_s'], '.2e')} | {fmt(r['yade_free_step_s'], '.2e')} | "
            f"{fmt(r['yade_contact_step_s'], '.2e')} | {fmt(r['yade_first_contact_step_s'], '.2e')} | "
            f"{fmt(r['yade_last_contact_step_s'], '.2e')} |")
    with open(os.path.join(out, "polyhedra.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
