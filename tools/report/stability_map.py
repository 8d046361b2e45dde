#!/usr/bin/python3
"""Failure envelope of a scene: one scene parameter swept against the time-step factor.

For every value of PARAM (a JSON path into the scene, e.g. bodies.0.velocity.2) the scene is run
through `asperity stability` at the given step factors; the script collects status, energy drift
and peak-force error into one CSV and draws a map (parameter × factor, colour = status, numbers =
peak-force error against the converged reference; amber where a stable run's peak force or
energy balance is off by more than --accurate). An unstable cell is re-run once through `asperity run` at the same step
to read which criterion stopped it (energy growth, non-finite state, inverted element, runaway
penetration or overlap). With --dt-panel a second panel plots, against the parameter, the
predicted critical step and the measured limit (largest stable and first unstable step tried).
Used for reports/stability/.

  stability_map.py --asperity build/bin/asperity --scene S.json --param bodies.0.velocity.2 \\
      --values -0.1,-1,-10 --label "impact speed (m/s)" --factors 0.25,0.5,1,2,4 --out DIR

The swept value written into the scene is VALUE × --scale, or --template with {v} replaced by
VALUE (a string, e.g. a mesh file name). Relative mesh paths are resolved against the base scene.
"""
import argparse
import copy
import csv
import json
import math
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


def absolute_mesh_paths(scene, folder):
    for body in scene.get("bodies", []):
        shape = body.get("shape", {})
        if shape.get("type") == "mesh" and not pathlib.Path(shape["file"]).is_absolute():
            shape["file"] = str((folder / shape["file"]).resolve())


