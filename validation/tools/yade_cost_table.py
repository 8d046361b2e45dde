#!/usr/bin/env python3
"""Cross-checks validation cases against YADE and writes the side-by-side table.

    python3 validation/tools/yade_cost_table.py ASPERITY_EXE OUT_DIR [CASE_OR_FOLDER ...]

Runs `asperity crosscheck CASE --out OUT_DIR/runs/NAME` for every case whose bodies are spheres,
planes and boxes (default: validation/cases), then writes OUT_DIR/crosscheck.csv and
OUT_DIR/crosscheck.md: per case the relative differences (asperity - YADE)/YADE of peak force,
impulse and contact duration, and both codes' CPU seconds with their ratio, measured in the same
process on the same machine. YADE's CPU time is its engine loop alone (scene_to_yade.py times a
run without the per-step recorder). Exits 1 if any cross-check failed to run.
"""
import csv
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def sphere_case(path):
    """A case the cross-check covers: only sphere, plane and box bodies, no FEM model."""
    try:
        c = json.loads(path.read_text())
    except (OSError, ValueError):
        return False
    scene = c.get("scene")
    if not isinstance(scene, dict):
        return False
    if scene.get("contact", {}).get("law", "hertz-mindlin") == "potential":
        return False
    for b in scene.get("bodies", []):
        if b.get("shape", {}).get("type") not in ("sphere", "plane", "box") or b.get("model", "rigid") != "rigid":
            return False
    return True


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    exe, out = sys.argv[1], pathlib.Path(sys.argv[2])
    targets = [pathlib.Path(p) for p in sys.argv[3:]] or [ROOT / "validation" / "cases"]
    files = []
    for t in targets:
        files += sorted(t.rglob("*.json")) if t.is_dir() else [t]
    files = [f for f in files if sphere_case(f)]
    rows, failed = [], []
    for k, f in enumerate(files):
        name = json.loads(f.read_text())["case"]
        run_dir = out / "runs" / name
        p = subprocess.run([exe, "crosscheck", str(f), "--out", str(run_dir), "--quiet"], capture_output=True, text=True)
        if p.returncode != 0:
            failed.append((name, p.returncode, p.stderr.strip()))
            print(f"[{k + 1}/{len(files)}] {name}: FAILED ({p.returncode}) {p.stderr.strip()}", file=sys.stderr)
            continue
        c = json.loads((run_dir / "comparison.json").read_text())
        row = {"case": name, "law": c["contact_law"], "steps": c["steps"]}
        for q in ("peak_force", "impulse", "contact_duration"):
            row[q + "_rel_diff"] = c[q]["rel_diff"]
        row["cpu_asperity_s"] = c["cpu_seconds"]["asperity"]
        row["cpu_yade_s"] = c["cpu_seconds"]["yade"]
        row["ratio"] = c["cpu_seconds"]["ratio_asperity_over_yade"]
        rows.append(row)
        print(f"[{k + 1}/{len(files)}] {name}: ok", file=sys.stderr)

    out.mkdir(parents=True, exist_ok=True)
    with open(out / "crosscheck.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]) if rows else ["case"])
        w.writeheader()
        w.writerows(rows)

    def fmt(x, spec):
        return "" if x is None else format(x, spec)

    ratios = [r["ratio"] for r in rows if r["ratio"]]
    tot_a = sum(r["cpu_asperity_s"] for r in rows)
    tot_y = sum(r["cpu_yade_s"] for r in rows)
    lines = [
        "# asperity against YADE: agreement and cost, case by case",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} CPUs, {platform.platform()}; both codes single-threaded, "
        "same scene, same dt, same step count, run one after the other by `asperity crosscheck` "
        "(validation/tools/yade_cost_table.py). YADE's CPU time is its engine loop alone (no Python in the "
        "loop); asperity's includes its per-step recording. Relative differences are (asperity − YADE)/YADE. "
        "docs/crosscheck.md explains every systematic difference.",
        "",
        f"{len(rows)} cases cross-checked" + (f", {len(failed)} failed to run" if failed else "") + f". CPU in all: asperity "
        f"{tot_a:.3f} s, YADE {tot_y:.3f} s (ratio {tot_a / tot_y:.3f})." if tot_y > 0 else "",
        (f"Ratio asperity/YADE per case: median {statistics.median(ratios):.3f}, min {min(ratios):.3f}, max {max(ratios):.3f}."
         if ratios else ""),
        "",
        "| case | law | steps | Δ peak force | Δ impulse | Δ duration | asperity CPU s | YADE CPU s | asperity/YADE |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['case']} | {r['law']} | {r['steps']} | {fmt(r['peak_force_rel_diff'], '.2e')} | "
                     f"{fmt(r['impulse_rel_diff'], '.2e')} | {fmt(r['contact_duration_rel_diff'], '.2e')} | "
                     f"{r['cpu_asperity_s']:.5f} | {r['cpu_yade_s']:.5f} | {fmt(r['ratio'], '.3f')} |")
    for name, code, err in failed:
        lines.append(f"| {name} | failed (exit {code}) | {err} | | | | | | |")
    (out / "crosscheck.md").write_text("\n".join(lines) + "\n")
    print(f"{len(rows)} cases -> {out / 'crosscheck.md'}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
