#!/usr/bin/python3
"""The geometry term of a study's reference (issue 12: "is 2000 triangles enough?").

For a study that refines the fem model at two or more resolutions N (data/study/geometry.json),
the converged answer at each N (the Richardson limit of its refined levels, as `asperity study`
extrapolates it: tables/study_cases.cpp, docs/study.md "Guidelines") isolates the particle's shape
from the element size. Along N those answers form a second sequence, in the surface edge length
s ~ N^-1/2: its changes between successive N, its observed order in s where three levels allow
it, and its limit N -> infinity (the same Richardson step, with Roache's 1.25 on the last
correction as its estimated error). Each resolution's error against that limit, and whether it is
within 1, 2 and 5 %, answers the question per particle and at the median.

Reads DIR/study.json and DIR/cases.csv (checking the peak-force limits against its
extrapolated_peak_force and the finest resolution's against references.csv); writes
OUT/geometry.csv (every particle, metric and resolution, plus the N -> infinity row),
OUT/geometry_answer.csv (per particle and the median: the finest-but-one resolution against the
limit, and the verdicts) and OUT/geometry.md (both as Markdown). Usable as a module
(study_report.py) or alone: geometry_table.py DIR --out OUT.
"""
import argparse
import csv
import json
import math
import os
import statistics
import sys

from tabular import num, pct, read_csv  # beside this file

METRICS = [("peak_force", "peak force"), ("impulse", "impulse"), ("contact_duration", "contact duration")]
TOLERANCES = (0.01, 0.02, 0.05)
# As tables/study_cases.hpp: the assumed order bracket of two refined levels, the range an observed
# order is trusted in, and Roache's safety factor on an observed-order extrapolation.
ASSUMED_LOW, ASSUMED_HIGH = 1.2, 2.7
OBSERVED_MIN, OBSERVED_MAX = 0.5, 5.0
SAFETY_OBSERVED = 1.25


def richardson(sizes, values):
    """tables/study_cases.cpp's richardson(): (limit, relative error, order, observed)."""
    n = len(values)
    if n < 2 or any(not math.isfinite(v) for v in values):
        return math.nan, math.nan, math.nan, False
    v2, v3 = values[-2], values[-1]
    if n >= 3:
        v1 = values[-3]
        s1, s2, s3 = sizes[-3], sizes[-2], sizes[-1]
        d1, d2 = v2 - v1, v3 - v2
        if d1 * d2 > 0 and abs(d2) < abs(d1):
            target = d1 / d2

            def ratio(p):
                return (s1 ** p - s2 ** p) / (s2 ** p - s3 ** p)

            lo, hi = 1e-3, 20.0
            for _ in range(100):
                mid = 0.5 * (lo + hi)
                if ratio(mid) < target:
                    lo = mid
                else:
                    hi = mid
            p = 0.5 * (lo + hi)
            if OBSERVED_MIN <= p <= OBSERVED_MAX:
                correction = d2 / ((s2 / s3) ** p - 1)
                limit = v3 + correction
                return limit, SAFETY_OBSERVED * abs(correction) / abs(limit), p, True
    r, d = sizes[-2] / sizes[-1], v3 - v2
    lo = v3 + d / (r ** ASSUMED_LOW - 1)
    hi = v3 + d / (r ** ASSUMED_HIGH - 1)
    limit = 0.5 * (lo + hi)
    return limit, (0.5 * abs(lo - hi) / abs(limit) if limit else math.nan), 0.5 * (ASSUMED_LOW + ASSUMED_HIGH), False


def close(a, b, rel=1e-12):
    return math.isfinite(a) and math.isfinite(b) and abs(a - b) <= rel * abs(b)


class Mismatch(Exception):
    pass


