#!/usr/bin/python3
"""Failure envelope of a scene: one scene parameter swept against the time-step factor.

For every value of PARAM (a JSON path into the scene, e.g. bodies.0.velocity.2) the scene is run
through `asperity stability` at the given step factors; the script collects status, energy drift
and peak-force error into one CSV and draws a map (parameter × factor, colour = status, numbers =
peak-force error against the converged reference). Used for reports/stability/.

  stability_map.py --asperity build/bin/asperity --scene S.json --param bodies.0.velocity.2 \
      --values -0.1,-1,-10 --label "impact speed (m/s)" --factors 0.25,0.5,1,2,4 --out DIR
"""
import argparse
import copy
import csv
import json
import pathlib
import subprocess
import sys


def set_path(obj, path, value):
    keys = path.split(".")
    for k in keys[:-1]:
        obj = obj[int(k)] if isinstance(obj, list) else obj[k]
    last = keys[-1]
    if isinstance(obj, list):
        obj[int(last)] = value
    else:
        obj[last] = value


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--asperity", required=True)
    ap.add_argument("--scene", required=True, help="base scene, or a validation case (its 'scene' is used)")
    ap.add_argument("--param", required=True, help="JSON path of the swept scene value")
    ap.add_argument("--values", required=True, help="comma-separated values")
    ap.add_argument("--label", default=None, help="axis label for the parameter")
    ap.add_argument("--factors", default="0.1,0.25,0.5,0.75,1,1.5,2,3,5,10")
    ap.add_argument("--out", required=True)
    ap.add_argument("--title", default="")
    a = ap.parse_args()

    base = json.loads(pathlib.Path(a.scene).read_text())
    base = base.get("scene", base)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    values = [float(v) for v in a.values.split(",")]
    rows = []
    for k, value in enumerate(values):
        scene = copy.deepcopy(base)
        set_path(scene, a.param, value)
        scene["name"] = f"{base.get('name', 'scene')}-{k}"
        run_dir = out / "runs" / f"{k:02d}"
        run_dir.mkdir(parents=True, exist_ok=True)
        (run_dir / "scene.json").write_text(json.dumps(scene, indent=2))
        print(f"[{k + 1}/{len(values)}] {a.param} = {value:g}", file=sys.stderr, flush=True)
        proc = subprocess.run([a.asperity, "stability", str(run_dir / "scene.json"), "--out", str(run_dir),
                               "--factors", a.factors, "-q"], capture_output=True, text=True)
        if proc.returncode != 0:
            sys.exit(f"stability_map: {a.param} = {value:g}: asperity exited {proc.returncode}: {proc.stderr.strip()}")
        summary = json.loads((run_dir / "summary.json").read_text())
        with open(run_dir / "stability.csv") as f:
            for r in csv.DictReader(f):
                rows.append({"param": value, "factor": float(r["factor"]), "dt": float(r["dt"]), "status": r["status"],
                             "energy_drift": float(r["energy_drift"]), "peak_force_error": float(r["peak_force_error"]),
                             "impulse_error": float(r["impulse_error"]), "cpu_seconds": float(r["cpu_seconds"]),
                             "dt_critical_predicted": summary["dt_critical_predicted"],
                             "stable_factor_max": summary["stable_factor_max"]})
    with open(out / "map.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    factors = sorted({r["factor"] for r in rows})
    status_code = {"ok": 0, "no_contact": 1, "unstable": 2}
    grid = [[status_code[next(r["status"] for r in rows if r["param"] == v and r["factor"] == fa)] for fa in factors]
            for v in values]
    fig, ax = plt.subplots(figsize=(1.0 + 0.75 * len(factors), 1.2 + 0.5 * len(values)))
    ax.imshow(grid, cmap=ListedColormap(["#8fd18f", "#d9d9d9", "#e57373"]), vmin=0, vmax=2, aspect="auto")
    for i, v in enumerate(values):
        for j, fa in enumerate(factors):
            r = next(r for r in rows if r["param"] == v and r["factor"] == fa)
            text = "unstable" if r["status"] == "unstable" else f"{100 * r['peak_force_error']:+.1f}%"
            ax.text(j, i, text, ha="center", va="center", fontsize=7)
    ax.set_xticks(range(len(factors)), [f"{f:g}" for f in factors])
    ax.set_yticks(range(len(values)), [f"{v:g}" for v in values])
    ax.set_xlabel("time step / predicted critical step")
    ax.set_ylabel(a.label or a.param)
    ax.set_title(a.title or "stability map: status and peak-force error against the converged reference", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "map.png", dpi=120)
    print(f"stability_map: {len(rows)} runs -> {out / 'map.csv'}, {out / 'map.png'}", file=sys.stderr)


if __name__ == "__main__":
    main()
