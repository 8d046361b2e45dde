#!/usr/bin/python3
"""How much of the peak force's change with mesh resolution the penalty layer makes.

Reads the studies that tools/report/penalty_sensitivity.sh ran (the same cases at several
values of Munjiza's penalty p = alpha E) and writes OUT/penalty_sensitivity.csv, .md and .png:
peak force and impulse per particle, model, resolution and alpha, and for each case the change
from the stiffest alpha (the limit the penalty approaches as its compliance vanishes). The
summary per alpha (medians over the fem cases) is OUT/penalty_summary.csv, written by
build/bin/penalty_summary (study/penalty_summary.cpp) and only read here.

Usage: penalty_sensitivity.py --out OUT STUDY_DIR [STUDY_DIR ...]
Runs under Debian's /usr/bin/python3 with python3-matplotlib.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

from tabular import read_csv  # noqa: E402  (beside this file)

SUMMARY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "bin",
                       "penalty_summary")


def read_study(folder):
    rows = [r for r in read_csv(os.path.join(folder, "cases.csv")) if r["status"] == "ok"]
    # The particle's Young's modulus as the study wrote it (study.json), for a summary older than
    # its penalty_alpha key: the C++ owns E, this script does not type it.
    with open(os.path.join(folder, "study.json")) as f:
        young = json.load(f)["material"]["young"]
    out = []
    for r in rows:
        case = f"{r['model']}-{r['resolution']}-{r['placement']}"
        with open(os.path.join(folder, "cases", r["particle"], case, "summary.json")) as f:
            s = json.load(f)
        alpha = s["penalty"] / young if s.get("penalty_alpha") is None else s["penalty_alpha"]
        out.append({"particle": r["particle"], "model": r["model"],
                    "resolution": int(r["resolution"]), "alpha": round(alpha, 6),
                    "peak_force": float(r["peak_force"]), "impulse": float(r["impulse"]),
                    "contact_duration": float(r["contact_duration"]),
                    "cpu_seconds": float(r["cpu_seconds"]), "dt": float(r["dt"])})
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--summary-program", default=SUMMARY, help="build/bin/penalty_summary (the C++ "
                    "that computes the summary)")
    ap.add_argument("studies", nargs="+")
    a = ap.parse_args()
    rows = [x for d in a.studies for x in read_study(d)]
    alphas = sorted({r["alpha"] for r in rows})
    stiff = alphas[-1]
    key = {(r["particle"], r["model"], r["resolution"], r["alpha"]): r for r in rows}
    for r in rows:
        ref = key.get((r["particle"], r["model"], r["resolution"], stiff))
        r["peak_vs_stiffest"] = r["peak_force"] / ref["peak_force"] - 1 if ref else math.nan
        r["impulse_vs_stiffest"] = r["impulse"] / ref["impulse"] - 1 if ref else math.nan
        fine = key.get((r["particle"], r["model"], max(x["resolution"] for x in rows), r["alpha"]))
        r["peak_vs_finest"] = r["peak_force"] / fine["peak_force"] - 1 if fine else math.nan
    rows.sort(key=lambda r: (r["particle"], r["model"], r["resolution"], r["alpha"]))
    os.makedirs(a.out, exist_ok=True)
    cols = ["particle", "model", "resolution", "alpha", "peak_force", "impulse", "contact_duration",
            "cpu_seconds", "dt", "peak_vs_stiffest", "impulse_vs_stiffest", "peak_vs_finest"]
    with open(os.path.join(a.out, "penalty_sensitivity.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({c: r[c] for c in cols})

    particles = sorted({r["particle"] for r in rows})
    models = [m for m in ("fem", "rigid") if any(r["model"] == m for r in rows)]
    fig, axes = plt.subplots(len(models), len(particles), figsize=(4.2 * len(particles), 3.6 * len(models)),
                             squeeze=False)
    for i, m in enumerate(models):
        for j, p in enumerate(particles):
            ax = axes[i][j]
            for al in alphas:
                pts = sorted((r["resolution"], r["peak_force"]) for r in rows
                             if r["particle"] == p and r["model"] == m and r["alpha"] == al)
                if pts:
                    ax.plot([x for x, _ in pts], [y / 1e3 for _, y in pts], "o-", label=f"α = {al:g}")
            ax.set_xscale("log")
            res = sorted({r["resolution"] for r in rows})
            ax.set_xticks(res, [str(x) for x in res])
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.set_title(f"{p}, {m}")
            ax.set_xlabel("surface triangles")
            ax.set_ylabel("peak force (kN)")
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "penalty_sensitivity.png"), dpi=90)

    def pct(x):
        return "" if math.isnan(x) else f"{100 * x:+.1f} %"

    lines = ["# Peak force against resolution and penalty", "",
             "The same impacts (lowest-point placement, 2 m/s onto a 50 GPa block) at Munjiza penalties "
             f"p = α·E, α in {', '.join(f'{x:g}' for x in alphas)}. 'vs α = {stiff:g}': the change from the "
             "stiffest penalty run, the limit the contact approaches as the penalty layer's compliance vanishes; "
             "'vs finest': the change from the finest mesh at the same α. "
             "Regenerate: `bash tools/report/penalty_sensitivity.sh`.", "",
             "![Peak force against resolution, one line per penalty](penalty_sensitivity.png)", "",
             "| particle | model | triangles | α | peak force (N) | vs α = %g | vs finest | impulse vs α = %g | CPU (s) |"
             % (stiff, stiff), "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['particle']} | {r['model']} | {r['resolution']} | {r['alpha']:g} | "
                     f"{r['peak_force']:.4g} | {pct(r['peak_vs_stiffest'])} | {pct(r['peak_vs_finest'])} | "
                     f"{pct(r['impulse_vs_stiffest'])} | {r['cpu_seconds']:.3g} |")
    # The summary a reader wants: median |change| of the fem peak between the coarser meshes and
    # the finest, at each alpha; and median |change| of the fem peak from the stiffest alpha. The
    # C++ computes it (study/penalty_summary.cpp: OUT/penalty_summary.csv, which the study report
    # reads too); this script only formats it.
    summary_csv = os.path.join(a.out, "penalty_summary.csv")
    if not os.access(a.summary_program, os.X_OK):
        sys.exit(f"{a.summary_program}: not built (cmake --build build --target penalty_summary); "
                 "it computes the summary")
    subprocess.run([a.summary_program, os.path.join(a.out, "penalty_sensitivity.csv"), summary_csv],
                   check=True)
    summary = {float(r["alpha"]): r for r in read_csv(summary_csv)}
    lines += ["", "| α | fem: median \\|peak − finest\\| / finest (coarser meshes) | "
              f"fem: median \\|peak − peak(α = {stiff:g})\\| / peak(α = {stiff:g}) |", "|---:|---:|---:|"]
    for al in alphas:
        s = summary[al]
        lines.append(f"| {al:g} | {100 * float(s['peak_vs_finest_median']):.1f} % | "
                     f"{100 * float(s['peak_vs_stiffest_median']):.1f} % |")
    with open(os.path.join(a.out, "penalty_sensitivity.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
