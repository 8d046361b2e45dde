#!/usr/bin/python3
"""The particle-geometry study report (issue 7): Markdown + HTML with matplotlib charts.

Called by `asperity report DIR` (app/cmd_report.cpp) with the study folder that
`asperity study` wrote (cases.csv, classification.csv, ... and cases/**/force.csv). Reads only;
writes OUT/report.md, OUT/report.html, OUT/*.png and copies of the tables (CSV).
Runs under Debian's /usr/bin/python3 with python3-matplotlib.
"""
import argparse
import csv
import glob
import html
import json
import math
import os
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
# The same data gives the same SVG (fixed element ids, no date), so regenerated charts do not
# show as changed when their content did not.
matplotlib.rcParams["svg.hashsalt"] = "asperity"
matplotlib.rcParams["svg.fonttype"] = "path"
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

import geometry_table  # noqa: E402  (beside this file)
from tabular import fmt, num, pct, read_csv  # noqa: E402  (beside this file)

TABLES = ["cases.csv", "references.csv", "classification.csv", "particle_classes.csv", "cpu_fit.csv",
          "candidates.csv", "guidelines.csv", "discretization.csv", "answer.csv", "few_hundred.csv"]
OPTIONAL_TABLES = ["unreferenced.csv"]
MODEL_COLOURS = {"fem": "tab:blue", "rigid": "tab:orange", "rigid-penalty": "tab:red", "sphere": "tab:green",
                 "sphere-local": "tab:purple"}
SPHERES = ("sphere", "sphere-local")
METRICS = [("peak_force", "peak force"), ("impulse", "impulse"), ("contact_duration", "contact duration"),
           ("first_contact_time", "first-contact time")]


# answer.csv and few_hundred.csv (study/tables/answer_table.cpp).
ANSWER_COLUMNS = ["placement", "metric", "tolerance", "statistic", "answer", "model", "resolution", "element_size_rel",
                  "error", "reference_uncertainty", "cpu_seconds_median"]
ANSWER_NUMERIC = ["tolerance", "resolution", "element_size_rel", "error", "reference_uncertainty", "cpu_seconds_median"]
# What each input must hold (as `asperity study` writes it): the columns the report reads, and
# those that must be numbers (an empty cell is allowed: a failed case has no peak force).
SCHEMA = {
    "cases.csv": (["particle", "model", "resolution", "element_size", "element_size_rel", "placement", "status",
                   "peak_force", "impulse", "contact_duration", "first_contact_time", "cpu_seconds",
                   "max_asperity_change_rel", "peak_force_err", "impulse_err", "answer", "converged",
                   "discretization_error", "convergence_change", "extrapolated_peak_force", "extrapolation_error",
                   "extrapolation_order", "order_observed", "peak_force_err_fem", "impulse_err_fem",
                   "contact_duration_err_fem", "first_contact_shift_fem"],
                  ["extrapolated_peak_force", "extrapolation_error", "extrapolation_order", "resolution", "element_size", "element_size_rel", "peak_force", "impulse", "contact_duration",
                   "first_contact_time", "cpu_seconds", "max_asperity_change_rel", "peak_force_err", "impulse_err",
                   "discretization_error", "convergence_change", "peak_force_err_fem", "impulse_err_fem",
                   "contact_duration_err_fem", "first_contact_shift_fem"]),
    "references.csv": (["particle", "placement", "resolution", "levels", "peak_force", "peak_force_order",
                        "order_observed", "geometry_from", "peak_force_discretization", "peak_force_geometry",
                        "peak_force_uncertainty", "impulse_uncertainty", "contact_duration_discretization",
                        "contact_duration_geometry", "contact_duration_uncertainty"],
                       ["resolution", "levels", "peak_force", "peak_force_order", "peak_force_discretization",
                        "peak_force_geometry", "peak_force_uncertainty", "impulse_uncertainty",
                        "contact_duration_discretization", "contact_duration_geometry",
                        "contact_duration_uncertainty"]),
    "classification.csv": (["particle", "model", "placement", "resolution", "lag_rel", "first_contact_shift_rel",
                            "duration_ratio", "skewness_diff", "class"],
                           ["resolution", "lag_rel", "first_contact_shift_rel", "duration_ratio", "skewness_diff"]),
    "particle_classes.csv": (["particle", "model", "placement", "classes", "coarsest_class"], []),
    "cpu_fit.csv": (["model", "placement", "exponent", "coefficient", "points"], ["exponent", "coefficient"]),
    "candidates.csv": (["placement", "model", "resolution", "element_size_rel", "particles", "peak_force_err_median",
                        "peak_force_err_p90", "impulse_err_median", "impulse_err_p90", "contact_duration_err_median",
                        "contact_duration_err_p90", "first_contact_time_err_median", "first_contact_time_err_p90",
                        "cpu_seconds_median"],
                       ["resolution", "element_size_rel", "particles", "peak_force_err_median", "peak_force_err_p90",
                        "impulse_err_median", "impulse_err_p90", "contact_duration_err_median",
                        "contact_duration_err_p90", "first_contact_time_err_median", "first_contact_time_err_p90",
                        "cpu_seconds_median"]),
    "discretization.csv": (["placement", "resolution", "sequences", "converged", "coarse_error_median",
                            "coarse_error_p90", "finest_level_error_median", "limit_error_median", "limit_error_p90",
                            "geometry_median", "geometry_p90", "last_change_median", "particles",
                            "sequence_cpu_median", "sequence_cpu_p90", "sequence_cpu_worst", "worst_particle",
                            "coarse_cpu_median"],
                           ["resolution", "sequences", "converged", "coarse_error_median", "coarse_error_p90",
                            "finest_level_error_median", "limit_error_median", "limit_error_p90", "geometry_median",
                            "geometry_p90", "last_change_median", "particles", "sequence_cpu_median",
                            "sequence_cpu_p90", "sequence_cpu_worst", "coarse_cpu_median"]),
    "answer.csv": (ANSWER_COLUMNS, ANSWER_NUMERIC),
    "few_hundred.csv": (ANSWER_COLUMNS, ANSWER_NUMERIC),
    "guidelines.csv": (["placement", "metric", "tolerance", "statistic", "model", "resolution", "element_size_rel",
                        "error", "reference_uncertainty", "resolvable", "cpu_seconds_median", "is_reference"],
                       ["tolerance", "resolution", "element_size_rel", "error", "reference_uncertainty",
                        "cpu_seconds_median"]),
}
SUMMARY_KEYS = {"study": str, "particles": int, "resolutions": list, "models": list, "placements": list,
                "cases": int, "done": int, "failed": int, "cpu_seconds_total": (int, float), "published": dict,
                "last_run": dict}
MAX_INPUT_BYTES = 256 << 20  # far above a 1100-case study's tables (about 1 MB)


class BadInput(Exception):
    """An input file that is not what `asperity study` writes: exit 2, one line, nothing written."""


def read_text(path):
    if not os.path.isfile(path):
        raise BadInput(f"{path}: missing or not a regular file (run asperity study first)")
    if os.path.getsize(path) > MAX_INPUT_BYTES:
        raise BadInput(f"{path}: {os.path.getsize(path)} bytes, more than a study writes")
    with open(path, "rb") as fh:
        data = fh.read()
    nul = data.find(b"\0")
    if nul >= 0:
        raise BadInput(f"{path}: binary content (a NUL byte at offset {nul})")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise BadInput(f"{path}: not UTF-8 text (byte {e.start})") from None