def converged_answers(study):
    """{(particle, placement): {N: {metric: (limit, error), "levels": [...]}}} for every refined N,
    each peak-force limit checked against cases.csv's extrapolated_peak_force."""
    with open(os.path.join(study, "study.json")) as f:
        definition = json.load(f)
    refinement = definition.get("refinement") or {}
    sizes = sorted(refinement.get("sizes") or [], reverse=True)
    cases = [c for c in read_csv(os.path.join(study, "cases.csv")) if c["model"] == "fem" and c["status"] == "ok"]
    levels = {}
    for c in cases:
        key = (c["particle"], c["placement"], int(c["resolution"]))
        levels.setdefault(key, {})[num(c["element_size_rel"]) if c["element_size"] else 0.0] = c
    out = {}
    for (particle, placement, n), by_size in sorted(levels.items()):
        refined = [by_size[h] for h in sizes if h in by_size]
        if len(refined) < 2 or len(refined) != len(sizes):
            continue
        hs = [num(c["element_size_rel"]) for c in refined]
        entry = {"coarse": by_size.get(0.0), "levels": refined}
        for m, _ in METRICS:
            limit, error, order, observed = richardson(hs, [num(c[m]) for c in refined])
            entry[m] = (limit, error)
        answer = refined[-1]
        if not close(entry["peak_force"][0], num(answer["extrapolated_peak_force"])):
            raise Mismatch(f"{particle} {n}: peak limit {entry['peak_force'][0]!r} against cases.csv's "
                           f"{answer['extrapolated_peak_force']}")
        out.setdefault((particle, placement), {})[n] = entry
    references = read_csv(os.path.join(study, "references.csv"))
    for r in references:
        got = out.get((r["particle"], r["placement"]), {}).get(int(r["resolution"]))
        for m, _ in METRICS:
            if got and not close(got[m][0], num(r[m])):
                raise Mismatch(f"{r['particle']} {r['resolution']}: {m} limit {got[m][0]!r} against "
                               f"references.csv's {r[m]}")
    return out


def geometry_sequence(answers):
    """Per metric along N: changes (relative to the finer N), the observed order in s ~ N^-1/2 of
    each three successive N, and the N -> infinity limit from the last three (or none)."""
    ns = sorted(answers)
    rows, verdicts = [], {}
    for m, _ in METRICS:
        values = [answers[n][m][0] for n in ns]
        s = [math.sqrt(ns[0] / n) for n in ns]  # the surface edge length over the coarsest's
        orders = {}
        for k in range(2, len(ns)):
            limit, error, order, observed = richardson(s[k - 2:k + 1], values[k - 2:k + 1])
            orders[ns[k]] = order if observed else math.nan
        inf = (math.nan, math.nan)
        if len(ns) >= 3:
            limit, error, order, observed = richardson(s, values)
            if observed:
                inf = (limit, error)
        for k, n in enumerate(ns):
            rows.append({"metric": m, "resolution": n, "value": values[k], "discretization_error": answers[n][m][1],
                         "change": (values[k] - values[k - 1]) / values[k] if k else math.nan,
                         "order_observed": orders.get(n, math.nan),
                         "error_vs_limit": (values[k] - inf[0]) / inf[0] if math.isfinite(inf[0]) else math.nan})
        rows.append({"metric": m, "resolution": "inf", "value": inf[0], "discretization_error": math.nan,
                     "change": math.nan, "order_observed": math.nan, "error_vs_limit": math.nan,
                     "limit_error": inf[1]})
        verdicts[m] = inf
    return ns, rows, verdicts


def verdict(err, unc, last_change, tol):
    """yes: within tol even at the far end of the limit's error; no: beyond it even at the near
    end, or the last change of N alone beyond it (a limit comes only from a monotone sequence, so
    the error is at least that change); else undecided. With no limit (the changes of N not
    falling), the last change of N is the error estimate, as the study's own geometry term takes
    it: no when it exceeds tol, else likely (one change, no rate behind it)."""
    if math.isfinite(last_change) and abs(last_change) > tol:
        return "no"
    if math.isfinite(err):
        if abs(err) + unc <= tol:
            return "yes"
        if abs(err) - unc > tol:
            return "no"
        return "undecided"
    return "likely" if math.isfinite(last_change) else "undecided"


def median_verdict(verdicts):
    """At the median, as the guidelines count it: met when half the particles are within. yes
    when half say yes; likely when half say yes or likely; no when more than half say no (fewer
    than half can be within); else undecided."""
    half = math.ceil(len(verdicts) / 2)
    if verdicts.count("yes") >= half:
        return "yes"
    if verdicts.count("yes") + verdicts.count("likely") >= half:
        return "likely"
    if verdicts.count("no") > len(verdicts) - half:
        return "no"
    return "undecided"


def g(x, digits=6):
    return "" if not math.isfinite(x) else f"{x:.{digits}g}"


def cell(x):
    return "" if isinstance(x, float) and not math.isfinite(x) else repr(x) if isinstance(x, float) else str(x)