def reason_of(message):
    """Short name of the criterion in an unstable run's message (run/run_monitor.hpp, run_fdem)."""
    for key, short in (("runaway penetration", "penetration"), ("runaway overlap", "overlap"),
                       ("inverted", "inverted"), ("non-finite", "non-finite"),
                       ("energy grew", "energy")):
        if key in message:
            return short
    return "unstable"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--asperity", required=True)
    ap.add_argument("--scene", required=True, help="base scene, or a validation case (its 'scene' is used)")
    ap.add_argument("--param", required=True, help="JSON path of the swept scene value")
    ap.add_argument("--values", required=True, help="comma-separated values")
    ap.add_argument("--scale", type=float, default=1.0, help="scene value = VALUE × scale")
    ap.add_argument("--template", default=None, help="scene value = this string with {v} replaced by VALUE")
    ap.add_argument("--also", action="append", default=[], metavar="PATH=EXPR",
                    help="another scene value set with each VALUE: a python expression in v (repeatable)")
    ap.add_argument("--label", default=None, help="axis label for the parameter")
    ap.add_argument("--factors", default="0.1,0.25,0.5,0.75,1,1.5,2,3,5,10")
    ap.add_argument("--reference-factor", default=None, help="passed to asperity stability")
    ap.add_argument("--accurate", type=float, default=0.05,
                    help="a stable run whose peak force or energy is off by more than this fraction is drawn amber")
    ap.add_argument("--dt-panel", action="store_true", help="add the predicted/measured critical step panel")
    ap.add_argument("--dt-panel-xscale", default="log", choices=["log", "linear"])
    ap.add_argument("--expect", default=None,
                    help="python expression in v (math names allowed): expected critical step up to a "
                         "constant, drawn through the predicted step at --expect-anchor")
    ap.add_argument("--expect-anchor", type=int, default=0, help="index of the value the --expect curve passes through")
    ap.add_argument("--expect-label", default="expected scaling")
    ap.add_argument("--out", required=True)
    ap.add_argument("--title", default="")
    a = ap.parse_args()

    scene_path = pathlib.Path(a.scene).resolve()
    base = json.loads(scene_path.read_text())
    base = base.get("scene", base)
    absolute_mesh_paths(base, scene_path.parent)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    values = [float(v) for v in a.values.split(",")]
    rows = []
    for k, value in enumerate(values):
        scene = copy.deepcopy(base)
        if a.template:
            set_path(scene, a.param, a.template.replace("{v}", f"{value:g}"))
            absolute_mesh_paths(scene, scene_path.parent)
        else:
            set_path(scene, a.param, value * a.scale)
        for also in a.also:
            path, expr = also.split("=", 1)
            set_path(scene, path, eval(expr, {"__builtins__": {}}, {**vars(math), "v": value}))
        scene["name"] = f"{base.get('name', 'scene')}-{k}"
        run_dir = out / "runs" / f"{k:02d}"
        run_dir.mkdir(parents=True, exist_ok=True)
        (run_dir / "scene.json").write_text(json.dumps(scene, indent=2))
        print(f"[{k + 1}/{len(values)}] {a.param} = {value:g}", file=sys.stderr, flush=True)
        cmd = [a.asperity, "stability", str(run_dir / "scene.json"), "--out", str(run_dir), "--factors", a.factors, "-q"]
        if a.reference_factor:
            cmd += ["--reference-factor", a.reference_factor]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            sys.exit(f"stability_map: {a.param} = {value:g}: asperity exited {proc.returncode}: {proc.stderr.strip()}")
        summary = json.loads((run_dir / "summary.json").read_text())
        with open(run_dir / "stability.csv") as f:
            for r in csv.DictReader(f):
                reason = ""
                if r["status"] == "unstable":
                    # Same scene at the same step (deterministic): the run's summary names the criterion.
                    one = copy.deepcopy(scene)
                    one["dt"] = float(r["dt"])
                    one["allow_unsafe_dt"] = True
                    one_dir = run_dir / f"unstable-{float(r['factor']):g}"
                    one_dir.mkdir(exist_ok=True)
                    (one_dir / "scene.json").write_text(json.dumps(one, indent=2))
                    subprocess.run([a.asperity, "run", str(one_dir / "scene.json"), "--out", str(one_dir), "-q"],
                                   capture_output=True, text=True)
                    reason = reason_of(json.loads((one_dir / "summary.json").read_text()).get("message", ""))
                rows.append({"param": value, "factor": float(r["factor"]), "dt": float(r["dt"]), "status": r["status"],
                             "reason": reason,
                             "energy_drift": float(r["energy_drift"]), "peak_force_error": float(r["peak_force_error"]),
                             "impulse_error": float(r["impulse_error"]), "cpu_seconds": float(r["cpu_seconds"]),
                             "dt_critical_predicted": summary["dt_critical_predicted"],
                             "stable_factor_max": summary["stable_factor_max"],
                             "first_unstable_factor": summary["first_unstable_factor"]})
    with open(out / "map.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    factors = sorted({r["factor"] for r in rows})
    cell = {(r["param"], r["factor"]): r for r in rows}

    def code(r):
        if r["status"] == "unstable":
            return 3
        if r["status"] == "no_contact":
            return 1
        return 2 if max(abs(r["peak_force_error"]), r["energy_drift"]) > a.accurate else 0

    grid = [[code(cell[(v, fa)]) for fa in factors] for v in values]
    width = 1.0 + 0.75 * len(factors)
    if a.dt_panel:
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(width + 4.5, 1.6 + 0.5 * len(values)),
                                      gridspec_kw={"width_ratios": [width, 4.0]})
    else:
        fig, ax = plt.subplots(figsize=(width, 1.2 + 0.5 * len(values)))
    ax.imshow(grid, cmap=ListedColormap(["#8fd18f", "#d9d9d9", "#f2c46d", "#e57373"]), vmin=0, vmax=3, aspect="auto")
    for i, v in enumerate(values):
        for j, fa in enumerate(factors):
            r = cell[(v, fa)]
            text = (r["reason"] or "unstable") if r["status"] == "unstable" else f"{100 * r['peak_force_error']:+.1f}%"
            ax.text(j, i, text, ha="center", va="center", fontsize=7)
    ax.set_xticks(range(len(factors)), [f"{f:g}" for f in factors])
    ax.set_yticks(range(len(values)), [f"{v:g}" for v in values])
    ax.set_xlabel("time step / predicted critical step")
    ax.set_ylabel(a.label or a.param)
    ax.set_title(a.title or "stability map: status and peak-force error against the converged reference", fontsize=9)

    if a.dt_panel:
        xs = [abs(v) for v in values]
        pred = [next(r for r in rows if r["param"] == v)["dt_critical_predicted"] for v in values]
        stable = [next(r for r in rows if r["param"] == v)["stable_factor_max"] for v in values]
        first = [next(r for r in rows if r["param"] == v)["first_unstable_factor"] for v in values]
        ax2.plot(xs, pred, "k-o", ms=4, label="predicted critical step")
        sx = [x for x, s in zip(xs, stable) if s]
        ax2.plot(sx, [p * s for p, s in zip(pred, stable) if s], "v", color="#2e7d32", label="largest stable step tried")
        fx = [x for x, u in zip(xs, first) if u]
        ax2.plot(fx, [p * u for p, u in zip(pred, first) if u], "^", color="#c62828", label="first unstable step tried")
        if a.expect:
            f = [eval(a.expect, {"__builtins__": {}}, {**vars(math), "v": x}) for x in xs]
            c = pred[a.expect_anchor] / f[a.expect_anchor]
            ax2.plot(xs, [c * y for y in f], "--", color="#1565c0", label=a.expect_label)
        ax2.set_xscale(a.dt_panel_xscale)
        ax2.set_yscale("log")
        ax2.set_xlabel(a.label or a.param)
        ax2.set_ylabel("time step (s)")
        ax2.legend(fontsize=7)
        ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "map.png", dpi=120)
    print(f"stability_map: {len(rows)} runs -> {out / 'map.csv'}, {out / 'map.png'}", file=sys.stderr)


if __name__ == "__main__":
    main()