def check_table(path, columns, numeric, may_be_empty=False):
    text = read_text(path)
    try:
        rows = list(csv.reader(text.splitlines()))
    except csv.Error as e:
        raise BadInput(f"{path}: not CSV ({e})") from None
    if not rows:
        raise BadInput(f"{path}: empty (no header)")
    header = rows[0]
    missing = [c for c in columns if c not in header]
    if missing:
        raise BadInput(f"{path}: line 1: header lacks column {missing[0]!r}" +
                       (f" (and {len(missing) - 1} more)" if len(missing) > 1 else ""))
    if len(rows) < 2 and not may_be_empty:
        raise BadInput(f"{path}: no rows below the header (truncated?)")
    for i, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise BadInput(f"{path}: line {i}: {len(row)} fields, the header has {len(header)} (truncated?)")
        for c in numeric:
            cell = row[header.index(c)]
            if cell == "":
                continue
            try:
                float(cell)
            except ValueError:
                raise BadInput(f"{path}: line {i}: {c}: not a number (got {cell[:40]!r})") from None


def check_json(path, keys=None, nested=None):
    text = read_text(path)
    try:
        j = json.loads(text)
    except (ValueError, RecursionError) as e:
        raise BadInput(f"{path}: invalid JSON ({str(e)[:80]})") from None
    if not isinstance(j, dict):
        raise BadInput(f"{path}: must be a JSON object")
    for k, t in (keys or {}).items():
        if k not in j:
            raise BadInput(f"{path}: {k}: missing required key")
        if not isinstance(j[k], t) or isinstance(j[k], bool):
            raise BadInput(f"{path}: {k}: wrong type (got {json.dumps(j[k])[:40]})")
    for k, sub in (nested or {}).items():
        missing = [s for s in sub if s not in j[k]]
        if missing:
            raise BadInput(f"{path}: {k}.{missing[0]}: missing required key")


def check_inputs(study):
    """Every input checked before anything is written (exit 2 and one line otherwise)."""
    if not os.path.isdir(study):
        raise BadInput(f"{study}: not a folder")
    summary = os.path.join(study, "study_summary.json")
    check_json(summary, SUMMARY_KEYS,
               {"published": ["simulations", "cpu_seconds_100", "cpu_seconds_1000", "cpu_growth_100_1000"],
                "last_run": ["wall_seconds", "cpu_seconds", "ran", "kept"]})
    with open(summary) as f:
        models = json.load(f)["models"]
    # Every table but cases.csv is measured against the fem reference or fitted over resolutions:
    # a study of sphere models alone has none of them (headers only, as study/tables/ writes them).
    spheres_only = all(m in SPHERES for m in models)
    for t in TABLES:
        columns, numeric = SCHEMA[t]
        # A study with no surface of at most 500 triangles has no few-hundred answer.
        check_table(os.path.join(study, t), columns, numeric,
                    may_be_empty=t == "few_hundred.csv" or (spheres_only and t != "cases.csv"))
    check_json(os.path.join(study, "guidelines.json"))


class Doc:
    """Markdown and HTML written side by side from the same calls."""

    def __init__(self):
        self.md, self.html = [], []

    def h(self, level, text):
        self.md.append("#" * level + " " + text + "\n")
        self.html.append(f"<h{level}>{html.escape(text)}</h{level}>")

    def p(self, text):
        self.md.append(text + "\n")
        self.html.append(f"<p>{html.escape(text)}</p>")

    def table(self, header, rows):
        if not rows:
            self.p("(no rows)")
            return
        self.md.append("| " + " | ".join(header) + " |")
        self.md.append("|" + "---|" * len(header))
        for r in rows:
            self.md.append("| " + " | ".join(str(c) for c in r) + " |")
        self.md.append("")
        out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr></thead><tbody>"]
        for r in rows:
            out.append("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>")
        out.append("</tbody></table>")
        self.html.append("".join(out))

    def image(self, name, alt):
        self.md.append(f"![{alt}]({name})\n")
        self.html.append(f'<figure><img src="{html.escape(name)}" alt="{html.escape(alt)}">'
                         f"<figcaption>{html.escape(alt)}</figcaption></figure>")


def save_chart(fig, out, name, dpi):
    """The chart as PNG (the report's) and as SVG beside it (vector, for papers)."""
    fig.savefig(os.path.join(out, name), dpi=dpi)
    fig.savefig(os.path.join(out, name[:-4] + ".svg"), metadata={"Date": None})
    plt.close(fig)


def write_markdown_table(csv_path, md_path):
    """A CSV table also as a Markdown table (every column, the cells as written)."""
    rows = read_csv(csv_path)
    if not rows:
        return
    header = list(rows[0].keys())
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in rows:
        lines.append("| " + " | ".join((r[h] or "").replace("|", "\\|") for h in header) + " |")
    with open(md_path, "w") as fh:
        fh.write("\n".join(lines) + "\n")


def case_folder(c):
    """The case's folder name (study_run.hpp): MODEL-N-PLACEMENT, fem-N-hSIZE-PLACEMENT, sphere-PLACEMENT."""
    if c["model"] in SPHERES:
        return f"{c['model']}-{c['placement']}"
    h = f"h{num(c['element_size_rel']):g}-" if c.get("element_size_rel") else ""
    return f"{c['model']}-{c['resolution']}-{h}{c['placement']}"


def read_force(path):
    t, f = [], []
    with open(path) as fh:
        next(fh)
        for line in fh:
            parts = line.split(",")
            if len(parts) >= 5:
                t.append(float(parts[0]))
                f.append(float(parts[4]))
    return t, f


def reference_case(cases, particle, placement):
    """The converged fem reference of a particle and placement: the answer of the fem sequence at the finest
    resolution (cases.csv `answer`), or None."""
    fem = [c for c in cases if c["particle"] == particle and c["placement"] == placement and c["model"] == "fem"
           and c["answer"] == "true"]
    return max(fem, key=lambda c: num(c["resolution"])) if fem else None


# Per-particle charts (force curves, impact pictures) of a study of more particles than this show
# a selection (chart_particles): one chart per particle of a 50-particle study would be 50 charts
# nobody compares, and about 7 MB in reports/.
CHART_PARTICLES = 8


def chart_particles(cases, k=CHART_PARTICLES):
    """The particles whose force curves and impact pictures the report shows, in the study's order,
    and the rule that chose them. All of them when there are k or fewer; else k at evenly spaced ranks
    (smallest, median and largest included) of |discretization error| of the coarse fem at the
    reference's resolution (the finest with a converged answer), the spread a reader wants to see:
    the coarse mesh's best, typical and worst particle."""
    particles = list(dict.fromkeys(c["particle"] for c in cases))
    if len(particles) <= k:
        return particles, ""
    key = {}
    for p in particles:
        refs = [c for c in cases if c["particle"] == p and c["model"] == "fem" and c["answer"] == "true"]
        if not refs:
            continue
        ref = max(refs, key=lambda c: (num(c["resolution"]), c["placement"]))
        coarse = [c for c in cases if c["particle"] == p and c["model"] == "fem" and not c["element_size"]
                  and c["resolution"] == ref["resolution"] and c["placement"] == ref["placement"]
                  and c["discretization_error"] != ""]
        if coarse:
            key[p] = abs(num(coarse[0]["discretization_error"]))
    ranked = sorted(key, key=lambda p: (key[p], p))
    if len(ranked) < 2:
        return particles[:k], f"the first {k} of the {len(particles)} particles"
    picked = {ranked[round(i * (len(ranked) - 1) / (k - 1))] for i in range(k)}
    rule = (f"{len(picked)} of the {len(particles)} particles, at evenly spaced ranks (smallest, median and largest "
            "included) of the coarse fem's |discretization error| in peak force at the reference's resolution; every "
            "particle's curves are in the study folder's cases/PARTICLE/*/force.csv")
    return [p for p in particles if p in picked], rule