def build(study):
    answers = converged_answers(study)
    seq_rows, answer_rows = [], []
    for (particle, placement), by_n in answers.items():
        ns, rows, inf = geometry_sequence(by_n)
        if len(ns) < 2:
            continue
        # The resolution asked about: the finest but one (2000 of 500-4000); the finest's change
        # from it is the last step of N.
        asked = ns[-2]
        for r in rows:
            seq_rows.append({"particle": particle, "placement": placement, **r})
        for m, _ in METRICS:
            at = next(r for r in rows if r["metric"] == m and r["resolution"] == asked)
            last = next(r for r in rows if r["metric"] == m and r["resolution"] == ns[-1])
            limit, unc = inf[m]
            row = {"particle": particle, "placement": placement, "metric": m, "resolution": asked,
                   "value": at["value"], "limit": limit, "limit_error": unc, "error": at["error_vs_limit"],
                   "last_change": last["change"], "discretization_error": at["discretization_error"]}
            has_limit = math.isfinite(row["error"])
            row["error_estimate"] = abs(row["error"]) if has_limit else abs(row["last_change"])
            row["estimate_from"] = "limit" if has_limit else "last change"
            for tol in TOLERANCES:
                row[f"within_{round(100 * tol)}pct"] = verdict(row["error"], unc if math.isfinite(unc) else 0,
                                                                row["last_change"], tol)
            answer_rows.append(row)
    # The median over the particles (per placement and metric) of each particle's error estimate
    # (|error| against the limit where there is one, else |last change|) and of the limits' errors.
    medians = []
    for placement in sorted({r["placement"] for r in answer_rows}):
        for m, _ in METRICS:
            rs = [r for r in answer_rows if r["placement"] == placement and r["metric"] == m]
            ests = [r["error_estimate"] for r in rs if math.isfinite(r["error_estimate"])]
            uncs = [r["limit_error"] for r in rs if math.isfinite(r["limit_error"])]
            sources = {r["estimate_from"] for r in rs}

            def median(v):
                return statistics.median(v) if v else math.nan

            row = {"particle": "median", "placement": placement, "metric": m, "resolution": rs[0]["resolution"],
                   "value": math.nan, "limit": math.nan, "limit_error": median(uncs) if len(uncs) == len(rs) else math.nan, "error": math.nan,
                   "last_change": median([abs(r["last_change"]) for r in rs if math.isfinite(r["last_change"])]),
                   "error_estimate": median(ests),
                   "estimate_from": sources.pop() if len(sources) == 1 else "limit or last change",
                   "discretization_error": median([r["discretization_error"] for r in rs
                                                   if math.isfinite(r["discretization_error"])])}
            for tol in TOLERANCES:
                key = f"within_{round(100 * tol)}pct"
                row[key] = median_verdict([r[key] for r in rs])
            medians.append(row)
    return seq_rows, answer_rows + medians


SEQ_HEADER = ["particle", "placement", "metric", "resolution", "value", "discretization_error", "change",
              "order_observed", "error_vs_limit", "limit_error"]
ANSWER_HEADER = ["particle", "placement", "metric", "resolution", "value", "limit", "limit_error", "error",
                 "last_change", "error_estimate", "estimate_from", "discretization_error"] + [f"within_{round(100 * t)}pct" for t in TOLERANCES]


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for r in rows:
            w.writerow([cell(r.get(h, math.nan)) for h in header])


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
    """Writes OUT/geometry.csv, OUT/geometry_answer.csv and OUT/geometry.md; returns tables()'s
    list (None when the study refines fewer than two resolutions)."""
    seq_rows, answer_rows = build(study)
    if not answer_rows:
        return None
    os.makedirs(out, exist_ok=True)
    write_csv(os.path.join(out, "geometry.csv"), SEQ_HEADER, seq_rows)
    write_csv(os.path.join(out, "geometry_answer.csv"), ANSWER_HEADER, answer_rows)
    with open(os.path.join(out, "geometry.md"), "w") as f:
        f.write("# The geometry term\n\n" + markdown(seq_rows, answer_rows))
    return tables(seq_rows, answer_rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    try:
        if write(a.study, a.out) is None:
            print(f"geometry_table: {a.study}: fewer than two resolutions refined, no geometry sequence",
                  file=sys.stderr)
            return 2
    except Mismatch as e:
        print(f"geometry_table: {a.study}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
