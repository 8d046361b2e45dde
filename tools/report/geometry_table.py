#!/usr/bin/python3
"""The geometry term of a study's reference (issue 12: "is 2000 triangles enough?"), as Markdown.

For a study that refines the fem model at two or more resolutions N (data/study/geometry.json),
`asperity study` writes the geometry term beside its other tables (study/tables/geometry_table.cpp,
docs/study.md "The geometry term"): DIR/geometry.csv, the converged answer at each N (the
Richardson limit of its refined levels) per particle and metric, its change along N, the observed
order in the surface edge length s ~ N^-1/2 and the N -> infinity limit; DIR/geometry_answer.csv,
per particle and the median, the finest-but-one resolution against that limit and whether it is
within 1, 2 and 5 %. This script only reads them: it copies both into OUT and writes
OUT/geometry.md. Usable as a module (study_report.py) or alone: geometry_table.py DIR --out OUT.
"""
import argparse
import math
import os
import shutil
import sys

from tabular import num, pct, read_csv  # beside this file

METRICS = [("peak_force", "peak force"), ("impulse", "impulse"), ("contact_duration", "contact duration")]
TABLES = ("geometry.csv", "geometry_answer.csv")
TEXT = ("particle", "placement", "metric", "resolution", "estimate_from", "within_1pct", "within_2pct", "within_5pct")


def g(x, digits=6):
    return "" if not math.isfinite(x) else f"{x:.{digits}g}"


def rows_of(path):
    """A table's rows with its numbers as floats (empty: NaN) and resolutions as ints ("inf" kept)."""
    out = []
    for r in read_csv(path):
        row = {k: (v if k in TEXT else num(v)) for k, v in r.items()}
        row["resolution"] = int(r["resolution"]) if r["resolution"] != "inf" else "inf"
        out.append(row)
    return out


def build(study):
    """(geometry.csv's rows, geometry_answer.csv's rows) from the study folder; ([], []) when the study
    refines fewer than two resolutions (asperity study writes neither)."""
    if not all(os.path.exists(os.path.join(study, t)) for t in TABLES):
        return [], []
    return rows_of(os.path.join(study, TABLES[0])), rows_of(os.path.join(study, TABLES[1]))


def tables(seq_rows, answer_rows):
    """The sequence per metric (value, change, order; the limit) and the answer, as
    [(caption, header, rows)]: geometry.md and the report's section render the same."""
    out = []
    names = dict(METRICS)
    particles = sorted({(r["particle"], r["placement"]) for r in seq_rows})
    for m, label in METRICS:
        # Every N any particle has; a particle without a converged answer at one (a refined case
        # failed) shows a dash there.
        ns = sorted({r["resolution"] for r in seq_rows if r["resolution"] != "inf"}) + ["inf"]
        rows = []
        for p, pl in particles:
            cells = []
            mine = {r["resolution"]: r for r in seq_rows if r["metric"] == m and (r["particle"], r["placement"]) == (p, pl)}
            for n in ns:
                r = mine.get(n)
                if r is None:
                    cells.append("-")
                    continue
                if r["resolution"] == "inf":
                    # An order (and so a limit) needs three resolutions; with two, none is sought.
                    levels = sum(1 for k in mine if k != "inf")
                    cells.append(f"{g(r['value'])} ± {pct(r['limit_error'])}" if math.isfinite(r["value"])
                                 else "none (changes not falling)" if levels >= 3 else
                                 f"none ({levels} resolutions: an order needs three)")
                    continue
                c = g(r["value"])
                if math.isfinite(r["change"]):
                    c += f" ({'+' if r['change'] >= 0 else ''}{pct(r['change'])}"
                    c += f", p = {r['order_observed']:.2f})" if math.isfinite(r["order_observed"]) else ")"
                cells.append(c)
            rows.append([p] + cells)
        out.append((f"{label[0].upper() + label[1:]}: the converged answer (the limit of the refined levels) at each "
                    "N, in brackets its change from the next coarser N (relative to the finer) and the observed "
                    "order in N^-1/2 (the surface edge length) of the three N ending there; the N -> infinity "
                    "limit with its estimated error (Roache's 1.25 on the last correction). A dash: no converged answer "
                    "at that N (a refined case failed).",
                    ["particle"] + [f"N = {n}" if n != "inf" else "N -> infinity" for n in ns], rows))
    asked = answer_rows[0]["resolution"] if answer_rows else ""
    out.append((f"Is {asked} triangles enough? Its converged answer against the N -> infinity limit (error, and the "
                "limit's estimated error). yes: within the tolerance even at the far end of the limit's error; no: "
                "beyond it even at the near end, or the last change of N (to the finest) alone beyond it (a limit "
                "comes only from a monotone sequence, whose remaining error is at least that change); undecided "
                "between. With no limit (the changes of N not falling), the last change of N is the error estimate, "
                "as the study's geometry term takes it: no when beyond the tolerance, likely when within it (one "
                "change, no rate behind it). The median row counts as the guidelines do (met when half the "
                "particles are within): yes or likely when half the particles say so, no when more than half say "
                "no; its columns are medians of |value|. The discretization error (h) is the converged answer's "
                "own, from its extrapolation in element size.",
                ["particle", "metric", f"error of {asked}", "limit's error", "last change of N",
                 f"error estimate of {asked} (from)", "discretization error (h)", "1 %", "2 %", "5 %"],
                [[r["particle"], names[r["metric"]], pct(r["error"]), pct(r["limit_error"]), pct(r["last_change"]),
                  f"{pct(r['error_estimate'])} ({r['estimate_from']})", pct(r["discretization_error"]),
                  r["within_1pct"], r["within_2pct"], r["within_5pct"]] for r in answer_rows]))
    return out


def markdown(seq_rows, answer_rows):
    lines = []
    for caption, header, rows in tables(seq_rows, answer_rows):
        lines.append(caption + "\n")
        lines.append("| " + " | ".join(header) + " |")
        lines.append("|---|" + "---:|" * (len(header) - 1))
        lines.extend("| " + " | ".join(str(c) for c in r) + " |" for r in rows)
        lines.append("")
    return "\n".join(lines)


def write(study, out):
    """Copies geometry.csv and geometry_answer.csv into OUT and writes OUT/geometry.md; returns tables()'s
    list (None when the study refines fewer than two resolutions)."""
    seq_rows, answer_rows = build(study)
    if not answer_rows:
        return None
    os.makedirs(out, exist_ok=True)
    for t in TABLES:
        if os.path.abspath(os.path.join(study, t)) != os.path.abspath(os.path.join(out, t)):
            shutil.copyfile(os.path.join(study, t), os.path.join(out, t))
    with open(os.path.join(out, "geometry.md"), "w") as f:
        f.write("# The geometry term\n\n" + markdown(seq_rows, answer_rows))
    return tables(seq_rows, answer_rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    if write(a.study, a.out) is None:
        print(f"geometry_table: {a.study}: no geometry.csv (fewer than two resolutions refined)", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