def force_overlays(study, out, cases, doc):
    particles, rule = chart_particles(cases)
    if rule:
        doc.p(f"Force-time curves of {rule}.")
    placements = sorted({c["placement"] for c in cases})
    models = [m for m in ("fem", "rigid", "rigid-penalty") if any(c["model"] == m for c in cases)]
    if not models:
        models = ["sphere"]
    names = []
    for p in particles:
        fig, axes = plt.subplots(len(placements), len(models), figsize=(4.2 * len(models), 2.6 * len(placements)),
                                 squeeze=False, sharex=True)
        for i, pl in enumerate(placements):
            for j, m in enumerate(models):
                ax = axes[i][j]
                rows = [c for c in cases if c["particle"] == p and c["placement"] == pl and c["model"] == m
                        and c["status"] == "ok" and not c["element_size"]]
                rows.sort(key=lambda c: num(c["resolution"]))
                cmap = plt.get_cmap("viridis")
                # the converged fem reference (the answer at the finest resolution), thick grey
                ref = reference_case(cases, p, pl)
                if ref:
                    t, f = read_force(os.path.join(study, "cases", p, case_folder(ref), "force.csv"))
                    ax.plot([1e3 * x for x in t], f, color="0.6", lw=2.4, zorder=0, label="fem reference")
                for k, c in enumerate(rows):
                    t, f = read_force(os.path.join(study, "cases", p, case_folder(c), "force.csv"))
                    ax.plot([1e3 * x for x in t], f, color=cmap(k / max(1, len(rows) - 1)), lw=1.0,
                            label=f"{c['resolution']}")
                for sm, style in (("sphere", "k--"), ("sphere-local", "k:")):
                    if any(c["particle"] == p and c["placement"] == pl and c["model"] == sm and c["status"] == "ok"
                           for c in cases):
                        t, f = read_force(os.path.join(study, "cases", p, f"{sm}-{pl}", "force.csv"))
                        ax.plot([1e3 * x for x in t], f, style, lw=0.8, label=sm)
                ax.set_title(f"{m}, placed by {pl}", fontsize=9)
                ax.tick_params(labelsize=7)
                if i == len(placements) - 1:
                    ax.set_xlabel("t (ms)", fontsize=8)
                if j == 0:
                    ax.set_ylabel("|F| (N)", fontsize=8)
                ax.legend(fontsize=6, title="triangles", title_fontsize=6)
        fig.suptitle(f"{p}: force against time", fontsize=10)
        fig.tight_layout()
        name = f"force_{p}.png"
        save_chart(fig, out, name, 72)
        names.append((p, name))
    for p, name in names:
        doc.image(name, f"Force-time curves of {p} at every resolution")
        # Its impact at peak force, when `impact_pictures.py --study` rendered it from the frames.
        picture = os.path.join(study, "pictures", f"impact_{p}.png")
        if os.path.exists(picture):
            shutil.copyfile(picture, os.path.join(out, f"impact_{p}.png"))
            doc.image(f"impact_{p}.png", f"{p} at peak force, fem and rigid: surface von Mises stress and contact "
                      "pressure, rendered from the ParaView frames of a rerun of the study's case")


def onset(r):
    """The first-contact shift over the reference duration (classification.csv; an older table has only the lag)."""
    return num(r.get("first_contact_shift_rel", r["lag_rel"]))


CLASS_MEASURE = {"overlapping": lambda r: -max(abs(onset(r)), abs(num(r["duration_ratio"]) - 1)),
                 "shifted": lambda r: abs(onset(r)), "tail": lambda r: num(r["duration_ratio"]),
                 "short": lambda r: -num(r["duration_ratio"]), "asymmetric": lambda r: abs(num(r["skewness_diff"]))}


def class_examples(study, out, cases, classification, doc):
    """One overlay per response class met: the example curve against the converged fem reference's (its finest
    refined level). The example is a curve of that class alone when there is one, else one whose classes include it;
    among those, the clearest: the largest first-contact shift (shifted), largest or smallest duration ratio (tail,
    short), skewness difference (asymmetric), or the smallest of shift and duration change (overlapping)."""
    picks = []
    for label, clearest in CLASS_MEASURE.items():
        rows = [r for r in classification if label in r["class"].split("+")]
        if not rows:
            continue
        pure = [r for r in rows if r["class"] == label]
        picks.append((label, max(pure or rows, key=lambda r: clearest(r) if not math.isnan(clearest(r)) else -1e300)))
    if not picks:
        return
    fig, axes = plt.subplots(1, len(picks), figsize=(3.6 * len(picks), 2.8), squeeze=False)
    for ax, (label, r) in zip(axes[0], picks):
        ref = reference_case(cases, r["particle"], r["placement"])
        if ref:
            t, f = read_force(os.path.join(study, "cases", r["particle"], case_folder(ref), "force.csv"))
            ax.plot([1e3 * x for x in t], f, color="0.6", lw=2.4, label="fem reference")
        c = {"model": r["model"], "resolution": r["resolution"], "placement": r["placement"], "element_size_rel": ""}
        t, f = read_force(os.path.join(study, "cases", r["particle"], case_folder(c), "force.csv"))
        ax.plot([1e3 * x for x in t], f, color=MODEL_COLOURS.get(r["model"], "k"), lw=1.0,
                label=f"{r['model']} {r['resolution']}")
        ax.set_title(f"{label}: {r['particle']}, {r['model']} {r['resolution']}\n(class {r['class']}; onset "
                     f"{100 * onset(r):+.1f} %, duration x{num(r['duration_ratio']):.2f})", fontsize=7)
        ax.set_xlabel("t (ms)", fontsize=8)
        ax.set_ylabel("|F| (N)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
    fig.tight_layout()
    save_chart(fig, out, "class_examples.png", 80)
    doc.image("class_examples.png", f"One example of each response class met, against {REFERENCE['name']} "
              "(its finest refined level): " + ", ".join(f"{label}: {r['particle']} {r['model']} {r['resolution']}"
                                                          for label, r in picks))
    missing = [label for label in CLASS_MEASURE if label not in {p[0] for p in picks}]
    if missing:
        doc.p("No curve of the class " + ", ".join(missing) + " in this study.")


def cpu_chart(out, cases, fits, doc):
    fig, ax = plt.subplots(figsize=(6, 4))
    for m in ("fem", "rigid"):
        for pl, marker in (("centroid", "o"), ("lowest", "s")):
            rows = [c for c in cases if c["model"] == m and c["placement"] == pl and c["status"] == "ok"]
            if not rows:
                continue
            ax.scatter([num(c["resolution"]) for c in rows], [num(c["cpu_seconds"]) for c in rows], s=10, alpha=0.35,
                       color=MODEL_COLOURS[m], marker=marker)
            fit = [f for f in fits if f["model"] == m and f["placement"] == pl]
            if fit:
                p, c0 = num(fit[0]["exponent"]), num(fit[0]["coefficient"])
                xs = sorted({num(c["resolution"]) for c in rows})
                ax.plot(xs, [c0 * x ** p for x in xs], color=MODEL_COLOURS[m],
                        ls="-" if pl == "centroid" else ":", label=f"{m}, {pl}: CPU ~ N^{p:.2f}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("surface triangles N")
    ax.set_ylabel("CPU time per case (s)")
    ax.set_title("CPU time against resolution (median fit)")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_chart(fig, out, "cpu_vs_resolution.png", 80)
    doc.image("cpu_vs_resolution.png", "CPU time against resolution, log-log, with the fitted exponent")


def pareto(points):
    """Indices of the points no other point beats in both cost and error (lower is better)."""
    front = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for j, (c2, e2) in enumerate(points) if j != i):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def accuracy_cost_chart(out, candidates, uncertainty, doc):
    """Median |error| against the converged fem reference (dots) and its 90th percentile (triangles) against the
    median CPU, per placement and metric; the reference's own uncertainty (median over the particles) as a grey band
    from the axis up: an error inside it cannot be told from the reference's. The reference itself (error 0) is not
    drawn: a log axis has no place for it, and no floor is invented for it."""
    placements = sorted({c["placement"] for c in candidates})
    if not placements:
        doc.p("No chart: no model is measured against a fem reference (a study of sphere models alone).")
        return
    fig, axes = plt.subplots(len(placements), 2, figsize=(10, 3.8 * len(placements)), squeeze=False)
    for i, pl in enumerate(placements):
        rows = [c for c in candidates if c["placement"] == pl]
        for j, (metric, title) in enumerate((("peak_force", "peak force"), ("impulse", "impulse"))):
            ax = axes[i][j]
            pts = []
            for c in rows:
                cost = num(c["cpu_seconds_median"])
                err, p90 = num(c[f"{metric}_err_median"]), num(c[f"{metric}_err_p90"])
                if not err > 0:
                    continue
                pts.append((cost, err))
                colour = MODEL_COLOURS.get(c["model"], "k")
                marker = "o" if not c["element_size_rel"] else "D"
                ax.scatter([cost], [err], color=colour, s=25, zorder=3, marker=marker)
                if p90 > 0:
                    ax.scatter([cost], [p90], color=colour, s=12, marker="^", alpha=0.5)
                label = c["resolution"] or c["model"]
                if c["element_size_rel"]:
                    label += f" h{num(c['element_size_rel']):g}"
                ax.annotate(label, (cost, err), fontsize=6, xytext=(3, 3), textcoords="offset points")
            if pts:
                front = pareto(pts)
                ax.plot([pts[k][0] for k in front], [pts[k][1] for k in front], "k-", lw=0.8,
                        label="Pareto front (median)")
            u = num((uncertainty.get((pl, metric)) or {}).get("median"))
            if u > 0:
                lo = min([e for _, e in pts] + [u]) / 3
                ax.axhspan(lo, u, color="0.5", alpha=0.18, lw=0, label=f"reference uncertainty (median {100 * u:.2g} %)")
            for m, col in MODEL_COLOURS.items():
                ax.scatter([], [], color=col, label=m)
            ax.scatter([], [], color="grey", marker="D", s=20, label="fem, refined element size")
            ax.scatter([], [], color="grey", marker="^", s=12, label="90th percentile")
            for tol in (0.02, 0.05, 0.10):
                ax.axhline(tol, color="grey", lw=0.5, ls=":")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("median CPU time per case (s)")
            ax.set_ylabel(f"|error| in {title} vs converged fem")
            ax.set_title(f"{title}, placed by {pl}", fontsize=9)
            ax.legend(fontsize=6)
            ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_chart(fig, out, "accuracy_vs_cost.png", 80)
    doc.image("accuracy_vs_cost.png", "Accuracy against cost: error in peak force and impulse against "
              f"{REFERENCE['name']}, against CPU time, every model, resolution and element size; the grey band is the "
              "reference's own uncertainty; the reference itself (error 0) is not drawn")


REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def shown(path):
    """A path as a report shows it: relative to the repository when inside it, so that a committed
    report does not carry the machine's folders."""
    full = os.path.abspath(path)
    return os.path.relpath(full, REPO) if full.startswith(REPO + os.sep) else path


def stability_files(stab_dir):
    """stability.csv files (asperity stability --out) or map.csv files (stability maps) under stab_dir."""
    found = []
    for name in ("stability.csv", "map.csv"):
        found += glob.glob(os.path.join(stab_dir, name)) + glob.glob(os.path.join(stab_dir, "*", name))
    return sorted(set(found))


def stability_section(out, stab_dir, doc):
    files = stability_files(stab_dir)
    if not files:
        return
    doc.h(2, "Stability map and accuracy against step")
    doc.p(f"From {shown(stab_dir)}: each time step tried, as a multiple of the predicted critical step (asperity "
          "stability); green stable, red flagged unstable.")
    colours = {"ok": "tab:green", "no_contact": "tab:grey", "unstable": "tab:red"}
    fig, axes = plt.subplots(len(files), 2, figsize=(10, 3.2 * len(files)), squeeze=False)
    summary = []
    for i, path in enumerate(files):
        rows = read_csv(path)
        label = os.path.relpath(path, stab_dir)
        ax = axes[i][0]
        for r in rows:
            ax.scatter([num(r["factor"])], [max(num(r["energy_drift"]), 1e-16)], color=colours.get(r["status"], "k"),
                       s=14)
        ax.axvline(1.0, color="k", lw=0.5, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("dt / predicted critical step", fontsize=8)
        ax.set_ylabel("energy drift", fontsize=8)
        ax.set_title(f"stability map: {label}", fontsize=9)
        ax = axes[i][1]
        ok = [r for r in rows if r["status"] == "ok" and "peak_force_error" in r and not math.isnan(num(r["peak_force_error"]))]
        if ok:
            ax.scatter([num(r["factor"]) for r in ok], [max(abs(num(r["peak_force_error"])), 1e-16) for r in ok], s=14,
                       label="peak force")
            if "impulse_error" in ok[0]:
                ax.scatter([num(r["factor"]) for r in ok], [max(abs(num(r["impulse_error"])), 1e-16) for r in ok],
                           s=14, marker="^", label="impulse")
            ax.set_yscale("log")
            ax.legend(fontsize=7)
        ax.set_xscale("log")
        ax.set_xlabel("dt / predicted critical step", fontsize=8)
        ax.set_ylabel("|relative error|", fontsize=8)
        ax.set_title(f"accuracy against step: {label}", fontsize=9)
        stable = [num(r["factor"]) for r in rows if r["status"] == "ok"]
        unstable = [num(r["factor"]) for r in rows if r["status"] == "unstable"]
        summary.append([label, len(rows), fmt(max(stable)) if stable else "-", fmt(min(unstable)) if unstable else "-"])
        shutil.copyfile(path, os.path.join(out, "stability_" + label.replace(os.sep, "_")))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "stability.png"), dpi=72)
    fig.savefig(os.path.join(out, "stability.svg"), metadata={"Date": None})
    plt.close(fig)
    doc.image("stability.png", "Stability map and accuracy against time step")
    doc.table(["sweep", "steps tried", "largest stable factor", "smallest unstable factor"], summary)


def yade_section(out, yade_dir, doc):
    table = os.path.join(yade_dir, "crosscheck.csv")
    files = sorted(glob.glob(os.path.join(yade_dir, "**", "comparison.json"), recursive=True))
    if not os.path.exists(table) and not files:
        return
    doc.h(2, "YADE comparison")
    if os.path.exists(table):
        rows = read_csv(table)
        shutil.copyfile(table, os.path.join(out, "yade_crosscheck.csv"))
        doc.p(f"From {shown(table)} (asperity crosscheck, {len(rows)} cases): relative differences (asperity - YADE) / YADE, "
              "largest magnitude per contact law, and the CPU ratio asperity/YADE. Every case: yade_crosscheck.csv.")
        laws = sorted({r["law"] for r in rows})
        out_rows = []
        for law in laws:
            rs = [r for r in rows if r["law"] == law]
            def worst(k):
                return fmt(max(abs(num(r[k])) for r in rs), 3)
            ratios = sorted(num(r["ratio"]) for r in rs)
            out_rows.append([law, len(rs), worst("peak_force_rel_diff"), worst("impulse_rel_diff"),
                             worst("contact_duration_rel_diff"), fmt(ratios[len(ratios) // 2], 3)])
        doc.table(["law", "cases", "max abs d peak", "max abs d impulse", "max abs d duration", "median CPU ratio"], out_rows)
        return
    doc.p(f"From {yade_dir} (asperity crosscheck): relative difference (asperity - YADE) / YADE.")
    rows = []
    for f in files:
        with open(f) as fh:
            j = json.load(fh)
        cells = [j.get("scene") or os.path.basename(os.path.dirname(f))]
        for key in ("peak_force", "impulse", "contact_duration"):
            e = j.get(key) if isinstance(j.get(key), dict) else {}
            d = e.get("rel_diff", e.get("relative_difference"))
            cells += [fmt(e.get("asperity")), fmt(e.get("yade")), pct(d.get("yade") if isinstance(d, dict) else d)]
        rows.append(cells)
    header = ["scene"] + [f"{k} {w}" for k in ("peak_force", "impulse", "contact_duration")
                          for w in ("asperity", "YADE", "diff")]
    doc.table(header, rows)
    with open(os.path.join(out, "yade_comparison.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


CSS = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}"
       "table{border-collapse:collapse;font-size:12px;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px}"
       "th{background:#eee}img{max-width:100%}figure{margin:1em 0}figcaption{font-size:12px;color:#555}")


def penalty_section(out, pen_dir, doc):
    """The penalty-sensitivity runs (tools/report/penalty_sensitivity.sh), when present."""
    table = os.path.join(pen_dir, "penalty_sensitivity.csv")
    if not os.path.exists(table):
        return
    summary_csv = os.path.join(pen_dir, "penalty_summary.csv")
    if not os.path.isfile(summary_csv):
        raise BadInput(f"{summary_csv}: missing beside {table} (tools/report/penalty_sensitivity.sh "
                       "writes both)")
    rows = read_csv(summary_csv)
    doc.h(2, "Peak force, resolution and the penalty")
    doc.p("Munjiza's potential contact adds a penalty layer whose compliance grows with the element size: with "
          "p = alpha E, a coarse mesh meets the block through a softer contact than a fine one. The same impacts at "
          "alpha = 10, 100 and 1000 (reports/study/penalty/, made by tools/report/penalty_sensitivity.sh) separate that from "
          "the geometry: median over particles and coarser meshes of |peak - peak at the finest mesh| / peak at the "
          "finest mesh, same alpha, and median |peak - peak at the stiffest alpha| / peak at the stiffest alpha, fem.")
    # The medians and the mean per alpha as the C++ computed them (study/penalty_summary.cpp).
    finest = max(int(num(r["finest_resolution"])) for r in rows)
    summary = [[fmt(r["alpha"]), pct(r["peak_vs_finest_median"]), pct(r["peak_vs_stiffest_median"]),
                pct(r["impulse_vs_stiffest_median"]), fmt(r["cpu_seconds_finest_mean"], 3)] for r in rows]
    doc.table(["alpha", "peak vs finest mesh", "peak vs stiffest alpha", "impulse vs stiffest alpha",
               f"CPU at {finest} (s, mean)"], summary)
    png = os.path.join(pen_dir, "penalty_sensitivity.png")
    if os.path.exists(png):
        if os.path.abspath(png) != os.path.abspath(os.path.join(out, "penalty_sensitivity.png")):
            shutil.copyfile(png, os.path.join(out, "penalty_sensitivity.png"))
        doc.image("penalty_sensitivity.png", "Peak force against resolution, one line per penalty alpha")


def geometry_section(doc, study, out):
    """The geometry term (geometry_table.py: OUT/geometry.csv, geometry_answer.csv, geometry.md) when
    the study refines two or more resolutions (data/study/geometry.json): the converged answer's
    sequence in N and whether the finest-but-one N is enough. First, because it is such a study's
    question; a study refining one resolution (the default) has no such section."""
    t = geometry_table.write(study, out)
    if t is None:
        return
    doc.h(2, "The geometry term")
    doc.p("Each resolution N refined at its strike point gives a converged answer (the limit in element size), "
          "which isolates the particle's shape from the elements; along N these answers say whether the finest "
          "geometry is fine enough (docs/study.md, 'The geometry term'). Tables: geometry.csv, geometry_answer.csv, "
          "geometry.md.")
    for caption, header, rows in t:
        doc.p(caption)
        doc.table(header, rows)


def candidate_name(r):
    """model, surface triangles and element size at the strike point over the equivalent radius (refined)"""
    what = r["model"] + (f" {r['resolution']}" if r["resolution"] else "")
    if r["element_size_rel"]:
        what += f" h={num(r['element_size_rel']):g}R"
    return what


def few_hundred_sentence(rows, names):
    """One sentence per metric from few_hundred.csv: the best studied surface of at most 500 triangles, at the
    median and at p90, and the smallest tolerance of the answer it meets."""
    parts = []
    for metric, title in names:
        by = {r["statistic"]: r for r in rows if r["metric"] == metric}
        if not by:
            continue

        def said(r, share):
            within = (f"within {pct(r['tolerance'], 0)}" if r["answer"] == "studied"
                      else "not within 10 %")
            return (f"{within} for {share} ({candidate_name(r)}: {pct(r['error'], 1)} ± "
                    f"{pct(r['reference_uncertainty'], 1)})")

        clauses = [said(by[st], share) for st, share in (("median", "half the particles"), ("p90", "90 %"))
                   if st in by]
        parts.append(f"{title}: " + ", ".join(clauses))
    return "; ".join(parts)


def answer_section(doc, study, published):
    """The report's first section (answer.csv and few_hundred.csv, which asperity study computes): to get X % on a
    metric, what to use, with its error and the reference's uncertainty, beside the published study's CPU."""
    answer = read_csv(os.path.join(study, "answer.csv"))
    placements = sorted({r["placement"] for r in answer})
    if not placements:
        doc.p("No answer: the study has no fem reference.")
        return
    pl = "lowest" if "lowest" in placements else placements[0]
    names = [(m, t) for m, t in METRICS + [("peak_force+impulse", "peak force and impulse")]
             if any(r["metric"] == m and r["placement"] == pl for r in answer)]
    doc.h(2, "The answer")
    few = [r for r in read_csv(os.path.join(study, "few_hundred.csv")) if r["placement"] == pl]
    if few:
        doc.p("Is a few hundred triangles (at most 500) enough? " + few_hundred_sentence(few, names) + ".")
    with open(os.path.join(study, "study.json")) as fh:
        definition = json.load(fh)
    k = (definition.get("orientations") or {}).get("random")
    over = (f" Each particle is studied at {k} random orientations, each against its own reference: 'particles' below "
            f"are the {len(definition['particles'])} particle-orientations ({len(definition['particles']) // k} "
            f"particles x {k}), so each error is a distribution over particles and orientations." if k else "")
    references = read_csv(os.path.join(study, "references.csv"))
    missing = unreferenced_note(study, definition)
    if missing:
        doc.p(missing)
    if geometry_unmeasured(references):
        doc.p(GEOMETRY_UNMEASURED)
    doc.p(f"To get within X % of {REFERENCE['name']}, placed by {pl}, use the cheapest model below; "
          "'median' holds for half the particles, 'p90' for 90 % of them. Each entry: model, surface triangles, "
          "element size at the strike point over the equivalent radius when refined, its error "
          "± the reference's uncertainty (same statistic), its median CPU per case; 'none of the studied' where no "
          "studied model, resolution or element size meets the tolerance, with the closest. Rows that are 0 by "
          "construction are left out (the first-contact time under lowest placement, where every model starts "
          "with its lowest point at the same gap). The published study (Zhang & Zsaki 2019, "
          f"fem): {published['cpu_seconds_100']} s at 100 and {published['cpu_seconds_1000']} s at 1000 triangles "
          "per simulation." + over)

    def entry(r):
        if not r:
            return "-"
        said = (f"{candidate_name(r)}: {pct(r['error'], 1)} ± {pct(r['reference_uncertainty'], 1)}, "
                f"{fmt(r['cpu_seconds_median'], 3)} s")
        return said if r["answer"] == "studied" else f"none of the studied (closest: {said})"

    rows = []
    for metric, title in names:
        for tol in ("0.02", "0.05", "0.1"):
            pick = {st: next((r for r in answer if r["placement"] == pl and r["metric"] == metric
                              and num(r["tolerance"]) == num(tol) and r["statistic"] == st), None)
                    for st in ("median", "p90")}
            rows.append([f"{pct(tol, 0)} on {title}", entry(pick["median"]), entry(pick["p90"])])
    doc.table(["to get", "median", "p90"], rows)


def axes_section(doc, study, cases):
    """Geometry against discretization per resolution (discretization.csv, which asperity study computes): the
    coarse fem case against the converged answer at the same resolution (discretization), and the converged answer
    against the reference (geometry)."""
    fem = [c for c in cases if c["model"] == "fem" and c["status"] == "ok"]
    if not any(c["element_size"] for c in fem):
        return
    doc.h(2, "Geometry and discretization")
    doc.p("For each resolution N and placement, over the particles that were refined: the discretization error "
          "(the coarse fem peak force, the surface triangles as the elements' faces as in the published study, "
          "against the limit of the refinement sequence at the same N), the finest refined level against that "
          "limit, the limit's estimated error, the geometry effect (the limit at N against the reference: the limit "
          "at the finest N), and how many sequences met the 1 % convergence criterion (the last refinement moved "
          "the peak by less). Medians of |value|; the published study's differences mixed the two. The limit is a "
          "Richardson extrapolation of the refined levels (docs/study.md, 'Guidelines'): at the order observed "
          "from three refined levels when they change monotonically at an order in 0.5-5 (error: 1.25 times its "
          "last correction, Roache's safety factor), else from the two finest at orders 1.2 and 2.7, the range "
          "the Hertz gate measured on the same graded refinement (reports/fem/hertz_convergence.md): the limit "
          "their mean, its error half their spread.")

    def spread(r, key):
        """median (p90) of discretization.csv's KEY_median and KEY_p90, as percentages"""
        if not r[key + "_median"] and not r[key + "_p90"]:
            return "-"
        return f"{pct(r[key + '_median'])} ({pct(r[key + '_p90'])})"

    rows = []
    cost = []
    for r in read_csv(os.path.join(study, "discretization.csv")):
        pl, n = r["placement"], r["resolution"]
        answers = [c for c in fem if c["placement"] == pl and c["resolution"] == n and c["answer"] == "true"
                   and c["element_size"]]
        orders = sorted({("observed " if a["order_observed"] == "true" else "assumed ") +
                         f"{num(a['extrapolation_order']):.3g}" for a in answers if a["extrapolation_order"]})
        rows.append([pl, n, r["sequences"], r["converged"], spread(r, "coarse_error"),
                     pct(r["finest_level_error_median"]), spread(r, "limit_error"), ", ".join(orders) or "-",
                     spread(r, "geometry"), pct(r["last_change_median"])])
        cost.append([pl, n, r["particles"], fmt(r["sequence_cpu_median"], 3), fmt(r["sequence_cpu_p90"], 3),
                     f"{fmt(r['sequence_cpu_worst'], 3)} ({r['worst_particle']})", fmt(r["coarse_cpu_median"], 3)])
    doc.table(["placement", "N", "sequences", "converged (< 1 %)",
               "discretization error (coarse vs limit), median (p90)", "finest level vs limit",
               "limit's estimated error, median (p90)", "order (peak)",
               "geometry effect (limit vs reference), median (p90)", "last refinement change"], rows)
    doc.p("What a converged answer costs: the CPU of the whole sequence at N (the coarse case and every refined "
          "level, the cases' own CPU, meshing apart), per particle; beside it the coarse case alone. The published "
          "study's fem: 4 s at 100 and 572 s at 1000 triangles per simulation (Zhang & Zsaki 2019).")
    doc.table(["placement", "N", "particles", "sequence CPU median (s)", "p90 (s)", "worst (s)",
               "coarse case CPU median (s)"], cost)
    per = [[a["particle"], a["placement"], a["resolution"], fmt(a["peak_force"]), fmt(a["extrapolated_peak_force"]),
            pct(a["extrapolation_error"]), ("observed " if a["order_observed"] == "true" else "assumed ")
            + fmt(a["extrapolation_order"], 3), pct(a["convergence_change"]), a["converged"]]
           for a in fem if a["answer"] == "true" and a["extrapolated_peak_force"]]
    doc.p("Per sequence (the peak force, N):")
    doc.table(["particle", "placement", "N", "finest level", "limit", "limit's error", "order", "last change",
               "converged (< 1 %)"], per)


def source_reference_section(doc, references):
    """The source reference ("reference": "source" in study.json; references.csv's source columns): the particle
    itself, its source surface refined at the strike point in three levels (a fourth where their peak force shows no
    steady order), and the terms of its uncertainty."""
    doc.p("Per particle: the reference is the particle itself (\"reference\": \"source\"): its source surface kept "
          "around the strike point, refined there in three levels (a fourth at half the finest size where the three's "
          "peak force shows no steady order: the limit is then of levels 2-4), and their Richardson limit, with the "
          "order and whether it was observed; its uncertainty adds in quadrature the extrapolation's estimated error "
          "(discretization) and, where the doubled patch ran, the patch check's change ('-' where not run). An "
          "assumed order is followed by the levels' own order where they fall monotonically outside the range the "
          "extrapolation trusts (0.5-5): those levels are not asymptotic. Every error of this report is against it: "
          "there is no geometry term.")
    rows = []
    for r in references:
        order, changes = r["peak_force_source_order"], r.get("peak_force_changes_order", "")
        said = "-"
        if order:
            observed = r["peak_force_source_order_observed"] == "true"
            said = ("observed " if observed else "assumed ") + fmt(order, 3)
            if not observed and changes:  # the levels' own order, outside the trusted range
                said += f" (levels: {fmt(changes, 2)})"
        # Which levels the limit is from (references.csv before the fourth level: the three).
        levels = r.get("source_limit_levels") or "L1-L3"
        rows.append([r["particle"], r["placement"], levels, fmt(r["peak_force"]), said,
                     pct(r["peak_force_discretization"]),
                     pct(r["peak_force_patch_change"]) if r["peak_force_patch_change"] else "-",
                     pct(r["peak_force_uncertainty"]), pct(r["contact_duration_uncertainty"]),
                     pct(r["impulse_uncertainty"])])
    doc.table(["particle", "placement", "levels", "peak force (N)", "order (peak)", "discretization", "patch check",
               "uncertainty (peak)", "uncertainty (duration)", "uncertainty (impulse)"], rows)


def unreferenced_note(study, definition):
    """unreferenced_paragraph of the study folder's unreferenced.csv (asperity study) over its study.json's
    particles x placements; None where every particle has its reference or the folder predates the table."""
    path = os.path.join(study, "unreferenced.csv")
    rows = read_csv(path) if os.path.exists(path) else []
    return unreferenced_paragraph(rows, len(definition["particles"]) * len(definition["placements"]))


def unreferenced_paragraph(rows, total):
    """One paragraph naming each particle (and placement) the study could make no reference for, and why: they
    are left out of every error, so every median and p90 is over the others."""
    if not rows:
        return None
    listed = "; ".join(f"{r['particle']} ({r['placement']}): {r['why']}" for r in rows)
    return (f"No reference for {len(rows)} of {total} particle and placement pairs, left out of every error below "
            f"(each median and p90 is over the other {total - len(rows)}): {listed}.")


def geometry_unmeasured(references):
    """True for a finest-resolution reference whose geometry term no particle measured (no coarser resolution
    refined): its uncertainty is the discretization term alone."""
    finest = [r for r in references if r.get("reference", "finest") != "source"]
    return bool(finest) and not any(r["geometry_from"] for r in finest)


# What a reader of such a report must know: the source reference's measurement (docs/study.md, "The source
# reference": 11 generated particles, the full study's converged fem at 2000 triangles against each particle's own
# surface, lowest placement).
GEOMETRY_UNMEASURED = (
    "**This reference is fem at the finest resolution, not the particle, and its geometry term is not measured "
    "here** (no coarser resolution was refined): every uncertainty below is its discretization term alone and "
    "understates its distance from the particle. Measured against the particles' own source surfaces, the "
    "converged fem at 2000 triangles is 5.0 % (median) and 6.4 % (p90) from the particle in peak force "
    "(docs/study.md, 'The source reference'); `\"reference\": \"source\"` measures every error against the "
    "particle (data/study/source.json, this study's twin: reports/study-source/).")


def references_section(doc, references, growth, contact_factor=0, missing=None):
    """The reference of each particle and the two terms of its uncertainty (references.csv); `growth` the refined
    levels' far-field grading (study.json), whose bias the uncertainty does not include; `contact_factor` their
    contact.max_contact_factor (study.json refinement.max_contact_factor, 0: none); `missing` the paragraph on the
    particles with no reference (unreferenced_paragraph), or None."""
    if not references and not missing:
        return
    doc.h(2, "The reference and its uncertainty")
    if missing:
        doc.p(missing)
    if not references:
        return
    if any(r.get("reference") == "source" for r in references):
        source_reference_section(doc, references)
        return
    doc.p("Per particle: the reference (the limit of the fem sequence at the finest resolution), the order its peak "
          "force was extrapolated at (observed from three refined levels, or the assumed bracket's middle), and the "
          "two terms of its uncertainty, added in quadrature: discretization (the extrapolation's estimated error) "
          "and geometry (the change of the limit from the next coarser resolution that was refined: is the finest "
          "geometry fine enough?; 'not measured' where none was). The larger term is the one to refine.")
    if geometry_unmeasured(references):
        doc.p(GEOMETRY_UNMEASURED)
    rows = []
    for r in references:
        d, g = num(r["peak_force_discretization"]), num(r["peak_force_geometry"])
        dominant = ("-" if math.isnan(d) else "unknown: geometry not measured" if not r["geometry_from"]
                    else "discretization" if math.isnan(g) or d >= g else "geometry")
        rows.append([r["particle"], r["placement"], r["resolution"], fmt(r["peak_force"]),
                     (("observed " if r["order_observed"] == "true" else "assumed ") + fmt(r["peak_force_order"], 3))
                     if r["peak_force_order"] else "-",
                     pct(r["peak_force_discretization"]),
                     (pct(r["peak_force_geometry"]) + f" (from {r['geometry_from']})") if r["geometry_from"] else "not measured",
                     pct(r["peak_force_uncertainty"]), dominant, pct(r["contact_duration_uncertainty"]),
                     pct(r["impulse_uncertainty"])])
    doc.table(["particle", "placement", "N", "peak force (N)", "order (peak)", "discretization", "geometry",
               "uncertainty (peak)", "larger term", "uncertainty (duration)", "uncertainty (impulse)"], rows)
    if growth is not None and growth > 0.15:
        doc.p(f"Not in the uncertainty: the refined levels grow at {growth:g} beyond the strike point. At 0.3 the "
              "limits were measured 0.8-3.1 % (median 1.5 %) stiffer in peak force than at 0.15 on three of these "
              "particles, and a sphere's limit +3.0 % from the finite-sphere reference against +1.5 % at 0.15 "
              "(docs/study.md, 'Grading 0.15 or a third level'): read the peak-force reference as about 1.5 % high.")
    if contact_factor:
        doc.p(f"The refined levels' contact step is held within {contact_factor:g}x of their elements' own: where the "
              "study's penalty on a small surface face would set a shorter step, that face's penalty is lowered "
              "(refinement.max_contact_factor; docs/study.md, 'Grading 0.15 or a third level', for its measured effect "
              "on the peak force).")


# What the errors are against, set by main() from the study's definition ("reference": "finest" or "source").
REFERENCE = {"name": "the converged fem reference"}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("study")
    ap.add_argument("--out", required=True)
    ap.add_argument("--stability", default="")
    ap.add_argument("--yade", default="")
    ap.add_argument("--penalty", default="")
    a = ap.parse_args()
    check_inputs(a.study)
    os.makedirs(a.out, exist_ok=True)
    # unreferenced.csv is optional: a folder written before the table existed has none.
    tables = TABLES + [t for t in OPTIONAL_TABLES if os.path.exists(os.path.join(a.study, t))]
    for t in tables + ["study_summary.json", "guidelines.json"]:
        src = os.path.join(a.study, t)
        if os.path.abspath(src) != os.path.abspath(os.path.join(a.out, t)):
            shutil.copyfile(src, os.path.join(a.out, t))
    cases = read_csv(os.path.join(a.study, "cases.csv"))
    fits = read_csv(os.path.join(a.study, "cpu_fit.csv"))
    candidates = read_csv(os.path.join(a.study, "candidates.csv"))
    guidelines = read_csv(os.path.join(a.study, "guidelines.csv"))
    classes = read_csv(os.path.join(a.study, "particle_classes.csv"))
    classification = read_csv(os.path.join(a.study, "classification.csv"))
    with open(os.path.join(a.study, "study_summary.json")) as fh:
        summary = json.load(fh)
    with open(os.path.join(a.study, "study.json")) as fh:
        definition = json.load(fh)
    if definition.get("reference") == "source":
        REFERENCE["name"] = "the particle itself (its source reference)"

    for t in tables:
        write_markdown_table(os.path.join(a.study, t), os.path.join(a.out, t[:-4] + ".md"))
    uncertainty = {}
    for g in guidelines:
        uncertainty.setdefault((g["placement"], g["metric"]), {})[g["statistic"]] = g["reference_uncertainty"]

    doc = Doc()
    doc.h(1, f"Particle-geometry study: {summary['study']}")
    geometry_section(doc, a.study, a.out)
    answer_section(doc, a.study, summary["published"])
    axes_section(doc, a.study, cases)
    refinement = definition.get("refinement") or {}
    reference_is = ("the particle itself: the Richardson limit of its source surface's three refined levels "
                    "('The reference and its uncertainty' above)" if definition.get("reference") == "source" else
                    "the limit of the fem refinement sequence (refined at the strike point, extrapolated as above) at "
                    "the finest resolution")
    references_section(doc, read_csv(os.path.join(a.study, "references.csv")), refinement.get("growth"),
                       refinement.get("max_contact_factor") or 0,
                       unreferenced_note(a.study, definition))
    doc.p(f"{summary['particles']} particles x resolutions {summary['resolutions']} x models "
          f"{', '.join(summary['models'])} x placements {', '.join(summary['placements'])}: {summary['cases']} cases, "
          f"{summary['done']} done, {summary['failed']} failed. Each particle is launched straight down onto a fixed "
          "block under gravity. Errors are relative to the finest resolution of the same model (err) and to the "
          f"reference (err_fem): {reference_is}, same placement (docs/study.md). The sphere, rigid and sphere-local "
          "models strike a rigid block, as the fem does. "
          "Tables: cases, references, unreferenced, classification, particle_classes, cpu_fit, candidates, guidelines, discretization, "
          "answer, few_hundred, as CSV and as Markdown "
          "beside this file; every chart as PNG and SVG.")

    doc.h(2, "Cost")
    pub = summary["published"]
    growth = summary.get("fem_cpu_growth") or {}
    rows = [["this study", summary["cases"], fmt(summary["cpu_seconds_total"]),
             fmt(summary.get("fem_cpu_growth_100_1000")) or "-",
             f"{growth.get('from')} -> {growth.get('to')}: {fmt(growth.get('ratio'))}" if growth else "-"],
            ["Zhang & Zsaki 2019", pub["simulations"], f"{pub['cpu_seconds_100']} s at 100, {pub['cpu_seconds_1000']} s "
             "at 1000 triangles", fmt(pub["cpu_growth_100_1000"]), "-"]]
    doc.table(["study", "simulations", "total CPU (s)", "fem CPU growth 100 -> 1000", "fem CPU growth, study range"],
              rows)
    by = summary.get("cpu_seconds_by_model", {})
    doc.p("CPU seconds by model: " + ", ".join(f"{k} {fmt(v)}" for k, v in by.items()) +
          (f". Wall time of the {summary['runs_computing']} run(s) that computed the cases: "
           f"{fmt(summary['wall_seconds_computing'])} s" if summary.get("runs_computing") else "") +
          f". Last run: {fmt(summary['last_run']['wall_seconds'])} s wall, "
          f"{fmt(summary['last_run']['cpu_seconds'])} s CPU, {summary['last_run']['ran']} cases run, "
          f"{summary['last_run']['kept']} kept from before.")
    doc.table(["model", "placement", "exponent p (CPU ~ N^p)", "coefficient", "resolutions"],
              [[f["model"], f["placement"], fmt(f["exponent"], 3), fmt(f["coefficient"]), f["points"]] for f in fits])
    cpu_chart(a.out, cases, fits, doc)

    doc.h(2, "Accuracy against cost")
    doc.p(f"Median over the particles of |error| against {REFERENCE['name']}, and its 90th percentile, "
          "against the median CPU time of each model, resolution and element size.")
    accuracy_cost_chart(a.out, candidates, uncertainty, doc)
    doc.table(["placement", "model", "resolution", "h/R", "particles", "peak err median", "peak err p90",
               "impulse err median", "impulse err p90", "duration err median", "arrival shift median",
               "CPU median (s)"],
              [[c["placement"], c["model"], c["resolution"] or "-", fmt(c["element_size_rel"]) or "coarse",
                c["particles"], pct(c["peak_force_err_median"]), pct(c["peak_force_err_p90"]),
                pct(c["impulse_err_median"]), pct(c["impulse_err_p90"]), pct(c["contact_duration_err_median"]),
                pct(c["first_contact_time_err_median"]), fmt(c["cpu_seconds_median"])] for c in candidates])

    doc.h(2, "Guidelines")
    doc.p("For each tolerance on peak force, impulse, contact duration, first-contact time (its shift over the "
          "reference's contact duration) or peak force and impulse together, the cheapest model, resolution and "
          f"element size (lowest median CPU) whose |error| against {REFERENCE['name']} stays within it for "
          "half the particles (median) or for 90 % of them (p90), with the reference's own uncertainty (same "
          "statistic over the particles). 'reference' means nothing cheaper met it; 'unresolved' that the "
          "reference is uncertain by more than the tolerance.")
    doc.table(["placement", "metric", "tolerance", "statistic", "model", "triangles", "h/R", "error",
               "reference uncertainty", "CPU median (s)"],
              [[g["placement"], g["metric"], pct(g["tolerance"], 0), g["statistic"], g["model"],
                (g["resolution"] or "-") + (" (reference)" if g["is_reference"] == "true" else ""),
                fmt(g["element_size_rel"]) or "coarse", pct(g["error"]),
                pct(g["reference_uncertainty"]) + (" (unresolved)" if g["resolvable"] == "false" else ""),
                fmt(g["cpu_seconds_median"])] for g in guidelines])

    if a.penalty:
        penalty_section(a.out, a.penalty, doc)

    doc.h(2, "Response classes")
    doc.p("Each model's force curve at each resolution (fem: the coarse default) against "
          f"{REFERENCE['name']} (the thick grey curve in the overlays below): shifted when the first contact comes more than "
          "5 % of the reference contact duration earlier or later (the 5 % tolerance of the first-contact "
          "guideline); tail when the contact lasts more than 10 % longer, short when more than 10 % shorter (the "
          "10 % tolerance on contact duration: a short pulse is the stiff response, which the cross-correlation "
          "lag used before mistook for a shift); asymmetric when the skewness of the force curve (time weighted by "
          "force) differs by more than 0.3; overlapping otherwise (criteria and reasons in docs/study.md). Classes: every label met at any coarser "
          "resolution; coarsest: the label at the coarsest resolution.")
    doc.table(["particle", "model", "placement", "classes", "coarsest"],
              [[c["particle"], c["model"], c["placement"], c["classes"], c["coarsest_class"]] for c in classes])
    counts = {}
    for c in classification:
        counts[c["class"]] = counts.get(c["class"], 0) + 1
    doc.p("Resolutions by class: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) + ".")
    class_examples(a.study, a.out, cases, classification, doc)

    doc.h(2, "Force-time curves")
    force_overlays(a.study, a.out, cases, doc)

    doc.h(2, "Cases")
    doc.table(["particle", "model", "N", "h (mm)", "placement", "status", "peak (N)", "impulse (N s)",
               "duration (s)", "first contact (s)", "CPU (s)", "converged", "discretization err", "peak err ref",
               "impulse err ref"],
              [[c["particle"], c["model"], c["resolution"] or "-",
                fmt(1e3 * num(c["element_size"]), 3) if c["element_size"] else "-", c["placement"], c["status"],
                fmt(c["peak_force"]), fmt(c["impulse"]), fmt(c["contact_duration"]), fmt(c["first_contact_time"]),
                fmt(c["cpu_seconds"], 3), c["converged"], pct(c["discretization_error"]),
                pct(c["peak_force_err_fem"]), pct(c["impulse_err_fem"])] for c in cases])

    if a.stability:
        stability_section(a.out, a.stability, doc)
    if a.yade:
        yade_section(a.out, a.yade, doc)

    with open(os.path.join(a.out, "report.md"), "w") as fh:
        fh.write("\n".join(doc.md) + "\n")
    with open(os.path.join(a.out, "report.html"), "w") as fh:
        fh.write("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
                 + html.escape(f"Particle-geometry study: {summary['study']}") + "</title><style>" + CSS
                 + "</style></head><body>\n" + "\n".join(doc.html) + "\n</body></html>\n")


if __name__ == "__main__":
    try:
        main()
    except BadInput as e:
        print(f"asperity: {e}", file=sys.stderr)
        sys.exit(2)
    except Exception as e:  # a defect here, not bad input: one line, not a traceback
        print(f"asperity: error: report: {type(e).__name__}: {str(e)[:200]}", file=sys.stderr)
        sys.exit(1)
